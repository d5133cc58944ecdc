#include "core/commands/snapshot_command.h"

namespace trispline::core {

std::filesystem::path CommandContext::resolve(const std::string& path) const {
  const std::filesystem::path p(path);
  return p.is_absolute() || base_dir.empty() ? p : base_dir / p;
}

std::filesystem::path CommandContext::resolve_output(const std::string& path, const char* field) const {
  namespace fs = std::filesystem;
  const auto refuse = [&](const std::string& why) {
    throw CommandError(std::string("field '") + field + "': " + why, field);
  };
  if (path.empty()) refuse("must not be empty");
  for (const char c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) refuse("an output path must not hold control characters");
  const fs::path p(path);
  if (p.is_absolute())
    refuse("'" + path +
           "' is absolute: a log writes only under its output folder (replay's --out, the scene's "
           "folder), so an output path is relative to it");
  std::error_code ec;
  const fs::path& dir = output_dir.empty() ? base_dir : output_dir;
  const fs::path root = fs::weakly_canonical(fs::absolute(dir.empty() ? fs::path(".") : dir, ec), ec);
  if (ec) refuse("the output folder '" + dir.string() + "' cannot be resolved: " + ec.message());
  const fs::path target = fs::weakly_canonical(root / p, ec);
  if (ec) refuse("'" + path + "' cannot be resolved: " + ec.message());
  // Component by component: "/out2/x" is not under "/out".
  auto t = target.begin();
  for (auto r = root.begin(); r != root.end() && !r->empty(); ++r, ++t)
    if (t == target.end() || *t != *r)
      refuse("'" + path + "' leaves the output folder '" + root.string() + "' (it resolves to '" + target.string() +
             "'): a log writes only under its output folder");
  if (t == target.end() || target.filename().empty() || fs::is_directory(target, ec))
    refuse("'" + path + "' names a folder, not a file");
  // weakly_canonical follows the links that lead somewhere; a link left in the result dangles, and a write through
  // it would create its target wherever it points.
  fs::path prefix = root;
  for (; t != target.end(); ++t)
    if (prefix /= *t; fs::is_symlink(fs::symlink_status(prefix, ec)))
      refuse("'" + path + "' goes through the dangling symlink '" + prefix.string() +
             "': a log writes only under its "
             "output folder");
  return target;
}

const SceneObject& require_object(const Scene& scene, const std::string& name, const char* field) {
  const SceneObject* o = scene.find(name);
  if (!o) throw CommandError("field '" + std::string(field) + "': no object named '" + name + "'", field);
  return *o;
}

const SceneObject& require_deformed_object(const Scene& scene, const std::string& name) {
  const SceneObject* o = &require_object(scene, name);
  if (!o->ffd)
    throw CommandError(
        "field 'object': '" + name + "' has no FFD lattice (place it with place.sketch or lattice.ring first)",
        "object");
  return *o;
}

std::vector<glm::dvec3> positions_with_tile_layers(const SceneObject& object, const TriMesh& world_rest) {
  std::vector<glm::dvec3> out = world_rest.positions;
  const glm::dmat4 m = object.transform.matrix();
  for (const auto& layer : object.ddm_layers)
    if (layer && layer->mesh)
      for (const glm::dvec3& p : layer->mesh->positions) out.push_back(glm::dvec3(m * glm::dvec4(p, 1.0)));
  return out;
}

void require_no_tile_layers(const SceneObject& object, const std::string& change) {
  if (object.ddm_layers.empty()) return;
  std::string names;
  for (const auto& layer : object.ddm_layers) names += (names.empty() ? "" : ", ") + layer->name;
  throw CommandError("field 'object': '" + object.name + "' holds tile layers (" + names +
                         ") laid on its current mesh, which " + change +
                         " would replace; bake them (ddm.bake) or remove them (ddm.remove) first",
                     "object");
}

}  // namespace trispline::core
