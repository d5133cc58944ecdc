#include "core/mesh/mesh_precheck.h"

#include <iconv.h>

#include <algorithm>
#include <cstring>
#include <string_view>

#include "core/mesh/file_check.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

// Peak bytes of a load per byte of a text file (assimp's parse + its per-corner meshes + our welded double
// TriMesh), measured on real OBJ/OFF/PLY/STL files (docs/decisions.md "Mesh files").
constexpr std::uintmax_t kTextPeakPerByte = 12;
// Peak bytes per value of a PLY file: assimp keeps every value of every element in a DOM node.
constexpr std::uintmax_t kPlyPeakPerValue = 48;

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// A file that is not what its extension says: "cannot parse" (the word every mesh reader's parse error carries).
[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why) {
  throw MeshIoError(quoted(path) + ": cannot parse: " + why);
}
// A well-formed file trispline does not take (over a budget, 4-D).
[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& why) {
  throw MeshIoError(quoted(path) + ": " + why);
}

std::string_view as_text(const std::vector<unsigned char>& bytes) {
  return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
}

void check_no_nul(const std::filesystem::path& path, std::string_view text, std::size_t from, const char* kind) {
  const std::size_t nul = text.find('\0', from);
  if (nul != std::string_view::npos)
    fail(path, std::string("binary data (a NUL byte) at byte ") + std::to_string(nul) + " of a text " + kind +
                   " file (corrupt, or not " + kind + ")");
}

void check_text_budget(const std::filesystem::path& path, std::uintmax_t size, const char* kind) {
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

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::size_t count_tokens(std::string_view s) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.size();) {
    while (i < s.size() && is_space(s[i])) ++i;
    if (i < s.size()) ++n;
    while (i < s.size() && !is_space(s[i])) ++i;
  }
  return n;
}

std::string_view first_token(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size() && is_space(s[i])) ++i;
  std::size_t j = i;
  while (j < s.size() && !is_space(s[j])) ++j;
  return s.substr(i, j - i);
}

void check_obj(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size, bool whole) {
  check_text_budget(path, file_size, "OBJ");
  check_no_nul(path, text, 0, "OBJ");
  if (!whole) return;
  for_each_line(text, [&](long long number, std::string_view line) {
    const std::string_view tag = first_token(line);
    if (tag == "f") {
      const std::size_t corners = count_tokens(line) - 1;
      if (corners < 3)
        fail(path, "line " + std::to_string(number) + ": a face needs at least 3 corners, " + std::to_string(corners) +
                       " given (a line element is written 'l')");
    } else if (tag == "v") {
      const std::size_t coords = count_tokens(line) - 1;
      if (coords < 3)
        fail(path, "line " + std::to_string(number) + ": a vertex needs 3 coordinates, " + std::to_string(coords) +
                       " given (truncated line?)");
    }
  });
}

// Parses a non-negative decimal count; -1 when `s` is not one.
long long parse_count(std::string_view s) {
  if (s.empty() || s.size() > 18) return -1;
  long long n = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return -1;
    n = n * 10 + (c - '0');
  }
  return n;
}

// OFF (Geomview): optional comments, a keyword [ST][C][N][4][n]OFF, optional "BINARY", then NV NF NE.
void check_off(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size) {
  std::vector<std::string_view> tokens;  // the keyword and the three counts, comments skipped
  bool binary = false;
  std::size_t pos = 0;
  while (pos < text.size() && tokens.size() < 4) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(pos, end - pos);
    pos = end + 1;
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    for (std::size_t i = 0; i < line.size() && tokens.size() < 4;) {
      while (i < line.size() && is_space(line[i])) ++i;
      std::size_t j = i;
      while (j < line.size() && !is_space(line[j])) ++j;
      if (j > i) {
        const std::string_view tok = line.substr(i, j - i);
        if (tokens.size() == 1 && tok == "BINARY") {
          binary = true;
        } else {
          tokens.push_back(tok);
        }
      }
      i = j;
    }
    if (binary && tokens.size() == 1) break;  // binary counts follow as int32
  }
  if (!tokens.empty() && parse_count(tokens[0]) >= 0) tokens.insert(tokens.begin(), "OFF");  // keyword is optional
  if (tokens.empty() || tokens[0].size() < 3 || tokens[0].substr(tokens[0].size() - 3) != "OFF")
    fail(path, "no OFF header (the file must start with OFF, COFF, NOFF, STOFF, … or the counts, after comments)");
  const std::string_view key = tokens[0].substr(0, tokens[0].size() - 3);
  if (key.find('4') != std::string_view::npos || key.find('n') != std::string_view::npos)
    refuse(path, "'" + std::string(tokens[0]) + "' is a 4-D or n-D OFF file (a polytope in more than 3 dimensions), " +
                     "not a 3-D mesh");
  if (key.find_first_not_of("STCN") != std::string_view::npos)
    fail(path, "unknown OFF keyword '" + std::string(tokens[0]) + "'");
  if (binary) refuse(path, "binary OFF files are not supported (save as ASCII OFF, PLY or glTF)");
  check_text_budget(path, file_size, "OFF");
  check_no_nul(path, text, 0, "OFF");
  if (tokens.size() < 3) fail(path, "truncated OFF header: vertex and face counts are missing");
  const long long nv = parse_count(tokens[1]), nf = parse_count(tokens[2]);
  if (nv < 0 || nf < 0) fail(path, "bad OFF counts '" + std::string(tokens[1]) + " " + std::string(tokens[2]) + "'");
  // An ASCII vertex takes at least "0 0 0\n" (6 bytes), a face at least "3 0 1 2\n" (8 bytes).
  if (static_cast<unsigned long long>(nv) > file_size / 6 || static_cast<unsigned long long>(nf) > file_size / 8)
    fail(path, "the OFF header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                   " faces, more than a file of " + format_bytes(file_size) + " can hold (truncated or corrupt)");
}

// One PLY element as its header lays it out: per property, a scalar of `size` bytes or a list (a count of
// `count_size` bytes, signed or not, then that many items of `size` bytes).
struct PlyProperty {
  bool list = false;
  bool count_signed = false;
  unsigned long long count_size = 0;
  unsigned long long size = 0;
};
struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> properties;
  std::vector<std::string> property_names;
};

// Names as assimp's PLY reader matches them: without regard to case.
bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
           return lower(x) == lower(y);
         });
}

bool is_signed(std::string_view t) {
  return t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
}

[[noreturn]] void bad_list(const std::filesystem::path& path, const PlyElement& e, unsigned long long index,
                           const std::string& count, unsigned long long room) {
  fail(path, "PLY " + e.name + " " + std::to_string(index) + ": a list of " + count + " items, more than the " +
                 std::to_string(room) + " items left in the file can hold (corrupt or truncated)");
}
[[noreturn]] void short_body(const std::filesystem::path& path, const PlyElement& e, unsigned long long index) {
  fail(path, "the PLY body ends in " + e.name + " " + std::to_string(index) + " of the " + std::to_string(e.count) +
                 " its header declares (truncated)");
}

// Walks an ASCII PLY body as assimp reads it — one element a line (blank lines and `comment` lines skipped), its
// properties' values in order, anything after them on the line ignored — and returns the number of values it holds.
// Every line must hold its element's values, and every list count must be a non-negative integer no larger than the
// values left on its line: assimp resizes a vector by the count before reading the items (a count of -1 read as
// 4294967295, or 3579139413 on a short line, asked for tens of GB).
unsigned long long walk_ply_ascii(const std::filesystem::path& path, std::string_view body,
                                  const std::vector<PlyElement>& layout) {
  std::size_t next_line = 0;
  std::string_view line;  // what is left of the current element's line
  auto token = [&]() -> std::string_view {
    std::size_t i = 0;
    while (i < line.size() && is_space(line[i])) ++i;
    std::size_t j = i;
    while (j < line.size() && !is_space(line[j])) ++j;
    const std::string_view t = line.substr(i, j - i);
    line.remove_prefix(j);
    return t;
  };
  auto bad = [&](const PlyElement& e, unsigned long long i, const std::string& why) {
    fail(path, "PLY " + e.name + " " + std::to_string(i) + ": " + why);
  };
  unsigned long long values = 0;
  for (const PlyElement& e : layout)
    for (unsigned long long i = 0; i < e.count; ++i) {
      line = {};
      while (next_line < body.size()) {
        std::size_t end = body.find_first_of("\r\n", next_line);
        if (end == std::string_view::npos) end = body.size();
        line = body.substr(next_line, end - next_line);
        next_line = end + 1;
        const std::string_view first = first_token(line);
        if (!first.empty() && first != "comment") break;
        line = {};
      }
      if (line.empty()) short_body(path, e, i);
      for (const PlyProperty& p : e.properties) {
        const std::string_view t = token();
        if (t.empty())
          bad(e, i,
              "its line holds fewer values than the element's " + std::to_string(e.properties.size()) + " properties");
        ++values;
        if (!p.list) continue;
        const bool negative = t[0] == '-';
        const std::string_view number = t.substr(negative || t[0] == '+' ? 1 : 0);
        const std::string_view digits =
            number.substr(0, std::min(number.find_first_not_of("0123456789"), number.size()));
        if (digits.empty()) bad(e, i, "list count '" + std::string(t.substr(0, 24)) + "' is not a number");
        if (negative && digits.find_first_not_of('0') != std::string_view::npos)
          bad(e, i, "a list of " + std::string(t.substr(0, 24)) + " items (a count cannot be negative)");
        const std::size_t left = count_tokens(line);
        const long long n = negative ? 0 : parse_count(digits);  // -1: more than 18 digits
        if (n < 0 || static_cast<unsigned long long>(n) > left)
          bad(e, i,
              "a list of " + std::string(digits.substr(0, 24)) + " items, more than the " + std::to_string(left) +
                  " values left on its line (corrupt or truncated)");
        for (long long k = 0; k < n; ++k) token();
        values += static_cast<unsigned long long>(n);
      }
    }
  return values;
}

// Walks a binary PLY body as the header lays it out; returns the number of values it holds. Every list count must be
// non-negative and its items must fit in the bytes left.
unsigned long long walk_ply_binary(const std::filesystem::path& path, std::string_view body,
                                   const std::vector<PlyElement>& layout, const std::string& format) {
  const bool big = format == "binary_big_endian";
  std::size_t at = 0;
  unsigned long long values = 0;
  for (const PlyElement& e : layout) {
    // Elements of scalars only have a fixed size: skip them whole.
    const bool fixed =
        std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.list; });
    if (fixed) {
      unsigned long long size = 0;
      for (const PlyProperty& p : e.properties) size += p.size;
      if (size != 0 && e.count > (body.size() - at) / size) short_body(path, e, (body.size() - at) / size);
      at += static_cast<std::size_t>(size * e.count);
      values += e.count * e.properties.size();
      continue;
    }
    for (unsigned long long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        const std::size_t left = body.size() - at;
        if (left < (p.list ? p.count_size : p.size)) short_body(path, e, i);
        ++values;
        if (!p.list) {
          at += p.size;
          continue;
        }
        unsigned long long raw = 0;
        for (unsigned long long b = 0; b < p.count_size; ++b) {
          const unsigned long long byte = static_cast<unsigned char>(body[at + (big ? b : p.count_size - 1 - b)]);
          raw = (raw << 8) | byte;
        }
        at += p.count_size;
        if (p.count_signed && (raw >> (8 * p.count_size - 1)) != 0)
          fail(path, "PLY " + e.name + " " + std::to_string(i) + ": a list of " +
                         std::to_string(static_cast<long long>(raw) - (1ll << (8 * p.count_size))) +
                         " items (a count cannot be negative)");
        const unsigned long long room = p.size == 0 ? 0 : (body.size() - at) / p.size;
        if (raw > room) bad_list(path, e, i, std::to_string(raw), room);
        at += static_cast<std::size_t>(raw * p.size);
        values += raw;
      }
  }
  return values;
}

// A PLY header written back as it was read: `ply`, the format, each element and its properties, `end_header`, one
// line each, lowercase keywords, no comments or free text. `body_offset`: where the body starts in the file.
struct PlyCanonical {
  std::string header;
  std::size_t body_offset = 0;
};

// The header must follow the PLY grammar line by line (Turk's specification, as assimp's reader expects it): `ply`,
// one `format` before the elements, `element NAME N`, `property TYPE NAME` / `property list T T NAME` after an
// element (each directly after its element's line or another property; blank lines aside), a line that is
// `end_header`; other lines are free text (comments). assimp's reader does not check the
// grammar and reads beyond its buffers on a header it misparses (properties before any element and no end_header
// line crashed it), so those are refused here.
//
// With the whole file (`whole`), the body is walked element by element as the header lays it out (walk_ply_body), so
// a list whose count the body cannot hold is refused before assimp sizes a vector by it.
void check_ply(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size, bool whole,
               PlyCanonical* canonical = nullptr) {
  if (text.substr(0, 3) != "ply") fail(path, "not a PLY file (no 'ply' magic)");
  std::size_t header_end = std::string_view::npos;  // offset of the line "end_header"
  for (std::size_t at = text.find("\nend_header"); at != std::string_view::npos;
       at = text.find("\nend_header", at + 1)) {
    std::size_t e = at + 11;
    while (e < text.size() && (text[e] == ' ' || text[e] == '\t' || text[e] == '\r')) ++e;
    if (e < text.size() && text[e] == '\n') {  // a line of its own, ended by a line break (the body follows)
      header_end = at + 1;
      break;
    }
  }
  if (header_end == std::string_view::npos)
    fail(path, "incomplete PLY header (no end_header line ended by a line break in its first " +
                   format_bytes(kMeshHeadBytes) + ")");
  const std::string_view header = text.substr(0, header_end);
  // The header is ASCII text: assimp's line reader looped forever on a header holding control characters.
  for (std::size_t i = 0; i < header.size(); ++i) {
    const auto c = static_cast<unsigned char>(header[i]);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t')
      fail(path, "PLY header holds a control character (0x" + std::string(1, "0123456789abcdef"[c >> 4]) +
                     std::string(1, "0123456789abcdef"[c & 15]) + ") at byte " + std::to_string(i));
  }
  std::string format;
  unsigned long long total_values = 0, total_elements = 0;
  long long count = 0;
  // Binary body size the header describes: at least min_body bytes, at most max_body (unbounded with a 4-byte list
  // count). Element sizes are summed per element, then multiplied by its count (saturating).
  unsigned long long min_body = 0, max_body = 0, element_min = 0, element_max = 0;
  bool bounded = true;
  auto saturating = [](unsigned long long a, unsigned long long b) { return b != 0 && a > ~0ull / b ? ~0ull : a * b; };
  auto close_element = [&] {
    min_body += saturating(element_min, static_cast<unsigned long long>(count));
    max_body += saturating(element_max, static_cast<unsigned long long>(count));
    element_min = element_max = 0;
  };
  auto type_size = [&](std::string_view t) -> unsigned long long {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    fail(path, "unknown PLY property type '" + std::string(t) + "'");
  };
  bool has_element = false;
  bool in_properties = false;  // the previous line (blank lines aside) was an element or a property
  std::string declarations;    // the format, element and property lines, one space between words
  std::vector<PlyElement> layout;
  for_each_line(header, [&](long long number, std::string_view line) {
    const std::string_view tag = first_token(line);
    std::vector<std::string_view> words;
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && is_space(line[i])) ++i;
      std::size_t j = i;
      while (j < line.size() && !is_space(line[j])) ++j;
      if (j > i) words.push_back(line.substr(i, j - i));
      i = j;
    }
    auto bad_line = [&](const char* why) {
      fail(path,
           "bad PLY header line " + std::to_string(number) + " '" + std::string(line.substr(0, 80)) + "': " + why);
    };
    // assimp matches some keywords without regard to case: one written in another case would be a property to assimp
    // and free text here, so the two would read different layouts.
    std::string lower(tag);
    for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    if (lower != tag)
      for (const char* keyword : {"ply", "format", "element", "property", "comment", "obj_info", "end_header"})
        if (lower == keyword) bad_line("header keywords are lowercase");
    if (number == 1) {
      if (words.size() != 1 || words[0] != "ply") bad_line("the first line must be 'ply'");
    } else if (tag == "format") {
      if (words.size() != 3 || !format.empty() || has_element)
        bad_line("one 'format TYPE VERSION' before the elements");
      format = std::string(words[1]);
      declarations += "format " + format + " " + std::string(words[2]) + "\n";
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        fail(path, "unknown PLY format '" + format + "'");
    } else if (tag == "element") {
      if (words.size() != 3) bad_line("expected 'element NAME COUNT'");
      has_element = true;
      close_element();
      count = words.size() >= 3 ? parse_count(words[2]) : -1;
      if (count < 0)
        fail(path, "bad PLY element count '" + std::string(words.size() >= 3 ? words[2] : "") + "' for " +
                       std::string(words.size() >= 2 ? words[1] : "?"));
      total_elements += static_cast<unsigned long long>(count);
      // assimp fills one array per element kind: a second "face" element wrote past the first one's faces.
      for (const PlyElement& e : layout)
        if (same_name(e.name, words[1])) bad_line("an element of this name is already declared");
      layout.push_back({std::string(words[1]), static_cast<unsigned long long>(count), {}, {}});
      declarations += "element " + std::string(words[1]) + " " + std::to_string(count) + "\n";
    } else if (tag == "property") {
      if (!layout.empty() && words.size() >= 3)
        for (const std::string& name : layout.back().property_names)
          if (same_name(name, words.back())) bad_line("a property of this name is already declared in this element");
      // A list is at least its count; with a face's 3 corners, 4 values.
      const bool list = words.size() >= 2 && words[1] == "list";
      if (!has_element) bad_line("a property before any element");
      // assimp reads a list where it expects a vertex coordinate (or a scalar where it expects a face's corners) as
      // something else: a vertex element with a list 'x' loaded 2 vertices of 3.
      if (!layout.empty() && same_name(layout.back().name, "vertex") && list)
        bad_line("a vertex property cannot be a list");
      if (!layout.empty() && !list && words.size() == 3 &&
          (same_name(words[2], "vertex_indices") || same_name(words[2], "vertex_index")))
        bad_line("a face's vertex indices must be a list");
      if (!in_properties)
        bad_line(
            "a property must follow its element's line or another property (assimp's reader ends an element's "
            "properties at the first other line, a comment too, and would misread the body)");
      if (words.size() != (list ? 5u : 3u))
        bad_line(list ? "expected 'property list COUNT_TYPE ITEM_TYPE NAME'" : "expected 'property TYPE NAME'");
      total_values += (list ? 4 : 1) * static_cast<unsigned long long>(count);
      if (list && words.size() >= 4) {
        if (words[2] == "float" || words[2] == "float32" || words[2] == "double" || words[2] == "float64")
          bad_line("a list's count type must be an integer type");
        const unsigned long long count_size = type_size(words[2]), item = type_size(words[3]);
        element_min += count_size;
        if (count_size >= 4) bounded = false;
        element_max += count_size + item * ((1ull << (8 * count_size)) - 1);
        layout.back().properties.push_back({true, is_signed(words[2]), count_size, item});
        layout.back().property_names.emplace_back(words[4]);
        declarations +=
            "property list " + std::string(words[2]) + " " + std::string(words[3]) + " " + std::string(words[4]) + "\n";
      } else if (!list && words.size() >= 2) {
        element_min += type_size(words[1]);
        element_max += type_size(words[1]);
        layout.back().properties.push_back({false, false, 0, type_size(words[1])});
        layout.back().property_names.emplace_back(words[2]);
        declarations += "property " + std::string(words[1]) + " " + std::string(words[2]) + "\n";
      }
    }
    // Any other line is free text, as in assimp's reader: Blender 2.47 wrote a bare "Created by Blender3D …" line.
    if (!words.empty()) in_properties = tag == "element" || tag == "property";
  });
  close_element();
  if (format.empty()) fail(path, "incomplete PLY header (no format line)");
  const std::uintmax_t body = file_size - header_end;
  // Every element takes at least one byte of the body: a larger count is a corrupt or truncated header.
  if (total_elements > body)
    fail(path, "PLY element counts (" + std::to_string(total_elements) + " elements) exceed what a body of " +
                   format_bytes(body) + " can hold (truncated or corrupt)");
  if (total_values > kMeshLoadMemoryBudget / kPlyPeakPerValue)
    refuse(path, "a PLY file of " + std::to_string(total_values) + " values would need about " +
                     format_bytes(total_values * kPlyPeakPerValue) + " to load, over the " +
                     format_bytes(kMeshLoadMemoryBudget) + " memory budget");
  if (format != "ascii") {
    const std::size_t eol = text.find('\n', header_end);  // the body starts after end_header's line break
    const std::uintmax_t data = eol == std::string_view::npos ? 0 : file_size - (eol + 1);
    if (data < min_body)
      fail(path, "binary PLY body of " + std::to_string(data) + " bytes is shorter than the " +
                     std::to_string(min_body) + " its header describes (truncated)");
    // Bytes past what the header can describe are not mesh data: refuse rather than read them (a 2 GB sparse file
    // with a 3-vertex header). A little slack for trailing line breaks some writers add.
    if (bounded && data > max_body + 4096)
      fail(path, "binary PLY body of " + format_bytes(data) + " is longer than its header can describe (at most " +
                     format_bytes(max_body) + ")");
  } else {
    check_text_budget(path, file_size, "PLY");
    check_no_nul(path, text, header_end, "PLY");
  }
  // A mesh needs an element "vertex" with x, y and z and a face (or triangle strip) element with its vertex indices.
  // assimp reads a file without them in ways of its own (a header whose vertex element was misspelt took 11 GB).
  auto find_element = [&](std::initializer_list<const char*> names) -> const PlyElement* {
    for (const PlyElement& e : layout)
      for (const char* n : names)
        if (e.name == n) return &e;
    return nullptr;
  };
  auto has_property = [](const PlyElement& e, std::initializer_list<const char*> names) {
    for (const std::string& p : e.property_names)
      for (const char* n : names)
        if (p == n) return true;
    return false;
  };
  const PlyElement* vertex = find_element({"vertex"});
  if (!vertex || !has_property(*vertex, {"x"}) || !has_property(*vertex, {"y"}) || !has_property(*vertex, {"z"}))
    fail(path, "the PLY header declares no element 'vertex' with properties x, y and z");
  const PlyElement* face = find_element({"face", "tristrips"});
  if (!face || !has_property(*face, {"vertex_indices", "vertex_index"}))
    refuse(path,
           "empty mesh (no triangles): the PLY header declares no element 'face' with vertex_indices (a point "
           "cloud?)");
  if (canonical) {
    const std::size_t eol = text.find('\n', header_end);
    canonical->header = "ply\n" + declarations + "end_header\n";
    canonical->body_offset = eol == std::string_view::npos ? text.size() : eol + 1;
  }
  if (!whole) return;
  const std::size_t eol = text.find('\n', header_end);
  const std::string_view data = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
  const unsigned long long values =
      format == "ascii" ? walk_ply_ascii(path, data, layout) : walk_ply_binary(path, data, layout, format);
  if (values > kMeshLoadMemoryBudget / kPlyPeakPerValue)
    refuse(path, "a PLY file of " + std::to_string(values) + " values would need about " +
                     format_bytes(values * kPlyPeakPerValue) + " to load, over the " +
                     format_bytes(kMeshLoadMemoryBudget) + " memory budget");
}

// Binary STL is 84 + 50·n bytes; anything else must be ASCII ("solid").
void check_stl(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size) {
  check_text_budget(path, file_size, "STL");  // binary STL costs about as much per byte as text (50 bytes a triangle)
  if (text.size() >= 84) {
    std::uint32_t n = 0;
    for (int i = 0; i < 4; ++i) n |= static_cast<std::uint32_t>(static_cast<unsigned char>(text[80 + i])) << (8 * i);
    if (file_size == 84 + 50ull * n) return;
  }
  if (text.substr(0, 5) != "solid")
    fail(path, "neither ASCII STL (starting 'solid') nor a binary STL whose size matches its triangle count");
  check_no_nul(path, text, 0, "STL");
}

// Text in UTF-16/32 with a byte order mark → UTF-8, through glibc's iconv (the BOM picks the byte order).
std::vector<unsigned char> to_utf8(const std::filesystem::path& path, std::vector<unsigned char>& in,
                                   const char* from) {
  const iconv_t cd = ::iconv_open("UTF-8", from);
  if (cd == reinterpret_cast<iconv_t>(-1)) fail(path, std::string("cannot convert ") + from + " text to UTF-8");
  std::vector<unsigned char> out(in.size() * 2 + 16);  // UTF-16 → UTF-8 at most 1.5×; UTF-32 shrinks
  char* src = reinterpret_cast<char*>(in.data());
  char* dst = reinterpret_cast<char*>(out.data());
  std::size_t src_left = in.size(), dst_left = out.size();
  const std::size_t r = ::iconv(cd, &src, &src_left, &dst, &dst_left);
  ::iconv_close(cd);
  if (r == static_cast<std::size_t>(-1))
    fail(path, std::string("invalid ") + from + " text at byte " + std::to_string(in.size() - src_left));
  out.resize(out.size() - dst_left);
  return out;
}

bool starts_with(const std::vector<unsigned char>& b, std::initializer_list<unsigned char> magic) {
  return b.size() >= magic.size() && std::equal(magic.begin(), magic.end(), b.begin());
}

}  // namespace

void prepare_mesh_bytes(const std::filesystem::path& path, const std::string& ext, std::vector<unsigned char>& bytes) {
  if (ext == ".stl") return;  // binary STL may start with any bytes; ASCII STL is plain ASCII
  const bool utf32 = starts_with(bytes, {0xFF, 0xFE, 0x00, 0x00}) || starts_with(bytes, {0x00, 0x00, 0xFE, 0xFF});
  const bool utf16 = !utf32 && (starts_with(bytes, {0xFF, 0xFE}) || starts_with(bytes, {0xFE, 0xFF}));
  if (utf16 || utf32) bytes = to_utf8(path, bytes, utf32 ? "UTF-32" : "UTF-16");
  if (starts_with(bytes, {0xEF, 0xBB, 0xBF})) bytes.erase(bytes.begin(), bytes.begin() + 3);
  if (ext == ".ply") {
    // assimp is handed the header as check_ply read it, so the two cannot read different layouts: assimp's header
    // reader ends an element at a comment, matches keywords in any case and loops on some free text, and the body walk
    // (the list counts checked against the bytes) is only as good as the layout they share.
    PlyCanonical canonical;
    check_ply(path, as_text(bytes), bytes.size(), false, &canonical);
    std::vector<unsigned char> out(canonical.header.begin(), canonical.header.end());
    out.insert(out.end(), bytes.begin() + static_cast<std::ptrdiff_t>(canonical.body_offset), bytes.end());
    bytes = std::move(out);
    return;
  }
  if (ext == ".off") {  // binary OFF is refused by precheck_mesh_file; its header has no comment to remove
    std::size_t out = 0;
    bool comment = false;
    for (const unsigned char c : bytes) {
      if (c == '\n' || c == '\r')
        comment = false;
      else if (c == '#')
        comment = true;
      if (!comment) bytes[out++] = c;
    }
    bytes.resize(out);
    // The keyword is optional, but assimp reads a leading 4 / C / N / ST / n as a keyword prefix even without "OFF":
    // a header "4 1 20…" would be read as a 4-D file of 1 vertex and 20… faces. With the keyword written, assimp
    // reads the counts check_off checked.
    std::size_t first = 0;
    while (first < bytes.size() && (is_space(static_cast<char>(bytes[first])) || bytes[first] == '\n')) ++first;
    if (first < bytes.size() && bytes[first] >= '0' && bytes[first] <= '9') {
      static constexpr std::string_view kKeyword = "OFF\n";
      bytes.insert(bytes.begin(), kKeyword.begin(), kKeyword.end());
    }
  }
}

void precheck_mesh_head(const std::filesystem::path& path, const std::string& ext,
                        const std::vector<unsigned char>& head, std::uintmax_t file_size) {
  if (file_size == 0) fail(path, "empty file");
  if (starts_with(head, {0xFF, 0xFE}) || starts_with(head, {0xFE, 0xFF}) || starts_with(head, {0x00, 0x00, 0xFE, 0xFF}))
    return;  // UTF-16/32 text: checked once converted (precheck_mesh_file)
  const std::string_view text = as_text(head);
  if (ext == ".obj") check_obj(path, text, file_size, false);
  if (ext == ".off") check_off(path, text, file_size);
  if (ext == ".ply") check_ply(path, text, file_size, false);
  if (ext == ".stl") check_stl(path, text, file_size);
}

void precheck_mesh_file(const std::filesystem::path& path, const std::string& ext,
                        const std::vector<unsigned char>& bytes) {
  const std::string_view text = as_text(bytes);
  if (text.empty()) fail(path, "empty file");
  if (ext == ".obj") check_obj(path, text, text.size(), true);
  if (ext == ".off") check_off(path, text, text.size());
  if (ext == ".ply") check_ply(path, text, text.size(), true);
  if (ext == ".stl") check_stl(path, text, text.size());
}

}  // namespace trispline::core
