#include "core/mesh/ply_precheck.h"

#include <algorithm>
#include <vector>

#include "core/mesh/precheck_text.h"

namespace trispline::core::precheck {
namespace {

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

// The header must follow the PLY grammar line by line (Turk's specification, as assimp's reader expects it): `ply`,
// one `format` before the elements, `element NAME N`, `property TYPE NAME` / `property list T T NAME` after an
// element (each directly after its element's line or another property; blank lines aside), a line that is
// `end_header`; other lines are free text (comments). assimp's reader does not check the
// grammar and reads beyond its buffers on a header it misparses (properties before any element and no end_header
// line crashed it), so those are refused here.
//
// With the whole file (`whole`), the body is walked element by element as the header lays it out (walk_ply_ascii,
// walk_ply_binary), so a list whose count the body cannot hold is refused before assimp sizes a vector by it.
}  // namespace

void check_ply(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size, bool whole,
               PlyCanonical* canonical) {
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
    const std::vector<std::string_view> words = split_words(line);
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

}  // namespace trispline::core::precheck
