#include "core/mesh/gltf_io.h"

#include "core/mesh/mesh_io.h"

// The Debian package ships tinygltf as a shared library built with its default options (stb_image, stb_image_write,
// nlohmann json, file system callbacks): include the header with no configuration macros so the declarations match
// that library, and never define TINYGLTF_IMPLEMENTATION.
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "core/mesh/gltf_model.h"
#include "core/mesh/gltf_read.h"

namespace trispline::core {
namespace {

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

glm::vec3 base_color(const tinygltf::Material& m, const glm::vec3& fallback) {
  const auto& f = m.pbrMetallicRoughness.baseColorFactor;
  return f.size() >= 3 ? glm::vec3(float(f[0]), float(f[1]), float(f[2])) : fallback;
}

// Node-local matrix: `matrix` if given, else T · R · S (glTF 2.0 §5.25).
glm::dmat4 local_matrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());  // column-major, as glm
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
  if (n.rotation.size() == 4) {
    const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);  // glTF stores x, y, z, w
    m = m * glm::dmat4(glm::mat3_cast(q));
  }
  if (n.scale.size() == 3) {
    glm::dmat4 s(1.0);
    for (int i = 0; i < 3; ++i) s[i][i] = n.scale[i];
    m = m * s;
  }
  return m;
}

using gltf_read::kMaxMeshFileTriangles;
using gltf_read::kMaxMeshFileVertices;

// Vertices and triangles read so far from one file, against kMaxMeshFileVertices / kMaxMeshFileTriangles.
struct Totals {
  std::size_t vertices = 0, triangles = 0;
};

[[noreturn]] void over_vertex_budget(const std::filesystem::path& path) {
  throw MeshIoError(quoted(path) + ": the file's meshes have more than " + std::to_string(kMaxMeshFileVertices) +
                    " vertices (the limit for mesh files; a mesh used by several nodes counts once per node)");
}

[[noreturn]] void over_triangle_budget(const std::filesystem::path& path) {
  throw MeshIoError(quoted(path) + ": the file's meshes have more than " + std::to_string(kMaxMeshFileTriangles) +
                    " triangles (the limit for mesh files)");
}

bool is_surface_mode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// Triangles `count` indices (or vertices) make in `mode`.
std::size_t triangle_count(int mode, std::size_t count) {
  return mode == TINYGLTF_MODE_TRIANGLES ? count / 3 : count >= 3 ? count - 2 : 0;
}

// Element count of vertex attribute `index`, which must equal the primitive's POSITION count `n`.
void require_count(const tinygltf::Model& model, int index, const std::string& what, std::size_t n,
                   const std::string& where, const std::filesystem::path& path) {
  const std::size_t count = gltf_read::accessor_layout(model, index, what, path).count;
  if (count != n)
    throw MeshIoError(quoted(path) + ": " + where + ": " + what + " has " + std::to_string(count) +
                      " elements, POSITION has " + std::to_string(n));
}

// Vertex attribute `index` as #n × comps finite doubles: float components, or (normalised) unsigned byte/short.
std::vector<double> read_attribute(const tinygltf::Model& model, int index, int comps, const std::string& what,
                                   std::size_t n, const std::string& where, const std::filesystem::path& path) {
  const auto layout = gltf_read::accessor_layout(model, index, what, path);
  if (layout.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT &&
      layout.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      layout.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
    throw MeshIoError(quoted(path) + ": " + what + " must be float (or normalised unsigned)");
  // Sparse substitution is not applied here (MeshClip mirrors this).
  std::vector<double> out = gltf_read::read_accessor(model, index, comps, what, path, n, /*sparse=*/false);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (!std::isfinite(out[i]))
      throw MeshIoError(quoted(path) + ": " + where + ": non-finite " + what + " value (vertex " +
                        std::to_string(i / comps) + ")");
  return out;
}

// Appends the primitive's vertices (POSITION through xf, NORMAL through its inverse transpose, TEXCOORD_0); returns
// the first vertex and the count. Counts are checked against POSITION and the file's budget before any read.
std::pair<std::uint32_t, std::size_t> append_vertices(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                                      const glm::dmat4& xf, TriMesh& mesh, bool& normals_ok,
                                                      Totals& totals, const std::string& where,
                                                      const std::filesystem::path& path) {
  const int pos_index = prim.attributes.at("POSITION");
  const std::size_t n = gltf_read::accessor_layout(model, pos_index, "POSITION", path).count;
  if (n > kMaxMeshFileVertices - totals.vertices) over_vertex_budget(path);
  const auto nrm_it = prim.attributes.find("NORMAL");
  const auto uv_it = prim.attributes.find("TEXCOORD_0");
  if (nrm_it != prim.attributes.end()) require_count(model, nrm_it->second, "NORMAL", n, where, path);
  if (uv_it != prim.attributes.end()) require_count(model, uv_it->second, "TEXCOORD_0", n, where, path);

  const auto pos = read_attribute(model, pos_index, 3, "POSITION", n, where, path);
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 p(xf * glm::dvec4(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2], 1.0));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw MeshIoError(quoted(path) + ": " + where + ": vertex " + std::to_string(i) +
                        " is not finite after its node's transform");
    mesh.positions.push_back(p);
  }
  totals.vertices += n;

  if (nrm_it != prim.attributes.end() && normals_ok) {
    const auto nrm = read_attribute(model, nrm_it->second, 3, "NORMAL", n, where, path);
    const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(xf)));
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec3 v = nm * glm::dvec3(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]);
      const double len = glm::length(v);
      mesh.normals.push_back(len > 0 ? v / len : v);
    }
    if (mesh.normals.size() != mesh.positions.size()) normals_ok = false;
  } else {
    normals_ok = false;
  }
  if (uv_it != prim.attributes.end()) {
    const auto uv = read_attribute(model, uv_it->second, 2, "TEXCOORD_0", n, where, path);
    mesh.uvs.resize(base, glm::dvec2(0));
    for (std::size_t i = 0; i < n; ++i) mesh.uvs.push_back({uv[2 * i], uv[2 * i + 1]});
  } else if (!mesh.uvs.empty()) {
    mesh.uvs.resize(mesh.positions.size(), glm::dvec2(0));
  }
  return {base, n};
}

std::size_t index_triangles(const tinygltf::Model& model, const tinygltf::Primitive& prim, int mode,
                            const glm::dmat4& xf, std::uint32_t base, std::size_t n, TriMesh& mesh, Totals& totals,
                            const std::string& where, const std::filesystem::path& path) {
  const bool indexed = prim.indices >= 0;
  const std::size_t count = indexed ? gltf_read::accessor_layout(model, prim.indices, "index", path).count : n;
  if (mode == TINYGLTF_MODE_TRIANGLES && count % 3 != 0)
    throw MeshIoError(quoted(path) + ": " + where + ": " + std::to_string(count) +
                      (indexed ? " indices" : " vertices without indices") + ", not a multiple of 3 (TRIANGLES)");
  if (triangle_count(mode, count) > kMaxMeshFileTriangles - totals.triangles) over_triangle_budget(path);
  std::vector<std::uint32_t> idx;
  if (indexed) {
    idx = gltf_read::read_indices(model, prim.indices, path, count);
  } else {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = static_cast<std::uint32_t>(i);
  }
  for (auto i : idx)
    if (i >= n)
      throw MeshIoError(quoted(path) + ": vertex index out of range (" + std::to_string(i) + " of " +
                        std::to_string(n) + " vertices)");
  const std::size_t triangles_before = mesh.triangles.size();
  mesh.triangles.reserve(triangles_before + triangle_count(mode, count));
  const bool flip = glm::determinant(glm::dmat3(xf)) < 0;  // mirrored node: keep CCW seen from outside
  auto tri = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    if (flip) std::swap(b, c);
    mesh.triangles.push_back(glm::uvec3(base + a, base + b, base + c));
  };
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t k = 0; k + 2 < idx.size(); k += 3) tri(idx[k], idx[k + 1], idx[k + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t k = 0; k + 2 < idx.size(); ++k)
      k % 2 ? tri(idx[k + 1], idx[k], idx[k + 2]) : tri(idx[k], idx[k + 1], idx[k + 2]);
  } else {
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) tri(idx[0], idx[k], idx[k + 1]);
  }
  totals.triangles += mesh.triangles.size() - triangles_before;
  return mesh.triangles.size() - triangles_before;
}

// Vertex accessors of a primitive (POSITION, NORMAL, TEXCOORD_0; -1 when absent) → first vertex and vertex count of
// the vertices already appended for them. Only "*.inside" primitives (write_glb's cut surfaces) reuse them; any other
// primitive appends its vertices, as mesh_clip.cpp expects (it mirrors this concatenation).
using SharedVertices = std::map<std::array<int, 3>, std::pair<std::uint32_t, std::size_t>>;

// Appends the primitive's triangles (and its vertices unless `reuse` and `shared` has them); returns the triangle
// count.
std::size_t append_primitive(const tinygltf::Model& model, const tinygltf::Primitive& prim, const glm::dmat4& xf,
                             TriMesh& mesh, bool& normals_ok, SharedVertices& shared, bool reuse, Totals& totals,
                             const std::string& where, const std::filesystem::path& path) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (!is_surface_mode(mode)) return 0;  // points and lines carry no surface
  const auto pos_it = prim.attributes.find("POSITION");
  if (pos_it == prim.attributes.end()) throw MeshIoError(quoted(path) + ": primitive without POSITION");
  auto accessor_of = [&](const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const std::array<int, 3> key{pos_it->second, accessor_of("NORMAL"), accessor_of("TEXCOORD_0")};
  const auto known = shared.find(key);
  std::uint32_t base = 0;
  std::size_t n = 0;
  if (reuse && known != shared.end()) {
    std::tie(base, n) = known->second;
  } else {
    std::tie(base, n) = append_vertices(model, prim, xf, mesh, normals_ok, totals, where, path);
    shared.emplace(key, std::make_pair(base, n));
  }
  return index_triangles(model, prim, mode, xf, base, n, mesh, totals, where, path);
}

bool is_inside(const tinygltf::Model& model, const tinygltf::Primitive& prim) {
  const int mat = prim.material;
  return mat >= 0 && mat < static_cast<int>(model.materials.size()) && ends_with(model.materials[mat].name, ".inside");
}

// One mesh node (or, without nodes, one mesh) in load order.
struct MeshUse {
  std::string name;
  int mesh = -1;
  glm::dmat4 world{1.0};
};

// Checks the vertices and triangles all uses will append against the budgets from accessor counts alone, as
// append_primitive counts them, so a file over them is refused before anything is decoded.
void check_budgets(const tinygltf::Model& model, const std::vector<MeshUse>& uses, const std::filesystem::path& path) {
  std::vector<std::pair<std::size_t, std::size_t>> per_mesh(model.meshes.size());  // (vertices, triangles)
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    std::set<std::array<int, 3>> seen;
    auto& [v, t] = per_mesh[m];
    for (const auto& prim : model.meshes[m].primitives) {
      const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      const auto pos = prim.attributes.find("POSITION");
      if (!is_surface_mode(mode) || pos == prim.attributes.end()) continue;  // skipped, or refused when read
      auto accessor_of = [&](const char* name) {
        const auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
      };
      const std::array<int, 3> key{pos->second, accessor_of("NORMAL"), accessor_of("TEXCOORD_0")};
      const std::size_t n = gltf_read::accessor_layout(model, pos->second, "POSITION", path).count;
      if (!(is_inside(model, prim) && seen.count(key))) {
        if (n > kMaxMeshFileVertices - std::min(v, kMaxMeshFileVertices)) over_vertex_budget(path);
        v += n;
        seen.insert(key);
      }
      const std::size_t count =
          prim.indices >= 0 ? gltf_read::accessor_layout(model, prim.indices, "index", path).count : n;
      const std::size_t tris = triangle_count(mode, count);
      if (tris > kMaxMeshFileTriangles - std::min(t, kMaxMeshFileTriangles)) over_triangle_budget(path);
      t += tris;
    }
  }
  std::size_t vertices = 0, triangles = 0;
  for (const MeshUse& u : uses) {
    const auto [v, t] = per_mesh.at(static_cast<std::size_t>(u.mesh));
    if (v > kMaxMeshFileVertices - vertices) over_vertex_budget(path);
    if (t > kMaxMeshFileTriangles - triangles) over_triangle_budget(path);
    vertices += v;
    triangles += t;
  }
}

bool finite_matrix(const glm::dmat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

std::vector<GltfObject> read_gltf_objects(const std::filesystem::path& path) {
  const tinygltf::Model model = gltf_read::read_model(path);  // checked: indices in range, nodes a forest

  std::vector<GltfObject> out;
  Totals totals;
  auto emit = [&](const std::string& name, int mesh_index, const glm::dmat4& xf) {
    if (mesh_index < 0 || mesh_index >= static_cast<int>(model.meshes.size()))
      throw MeshIoError(quoted(path) + ": node refers to a missing mesh");
    const auto& gm = model.meshes[mesh_index];
    GltfObject obj;
    obj.name = name.empty() ? gm.name : name;
    bool normals_ok = true;
    SharedVertices shared;
    std::vector<MaterialSlot> slots;  // per triangle
    bool any_inside = false;
    int color_material = -1;
    for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
      const auto& prim = gm.primitives[p];
      const int mat =
          prim.material >= 0 && prim.material < static_cast<int>(model.materials.size()) ? prim.material : -1;
      const bool inside = is_inside(model, prim);
      const std::string where = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
      const std::size_t added =
          append_primitive(model, prim, xf, obj.mesh, normals_ok, shared, inside, totals, where, path);
      slots.insert(slots.end(), added, inside ? kMaterialInside : kMaterialSurface);
      any_inside = any_inside || (inside && added > 0);
      if (inside && mat >= 0) obj.inside_color = base_color(model.materials[mat], obj.inside_color);
      if (!inside && color_material < 0) color_material = mat;
    }
    // A mesh of points or lines only (e.g. a volume's silhouettes in scene.glb) is no surface object.
    if (obj.mesh.triangles.empty() && obj.mesh.positions.empty()) return;
    if (!normals_ok) obj.mesh.normals.clear();
    if (any_inside) obj.mesh.face_material = std::move(slots);
    if (color_material < 0 && !gm.primitives.empty() && !any_inside) color_material = gm.primitives.front().material;
    if (color_material >= 0 && color_material < static_cast<int>(model.materials.size()))
      obj.color = base_color(model.materials[color_material], obj.color);
    out.push_back(std::move(obj));
  };

  // The mesh uses in load order: every mesh untransformed if there are no nodes, else the mesh nodes depth first
  // (read_model checked that the nodes form a forest, so the walk ends).
  std::vector<MeshUse> uses;
  if (model.nodes.empty()) {
    for (std::size_t i = 0; i < model.meshes.size(); ++i)
      uses.push_back({model.meshes[i].name, static_cast<int>(i), glm::dmat4(1)});
  }
  struct Item {
    int node;
    glm::dmat4 parent;
  };
  std::vector<Item> stack;
  const std::vector<int> roots = model.nodes.empty() ? std::vector<int>{} : gltf_model::root_nodes(model);
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1)});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.node < 0 || item.node >= static_cast<int>(model.nodes.size()))
      throw MeshIoError(quoted(path) + ": invalid node hierarchy");
    const auto& node = model.nodes[item.node];
    const glm::dmat4 world = item.parent * local_matrix(node);
    if (!finite_matrix(world))
      throw MeshIoError(quoted(path) + ": node " + std::to_string(item.node) + " has a non-finite transform");
    if (node.mesh >= 0) uses.push_back({node.name, node.mesh, world});
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back({*c, world});
  }
  check_budgets(model, uses, path);
  for (const MeshUse& u : uses) emit(u.name, u.mesh, u.world);
  return out;
}

namespace {

using gltf_model::add_view;

int add_accessor(tinygltf::Model& model, int view, int ctype, int type, std::size_t count) {
  tinygltf::Accessor acc;
  acc.bufferView = view;
  acc.componentType = ctype;
  acc.type = type;
  acc.count = count;
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

// A float32 vertex attribute of N components (TINYGLTF_TYPE_VEC`N` given as `type`) from `values` (#V × N doubles).
template <int N, class V>
int add_float_attribute(tinygltf::Model& model, const std::vector<V>& values, int type) {
  std::vector<float> f(values.size() * N);
  for (std::size_t i = 0; i < values.size(); ++i)
    for (int c = 0; c < N; ++c) f[N * i + c] = static_cast<float>(values[i][c]);
  return add_accessor(model, add_view(model, f.data(), f.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                      TINYGLTF_COMPONENT_TYPE_FLOAT, type, values.size());
}

// The node's line strips as LINE_STRIP primitives appended to `mesh`, sharing one unlit material.
void add_line_strips(tinygltf::Model& model, const GltfNode& gn, tinygltf::Mesh& mesh) {
  int material = -1;
  for (const std::vector<glm::vec3>& strip : *gn.line_strips) {
    if (strip.size() < 2) continue;
    std::vector<double> lo(3, std::numeric_limits<double>::infinity()), hi(3, -std::numeric_limits<double>::infinity());
    for (const glm::vec3& p : strip)
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(p[c])) throw MeshIoError("object '" + gn.name + "': a line strip has a non-finite point");
        lo[c] = std::min(lo[c], double(p[c]));
        hi[c] = std::max(hi[c], double(p[c]));
      }
    if (material < 0) {
      const bool has_triangles = !mesh.primitives.empty();
      material = gltf_model::add_material(model, has_triangles ? gn.name + ".lines" : gn.name, gn.color);
      model.materials[material].extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
      if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_materials_unlit") ==
          model.extensionsUsed.end())
        model.extensionsUsed.push_back("KHR_materials_unlit");
    }
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_LINE_STRIP;
    const int pa = add_float_attribute<3>(model, strip, TINYGLTF_TYPE_VEC3);
    model.accessors[pa].minValues = lo;
    model.accessors[pa].maxValues = hi;
    prim.attributes["POSITION"] = pa;
    prim.material = material;
    mesh.primitives.push_back(prim);
  }
}

}  // namespace

void write_glb(const std::filesystem::path& path, const std::vector<GltfNode>& nodes) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "trispline";
  model.buffers.resize(1);
  tinygltf::Scene scene;
  for (const auto& gn : nodes) {
    tinygltf::Node node;
    node.name = gn.name;
    if (gn.mesh && !gn.mesh->empty()) {
      const TriMesh& m = *gn.mesh;
      validate_mesh(m, "object '" + gn.name + "'");
      const std::size_t nv = m.positions.size();
      std::vector<double> lo(3, std::numeric_limits<double>::infinity()),
          hi(3, -std::numeric_limits<double>::infinity());
      for (const glm::dvec3& p : m.positions)
        for (int c = 0; c < 3; ++c) {  // bounds of the float positions written
          lo[c] = std::min(lo[c], double(static_cast<float>(p[c])));
          hi[c] = std::max(hi[c], double(static_cast<float>(p[c])));
        }
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      const int pa = add_float_attribute<3>(model, m.positions, TINYGLTF_TYPE_VEC3);
      model.accessors[pa].minValues = lo;
      model.accessors[pa].maxValues = hi;
      prim.attributes["POSITION"] = pa;
      if (m.normals.size() == nv)
        prim.attributes["NORMAL"] = add_float_attribute<3>(model, m.normals, TINYGLTF_TYPE_VEC3);
      if (m.uvs.size() == nv) prim.attributes["TEXCOORD_0"] = add_float_attribute<2>(model, m.uvs, TINYGLTF_TYPE_VEC2);
      if (!m.face_material.empty() && m.face_material.size() != m.triangles.size())
        throw MeshIoError("object '" + gn.name + "': face_material has " + std::to_string(m.face_material.size()) +
                          " entries for " + std::to_string(m.triangles.size()) + " triangles");
      // Faces of one slot (inside: any non-surface slot), in face order, as a uint32 index accessor.
      const bool two_slots = m.has_inside_faces();
      auto index_accessor = [&](bool inside) {
        std::vector<std::uint32_t> idx;
        idx.reserve(m.triangles.size() * 3);
        for (std::size_t f = 0; f < m.triangles.size(); ++f)
          if (!two_slots || (m.material(f) == kMaterialInside) == inside)
            for (int c = 0; c < 3; ++c) idx.push_back(m.triangles[f][c]);
        if (idx.empty()) return -1;
        return add_accessor(model, add_view(model, idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size());
      };

      tinygltf::Mesh mesh;
      mesh.name = gn.name;
      prim.indices = index_accessor(false);
      if (prim.indices >= 0) {
        prim.material = gltf_model::add_material(model, gn.name, gn.color);
        mesh.primitives.push_back(prim);
      }
      if (two_slots) {  // the cut surfaces: same vertex accessors, their own material
        tinygltf::Primitive inside = prim;
        inside.indices = index_accessor(true);
        inside.material = gltf_model::add_material(model, gn.name + ".inside", gn.inside_color);
        mesh.primitives.push_back(inside);
      }
      if (gn.line_strips) add_line_strips(model, gn, mesh);
      model.meshes.push_back(mesh);
      node.mesh = static_cast<int>(model.meshes.size()) - 1;
    } else if (gn.line_strips) {
      tinygltf::Mesh mesh;
      mesh.name = gn.name;
      add_line_strips(model, gn, mesh);
      if (!mesh.primitives.empty()) {
        model.meshes.push_back(mesh);
        node.mesh = static_cast<int>(model.meshes.size()) - 1;
      }
    }
    model.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  gltf_model::write_glb_atomically(model, path);
}

namespace gltf_model {

int add_view(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
  auto& buf = model.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  buf.insert(buf.end(), p, p + bytes);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int add_material(tinygltf::Model& model, const std::string& name, const glm::vec3& rgb) {
  tinygltf::Material mat;
  mat.name = name;
  mat.pbrMetallicRoughness.baseColorFactor = {rgb.x, rgb.y, rgb.z, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 0.6;
  mat.doubleSided = true;
  model.materials.push_back(mat);
  return static_cast<int>(model.materials.size()) - 1;
}

std::vector<int> root_nodes(const tinygltf::Model& model) {
  std::vector<int> roots;
  if (model.defaultScene >= 0 && model.defaultScene < static_cast<int>(model.scenes.size())) {
    roots = model.scenes[model.defaultScene].nodes;
  } else {
    for (const auto& s : model.scenes) roots.insert(roots.end(), s.nodes.begin(), s.nodes.end());
  }
  if (roots.empty() && model.scenes.empty()) {  // no scene: every node that is nobody's child is a root
    std::vector<char> is_child(model.nodes.size(), 0);
    for (const auto& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && c < static_cast<int>(is_child.size())) is_child[c] = 1;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
  }
  return roots;
}

void write_glb_atomically(tinygltf::Model& model, const std::filesystem::path& path) {
  if (!model.buffers.empty() && model.buffers[0].data.empty()) model.buffers.clear();  // a buffer must not be empty
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw MeshIoError(quoted(path) + ": cannot open '" + tmp.string() + "' for writing");
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/false, /*writeBinary=*/true) || !out.flush())
      throw MeshIoError(quoted(path) + ": writing glb failed");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw MeshIoError(quoted(path) + ": cannot rename temporary file: " + ec.message());
  }
}

}  // namespace gltf_model
}  // namespace trispline::core
