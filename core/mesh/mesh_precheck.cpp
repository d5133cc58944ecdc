#include "core/mesh/mesh_precheck.h"

#include <iconv.h>

#include <algorithm>
#include <cstring>
#include <string_view>

#include "core/mesh/file_check.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/ply_precheck.h"
#include "core/mesh/precheck_text.h"

namespace trispline::core {
using namespace precheck;
namespace {

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
    for (std::string_view tok = next_token(line); !tok.empty() && tokens.size() < 4; tok = next_token(line)) {
      if (tokens.size() == 1 && tok == "BINARY") {
        binary = true;
      } else {
        tokens.push_back(tok);
      }
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

// The faces of an ASCII OFF body (comments already removed, the keyword written): assimp reads a face a line, its
// corner count first. It takes a count larger than the indices on the line as given (reading past the face it built),
// and it drops a line whose count is 0 or over 9 without counting it as a face, so the next lines are read as faces
// and its face count wraps below zero (both segfaults found by fuzz_mesh_off). Every face line must hold 1 to 9
// corners and its count's indices; a larger polygon is refused rather than dropped.
constexpr long long kMaxOffCorners = 9;

void check_off_faces(const std::filesystem::path& path, std::string_view text) {
  std::vector<std::string_view> lines;
  for_each_line(text, [&](long long, std::string_view line) {
    if (!first_token(line).empty()) lines.push_back(line);
  });
  if (lines.empty()) return;
  std::vector<std::string_view> words;
  auto split = [&](std::string_view line) { words = split_words(line); };
  std::size_t at = 0;
  split(lines[at++]);
  if (words.size() < 4) {  // the counts on a line of their own
    if (at >= lines.size()) return;
    split(lines[at++]);
  } else {
    words.erase(words.begin());
  }
  if (words.size() < 2) return;  // check_off has refused it
  const long long nv = parse_count(words[0]), nf = parse_count(words[1]);
  if (nv < 0 || nf < 0) return;
  at += static_cast<std::size_t>(nv);
  for (long long f = 0; f < nf; ++f, ++at) {
    if (at >= lines.size())
      fail(path, "the OFF file ends after " + std::to_string(f) + " of its " + std::to_string(nf) + " faces");
    split(lines[at]);
    const long long n = parse_count(words[0]);
    if (n < 0 || static_cast<unsigned long long>(n) + 1 > words.size())
      fail(path, "OFF face " + std::to_string(f) + ": '" + std::string(lines[at].substr(0, 60)) +
                     "' does not hold the corner count and that many vertex indices");
    if (n == 0) fail(path, "OFF face " + std::to_string(f) + " has no corners");
    if (n > kMaxOffCorners)
      refuse(path, "OFF face " + std::to_string(f) + " has " + std::to_string(n) +
                       " corners; assimp's OFF reader takes at most " + std::to_string(kMaxOffCorners) +
                       " and would drop it (triangulate the mesh, or save it as OBJ, PLY or glTF)");
  }
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

// Collada is XML: text starting with '<' (after a byte order mark or white space).
void check_dae(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size) {
  check_text_budget(path, file_size, "Collada");
  std::size_t first = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") first = 3;
  while (first < text.size() && (is_space(text[first]) || text[first] == '\n')) ++first;
  if (first >= text.size() || text[first] != '<') fail(path, "not a Collada file (XML starts with '<')");
  check_no_nul(path, text, 0, "Collada");
}

// FBX: binary ("Kaydara FBX Binary  \0") or ASCII (assimp reads both); within the text budget either way.
void check_fbx(const std::filesystem::path& path, std::string_view text, std::uintmax_t file_size) {
  check_text_budget(path, file_size, "FBX");
  if (text.substr(0, 18) == "Kaydara FBX Binary") return;
  check_no_nul(path, text, 0, "FBX");
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

void prepare_mesh_bytes(const std::filesystem::path& path, const std::string& ext, std::vector<unsigned char>& bytes,
                        std::vector<std::string>* mtllibs) {
  if (ext == ".stl") return;  // binary STL may start with any bytes; ASCII STL is plain ASCII
  const bool utf32 = starts_with(bytes, {0xFF, 0xFE, 0x00, 0x00}) || starts_with(bytes, {0x00, 0x00, 0xFE, 0xFF});
  const bool utf16 = !utf32 && (starts_with(bytes, {0xFF, 0xFE}) || starts_with(bytes, {0xFE, 0xFF}));
  if (utf16 || utf32) bytes = to_utf8(path, bytes, utf32 ? "UTF-32" : "UTF-16");
  if (starts_with(bytes, {0xEF, 0xBB, 0xBF})) bytes.erase(bytes.begin(), bytes.begin() + 3);
  if (ext == ".ply") {
    // assimp is handed the file as check_ply walked it, so the two cannot read different layouts or values:
    // assimp's header reader ends an element at a comment, matches keywords in any case and loops on some free
    // text, its body reader splits values where a number stops parsing, and the body walk (the list counts checked
    // against the bytes) is only as good as the reading they share.
    std::string canonical;
    check_ply(path, as_text(bytes), bytes.size(), true, &canonical);
    bytes.assign(canonical.begin(), canonical.end());
    return;
  }
  if (ext == ".obj") {
    // Material libraries are never read (trispline keeps no OBJ materials): each `mtllib` line becomes a comment,
    // same length, so line numbers hold. assimp opens the library by the name the line gives, and a line naming the
    // served file itself had the OBJ parsed as a material library, which writes through a null material (SEGV).
    // With `mtllibs`, the names are collected and the first `mtllib` line names kServedMtlName instead (the same
    // line, so line numbers hold): assimp is then given the checked libraries under that one name.
    std::size_t start = 0;
    std::size_t served_line = std::string::npos, served_end = 0;
    while (start < bytes.size()) {
      std::size_t end = start;
      while (end < bytes.size() && bytes[end] != '\n') ++end;
      std::string_view line(reinterpret_cast<const char*>(bytes.data()) + start, end - start);
      std::string_view rest = line;
      if (next_token(rest) == "mtllib") {
        if (mtllibs) {
          while (!rest.empty() && is_space(rest.front())) rest.remove_prefix(1);
          while (!rest.empty() && is_space(rest.back())) rest.remove_suffix(1);
          if (!rest.empty()) mtllibs->emplace_back(rest);
          if (served_line == std::string::npos) served_line = start, served_end = end;
        }
        bytes[start + line.find("mtllib")] = '#';
      }
      start = end + 1;
    }
    if (served_line != std::string::npos) {
      const std::string served = std::string("mtllib ") + kServedMtlName;
      bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(served_line),
                  bytes.begin() + static_cast<std::ptrdiff_t>(served_end));
      bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(served_line), served.begin(), served.end());
    }
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
  if (ext == ".dae") check_dae(path, text, file_size);
  if (ext == ".fbx") check_fbx(path, text, file_size);
}

void precheck_mesh_file(const std::filesystem::path& path, const std::string& ext,
                        const std::vector<unsigned char>& bytes) {
  const std::string_view text = as_text(bytes);
  if (text.empty()) fail(path, "empty file");
  if (ext == ".obj") check_obj(path, text, text.size(), true);
  if (ext == ".off") {
    check_off(path, text, text.size());
    check_off_faces(path, text);
  }
  if (ext == ".stl") check_stl(path, text, text.size());
  if (ext == ".dae") check_dae(path, text, text.size());
  if (ext == ".fbx") check_fbx(path, text, text.size());
}

std::string check_mtl_text(const std::filesystem::path& mtl, std::string_view text) {
  if (text.size() > kMaxMtlFileBytes)
    refuse(mtl, format_bytes(text.size()) + " is over the " + format_bytes(kMaxMtlFileBytes) + " limit for MTL files");
  check_no_nul(mtl, text, 0, "MTL");
  // The statements assimp's MTL reader takes that trispline maps (assimp_material.h); the others are dropped.
  static const char* const kKept[] = {"newmtl", "Ka",   "Kd",       "Ks",       "Ke",     "Tf",     "Tr",     "d",
                                      "Ns",     "Ni",   "illum",    "map_Ka",   "map_Kd", "map_Ks", "map_Ke", "map_d",
                                      "map_Ns", "bump", "map_bump", "map_Bump", "norm",   "Pr",     "Pm"};
  std::string out;
  out.reserve(text.size());
  bool in_material = false;
  for_each_line(text, [&](long long number, std::string_view line) {
    if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::string_view rest = line;
    const std::string_view keyword = next_token(rest);
    if (keyword.empty()) return;
    if (std::find(std::begin(kKept), std::end(kKept), keyword) == std::end(kKept)) return;
    if (keyword == "newmtl") {
      in_material = true;
    } else if (!in_material) {
      fail(mtl, "line " + std::to_string(number) + ": '" + std::string(keyword) + "' before any newmtl");
    }
    out += keyword;
    for (std::string_view tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
      out += ' ';
      out += tok;
    }
    out += '\n';
  });
  return out;
}

}  // namespace trispline::core
