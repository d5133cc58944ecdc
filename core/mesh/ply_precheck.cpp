#include "core/mesh/ply_precheck.h"

#include <algorithm>
#include <vector>

#include "core/mesh/precheck_text.h"

namespace trispline::core::precheck {
namespace {

// How a value of a PLY type is written in an ASCII body (and read by assimp: strtoul10, strtol10, fast_atoreal_move).
enum class PlyKind { kUnsigned, kSigned, kReal };

// One PLY element as its header lays it out: per property, a scalar of `size` bytes or a list (a count of
// `count_size` bytes, signed or not, then that many items of `size` bytes). `declaration`: the property's header
// line as written back (lowercase keywords, one space between words).
struct PlyProperty {
  bool list = false;
  bool count_signed = false;
  unsigned long long count_size = 0;
  unsigned long long size = 0;
  PlyKind count_kind = PlyKind::kUnsigned;
  PlyKind kind = PlyKind::kReal;
  std::string declaration;
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
PlyKind kind_of(std::string_view t) {
  if (t == "float" || t == "float32" || t == "double" || t == "float64") return PlyKind::kReal;
  return is_signed(t) ? PlyKind::kSigned : PlyKind::kUnsigned;
}

bool all_digits(std::string_view s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string_view::npos;
}

// Whether `t` is a whole number of its kind, read to its last character by assimp's number parser: an unsigned
// integer is digits only (strtoul10 takes no sign), a signed one may carry a sign, a real is
// [+-]digits[.digits][e[+-]digits] (or .digits…) or nan / inf / infinity. Anything else (`1,5`, `5-111`, `1.0` for
// an integer) would leave characters that assimp then reads as the next value, and the two readings part ways.
bool is_ply_number(std::string_view t, PlyKind kind) {
  if (kind == PlyKind::kUnsigned) return all_digits(t);
  if (!t.empty() && (t[0] == '-' || t[0] == '+')) t.remove_prefix(1);
  if (kind == PlyKind::kSigned) return all_digits(t);
  if (same_name(t, "nan") || same_name(t, "inf") || same_name(t, "infinity")) return true;
  const std::size_t e = t.find_first_of("eE");
  if (e != std::string_view::npos) {
    std::string_view exponent = t.substr(e + 1);
    if (!exponent.empty() && (exponent[0] == '-' || exponent[0] == '+')) exponent.remove_prefix(1);
    if (!all_digits(exponent)) return false;
    t = t.substr(0, e);
  }
  const std::size_t dot = t.find('.');
  if (dot == std::string_view::npos) return all_digits(t);
  const std::string_view whole = t.substr(0, dot), fraction = t.substr(dot + 1);
  if (whole.empty()) return all_digits(fraction);                          // ".5"
  return all_digits(whole) && (fraction.empty() || all_digits(fraction));  // "1." and "1.5"
}

const char* kind_name(PlyKind kind) {
  return kind == PlyKind::kUnsigned ? "an unsigned integer" : kind == PlyKind::kSigned ? "an integer" : "a number";
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

// The elements written back for assimp: the ones a mesh is read from (`vertex`, `face`, `tristrips`), with their
// properties. Any other element is walked and checked, then left out: assimp does not skip an element it has no use
// for by its declared size (binary or ASCII, the face after an extra element was read from that element's data, a
// count of -20818 as 4294946478 corners, 34 GB: CI's fuzzer).
bool written_back(const PlyElement& e) {
  return !e.properties.empty() && (e.name == "vertex" || e.name == "face" || e.name == "tristrips");
}

// Walks an ASCII PLY body — one element a line (blank lines and `comment` lines skipped), its properties' values in
// order, anything after them on the line ignored — and returns the number of values it holds. With `out`, appends the
// body written back as walked: one line per element (written_back ones), its values one space apart, nothing else;
// assimp is handed that
// text, so its line and value boundaries are the ones checked here (it splits values by parsing numbers, not at
// spaces, and a face read from a line another reading took for a vertex once asked for 34 GB).
// Every value must be a whole number of its property's kind (is_ply_number), and every list count a non-negative
// integer no larger than the values left on its line: assimp resizes a vector by the count before reading the items.
unsigned long long walk_ply_ascii(const std::filesystem::path& path, std::string_view body,
                                  const std::vector<PlyElement>& layout, std::string* out) {
  // assimp's reader separates values by spaces and tabs only (any other character is part of a value, and refused).
  auto separator = [](char c) { return c == ' ' || c == '\t'; };
  std::size_t next_line = 0;
  std::string_view line;  // what is left of the current element's line
  auto token = [&] { return next_token(line, separator); };
  auto tokens_left = [&] { return count_tokens(line, separator); };
  auto bad = [&](const PlyElement& e, unsigned long long i, const std::string& why) {
    fail(path, "PLY " + e.name + " " + std::to_string(i) + ": " + why);
  };
  std::string* sink = nullptr;  // `out` while walking an element written back
  auto value = [&](const PlyElement& e, unsigned long long i, PlyKind kind, bool first) {
    const std::string_view t = token();
    if (t.empty())
      bad(e, i,
          "its line holds fewer values than the element's " + std::to_string(e.properties.size()) + " properties");
    if (!is_ply_number(t, kind)) bad(e, i, "'" + std::string(t.substr(0, 24)) + "' is not " + kind_name(kind));
    if (sink) {
      if (!first) sink->push_back(' ');
      sink->append(t);
    }
    return t;
  };
  unsigned long long values = 0;
  for (const PlyElement& e : layout) {
    sink = out && written_back(e) ? out : nullptr;
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
      bool first = true;
      for (const PlyProperty& p : e.properties) {
        ++values;
        if (!p.list) {
          value(e, i, p.kind, first);
          first = false;
          continue;
        }
        const std::string_view t = value(e, i, p.count_kind, first);
        first = false;
        const bool negative = t[0] == '-';
        const std::string_view digits = t.substr(negative || t[0] == '+' ? 1 : 0);
        if (negative && digits.find_first_not_of('0') != std::string_view::npos)
          bad(e, i, "a list of " + std::string(t.substr(0, 24)) + " items (a count cannot be negative)");
        const std::size_t left = tokens_left();
        const long long n = negative ? 0 : parse_count(digits);  // -1: more than 18 digits
        if (n < 0 || static_cast<unsigned long long>(n) > left)
          bad(e, i,
              "a list of " + std::string(digits.substr(0, 24)) + " items, more than the " + std::to_string(left) +
                  " values left on its line (corrupt or truncated)");
        for (long long k = 0; k < n; ++k) value(e, i, p.kind, false);
        values += static_cast<unsigned long long>(n);
      }
      if (sink) sink->push_back('\n');
    }
  }
  return values;
}

// Walks a binary PLY body as the header lays it out; returns the number of values it holds. Every list count must be
// non-negative and its items must fit in the bytes left.
// With `out`, appends the bytes of the elements written back (written_back; anything after the last element is
// not read).
unsigned long long walk_ply_binary(const std::filesystem::path& path, std::string_view body,
                                   const std::vector<PlyElement>& layout, const std::string& format, std::string* out) {
  const bool big = format == "binary_big_endian";
  std::size_t at = 0;
  unsigned long long values = 0;
  for (const PlyElement& e : layout) {
    const std::size_t start = at;
    const auto keep = [&] {
      if (out && written_back(e)) out->append(body.substr(start, at - start));
    };
    // Elements of scalars only have a fixed size: skip them whole.
    const bool fixed =
        std::none_of(e.properties.begin(), e.properties.end(), [](const PlyProperty& p) { return p.list; });
    if (fixed) {
      unsigned long long size = 0;
      for (const PlyProperty& p : e.properties) size += p.size;
      if (size != 0 && e.count > (body.size() - at) / size) short_body(path, e, (body.size() - at) / size);
      at += static_cast<std::size_t>(size * e.count);
      values += e.count * e.properties.size();
      keep();
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
    keep();
  }
  return values;
}

// Offset of the header's line "end_header" (one of its own, ended by a line break: the body follows).
std::size_t ply_header_end(const std::filesystem::path& path, std::string_view text) {
  for (std::size_t at = text.find("\nend_header"); at != std::string_view::npos;
       at = text.find("\nend_header", at + 1)) {
    std::size_t e = at + 11;
    while (e < text.size() && (text[e] == ' ' || text[e] == '\t' || text[e] == '\r')) ++e;
    if (e < text.size() && text[e] == '\n') return at + 1;
  }
  fail(path, "incomplete PLY header (no end_header line ended by a line break in its first " +
                 format_bytes(kMeshHeadBytes) + ")");
}

// The header is ASCII text: assimp's line reader looped forever on a header holding control characters.
void check_no_control_characters(const std::filesystem::path& path, std::string_view header) {
  for (std::size_t i = 0; i < header.size(); ++i) {
    const auto c = static_cast<unsigned char>(header[i]);
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t')
      fail(path, "PLY header holds a control character (0x" + std::string(1, "0123456789abcdef"[c >> 4]) +
                     std::string(1, "0123456789abcdef"[c & 15]) + ") at byte " + std::to_string(i));
  }
}

// The header's grammar, line by line (see check_ply), and what it declares.
struct PlyHeader {
  const std::filesystem::path& path;
  std::string format;
  unsigned long long total_values = 0, total_elements = 0;
  long long count = 0;  // of the current element
  // Binary body size the header describes: at least min_body bytes, at most max_body (unbounded with a 4-byte list
  // count). Element sizes are summed per element, then multiplied by its count (saturating).
  unsigned long long min_body = 0, max_body = 0, element_min = 0, element_max = 0;
  bool bounded = true;
  bool has_element = false;
  bool in_properties = false;  // the previous line (blank lines aside) was an element or a property
  std::vector<PlyElement> layout;

  explicit PlyHeader(const std::filesystem::path& file) : path(file) {}
  static unsigned long long saturating(unsigned long long a, unsigned long long b) {
    return b != 0 && a > ~0ull / b ? ~0ull : a * b;
  }
  void close_element() {
    min_body += saturating(element_min, static_cast<unsigned long long>(count));
    max_body += saturating(element_max, static_cast<unsigned long long>(count));
    element_min = element_max = 0;
  }
  unsigned long long type_size(std::string_view t) const {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    fail(path, "unknown PLY property type '" + std::string(t) + "'");
  }
  [[noreturn]] void bad_line(long long number, std::string_view line, const char* why) const {
    fail(path, "bad PLY header line " + std::to_string(number) + " '" + std::string(line.substr(0, 80)) + "': " + why);
  }
  void read_line(long long number, std::string_view line);
  void element_line(long long number, std::string_view line, const std::vector<std::string_view>& words);
  void property_line(long long number, std::string_view line, const std::vector<std::string_view>& words);
};

void PlyHeader::read_line(long long number, std::string_view line) {
  const std::string_view tag = first_token(line);
  const std::vector<std::string_view> words = split_words(line);
  // assimp matches some keywords without regard to case: one written in another case would be a property to assimp
  // and free text here, so the two would read different layouts.
  std::string lower(tag);
  for (char& c : lower) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  if (lower != tag)
    for (const char* keyword : {"ply", "format", "element", "property", "comment", "obj_info", "end_header"})
      if (lower == keyword) bad_line(number, line, "header keywords are lowercase");
  if (number == 1) {
    if (words.size() != 1 || words[0] != "ply") bad_line(number, line, "the first line must be 'ply'");
  } else if (tag == "format") {
    if (words.size() != 3 || !format.empty() || has_element)
      bad_line(number, line, "one 'format TYPE VERSION' before the elements");
    format = std::string(words[1]);
    if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
      fail(path, "unknown PLY format '" + format + "'");
  } else if (tag == "element") {
    element_line(number, line, words);
  } else if (tag == "property") {
    property_line(number, line, words);
  }
  // Any other line is free text, as in assimp's reader: Blender 2.47 wrote a bare "Created by Blender3D …" line.
  if (!words.empty()) in_properties = tag == "element" || tag == "property";
}

void PlyHeader::element_line(long long number, std::string_view line, const std::vector<std::string_view>& words) {
  if (words.size() != 3) bad_line(number, line, "expected 'element NAME COUNT'");
  has_element = true;
  close_element();
  count = words.size() >= 3 ? parse_count(words[2]) : -1;
  if (count < 0)
    fail(path, "bad PLY element count '" + std::string(words.size() >= 3 ? words[2] : "") + "' for " +
                   std::string(words.size() >= 2 ? words[1] : "?"));
  total_elements += static_cast<unsigned long long>(count);
  // assimp fills one array per element kind: a second "face" element wrote past the first one's faces.
  for (const PlyElement& e : layout)
    if (same_name(e.name, words[1])) bad_line(number, line, "an element of this name is already declared");
  layout.push_back({std::string(words[1]), static_cast<unsigned long long>(count), {}, {}});
}

void PlyHeader::property_line(long long number, std::string_view line, const std::vector<std::string_view>& words) {
  if (!layout.empty() && words.size() >= 3)
    for (const std::string& name : layout.back().property_names)
      if (same_name(name, words.back()))
        bad_line(number, line, "a property of this name is already declared in this element");
  // A list is at least its count; with a face's 3 corners, 4 values.
  const bool list = words.size() >= 2 && words[1] == "list";
  if (!has_element) bad_line(number, line, "a property before any element");
  // assimp reads a list where it expects a vertex coordinate (or a scalar where it expects a face's corners) as
  // something else: a vertex element with a list 'x' loaded 2 vertices of 3.
  if (!layout.empty() && same_name(layout.back().name, "vertex") && list)
    bad_line(number, line, "a vertex property cannot be a list");
  if (!layout.empty() && !list && words.size() == 3 &&
      (same_name(words[2], "vertex_indices") || same_name(words[2], "vertex_index")))
    bad_line(number, line, "a face's vertex indices must be a list");
  if (!in_properties)
    bad_line(number, line,
             "a property must follow its element's line or another property (assimp's reader ends an element's "
             "properties at the first other line, a comment too, and would misread the body)");
  if (words.size() != (list ? 5u : 3u))
    bad_line(number, line,
             list ? "expected 'property list COUNT_TYPE ITEM_TYPE NAME'" : "expected 'property TYPE NAME'");
  total_values += (list ? 4 : 1) * static_cast<unsigned long long>(count);
  if (list && words.size() >= 4) {
    if (words[2] == "float" || words[2] == "float32" || words[2] == "double" || words[2] == "float64")
      bad_line(number, line, "a list's count type must be an integer type");
    const unsigned long long count_size = type_size(words[2]), item = type_size(words[3]);
    element_min += count_size;
    if (count_size >= 4) bounded = false;
    element_max += count_size + item * ((1ull << (8 * count_size)) - 1);
    layout.back().properties.push_back(
        {true, is_signed(words[2]), count_size, item, kind_of(words[2]), kind_of(words[3]),
         "property list " + std::string(words[2]) + " " + std::string(words[3]) + " " + std::string(words[4])});
    layout.back().property_names.emplace_back(words[4]);
  } else if (!list && words.size() >= 2) {
    element_min += type_size(words[1]);
    element_max += type_size(words[1]);
    layout.back().properties.push_back({false, false, 0, type_size(words[1]), PlyKind::kUnsigned, kind_of(words[1]),
                                        "property " + std::string(words[1]) + " " + std::string(words[2])});
    layout.back().property_names.emplace_back(words[2]);
  }
}

// The body against the header: element counts and value budget; a binary body's size within what the header
// describes, a text body's budget and no NUL byte.
void check_ply_body_size(const std::filesystem::path& path, std::string_view text, std::size_t header_end,
                         std::uintmax_t file_size, const PlyHeader& h) {
  const std::uintmax_t body = file_size - header_end;
  // Every element takes at least one byte of the body: a larger count is a corrupt or truncated header.
  if (h.total_elements > body)
    fail(path, "PLY element counts (" + std::to_string(h.total_elements) + " elements) exceed what a body of " +
                   format_bytes(body) + " can hold (truncated or corrupt)");
  if (h.total_values > kMeshLoadMemoryBudget / kPlyPeakPerValue)
    refuse(path, "a PLY file of " + std::to_string(h.total_values) + " values would need about " +
                     format_bytes(h.total_values * kPlyPeakPerValue) + " to load, over the " +
                     format_bytes(kMeshLoadMemoryBudget) + " memory budget");
  if (h.format != "ascii") {
    const std::size_t eol = text.find('\n', header_end);  // the body starts after end_header's line break
    const std::uintmax_t data = eol == std::string_view::npos ? 0 : file_size - (eol + 1);
    if (data < h.min_body)
      fail(path, "binary PLY body of " + std::to_string(data) + " bytes is shorter than the " +
                     std::to_string(h.min_body) + " its header describes (truncated)");
    // Bytes past what the header can describe are not mesh data: refuse rather than read them (a 2 GB sparse file
    // with a 3-vertex header). A little slack for trailing line breaks some writers add.
    if (h.bounded && data > h.max_body + 4096)
      fail(path, "binary PLY body of " + format_bytes(data) + " is longer than its header can describe (at most " +
                     format_bytes(h.max_body) + ")");
  } else {
    check_text_budget(path, file_size, "PLY");
    check_no_nul(path, text, header_end, "PLY");
  }
}

// A mesh needs an element "vertex" with x, y and z and a face (or triangle strip) element with its vertex indices.
// assimp reads a file without them in ways of its own (a header whose vertex element was misspelt took 11 GB).
void check_ply_mesh_elements(const std::filesystem::path& path, const std::vector<PlyElement>& layout) {
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
}

// The header written back from the layout: `ply`, the format, each element written back (written_back) and its
// properties, one line each.
std::string canonical_header(const PlyHeader& h) {
  std::string header = "ply\nformat " + h.format + " 1.0\n";
  for (const PlyElement& e : h.layout) {
    if (!written_back(e)) continue;
    header += "element " + e.name + " " + std::to_string(e.count) + "\n";
    for (const PlyProperty& p : e.properties) header += p.declaration + "\n";
  }
  return header + "end_header\n";
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
               std::string* canonical) {
  if (text.substr(0, 3) != "ply") fail(path, "not a PLY file (no 'ply' magic)");
  const std::size_t header_end = ply_header_end(path, text);
  const std::string_view header = text.substr(0, header_end);
  check_no_control_characters(path, header);
  PlyHeader h(path);
  for_each_line(header, [&](long long number, std::string_view line) { h.read_line(number, line); });
  h.close_element();
  if (h.format.empty()) fail(path, "incomplete PLY header (no format line)");
  check_ply_body_size(path, text, header_end, file_size, h);
  check_ply_mesh_elements(path, h.layout);
  if (!whole) return;
  const std::size_t eol = text.find('\n', header_end);
  const std::string_view data = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
  if (canonical) *canonical = canonical_header(h);
  unsigned long long values = 0;
  if (h.format == "ascii") {
    values = walk_ply_ascii(path, data, h.layout, canonical);
  } else {
    values = walk_ply_binary(path, data, h.layout, h.format, canonical);
  }
  if (values > kMeshLoadMemoryBudget / kPlyPeakPerValue)
    refuse(path, "a PLY file of " + std::to_string(values) + " values would need about " +
                     format_bytes(values * kPlyPeakPerValue) + " to load, over the " +
                     format_bytes(kMeshLoadMemoryBudget) + " memory budget");
}

}  // namespace trispline::core::precheck
