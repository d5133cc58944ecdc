// trispline::core text helpers for names and file extensions (ASCII case folding: file extensions, MIME types, GL
// renderer strings and command names are ASCII) and UTF-8 well-formedness (log lines, names written to glTF).
//
// Header only, no dependencies beyond the standard library: every room of core/, gpu/, ui/ and editor/ may use it.
#pragma once

#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

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

// printf-style formatting into a std::string (libstdc++ 12 has no std::format): numbers in names and messages.
[[gnu::format(printf, 1, 2)]] inline std::string printf_string(const char* format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string out(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(out.data(), out.size() + 1, format, again);
  va_end(again);
  return out;
}

// UTF-8 (The Unicode Standard §3.9, Table 3-7 "Well-Formed UTF-8 Byte Sequences"; RFC 3629): for the lead bytes
// first…last, the sequence's length in bytes and the range of its second byte; every later byte is 80…BF. This is
// what rules out overlong forms, surrogates and code points above U+10FFFF.
struct Utf8Lead {
  unsigned char first, last, length, second_lo, second_hi;
};
inline constexpr Utf8Lead kUtf8Leads[] = {
    {0x00, 0x7F, 1, 0x80, 0xBF}, {0xC2, 0xDF, 2, 0x80, 0xBF}, {0xE0, 0xE0, 3, 0xA0, 0xBF},
    {0xE1, 0xEC, 3, 0x80, 0xBF}, {0xED, 0xED, 3, 0x80, 0x9F}, {0xEE, 0xEF, 3, 0x80, 0xBF},
    {0xF0, 0xF0, 4, 0x90, 0xBF}, {0xF1, 0xF3, 4, 0x80, 0xBF}, {0xF4, 0xF4, 4, 0x80, 0x8F}};

// The length of a well-formed sequence that starts with byte `lead`; 0 when no sequence starts with it (80…C1,
// F5…FF).
inline int utf8_lead_length(unsigned char lead) {
  for (const Utf8Lead& l : kUtf8Leads)
    if (lead >= l.first && lead <= l.last) return l.length;
  return 0;
}

// The length in bytes of the well-formed UTF-8 sequence that starts at text[i] (i < text.size()); 0 when the bytes
// there are not one (a bad lead byte, a bad continuation byte, or the text ends inside the sequence).
inline std::size_t utf8_sequence_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
  for (const Utf8Lead& l : kUtf8Leads) {
    if (byte(0) < l.first || byte(0) > l.last) continue;
    if (i + l.length > text.size()) return 0;
    if (l.length > 1 && (byte(1) < l.second_lo || byte(1) > l.second_hi)) return 0;
    for (std::size_t k = 2; k < l.length; ++k)
      if ((byte(k) & 0xC0) != 0x80) return 0;
    return l.length;
  }
  return 0;
}

}  // namespace trispline::core
