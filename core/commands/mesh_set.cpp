#include "core/commands/mesh_set.h"

#include <cmath>

#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

// A log line's array of triples, checked; `index_limit` > 0: integer indices below it (faces).
template <class V>
std::vector<V> triples(const nlohmann::json& line, const char* field, std::size_t index_limit) {
  const auto it = line.find(field);
  if (it == line.end() || !it->is_array() || it->empty())
    throw CommandError(std::string("field '") + field + "': a non-empty array of [a, b, c] is required", field);
  std::vector<V> out;
  out.reserve(it->size());
  for (const nlohmann::json& t : *it) {
    if (!t.is_array() || t.size() != 3)
      throw CommandError(std::string("field '") + field + "': every entry must be [a, b, c]", field);
    V v{};
    for (int c = 0; c < 3; ++c) {
      if (!t[c].is_number()) throw CommandError(std::string("field '") + field + "': not a number", field);
      const double x = t[c].get<double>();
      if (index_limit > 0) {
        if (!t[c].is_number_integer() || x < 0 || x >= double(index_limit))
          throw CommandError(std::string("field '") + field + "': " + t[c].dump() + " is not a vertex index in [0, " +
                                 std::to_string(index_limit) + ")",
                             field);
      } else if (!std::isfinite(x)) {
        throw CommandError(std::string("field '") + field + "': not finite", field);
      }
      v[c] = static_cast<typename V::value_type>(x);
    }
    out.push_back(v);
  }
  return out;
}

}  // namespace

MeshSetCommand::MeshSetCommand(std::string object, TriMesh mesh) : object_(std::move(object)) {
  mesh.normals.clear();
  mesh.uvs.clear();
  mesh.face_material.clear();
  compute_vertex_normals(mesh);
  mesh_ = std::make_shared<const TriMesh>(std::move(mesh));
}

CommandPtr MeshSetCommand::parse(const nlohmann::json& line) {
  const auto obj = line.find("object");
  if (obj == line.end() || !obj->is_string() || obj->get<std::string>().empty())
    throw CommandError("field 'object': an object name is required", "object");
  for (auto it = line.begin(); it != line.end(); ++it)
    if (it.key() != "cmd" && it.key() != "object" && it.key() != "vertices" && it.key() != "faces")
      throw CommandError("field '" + it.key() + "': unknown field of mesh.set", it.key());
  TriMesh mesh;
  mesh.positions = triples<glm::dvec3>(line, "vertices", 0);
  mesh.triangles = triples<glm::uvec3>(line, "faces", mesh.positions.size());
  return std::make_unique<MeshSetCommand>(obj->get<std::string>(), std::move(mesh));
}

nlohmann::json MeshSetCommand::to_json() const {
  nlohmann::json v = nlohmann::json::array(), f = nlohmann::json::array();
  for (const glm::dvec3& p : mesh_->positions) v.push_back({p.x, p.y, p.z});
  for (const glm::uvec3& t : mesh_->triangles) f.push_back({t.x, t.y, t.z});
  return {{"cmd", kId}, {"object", object_}, {"vertices", std::move(v)}, {"faces", std::move(f)}};
}

std::string MeshSetCommand::label() const {
  return "Set the mesh of '" + object_ + "' (" + std::to_string(mesh_->vertex_count()) + " vertices)";
}

std::optional<SceneObject> MeshSetCommand::build(const Scene& scene) {
  const SceneObject& object = require_object(scene, object_);
  require_no_tile_layers(object, "mesh.set");
  const char* bound = object.ffd     ? "an FFD lattice"
                      : object.dffd  ? "a DFFD split"
                      : object.clip  ? "a glTF clip"
                      : object.morph ? "a morph channel"
                                     : nullptr;
  if (bound)
    throw CommandError(
        "field 'object': '" + object_ + "' has " + bound + " bound to its vertices; set its mesh before deforming it",
        "object");
  const TriMesh& before = *object.rest_mesh;
  std::shared_ptr<const TriMesh> mesh = mesh_;
  const bool keep_uvs = !before.uvs.empty() && before.vertex_count() == mesh_->vertex_count();
  const bool keep_materials = !before.face_material.empty() && before.triangle_count() == mesh_->triangle_count();
  if (keep_uvs || keep_materials) {
    auto copy = std::make_shared<TriMesh>(*mesh_);
    if (keep_uvs) copy->uvs = before.uvs;
    if (keep_materials) copy->face_material = before.face_material;
    mesh = std::move(copy);
  }
  SceneObject out = object;
  out.rest_mesh = std::move(mesh);
  if (!keep_materials) out.parts.clear();
  out.refresh();
  stats_ = {{"vertices_before", before.vertex_count()},
            {"vertices_after", out.rest_mesh->vertex_count()},
            {"triangles_before", before.triangle_count()},
            {"triangles_after", out.rest_mesh->triangle_count()}};
  return out;
}

}  // namespace trispline::core
