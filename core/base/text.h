// trispline::core text helpers for names and file extensions (ASCII case folding: file extensions, MIME types, GL
// renderer strings and command names are ASCII).
//
// Header only, no dependencies beyond the standard library: every room of core/, gpu/, ui/ and editor/ may use it.
#pragma once

#include <filesystem>
#include <string>

namespace trispline::core {

// `s` with A–Z turned to a–z; other bytes (UTF-8 included) unchanged.
inline std::string ascii_lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

// The extension of `path` in lower case, with its dot (".ply"); "" when it has none.
inline std::string lower_extension(const std::filesystem::path& path) { return ascii_lower(path.extension().string()); }

// Whether `path`'s file name ends with `extension` (lower case, with its dot), ignoring case.
inline bool has_extension(const std::filesystem::path& path, const std::string& extension) {
  return ascii_lower(path.filename().string()).ends_with(extension);
}

}  // namespace trispline::core
