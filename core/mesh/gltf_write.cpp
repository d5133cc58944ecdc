// glTF export: write_glb (see gltf_io.h) and the shared model helpers (gltf_model.h).
#include <tiny_gltf.h>  // Debian's shared tinygltf: no configuration macros (see gltf_io.cpp)

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>

#include "core/base/text.h"
#include "core/mesh/gltf_io.h"
#include "core/mesh/gltf_materials.h"
#include "core/mesh/gltf_model.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/path_quote.h"

namespace trispline::core {

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

// The POSITION attribute of `points` (#V × 3, world units) with the bounds glTF requires: min/max of the float32
// values written.
template <class V>
int add_position_attribute(tinygltf::Model& model, const std::vector<V>& points) {
  const int a = add_float_attribute<3>(model, points, TINYGLTF_TYPE_VEC3);
  tinygltf::Accessor& acc = model.accessors[a];
  acc.minValues.assign(3, std::numeric_limits<double>::infinity());
  acc.maxValues.assign(3, -std::numeric_limits<double>::infinity());
  for (const V& p : points)
    for (int c = 0; c < 3; ++c) {
      acc.minValues[c] = std::min(acc.minValues[c], double(static_cast<float>(p[c])));
      acc.maxValues[c] = std::max(acc.maxValues[c], double(static_cast<float>(p[c])));
    }
  return a;
}

// The node's line strips as LINE_STRIP primitives appended to `mesh`, sharing one unlit material.
void add_line_strips(tinygltf::Model& model, const GltfNode& gn, tinygltf::Mesh& mesh) {
  int material = -1;
  for (const std::vector<glm::vec3>& strip : *gn.line_strips) {
    if (strip.size() < 2) continue;
    for (const glm::vec3& p : strip)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw MeshIoError("object '" + gn.name + "': a line strip has a non-finite point");
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
    prim.attributes["POSITION"] = add_position_attribute(model, strip);
    prim.material = material;
    mesh.primitives.push_back(prim);
  }
}

// The vertex attributes (POSITION with min/max, NORMAL, TEXCOORD_0) of `m`'s vertices `ids`, in that order, each
// position through `xf` and each normal through its inverse transpose (renormalised).
tinygltf::Primitive vertex_primitive(tinygltf::Model& model, const TriMesh& m, const std::vector<std::uint32_t>& ids,
                                     const glm::dmat4& xf) {
  const bool identity = xf == glm::dmat4(1.0);
  std::vector<glm::dvec3> pos;
  pos.reserve(ids.size());
  for (std::uint32_t i : ids)
    pos.push_back(identity ? m.positions[i] : glm::dvec3(xf * glm::dvec4(m.positions[i], 1.0)));
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_position_attribute(model, pos);
  if (m.normals.size() == m.positions.size()) {
    const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(xf)));
    std::vector<glm::dvec3> nrm;
    nrm.reserve(ids.size());
    for (std::uint32_t i : ids) {
      glm::dvec3 n = m.normals[i];
      if (!identity) {
        n = nm * n;
        const double len = glm::length(n);
        if (len > 0) n /= len;
      }
      nrm.push_back(n);
    }
    prim.attributes["NORMAL"] = add_float_attribute<3>(model, nrm, TINYGLTF_TYPE_VEC3);
  }
  if (m.uvs.size() == m.positions.size()) {
    std::vector<glm::dvec2> uv;
    uv.reserve(ids.size());
    for (std::uint32_t i : ids) uv.push_back(m.uvs[i]);
    prim.attributes["TEXCOORD_0"] = add_float_attribute<2>(model, uv, TINYGLTF_TYPE_VEC2);
  }
  return prim;
}

// The faces of `faces` (indices into `src`'s vertices, which [first, first + count) holds) as primitives of `mesh`,
// vertices through `xf`. Without materials: one "<name>" primitive of `color`, and "<name>.inside" for the
// kMaterialInside faces, sharing the vertex accessors (as ever). With materials: one primitive per slot used, in the
// order of their first faces, then the inside one; with one slot they share the vertex accessors as above, with several
// each primitive gets the vertices its faces use (in vertex order), as glTF exporters write per-material primitives, so
// a reader gets every material's faces on vertices of their own.
void add_triangle_primitives(tinygltf::Model& model, gltf_materials::GltfMaterialWriter& writer, const GltfNode& gn,
                             const TriMesh& src, std::uint32_t first, std::uint32_t count, const TriMesh& faces,
                             const glm::dmat4& xf, tinygltf::Mesh& mesh) {
  const bool with_materials = gn.materials && !gn.materials->empty();
  // Slots in order of their first face (a file's primitive order comes back), kMaterialInside last.
  std::vector<std::pair<MaterialSlot, std::vector<std::size_t>>> by_slot;
  std::map<MaterialSlot, std::size_t> where;
  std::vector<std::size_t> inside_faces;
  for (std::size_t f = 0; f < faces.triangles.size(); ++f) {
    const MaterialSlot s = faces.material(f);
    if (s == kMaterialInside) {
      inside_faces.push_back(f);
      continue;
    }
    const MaterialSlot slot = with_materials ? s : kMaterialSurface;
    const auto [it, fresh] = where.try_emplace(slot, by_slot.size());
    if (fresh) by_slot.emplace_back(slot, std::vector<std::size_t>());
    by_slot[it->second].second.push_back(f);
  }
  const std::size_t surface_slots = by_slot.size();
  if (!inside_faces.empty()) by_slot.emplace_back(kMaterialInside, std::move(inside_faces));
  const bool shared = surface_slots <= 1;
  tinygltf::Primitive shared_prim;
  if (shared) {
    std::vector<std::uint32_t> ids(count);
    for (std::uint32_t i = 0; i < count; ++i) ids[i] = first + i;
    shared_prim = vertex_primitive(model, src, ids, xf);
  }
  const std::vector<int>* gltf_material = with_materials ? &writer.materials(gn.materials) : nullptr;
  int fallback = -1;  // "<name>" of `color`: without materials, or for slots past the set's end
  for (const auto& [slot, list] : by_slot) {
    tinygltf::Primitive p;
    std::vector<std::uint32_t> idx;
    idx.reserve(list.size() * 3);
    if (shared) {
      p = shared_prim;
      for (std::size_t f : list)
        for (int c = 0; c < 3; ++c) idx.push_back(faces.triangles[f][c] - first);
    } else {
      std::vector<std::uint32_t> ids;
      for (std::size_t f : list)
        for (int c = 0; c < 3; ++c) ids.push_back(faces.triangles[f][c]);
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      for (std::size_t f : list)
        for (int c = 0; c < 3; ++c)
          idx.push_back(static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), faces.triangles[f][c]) -
                                                   ids.begin()));
      p = vertex_primitive(model, src, ids, xf);
    }
    p.indices = gltf_model::add_index_accessor(model, idx);
    if (slot == kMaterialInside) {
      p.material = gn.inside_material && !gn.inside_material->empty()
                       ? writer.materials(gn.inside_material)[0]
                       : gltf_model::add_material(model, gn.name + ".inside", gn.inside_color);
    } else if (gltf_material && slot < gltf_material->size()) {
      p.material = (*gltf_material)[slot];
    } else {
      if (fallback < 0) fallback = gltf_model::add_material(model, gn.name, gn.color);
      p.material = fallback;
    }
    mesh.primitives.push_back(std::move(p));
  }
}

void check_face_material(const GltfNode& gn, const TriMesh& m) {
  if (!m.face_material.empty() && m.face_material.size() != m.triangles.size())
    throw MeshIoError("object '" + gn.name + "': face_material has " + std::to_string(m.face_material.size()) +
                      " entries for " + std::to_string(m.triangles.size()) + " triangles");
}

// The parts cover the rest mesh exactly, in order, each triangle inside its part's vertices, parts of one mesh of
// equal vertex and triangle counts.
bool parts_fit(const GltfNode& gn) {
  if (!gn.parts || gn.parts->empty() || !gn.rest_mesh || gn.rest_mesh->empty()) return false;
  const TriMesh& m = *gn.rest_mesh;
  std::size_t v = 0, t = 0;
  std::map<int, const MeshPart*> first_of;  // instances must have equal counts
  for (const MeshPart& p : *gn.parts) {
    const MeshPart*& first = first_of[p.mesh_index];
    if (!first) first = &p;
    if (first->vertex_count != p.vertex_count || first->triangle_count != p.triangle_count) return false;
    if (p.first_vertex != v || p.first_triangle != t) return false;
    v += p.vertex_count;
    t += p.triangle_count;
    if (v > m.positions.size() || t > m.triangles.size()) return false;
    for (std::size_t f = p.first_triangle; f < t; ++f)
      for (int c = 0; c < 3; ++c)
        if (m.triangles[f][c] < p.first_vertex || m.triangles[f][c] >= v) return false;
    if (std::abs(glm::determinant(glm::dmat3(p.world))) < 1e-300) return false;
  }
  return v == m.positions.size() && t == m.triangles.size();
}

void set_matrix(tinygltf::Node& node, const glm::dmat4& m) {
  if (m == glm::dmat4(1.0)) return;
  node.matrix.resize(16);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) node.matrix[4 * c + r] = m[c][r];
}

// The node "<name>" of `object_to_world` with one child per part (see write_glb).
void add_part_tree(tinygltf::Model& model, gltf_materials::GltfMaterialWriter& writer, const GltfNode& gn, int node) {
  const TriMesh& m = *gn.rest_mesh;
  validate_mesh(m, "object '" + gn.name + "'");
  check_face_material(gn, m);
  set_matrix(model.nodes[node], gn.object_to_world);
  // Instances share the glTF mesh built from the one of largest |det| (the best conditioned inverse: a file may
  // place an instance at a near-zero scale).
  std::map<int, const MeshPart*> source;
  for (const MeshPart& part : *gn.parts) {
    const MeshPart*& best = source[part.mesh_index];
    if (!best ||
        std::abs(glm::determinant(glm::dmat3(part.world))) > std::abs(glm::determinant(glm::dmat3(best->world))))
      best = &part;
  }
  std::map<int, int> mesh_of;  // file mesh index → glTF mesh
  for (const MeshPart& instance : *gn.parts) {
    const MeshPart& part = *source[instance.mesh_index];
    tinygltf::Node child;
    child.name = gn.name + "/" + (instance.name.empty() ? std::to_string(instance.mesh_index) : instance.name);
    set_matrix(child, instance.world);
    const auto known = mesh_of.find(part.mesh_index);
    if (known != mesh_of.end()) {
      child.mesh = known->second;
    } else {
      tinygltf::Mesh mesh;
      mesh.name = child.name;
      TriMesh local;  // the part's triangles, CCW again in the node's own space when its matrix mirrors
      const bool flip = glm::determinant(glm::dmat3(part.world)) < 0;
      for (std::size_t f = part.first_triangle; f < part.first_triangle + part.triangle_count; ++f) {
        glm::uvec3 t = m.triangles[f];
        if (flip) std::swap(t[1], t[2]);
        local.triangles.push_back(t);
        local.face_material.push_back(m.material(f));
      }
      add_triangle_primitives(model, writer, gn, m, part.first_vertex, part.vertex_count, local,
                              glm::inverse(part.world), mesh);
      model.meshes.push_back(mesh);
      child.mesh = static_cast<int>(model.meshes.size()) - 1;
      mesh_of.emplace(part.mesh_index, child.mesh);
    }
    model.nodes.push_back(child);
    model.nodes[node].children.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
}

}  // namespace

void write_glb(const std::filesystem::path& path, const std::vector<GltfNode>& nodes) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "trispline";
  model.buffers.resize(1);
  gltf_materials::GltfMaterialWriter writer(model);
  tinygltf::Scene scene;
  scene.name = "Scene";  // named, so a scene without nodes is still written as an object (tinygltf drops `{}`)
  for (const auto& gn : nodes) {
    tinygltf::Node node;
    node.name = gn.name;
    if (parts_fit(gn)) {  // the node first, its children after it
      model.nodes.push_back(node);
      scene.nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
      add_part_tree(model, writer, gn, scene.nodes.back());
      continue;
    }
    if (gn.mesh && !gn.mesh->empty()) {
      const TriMesh& m = *gn.mesh;
      validate_mesh(m, "object '" + gn.name + "'");
      check_face_material(gn, m);
      tinygltf::Mesh mesh;
      mesh.name = gn.name;
      add_triangle_primitives(model, writer, gn, m, 0, static_cast<std::uint32_t>(m.positions.size()), m,
                              glm::dmat4(1.0), mesh);
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

int add_index_accessor(tinygltf::Model& model, const std::vector<std::uint32_t>& idx) {
  return add_accessor(model, add_view(model, idx.data(), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, idx.size());
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

namespace {

// `text` with every byte that does not start or continue a well-formed UTF-8 sequence (utf8_sequence_length)
// replaced by U+FFFD.
std::string utf8_repaired(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    if (const std::size_t len = utf8_sequence_length(text, i)) {
      out.append(text, i, len);
      i += len;
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

tinygltf::Value utf8_repaired(const tinygltf::Value& v) {
  if (v.IsString()) return tinygltf::Value(utf8_repaired(v.Get<std::string>()));
  if (v.IsArray()) {
    tinygltf::Value::Array a;
    for (std::size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(utf8_repaired(v.Get(static_cast<int>(i))));
    return tinygltf::Value(std::move(a));
  }
  if (v.IsObject()) {
    tinygltf::Value::Object o;
    for (const std::string& key : v.Keys()) o[utf8_repaired(key)] = utf8_repaired(v.Get(key));
    return tinygltf::Value(std::move(o));
  }
  return v;
}

void repair_utf8(tinygltf::ExtensionMap& extensions) {
  tinygltf::ExtensionMap out;
  for (const auto& [key, value] : extensions) out[utf8_repaired(key)] = utf8_repaired(value);
  extensions = std::move(out);
}

template <class Items>
void repair_utf8(Items& items) {
  for (auto& item : items) {
    item.name = utf8_repaired(item.name);
    item.extras = utf8_repaired(item.extras);
    repair_utf8(item.extensions);
  }
}

// Every string of `model` made valid UTF-8. Names come from the user's files (an OBJ group in Latin-1, a piece file
// someone else wrote), and tinygltf's JSON writer (nlohmann::json) throws on invalid UTF-8 where it cannot be caught.
void repair_utf8(tinygltf::Model& model) {
  repair_utf8(model.accessors), repair_utf8(model.animations), repair_utf8(model.buffers);
  repair_utf8(model.bufferViews), repair_utf8(model.materials), repair_utf8(model.meshes), repair_utf8(model.nodes);
  repair_utf8(model.textures), repair_utf8(model.images), repair_utf8(model.skins), repair_utf8(model.samplers);
  repair_utf8(model.cameras), repair_utf8(model.scenes), repair_utf8(model.lights);
  for (tinygltf::Image& image : model.images)
    image.uri = utf8_repaired(image.uri), image.mimeType = utf8_repaired(image.mimeType);
  for (tinygltf::Buffer& buffer : model.buffers) buffer.uri = utf8_repaired(buffer.uri);
  for (tinygltf::Material& m : model.materials) m.alphaMode = utf8_repaired(m.alphaMode);
  for (std::string* text :
       {&model.asset.generator, &model.asset.version, &model.asset.copyright, &model.asset.minVersion})
    *text = utf8_repaired(*text);
  model.asset.extras = utf8_repaired(model.asset.extras);
  model.extras = utf8_repaired(model.extras);
  for (auto* names : {&model.extensionsUsed, &model.extensionsRequired})
    for (std::string& name : *names) name = utf8_repaired(name);
}

}  // namespace

void write_glb_atomically(tinygltf::Model& model, const std::filesystem::path& path) {
  if (!model.buffers.empty() && model.buffers[0].data.empty()) model.buffers.clear();  // a buffer must not be empty
  repair_utf8(model);
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
