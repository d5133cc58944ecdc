#include "core/mesh/gltf_io.h"

#include "core/mesh/mesh_io.h"
#include "core/mesh/path_quote.h"

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

#include "core/mesh/gltf_materials.h"
#include "core/mesh/gltf_model.h"
#include "core/mesh/gltf_read.h"

namespace trispline::core {
namespace {

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

GltfFile read_gltf_file(const std::filesystem::path& path, bool materials) {
  const tinygltf::Model model = gltf_read::read_model(path);  // checked: indices in range, nodes a forest
  gltf_materials::ReadMaterials mats;
  if (materials) {
    mats = gltf_materials::read_gltf_materials(model, path);
  } else {  // the legacy slots: "*.inside" materials → kMaterialInside, every other → kMaterialSurface
    for (const tinygltf::Material& m : model.materials) mats.slot.push_back(ends_with(m.name, ".inside") ? -1 : 0);
  }
  int default_slot = -1;  // the glTF default material, appended for the first primitive without one

  GltfFile file;
  std::vector<GltfObject>& out = file.objects;
  Totals totals;
  auto emit = [&](const std::string& name, int mesh_index, const glm::dmat4& xf) {
    if (mesh_index < 0 || mesh_index >= static_cast<int>(model.meshes.size()))
      throw MeshIoError(quoted(path) + ": node refers to a missing mesh");
    const auto& gm = model.meshes[mesh_index];
    GltfObject obj;
    obj.name = name.empty() ? gm.name : name;
    obj.mesh_index = mesh_index;
    obj.world = xf;
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
      MaterialSlot slot = kMaterialInside;
      if (!inside && mat >= 0) {
        slot = static_cast<MaterialSlot>(mats.slot[mat]);
      } else if (!inside && added > 0) {
        if (default_slot < 0) {
          if (mats.set.materials.size() >= kMaxMaterialsPerMesh)
            throw MeshIoError(quoted(path) + ": more materials than the " + std::to_string(kMaxMaterialsPerMesh) +
                              " an object may have");
          default_slot = static_cast<int>(mats.set.materials.size());
          mats.set.materials.push_back(gltf_materials::default_material());
        }
        slot = static_cast<MaterialSlot>(default_slot);
      }
      slots.insert(slots.end(), added, slot);
      any_inside = any_inside || (inside && added > 0);
      if (inside && mat >= 0) obj.inside_color = base_color(model.materials[mat], obj.inside_color);
      if (!inside && color_material < 0) color_material = mat;
    }
    // A mesh of points or lines only (e.g. a volume's silhouettes in scene.glb) is no surface object.
    if (obj.mesh.triangles.empty() && obj.mesh.positions.empty()) return;
    if (!normals_ok) obj.mesh.normals.clear();
    // All slot 0 is what an empty face_material says.
    if (std::any_of(slots.begin(), slots.end(), [](MaterialSlot m) { return m != kMaterialSurface; }))
      obj.mesh.face_material = std::move(slots);
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
  // Only the materials of a file that names some (other than write_glb's "*.inside") make a MaterialSet.
  const bool named = materials && std::any_of(mats.slot.begin(), mats.slot.end(), [](int s) { return s >= 0; });
  if (named) {
    file.materials = std::make_shared<const MaterialSet>(std::move(mats.set));
    file.warnings = std::move(mats.warnings);
  } else {
    for (GltfObject& o : out)  // default-material slots of a file without materials: slot 0, the object colour
      for (MaterialSlot& m : o.mesh.face_material)
        if (m != kMaterialInside) m = kMaterialSurface;
  }
  return file;
}

std::vector<GltfObject> read_gltf_objects(const std::filesystem::path& path) {
  return read_gltf_file(path, /*materials=*/false).objects;
}

GltfModel read_gltf_model(const std::filesystem::path& path) {
  GltfFile file = read_gltf_file(path, /*materials=*/true);
  GltfModel out;
  TriMesh& mesh = out.mesh;
  bool all_normals = true, any_uvs = false, any_slots = false;
  for (const auto& obj : file.objects) {
    all_normals = all_normals && !obj.mesh.normals.empty();
    any_uvs = any_uvs || !obj.mesh.uvs.empty();
    any_slots = any_slots || !obj.mesh.face_material.empty();
  }
  for (const auto& obj : file.objects) {
    MeshPart part;
    part.name = obj.name;
    part.mesh_index = obj.mesh_index;
    part.world = obj.world;
    part.first_vertex = static_cast<std::uint32_t>(mesh.positions.size());
    part.vertex_count = static_cast<std::uint32_t>(obj.mesh.positions.size());
    part.first_triangle = static_cast<std::uint32_t>(mesh.triangles.size());
    part.triangle_count = static_cast<std::uint32_t>(obj.mesh.triangles.size());
    mesh.positions.insert(mesh.positions.end(), obj.mesh.positions.begin(), obj.mesh.positions.end());
    if (all_normals) mesh.normals.insert(mesh.normals.end(), obj.mesh.normals.begin(), obj.mesh.normals.end());
    if (any_uvs) {
      mesh.uvs.insert(mesh.uvs.end(), obj.mesh.uvs.begin(), obj.mesh.uvs.end());
      mesh.uvs.resize(mesh.positions.size(), glm::dvec2(0.0));  // nodes without TEXCOORD_0 get (0,0)
    }
    for (const auto& t : obj.mesh.triangles) mesh.triangles.push_back(t + glm::uvec3(part.first_vertex));
    if (any_slots) {
      if (obj.mesh.face_material.empty())
        mesh.face_material.resize(mesh.triangles.size(), kMaterialSurface);
      else
        mesh.face_material.insert(mesh.face_material.end(), obj.mesh.face_material.begin(),
                                  obj.mesh.face_material.end());
    }
    out.parts.push_back(std::move(part));
  }
  if (out.parts.size() < 2) out.parts.clear();
  out.materials = std::move(file.materials);
  out.warnings = std::move(file.warnings);
  return out;
}

}  // namespace trispline::core
