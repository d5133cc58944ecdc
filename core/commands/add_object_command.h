// trispline::core::AddObjectCommand — the base of commands that add one object (scene.load, scene.primitive): the
// object's name (made unique from default_name() when the line has none; the logged line then carries the name it
// got), transform and colour (codecs.h ObjectFields), and the vertex / triangle counts for report.json.
#pragma once

#include <optional>

#include "core/commands/snapshot_command.h"
#include "core/params/codecs.h"

namespace trispline::core {

class AddObjectCommand : public SnapshotCommand {
 public:
  nlohmann::json stats() const override { return {{"vertices", vertices_}, {"triangles", triangles_}}; }

 protected:
  // The name, transform and colour in the derived command's params.
  virtual ObjectFields& object_fields() = 0;
  // The rest mesh of the new object (object space, with normals). May throw (reported as CommandError).
  virtual TriMesh make_mesh() const = 0;
  virtual std::string default_name() const = 0;  // used when the line has no "name"
  virtual std::string source() const = 0;        // SceneObject::source
  std::string target() const override { return const_cast<AddObjectCommand*>(this)->object_fields().name; }
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  std::size_t vertices_ = 0, triangles_ = 0;
};

}  // namespace trispline::core
