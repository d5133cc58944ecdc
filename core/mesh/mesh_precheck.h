// Internal to trispline_mesh: checks done on a mesh file before OpenMesh reads it, because OpenMesh's readers do not
// check face indices (OBJ, OFF), loop forever or allocate without bound on some corrupt headers (PLY), and accept
// truncated binary STL as an empty mesh.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace trispline::core {

// Throws MeshIoError ("cannot parse ..." or "vertex index out of range ...") for `path` with lower-case extension
// `ext` (.obj .off .ply .stl). Returns the file's text with '#' comments removed when it is an ASCII OFF file that
// has comments (OpenMesh's OFF reader does not skip them); std::nullopt otherwise.
std::optional<std::string> precheck_mesh_file(const std::filesystem::path& path, const std::string& ext);

}  // namespace trispline::core
