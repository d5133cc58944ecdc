// Internal to trispline_mesh: the checks a PLY file passes before assimp reads it (mesh_precheck.h lists them all).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace trispline::core::precheck {

// Checks `text` (the head of a PLY file of `file_size` bytes, or with `whole` all of it) and throws MeshIoError
// naming `path` and what is wrong. The header must follow the PLY grammar (Turk's specification, as assimp's reader
// expects it); with `whole`, the body is walked element by element as the header lays it out, every ASCII value must
// be a whole number of its property's type, and with `canonical` the file is also written back as walked, with only
// the elements a mesh is read from (`vertex`, `face`, `tristrips`; others are checked, then left out): the header
// (`ply`, the format, each such element and its properties, one line each, lowercase keywords, no comments or free
// text), then the body (binary: those elements' bytes; ASCII: one line per element, its values one space apart).
// assimp reads that, so it reads the layout and the values checked here.
void check_ply(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size, bool whole,
               std::string* canonical = nullptr);

}  // namespace trispline::core::precheck
