// trispline::core names of enumerators and of library codes, looked up in one table instead of a switch per name.
//
//   const char* ddm_layout_name(DdmLayout l) { return enum_name(l, {"rect", "hex", "brick"}, "rect"); }
//   code_name(glGetError(), {{GL_INVALID_ENUM, "GL_INVALID_ENUM"}, ...}, "unknown GL error")
//
// Header only, no dependencies: every room of core/, gpu/, ui/ and editor/ may use it.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <utility>

namespace trispline::core {

// names[i] for the enumerator of value i (an enum whose enumerators are 0, 1, … in the order of `names`; a static
// check at the call is `std::size(names) == count`), `fallback` for any other value.
template <class E, std::size_t N>
constexpr const char* enum_name(E e, const char* const (&names)[N], const char* fallback = "?") {
  const auto i = static_cast<long long>(e);
  return i >= 0 && i < static_cast<long long>(N) ? names[i] : fallback;
}

// The name paired with `code` in `table` (GL and EGL error codes, message sources and the like), `fallback` when no
// entry has it.
template <class T>
constexpr const char* code_name(T code, std::initializer_list<std::pair<T, const char*>> table, const char* fallback) {
  for (const auto& [c, name] : table)
    if (c == code) return name;
  return fallback;
}

}  // namespace trispline::core
