#include "core/mesh/mesh_precheck.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why) {
  throw MeshIoError(quoted(path) + ": " + why);
}

// Vertex coordinates are checked here, because OpenMesh's text readers drop or zero "nan", "inf" and overflowing
// numbers (std::istream cannot read them) instead of reporting them.
void check_coordinate(const std::filesystem::path& path, const std::string& tok, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(tok.c_str(), &end);
  if (end == tok.c_str()) fail(path, "cannot parse vertex coordinate '" + tok + "' " + where);
  if (!std::isfinite(v)) fail(path, "non-finite vertex coordinate (NaN or inf) '" + tok + "' " + where);
}

void check_obj(const std::filesystem::path& path, std::istream& in) {
  long long nv = 0;
  int lineno = 0;
  std::string line;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      ++nv;
      std::string tok;
      for (int c = 0; c < 3 && ls >> tok; ++c) check_coordinate(path, tok, "on line " + std::to_string(lineno));
    } else if (tag == "f" || tag == "l") {
      std::string tok;
      while (ls >> tok) {
        long long idx = 0;
        try {
          idx = std::stoll(tok.substr(0, tok.find('/')));
        } catch (const std::exception&) {
          fail(path, "cannot parse face on line " + std::to_string(lineno));
        }
        const long long resolved = idx < 0 ? nv + idx + 1 : idx;  // negative indices count back from the last vertex
        if (idx == 0 || resolved < 1 || resolved > nv)
          fail(path, "vertex index out of range on line " + std::to_string(lineno) + " (" + std::to_string(idx) +
                         " with " + std::to_string(nv) + " vertices so far)");
      }
    }
  }
}

// Plain ASCII OFF ("OFF" or with N/ST prefixes; colour files are left to OpenMesh): counts and face indices.
std::optional<std::string> check_off(const std::filesystem::path& path, std::istream& in) {
  std::string text((std::istreambuf_iterator<char>(in)), {}), stripped;
  if (text.rfind("OFF BINARY", 0) == 0 || text.find("BINARY") < text.find('\n')) return std::nullopt;
  bool had_comment = false;
  std::vector<std::string> toks;
  std::istringstream all(text);
  std::string line;
  while (std::getline(all, line)) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) had_comment = true, line.resize(hash);
    stripped += line + '\n';
    std::istringstream ls(line);
    std::string t;
    while (ls >> t) toks.push_back(t);
  }
  if (toks.empty() || toks[0].find("OFF") == std::string::npos) fail(path, "cannot parse: no OFF header");
  const std::string& head = toks[0];
  if (head.find('C') != std::string::npos || head.find('4') != std::string::npos || head[0] == 'n')
    return had_comment ? std::optional<std::string>(stripped) : std::nullopt;
  const std::size_t per_vertex =
      3 + (head.find('N') != std::string::npos ? 3 : 0) + (head.find("ST") != std::string::npos ? 2 : 0);
  try {
    std::size_t k = 1;
    const long long nv = std::stoll(toks.at(k++)), nf = std::stoll(toks.at(k++));
    ++k;  // edge count
    if (nv < 0 || nf < 0) fail(path, "cannot parse: negative counts in OFF header");
    if (toks.size() < k + per_vertex * static_cast<std::size_t>(nv)) fail(path, "cannot parse: OFF file is truncated");
    for (long long v = 0; v < nv; ++v, k += per_vertex)
      for (int c = 0; c < 3; ++c) check_coordinate(path, toks[k + c], "of vertex " + std::to_string(v));
    for (long long f = 0; f < nf; ++f) {
      const long long n = std::stoll(toks.at(k++));
      for (long long i = 0; i < n; ++i) {
        const long long idx = std::stoll(toks.at(k++));
        if (idx < 0 || idx >= nv)
          fail(path, "vertex index out of range in face " + std::to_string(f) + " (" + std::to_string(idx) + " of " +
                         std::to_string(nv) + " vertices)");
      }
      while (k < toks.size() && toks[k].find('.') != std::string::npos) ++k;  // optional face colour
    }
  } catch (const std::logic_error&) {  // std::stoll and vector::at failures
    fail(path, "cannot parse OFF counts or faces");
  }
  return had_comment ? std::optional<std::string>(stripped) : std::nullopt;
}

// PLY header: magic, format, "element NAME COUNT" with counts the file can hold, end_header. For ASCII files whose
// first element is "vertex" (and, if the second is "face", has one list property) the body is checked too.
void check_ply(const std::filesystem::path& path, std::istream& in, std::uintmax_t file_size) {
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) fail(path, "cannot parse: not a PLY file");
  struct Element {
    std::string name;
    long long count = 0;
    int properties = 0;
    bool list = false;
  };
  std::vector<Element> elements;
  std::string format;
  bool ended = false;
  long long total = 0;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "format") {
      ls >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        fail(path, "cannot parse: unknown PLY format '" + format + "'");
    } else if (word == "element") {
      std::string name, count;
      ls >> name >> count;
      long long n = -1;
      try {
        std::size_t used = 0;
        n = std::stoll(count, &used);
        if (used != count.size()) n = -1;
      } catch (const std::exception&) {
      }
      if (n < 0) fail(path, "cannot parse: bad PLY element count '" + count + "' for " + name);
      total += n;
      elements.push_back({name, n});
    } else if (word == "property" && !elements.empty()) {
      std::string type;
      ls >> type;
      ++elements.back().properties;
      elements.back().list = elements.back().list || type == "list";
    } else if (word == "end_header") {
      ended = true;
      break;
    }
  }
  if (format.empty() || !ended) fail(path, "cannot parse: incomplete PLY header");
  // Every element takes at least one byte: a larger count is a corrupt header (and would make OpenMesh allocate it).
  if (static_cast<std::uintmax_t>(total) > file_size) fail(path, "cannot parse: PLY element counts exceed file size");
  if (format != "ascii" || elements.empty() || elements[0].name != "vertex" || elements[0].list) return;
  const long long nv = elements[0].count;
  for (long long v = 0; v < nv; ++v) {
    if (!std::getline(in, line)) fail(path, "cannot parse: PLY file is truncated");
    std::istringstream ls(line);
    std::string tok;
    for (int c = 0; c < elements[0].properties && ls >> tok; ++c)
      check_coordinate(path, tok, "of vertex " + std::to_string(v));
  }
  if (elements.size() < 2 || elements[1].name != "face" || elements[1].properties != 1 || !elements[1].list) return;
  for (long long f = 0; f < elements[1].count && std::getline(in, line); ++f) {
    std::istringstream ls(line);
    long long n = 0, idx = 0;
    ls >> n;
    for (long long i = 0; i < n && ls >> idx; ++i)
      if (idx < 0 || idx >= nv)
        fail(path, "vertex index out of range in face " + std::to_string(f) + " (" + std::to_string(idx) + " of " +
                       std::to_string(nv) + " vertices)");
  }
}

// Binary STL is 84 + 50·n bytes; anything else must be ASCII ("solid").
void check_stl(const std::filesystem::path& path, std::istream& in, std::uintmax_t file_size) {
  char header[84] = {};
  in.read(header, sizeof header);
  if (file_size >= 84) {
    std::uint32_t n = 0;
    for (int i = 0; i < 4; ++i) n |= static_cast<std::uint32_t>(static_cast<unsigned char>(header[80 + i])) << (8 * i);
    if (file_size == 84 + 50ull * n) return;
  }
  if (std::string(header, std::min<std::uintmax_t>(file_size, 5)) != "solid")
    fail(path, "cannot parse: neither ASCII STL nor a binary STL of consistent size");
  in.clear();
  in.seekg(0);
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string word, tok;
    ls >> word;
    if (word == "vertex")
      for (int c = 0; c < 3; ++c) {
        if (!(ls >> tok)) fail(path, "cannot parse vertex on line " + std::to_string(lineno));
        check_coordinate(path, tok, "on line " + std::to_string(lineno));
      }
  }
}

}  // namespace

std::optional<std::string> precheck_mesh_file(const std::filesystem::path& path, const std::string& ext) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open file");
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ext == ".obj") check_obj(path, in);
  if (ext == ".off") return check_off(path, in);
  if (ext == ".ply") check_ply(path, in, ec ? 0 : size);
  if (ext == ".stl") check_stl(path, in, ec ? 0 : size);
  return std::nullopt;
}

}  // namespace trispline::core
