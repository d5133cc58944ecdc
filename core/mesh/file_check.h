// trispline::core mesh files — what a path must be before a mesh reader spends anything on it.
//
//   kMaxMeshFileBytes   byte budget of one mesh file (a mesh file, a glTF file, one external glTF buffer)
//   check_input_file    the path is a regular file (symlinks followed) of at most max_bytes; MeshIoError otherwise
//   read_input_file     the same checks on the opened descriptor (no race between check and read), then its bytes
//
// A FIFO or a character device (/dev/zero) never ends and a directory reads as nothing, so they are refused by what
// they are, before any parser sees them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace trispline::core {

// 2 GiB: the largest real meshes the editor handles (tens of millions of triangles) are far smaller; tinygltf and
// OpenMesh hold the whole file in memory, and a loaded TriMesh costs several times its file size.
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(2) << 30;

// Throws MeshIoError unless `path` names (after following symlinks) a regular file of at most `max_bytes` bytes.
// `what` names the kind of file in the size message (e.g. "mesh files"). Messages:
//   "'PATH': file not found"
//   "'PATH': is a directory"
//   "'PATH': is a character device, not a regular file"   (likewise FIFO, block device, socket)
//   "'PATH': 3.2 GiB (3435973837 bytes) is over the 2 GiB limit for mesh files"
//   "'PATH': cannot access: <strerror>"                     (permission denied, symlink loop, …)
void check_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& what);

// Opens `path` without blocking, applies check_input_file's checks to the opened descriptor (fstat), then reads the
// whole file. Throws MeshIoError as check_input_file, plus "'PATH': cannot read: <strerror>" and "'PATH': grew past
// the … limit for <what> while being read".
std::vector<unsigned char> read_input_file(const std::filesystem::path& path, std::uintmax_t max_bytes,
                                           const std::string& what);

// "2 GiB", "512 MiB", "1.5 KiB", "17 bytes": a byte count for messages (binary units, at most one decimal).
std::string format_bytes(std::uintmax_t bytes);

}  // namespace trispline::core
