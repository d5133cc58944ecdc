// Internal to trispline_mesh: the text helpers the mesh file checks share (mesh_precheck.cpp, ply_precheck.cpp) —
// the two kinds of refusal, line and token scanning, the text budgets.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/file_check.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/mesh_precheck.h"
#include "core/mesh/path_quote.h"

namespace trispline::core::precheck {

// Peak bytes of a load per byte of a text file (assimp's parse + its per-corner meshes + our welded double
// TriMesh), measured on real OBJ/OFF/PLY/STL files (docs/decisions.md "Mesh files").
inline constexpr std::uintmax_t kTextPeakPerByte = 12;
// Peak bytes per value of a PLY file: assimp keeps every value of every element in a DOM node.
inline constexpr std::uintmax_t kPlyPeakPerValue = 48;

using trispline::core::quoted;

// A file that is not what its extension says: "cannot parse" (the word every mesh reader's parse error carries).
[[noreturn]] inline void fail(const std::filesystem::path& path, const std::string& why) {
  throw MeshIoError(quoted(path) + ": cannot parse: " + why);
}
// A well-formed file trispline does not take (over a budget, 4-D).
[[noreturn]] inline void refuse(const std::filesystem::path& path, const std::string& why) {
  throw MeshIoError(quoted(path) + ": " + why);
}

inline std::string_view as_text(const std::vector<unsigned char>& bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

inline void check_no_nul(const std::filesystem::path& path, std::string_view text, std::size_t from, const char* kind) {
  const std::size_t nul = text.find('\0', from);
  if (nul != std::string_view::npos)
    fail(path, std::string("binary data (a NUL byte) at byte ") + std::to_string(nul) + " of a text " + kind +
                   " file (corrupt, or not " + kind + ")");
}

inline void check_text_budget(const std::filesystem::path& path, std::uintmax_t size, const char* kind) {
  if (size > kMeshLoadMemoryBudget / kTextPeakPerByte)
    refuse(path, std::string("a text ") + kind + " file of " + format_bytes(size) + " would need about " +
                     format_bytes(size * kTextPeakPerByte) + " to load, over the " +
                     format_bytes(kMeshLoadMemoryBudget) + " memory budget (save it as binary PLY or glTF)");
}

// Splits text into lines (without '\n' / '\r').
template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t start = 0;
  long long number = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    f(++number, line);
    start = end + 1;
  }
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Takes the next token off the front of `s` (tokens are separated by characters for which `separator` holds) and
// returns it; empty when `s` holds no more.
template <class Separator = bool (*)(char)>
std::string_view next_token(std::string_view& s, Separator separator = is_space) {
  std::size_t i = 0;
  while (i < s.size() && separator(s[i])) ++i;
  std::size_t j = i;
  while (j < s.size() && !separator(s[j])) ++j;
  const std::string_view token = s.substr(i, j - i);
  s.remove_prefix(j);
  return token;
}

template <class Separator = bool (*)(char)>
std::size_t count_tokens(std::string_view s, Separator separator = is_space) {
  std::size_t n = 0;
  while (!next_token(s, separator).empty()) ++n;
  return n;
}

inline std::string_view first_token(std::string_view s) { return next_token(s); }

// The words of a line (split at spaces and tabs).
inline std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> words;
  for (std::string_view w = next_token(line); !w.empty(); w = next_token(line)) words.push_back(w);
  return words;
}

// Parses a non-negative decimal count; -1 when `s` is not one.
inline long long parse_count(std::string_view s) {
  if (s.empty() || s.size() > 18) return -1;
  long long n = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return -1;
    n = n * 10 + (c - '0');
  }
  return n;
}

}  // namespace trispline::core::precheck
