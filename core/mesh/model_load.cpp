// Model files with materials and parts. See model_load.h.
#include "core/mesh/model_load.h"

#include <algorithm>
#include <cstdio>
#include <set>

#include "core/mesh/assimp_io.h"
#include "core/mesh/file_check.h"
#include "core/mesh/gltf_io.h"

namespace trispline::core {
namespace {

namespace fs = std::filesystem;

bool inside(const fs::path& p, const fs::path& folder) {
  const fs::path rel = p.lexically_relative(folder);
  return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

// Part names made unique as Blender names objects: a second "bottle" becomes "bottle.001" (a Collada rack names
// every instance of a bottle alike; exported nodes are `<object>/<part>` and importers key objects by name). A
// name no later part holds is taken; an empty name becomes "part".
void make_part_names_unique(std::vector<MeshPart>& parts) {
  std::set<std::string> original, used;
  for (const MeshPart& p : parts) original.insert(p.name.empty() ? "part" : p.name);
  for (MeshPart& p : parts) {
    if (p.name.empty()) p.name = "part";
    if (used.insert(p.name).second) continue;
    for (int k = 1;; ++k) {
      char suffix[16];
      std::snprintf(suffix, sizeof suffix, ".%03d", k);
      const std::string candidate = p.name + suffix;
      if (!original.count(candidate) && used.insert(candidate).second) {
        p.name = candidate;
        break;
      }
    }
  }
}

}  // namespace

std::vector<std::string> LoadedModel::texture_errors() const {
  std::vector<std::string> out;
  if (!materials) return out;
  for (const auto& image : materials->images)
    if (image && !image->error.empty())
      out.push_back((image->uri.empty() ? image->name : image->uri) + ": " + image->error);
  return out;
}

std::vector<unsigned char> read_model_side_file(const fs::path& model, const std::string& relative,
                                                std::uintmax_t max_bytes) {
  std::string rel = relative;
  std::replace(rel.begin(), rel.end(), '\\', '/');  // files written on Windows
  const std::string label = "'" + relative + "'";
  if (rel.find('\0') != std::string::npos) throw MeshIoError(label + ": contains a NUL byte");
  if (rel.empty()) throw MeshIoError(label + ": empty file name");
  if (rel[0] == '/' || (rel.size() > 1 && rel[1] == ':'))
    throw MeshIoError(label + ": is an absolute path; a model may refer only to files in its own folder or below");
  if (rel.find("://") != std::string::npos)
    throw MeshIoError(label + ": is a URL; a model may refer only to files in its own folder or below");
  try {
    const fs::path folder = fs::weakly_canonical(fs::absolute(model).parent_path());
    const fs::path resolved = fs::weakly_canonical(folder / rel);
    if (!inside(resolved, folder))
      throw MeshIoError(label + ": resolves to '" + resolved.string() + "', outside the folder '" + folder.string() +
                        "' of the model (only files in that folder or below are read)");
    return read_input_file(resolved, max_bytes, "files a model refers to");
  } catch (const fs::filesystem_error& e) {
    throw MeshIoError(label + ": " + e.code().message());
  }
}

std::size_t finish_loaded_mesh(TriMesh& mesh, std::vector<MeshPart>& parts, const std::string& what) {
  validate_mesh(mesh, what);
  std::vector<glm::uvec3> before;
  if (!parts.empty()) before = mesh.triangles;
  const std::size_t removed = remove_duplicate_triangles(mesh);
  if (removed && !parts.empty()) {
    // The kept triangles are a subsequence of `before` (the first copy stays): walk both to count each part's.
    std::size_t k = 0;
    std::uint32_t kept_before = 0;
    for (MeshPart& part : parts) {
      std::uint32_t kept = 0;
      for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t)
        if (k < mesh.triangles.size() && mesh.triangles[k] == before[t]) ++k, ++kept;
      part.first_triangle = kept_before;
      part.triangle_count = kept;
      kept_before += kept;
    }
  }
  make_part_names_unique(parts);
  if (mesh.normals.empty()) compute_vertex_normals(mesh);
  return removed;
}

LoadedModel load_model(const fs::path& path, const MeshLoadOptions& options, MeshLoadReport* report) {
  const std::string ext = lower_extension(path);
  MeshLoadReport local;
  MeshLoadReport& r = report ? *report : local;
  LoadedModel out;
  if (ext != ".gltf" && ext != ".glb" && !is_assimp_extension(ext)) {  // the refusals of unknown extensions
    out.mesh = load_mesh(path, options, &r);
    return out;
  }
  r = {};
  auto take = [&out](auto&& model) {  // GltfModel or AssimpModel: the same four members
    out.mesh = std::move(model.mesh);
    out.materials = std::move(model.materials);
    out.parts = std::move(model.parts);
    out.warnings = std::move(model.warnings);
  };
  if (ext == ".gltf" || ext == ".glb") {  // tinygltf (gltf_io.h read_gltf_model): materials, images, parts
    r.loader = "tinygltf";
    take(read_gltf_model(path));
  } else {
    take(read_assimp_file(path, ext, options, r, true));
  }
  r.duplicate_faces = finish_loaded_mesh(out.mesh, out.parts, "'" + path.string() + "'");
  r.faces = out.mesh.triangles.size();
  return out;
}

}  // namespace trispline::core
