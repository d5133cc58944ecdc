// Internal to core/mesh: a path as the loaders' and writers' messages quote it ('/path/to/file').
#pragma once

#include <filesystem>
#include <string>

namespace trispline::core {

inline std::string quoted(const std::filesystem::path& p) {
  std::string q(1, '\'');  // appended piecewise: GCC 12 warns (-Wrestrict, false positive) on "'" + s
  q += p.string();
  q += '\'';
  return q;
}

}  // namespace trispline::core
