// trispline::core::AddObjectCommand — base of the commands that add one new object (scene.load,
// scene.primitive): shared fields name / translate / rotate_deg / scale / color, the unique-name rule and the
// vertex/triangle stats. Subclasses only say where the mesh comes from.
#pragma once

#include <optional>

#include "core/commands/snapshot_command.h"

namespace trispline::core {

class AddObjectCommand : public SnapshotCommand {
 public:
  nlohmann::json stats() const override { return {{"vertices", vertices_}, {"triangles", triangles_}}; }

 protected:
  // Reads name, translate, rotate_deg, scale and color from j (all optional).
  void parse_object_fields(const nlohmann::json& j);
  // Writes them into j.
  void put_object_fields(nlohmann::json& j) const;

  // The rest mesh of the new object (object space, with normals). May throw (reported as CommandError).
  virtual TriMesh make_mesh() const = 0;
  virtual std::string default_name() const = 0;  // used when the line has no "name"
  virtual std::string source() const = 0;        // SceneObject::source

  std::string target() const override { return name_; }
  std::optional<SceneObject> build(const Scene& scene) override;

  std::string name_;

 private:
  Transform transform_;
  std::optional<glm::dvec3> color_;
  std::size_t vertices_ = 0, triangles_ = 0;
};

}  // namespace trispline::core
