// Internal to trispline_mesh: the checks a PLY file passes before assimp reads it (mesh_precheck.h lists them all).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace trispline::core::precheck {

// A PLY header written back as it was read: `ply`, the format, each element and its properties, `end_header`, one
// line each, lowercase keywords, no comments or free text. `body_offset`: where the body starts in the file.
struct PlyCanonical {
  std::string header;
  std::size_t body_offset = 0;
};

// Checks `text` (the head of a PLY file of `file_size` bytes, or with `whole` all of it) and throws MeshIoError
// naming `path` and what is wrong. The header must follow the PLY grammar (Turk's specification, as assimp's reader
// expects it); with `whole`, the body is walked element by element as the header lays it out. With `canonical`,
// also returns the header written back as read.
void check_ply(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size, bool whole,
               PlyCanonical* canonical = nullptr);

}  // namespace trispline::core::precheck
