// Internal to trispline_mesh: what an OBJ (and its MTL), PLY, OFF, STL, Collada or FBX file must satisfy before assimp
// parses it.
//
// assimp reads every well-formed file of these formats, but it trusts counts in headers (a PLY or OFF header that
// claims 10⁹ vertices in a 100-byte file is allocated, not refused), keeps a PLY in a DOM of ~40 bytes a value, and
// reads a text file full of NUL bytes (a sparse file) to the end. These checks refuse such files by their size and
// header alone, naming the file and what is wrong; a file that passes is parsed once, by assimp.
//
//   * text formats (OBJ, ASCII OFF / PLY / STL): no NUL byte (the offset of the first one is named);
//   * OBJ: every 'f' line has at least 3 corners (a 2-corner face is malformed, not a line: 'l' is);
//   * OFF: a 3-D header ("OFF", "COFF", "NOFF", "STOFF", …; 4OFF / nOFF are 4-D or n-D polytopes, refused), counts
//     that the file's size can hold; with the whole file, every face line holding its corner count's indices;
//   * PLY: magic, the header grammar, known format, element counts the file's size can hold, and assimp's DOM within
//     the memory budget; with the whole file, the body walked as assimp reads it (ASCII: an element a line; binary:
//     byte by byte), every list count non-negative and within what is left of its line or of the body;
//   * STL: binary (84 + 50·n bytes exactly) or ASCII ("solid").
//   * Collada: text (no NUL byte) within the text budget, starting with '<' (XML); FBX: binary ("Kaydara FBX
//     Binary") or ASCII FBX, within the text budget (assimp's FBX DOM costs about as much per byte).
//   * MTL (check_mtl_text): text, every statement after a `newmtl` (assimp 5.2's MTL reader writes a statement before
//     the first `newmtl` through a null material), rewritten one statement a line with the keywords trispline maps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace trispline::core {

// Peak memory a mesh load may reach, estimated from the file before parsing: 3 GiB (the hostile-input bound is 4 GB;
// a real 10 M-triangle scan stays far below).
inline constexpr std::uintmax_t kMeshLoadMemoryBudget = std::uintmax_t(3) << 30;
// The head of a file read for precheck_mesh_head (PLY and OFF headers, STL's triangle count, the first NUL bytes).
inline constexpr std::size_t kMeshHeadBytes = 64 * 1024;

// Checks what the head of a file (its first kMeshHeadBytes, or all of a smaller file) and its size in bytes tell,
// before the whole file is read: the memory budget from the size (text formats, binary STL), PLY and OFF header
// counts against the size, STL's size against its triangle count, no NUL byte in a text head. Throws MeshIoError.
// Text with a UTF-16/32 byte order mark is left to precheck_mesh_file.
void precheck_mesh_head(const std::filesystem::path& path, const std::string& ext,
                        const std::vector<unsigned char>& head, std::uintmax_t file_size);

// Rewrites `bytes` (the whole file, extension `ext`) into what assimp reads fully: text with a UTF-16/32 byte order
// mark becomes UTF-8 (glibc iconv; assimp 5.2's own conversion loses every face of a UTF-16 BE file) and a UTF-8 byte
// order mark is dropped; OFF comments ('#' to the end of a line, which the OFF format allows anywhere and assimp's
// reader skips only before the header) are removed; an OBJ's `mtllib` lines become comments (no material library is
// ever read, or with `mtllibs` the first one names kServedMtlName and the names are collected); a PLY file is checked
// whole and written back as check_ply walked it (its header one line per format, element and property; only the mesh's
// elements; the ASCII body one element a line), so assimp reads the layout and values the walk checked. Throws
// MeshIoError on invalid UTF-16/32 or a PLY file check_ply refuses.
void prepare_mesh_bytes(const std::filesystem::path& path, const std::string& ext, std::vector<unsigned char>& bytes,
                        std::vector<std::string>* mtllibs = nullptr);

// The one material library name assimp is given for an OBJ read with materials: the checked MTL files, joined.
inline constexpr const char* kServedMtlName = "materials.mtl";

// Largest MTL file, bytes.
inline constexpr std::uintmax_t kMaxMtlFileBytes = std::uintmax_t(64) << 20;

// `text` (an MTL file named `mtl`) as assimp is given it: one statement a line, keyword and arguments separated by
// one space, comments and statements trispline does not map dropped. Throws MeshIoError "'MTL': cannot parse: line
// 3: 'Kd' before any newmtl" / "… binary data (a NUL byte) …".
std::string check_mtl_text(const std::filesystem::path& mtl, std::string_view text);

// Throws MeshIoError "'PATH': <reason>" when `bytes` (the whole file, after prepare_mesh_bytes) is not acceptable for
// extension `ext` (".obj" ".off" ".stl"; a PLY file was checked whole by prepare_mesh_bytes).
void precheck_mesh_file(const std::filesystem::path& path, const std::string& ext,
                        const std::vector<unsigned char>& bytes);

}  // namespace trispline::core
