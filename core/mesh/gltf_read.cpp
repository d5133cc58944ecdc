#include "core/mesh/gltf_read.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>

#include "core/mesh/file_check.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/model_load.h"
#include "core/mesh/path_quote.h"

namespace trispline::core::gltf_read {
namespace {

namespace fs = std::filesystem;

std::string num(std::uintmax_t v) { return std::to_string(v); }

// ---- 2. the JSON, streamed ------------------------------------------------------------------------------------------

struct ScannedBuffer {
  double byte_length = 0;  // as written (tinygltf refuses what is not a non-negative integer)
  bool has_uri = false;
  std::string uri;
};

// Counts values and depth and collects buffers[*].byteLength / .uri without building a document. Stops at the first
// limit exceeded (`problem`) or syntax error (`syntax_error`; tinygltf reports it in its own words).
class JsonScan : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::vector<ScannedBuffer> buffers;
  std::string problem;
  bool syntax_error = false;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t v) override { return number(static_cast<double>(v)); }
  bool number_unsigned(number_unsigned_t v) override { return number(static_cast<double>(v)); }
  bool number_float(number_float_t v, const string_t&) override { return number(v); }
  bool string(string_t& s) override {
    if (!value()) return false;
    if (in_buffer_object() && buffer_key_ == "uri") buffers.back().has_uri = true, buffers.back().uri = s;
    return true;
  }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    if (!value()) return false;
    if (in_buffers_array()) buffers.emplace_back();
    return open('o');
  }
  bool key(string_t& k) override {
    if (stack_.size() == 1) top_key_ = k;
    if (in_buffer_object()) buffer_key_ = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override {
    if (!value()) return false;
    if (stack_.size() == 1 && top_key_ == "buffers")
      buffers.clear();  // a repeated key: the JSON library keeps the last
    return open('a');
  }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    syntax_error = true;
    return false;
  }

 private:
  std::vector<char> stack_;  // 'o' object, 'a' array
  std::string top_key_, buffer_key_;
  std::size_t values_ = 0;

  bool in_buffers_array() const { return stack_.size() == 2 && stack_[1] == 'a' && top_key_ == "buffers"; }
  bool in_buffer_object() const { return stack_.size() == 3 && stack_[1] == 'a' && top_key_ == "buffers"; }
  bool value() {
    if (++values_ <= kMaxGltfJsonValues) return true;
    problem = "JSON has more than " + num(kMaxGltfJsonValues) + " values (the limit for glTF files)";
    return false;
  }
  bool number(double v) {
    if (!value()) return false;
    if (in_buffer_object() && buffer_key_ == "byteLength") buffers.back().byte_length = v;
    return true;
  }
  bool open(char c) {
    stack_.push_back(c);
    if (stack_.size() <= static_cast<std::size_t>(kMaxGltfJsonDepth)) return true;
    problem = "JSON nested deeper than " + num(kMaxGltfJsonDepth) + " levels (the limit for glTF files)";
    return false;
  }
  bool close() {
    if (!stack_.empty()) stack_.pop_back();
    return true;
  }
};

// tinygltf's URI decoding (dlib::urldecode, internal to the library): %XX and '+' → ' '.
std::string url_decode(const std::string& s) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return 0;
  };
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '+') {
      out += ' ';
    } else if (s[i] == '%' && s.size() > i + 2) {
      out += static_cast<char>((hex(s[i + 1]) << 4) | hex(s[i + 2]));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// "http:" for "http://x", "" for a relative reference (RFC 3986 §3.1: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":").
std::string uri_scheme(const std::string& uri) {
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return "";
  for (std::size_t i = 1; i < uri.size(); ++i) {
    const char c = uri[i];
    if (c == ':') return uri.substr(0, i + 1);
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return "";
  }
  return "";
}

// The decoded form of an external file's `uri` (a buffer's or an image's), refused with `label` when it holds a NUL
// byte, is absolute or has a scheme: a glTF file may refer only to files in its own folder or below.
std::string relative_uri(const std::string& uri, const std::string& label) {
  const std::string decoded = url_decode(uri);
  if (decoded.find('\0') != std::string::npos) throw MeshIoError(label + " contains a NUL byte");
  if (!decoded.empty() && decoded[0] == '/')
    throw MeshIoError(label + " is an absolute path; a glTF file may refer only to files in its own folder or below");
  if (const std::string scheme = uri_scheme(uri); !scheme.empty())
    throw MeshIoError(label + " has the scheme '" + scheme +
                      "'; only embedded data: URIs and relative paths to files in the glTF file's folder are read");
  return decoded;
}

struct ExternalBuffer {
  int index = 0;                 // first buffer with this URI, for messages
  std::uintmax_t max_bytes = 0;  // its byteLength (the largest, if several buffers share the file)
};

// The JSON text of the file: all of a .gltf, the first chunk of a GLB (empty if the GLB header is broken: tinygltf
// then refuses the file in its own words).
std::string_view json_text(const std::vector<unsigned char>& bytes, bool binary) {
  const char* p = reinterpret_cast<const char*>(bytes.data());
  if (!binary) return {p, bytes.size()};
  if (bytes.size() < 20 || std::memcmp(p, "glTF", 4) != 0) return {};
  std::uint32_t len = 0;
  std::memcpy(&len, p + 12, 4);  // little-endian hosts only, as tinygltf
  if (len > bytes.size() - 20) return {};
  return {p + 20, len};
}

// Check 2: returns the external buffer files by decoded URI (as tinygltf will ask for them).
std::map<std::string, ExternalBuffer> scan_json(std::string_view json, bool binary, const fs::path& path) {
  JsonScan scan;
  nlohmann::json::sax_parse(json.begin(), json.end(), &scan, nlohmann::json::input_format_t::json, true, false);
  if (!scan.problem.empty()) throw MeshIoError(quoted(path) + ": " + scan.problem);
  std::map<std::string, ExternalBuffer> external;
  if (scan.syntax_error) return external;  // tinygltf names the syntax error
  double total = 0;
  for (std::size_t i = 0; i < scan.buffers.size(); ++i) {
    const ScannedBuffer& b = scan.buffers[i];
    const std::string label = quoted(path) + ": buffer " + num(i);
    if (b.byte_length > 0) total += b.byte_length;
    if (!b.has_uri) {
      if (binary && i > 0)
        throw MeshIoError(label + " has no uri; only the first buffer of a GLB may use the file's BIN chunk");
      continue;
    }
    if (tinygltf::IsDataURI(b.uri)) continue;  // decoded from the JSON text itself
    const std::string decoded = relative_uri(b.uri, label + " URI '" + b.uri + "'");
    auto [it, fresh] = external.try_emplace(decoded, ExternalBuffer{static_cast<int>(i), 0});
    if (b.byte_length > 0)
      it->second.max_bytes = std::max(it->second.max_bytes, static_cast<std::uintmax_t>(std::min(b.byte_length, 1e18)));
    (void)fresh;
  }
  if (total > static_cast<double>(kMaxGltfBufferBytes))
    throw MeshIoError(quoted(path) + ": the buffers' byteLengths add up to " +
                      format_bytes(static_cast<std::uintmax_t>(std::min(total, 1e18))) + ", over the " +
                      format_bytes(kMaxGltfBufferBytes) + " limit for the buffers of one glTF file");
  return external;
}

// ---- 3. external files through tinygltf's file system callbacks -----------------------------------------------------

struct FsContext {
  fs::path gltf;       // the file being read, for messages
  fs::path folder;     // its folder, canonical
  std::string prefix;  // folder as tinygltf joins it with a URI: "<folder>/"
  std::map<std::string, ExternalBuffer> buffers;
  std::string refusal;  // the first refused buffer file: the error the load reports
};

bool inside(const fs::path& p, const fs::path& folder) {
  const fs::path rel = p.lexically_relative(folder);
  return !rel.empty() && *rel.begin() != ".." && rel != ".";
}

// Every candidate "exists": tinygltf then asks for the first one (folder + URI) and never falls back to the current
// directory; read_file decides.
bool file_exists(const std::string&, void*) { return true; }

std::string expand_path(const std::string& p, void*) { return p; }  // no ~ or $VAR expansion

bool read_file(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
  auto& ctx = *static_cast<FsContext*>(user);
  auto fail = [&](const std::string& why) {
    if (err) *err += why;
    return false;
  };
  if (file.compare(0, ctx.prefix.size(), ctx.prefix) != 0) return fail("not a path in the glTF file's folder");
  const std::string uri = file.substr(ctx.prefix.size());
  const auto it = ctx.buffers.find(uri);
  if (it == ctx.buffers.end()) return fail("not read: only buffer files are");  // images: tinygltf warns, keeps uri
  const std::string label = quoted(ctx.gltf) + ": buffer " + num(it->second.index) + " URI '" + uri + "'";
  auto refuse = [&](const std::string& why) {
    if (ctx.refusal.empty()) ctx.refusal = label + why;
    return fail(label + why);
  };
  try {
    const fs::path resolved = fs::weakly_canonical(ctx.folder / uri);
    if (!inside(resolved, ctx.folder))
      return refuse(" resolves to '" + resolved.string() + "', outside the folder '" + ctx.folder.string() +
                    "' of the glTF file (only files in that folder or below are read)");
    *out = read_input_file(resolved, it->second.max_bytes, "this buffer (its byteLength)");
    return true;
  } catch (const MeshIoError& e) {
    return refuse(std::string(": ") + e.what());
  } catch (const fs::filesystem_error& e) {
    return refuse(": " + e.code().message());
  }
}

bool write_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not allowed while reading";
  return false;
}

// Images are not decoded here (OpenImageIO does it, material_image.h). A data: URI image keeps its bytes in
// Image::image; a buffer view image keeps nothing (tinygltf passes its bytes before the view is checked, so they are
// taken from the checked view later, image_bytes); external image files are never read by tinygltf (read_file).
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->width = image->height = -1;
  return true;
}

// ---- 4. the model ---------------------------------------------------------------------------------------------------

std::string trimmed(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  return s.empty() ? "unknown error" : s;
}

// n elements of `elem` bytes, `stride` apart, from `offset` fit in `length` bytes (overflow-safe; stride ≥ elem ≥ 1).
bool fits(std::size_t offset, std::size_t n, std::size_t stride, std::size_t elem, std::size_t length) {
  if (offset > length) return false;
  if (n == 0) return true;
  if (elem > length - offset) return false;
  return n - 1 <= (length - offset - elem) / stride;
}

const tinygltf::BufferView& checked_view(const tinygltf::Model& model, int index, const std::string& label,
                                         const fs::path& path) {
  if (index < 0 || index >= static_cast<int>(model.bufferViews.size()))
    throw MeshIoError(quoted(path) + ": " + label + " refers to buffer view " + std::to_string(index) +
                      ", which does not exist (the file has " + num(model.bufferViews.size()) + ")");
  const auto& view = model.bufferViews[index];
  const std::string vl = quoted(path) + ": buffer view " + std::to_string(index);
  if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size()))
    throw MeshIoError(vl + " refers to buffer " + std::to_string(view.buffer) + ", which does not exist");
  const std::size_t size = model.buffers[view.buffer].data.size();
  if (view.byteLength > size || view.byteOffset > size - view.byteLength)
    throw MeshIoError(vl + " (byteOffset " + num(view.byteOffset) + ", byteLength " + num(view.byteLength) +
                      ") runs past the end of buffer " + std::to_string(view.buffer) + " (" + num(size) + " bytes)");
  if (view.byteStride != 0 && (view.byteStride < 4 || view.byteStride > 252))
    throw MeshIoError(vl + " has byteStride " + num(view.byteStride) + " (glTF allows 4 to 252)");
  return view;
}

bool known_component_type(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || t == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

bool unsigned_index_type(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

template <class T>
double as(const unsigned char* q) {
  T v;
  std::memcpy(&v, q, sizeof v);
  return static_cast<double>(v);
}

// One accessor component; normalised integers per glTF 2.0 §3.11 (signed: max(c / max, −1)).
double component(const unsigned char* q, int ctype, bool nrm) {
  using std::max;
  switch (ctype) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return as<float>(q);
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return nrm ? max(as<std::int8_t>(q) / 127.0, -1.0) : as<std::int8_t>(q);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return nrm ? as<std::uint8_t>(q) / 255.0 : as<std::uint8_t>(q);
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return nrm ? max(as<std::int16_t>(q) / 32767.0, -1.0) : as<std::int16_t>(q);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return nrm ? as<std::uint16_t>(q) / 65535.0 : as<std::uint16_t>(q);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return nrm ? as<std::uint32_t>(q) / 4294967295.0 : as<std::uint32_t>(q);
    default:
      return std::nan("");  // unreachable: accessor_layout admits only the types above
  }
}

std::uint32_t index_value(const unsigned char* q, int ctype) {
  if (ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return *q;
  if (ctype == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    std::uint16_t s;
    std::memcpy(&s, q, 2);
    return s;
  }
  std::uint32_t u;
  std::memcpy(&u, q, 4);
  return u;
}

void check_index(int index, std::size_t size, const std::string& label, const char* kind, const fs::path& path) {
  if (index < 0 || static_cast<std::size_t>(index) >= size)
    throw MeshIoError(quoted(path) + ": " + label + " refers to " + kind + " " + std::to_string(index) +
                      ", which does not exist (the file has " + num(size) + ")");
}

void check_optional_index(int index, std::size_t size, const std::string& label, const char* kind,
                          const fs::path& path) {
  if (index != -1) check_index(index, size, label, kind, path);
}

// Nodes form a forest: children in range, not themselves, one parent at most, no cycle.
void check_nodes(const tinygltf::Model& model, const fs::path& path) {
  const std::size_t n = model.nodes.size();
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string label = "node " + num(i);
    const auto& node = model.nodes[i];
    check_optional_index(node.mesh, model.meshes.size(), label, "mesh", path);
    check_optional_index(node.skin, model.skins.size(), label, "skin", path);
    for (int c : node.children) {
      check_index(c, n, label + " (its children)", "node", path);
      if (c == static_cast<int>(i)) throw MeshIoError(quoted(path) + ": node " + num(i) + " is its own child");
      if (parent[c] >= 0)
        throw MeshIoError(quoted(path) + ": node " + std::to_string(c) + " has two parents (nodes " +
                          std::to_string(parent[c]) + " and " + num(i) + "); glTF nodes form trees");
      parent[c] = static_cast<int>(i);
    }
  }
  // With one parent each, a node that no walk from the roots reaches lies on a cycle.
  std::vector<char> seen(n, 0);
  std::vector<int> stack;
  for (std::size_t i = 0; i < n; ++i)
    if (parent[i] < 0) stack.push_back(static_cast<int>(i));
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    seen[v] = 1;
    for (int c : model.nodes[v].children) stack.push_back(c);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!seen[i])
      throw MeshIoError(quoted(path) + ": node " + num(i) + " is its own ancestor (the nodes form a cycle)");
}

void validate_model(const tinygltf::Model& model, const fs::path& path) {
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i)
    checked_view(model, static_cast<int>(i), "buffer view " + num(i), path);
  for (std::size_t i = 0; i < model.accessors.size(); ++i) accessor_layout(model, static_cast<int>(i), "", path);
  const std::size_t na = model.accessors.size();
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const auto& prim = model.meshes[m].primitives[p];
      const std::string label = "mesh " + num(m) + " primitive " + num(p);
      for (const auto& [name, a] : prim.attributes) check_index(a, na, label + " " + name, "accessor", path);
      check_optional_index(prim.indices, na, label + " indices", "accessor", path);
      for (std::size_t t = 0; t < prim.targets.size(); ++t)
        for (const auto& [name, a] : prim.targets[t])
          check_index(a, na, label + " morph target " + num(t) + " " + name, "accessor", path);
    }
  check_nodes(model, path);
  for (std::size_t s = 0; s < model.scenes.size(); ++s)
    for (int n : model.scenes[s].nodes) check_index(n, model.nodes.size(), "scene " + num(s), "node", path);
  if (model.defaultScene >= static_cast<int>(model.scenes.size()))
    check_index(model.defaultScene, model.scenes.size(), "the file's default scene", "scene", path);
  for (std::size_t s = 0; s < model.skins.size(); ++s) {
    const auto& skin = model.skins[s];
    const std::string label = "skin " + num(s);
    for (int j : skin.joints) check_index(j, model.nodes.size(), label + " (its joints)", "node", path);
    check_optional_index(skin.skeleton, model.nodes.size(), label + " skeleton", "node", path);
    check_optional_index(skin.inverseBindMatrices, na, label + " inverseBindMatrices", "accessor", path);
  }
  for (std::size_t a = 0; a < model.animations.size(); ++a) {
    const auto& anim = model.animations[a];
    for (std::size_t s = 0; s < anim.samplers.size(); ++s) {
      const std::string label = "animation " + num(a) + " sampler " + num(s);
      check_index(anim.samplers[s].input, na, label + " input", "accessor", path);
      check_index(anim.samplers[s].output, na, label + " output", "accessor", path);
    }
    for (std::size_t c = 0; c < anim.channels.size(); ++c) {
      const std::string label = "animation " + num(a) + " channel " + num(c);
      check_index(anim.channels[c].sampler, anim.samplers.size(), label, "sampler", path);
      check_optional_index(anim.channels[c].target_node, model.nodes.size(), label, "node", path);
    }
  }
}

}  // namespace

tinygltf::Model read_model(const fs::path& path) {
  const std::vector<unsigned char> bytes = read_input_file(path, kMaxMeshFileBytes, "mesh files");  // check 1
  const bool binary = lower_extension(path) == ".glb";

  FsContext ctx;
  ctx.gltf = path;
  ctx.buffers = scan_json(json_text(bytes, binary), binary, path);  // check 2
  try {
    ctx.folder = fs::weakly_canonical(fs::absolute(path).parent_path());
  } catch (const fs::filesystem_error& e) {
    throw MeshIoError(quoted(path) + ": cannot resolve the file's folder: " + e.code().message());
  }
  ctx.prefix = ctx.folder.string();
  if (ctx.prefix.empty() || ctx.prefix.back() != '/') ctx.prefix += '/';

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_path, &read_file, &write_file, &ctx});  // check 3
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  std::string err, warn;
  const std::string base = ctx.folder.string();
  bool ok = false;
  try {  // tinygltf throws on some corrupt files (e.g. std::out_of_range for a zero-length GLB buffer)
    const auto size = static_cast<unsigned int>(bytes.size());  // ≤ kMaxMeshFileBytes = 2 GiB
    ok = binary
             ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base)
             : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()), size, base);
  } catch (const std::exception& e) {
    ok = false;
    err = e.what();
  }
  if (!ctx.refusal.empty()) throw MeshIoError(ctx.refusal);
  if (!ok) throw MeshIoError(quoted(path) + ": cannot parse glTF file: " + trimmed(err));
  validate_model(model, path);  // check 4
  return model;
}

AccessorLayout accessor_layout(const tinygltf::Model& model, int index, const std::string& what, const fs::path& path) {
  const std::string label = (what.empty() ? "" : what + " ") + "accessor " + std::to_string(index);
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw MeshIoError(quoted(path) + ": " + label + " does not exist (the file has " + num(model.accessors.size()) +
                      " accessors)");
  const auto& acc = model.accessors[index];
  const std::string at = quoted(path) + ": " + label;
  AccessorLayout l;
  l.comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(acc.type));
  if (l.comps <= 0) throw MeshIoError(at + " has an unknown type");
  if (!known_component_type(acc.componentType))
    throw MeshIoError(at + " has an unknown component type (" + std::to_string(acc.componentType) + ")");
  l.component_type = acc.componentType;
  l.component_size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(acc.componentType));
  l.normalized = acc.normalized;
  l.count = acc.count;
  const std::size_t elem = static_cast<std::size_t>(l.component_size) * l.comps;
  if (acc.bufferView >= 0) {
    const auto& view = checked_view(model, acc.bufferView, label, path);
    l.stride = view.byteStride ? view.byteStride : elem;
    if (l.stride < elem)
      throw MeshIoError(at + ": its buffer view's byteStride " + num(l.stride) + " is smaller than one element (" +
                        num(elem) + " bytes)");
    if (!fits(acc.byteOffset, acc.count, l.stride, elem, view.byteLength))
      throw MeshIoError(at + " (count " + num(acc.count) + ", byteOffset " + num(acc.byteOffset) + ", " + num(elem) +
                        "-byte elements, stride " + num(l.stride) + ") runs past the end of buffer view " +
                        std::to_string(acc.bufferView) + " (" + num(view.byteLength) + " bytes)");
    l.data = model.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset;
  } else {
    l.stride = elem;
  }
  if (acc.sparse.isSparse) {
    const auto& sp = acc.sparse;
    if (sp.count < 1 || static_cast<std::size_t>(sp.count) > acc.count)
      throw MeshIoError(at + " has a sparse count of " + std::to_string(sp.count) + " (1 to count = " + num(acc.count) +
                        " allowed)");
    if (!unsigned_index_type(sp.indices.componentType))
      throw MeshIoError(at + " has sparse indices that are not unsigned byte, short or int");
    const auto n = static_cast<std::size_t>(sp.count);
    const auto isize = static_cast<std::size_t>(
        tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(sp.indices.componentType)));
    struct Part {
      const char* name;
      int view, offset;
      std::size_t size;
    };
    for (const Part& part : {Part{"indices", sp.indices.bufferView, sp.indices.byteOffset, isize},
                             Part{"values", sp.values.bufferView, sp.values.byteOffset, elem}}) {
      const std::string pl = label + " sparse " + part.name;
      const auto& view = checked_view(model, part.view, pl, path);
      if (view.byteStride != 0) throw MeshIoError(quoted(path) + ": " + pl + ": its buffer view has a byteStride");
      if (part.offset < 0 || !fits(static_cast<std::size_t>(part.offset), n, part.size, part.size, view.byteLength))
        throw MeshIoError(quoted(path) + ": " + pl + " (count " + num(n) + ", byteOffset " +
                          std::to_string(part.offset) + ") run past the end of buffer view " +
                          std::to_string(part.view) + " (" + num(view.byteLength) + " bytes)");
      const unsigned char* p = model.buffers[view.buffer].data.data() + view.byteOffset + part.offset;
      (part.name[0] == 'i' ? l.sparse_indices : l.sparse_values) = p;
    }
    l.sparse_count = n;
    l.sparse_index_type = sp.indices.componentType;
  }
  return l;
}

std::vector<double> read_accessor(const tinygltf::Model& model, int index, int comps, const std::string& what,
                                  const fs::path& path, std::size_t max_count, bool sparse) {
  const AccessorLayout l = accessor_layout(model, index, what, path);
  const std::string at = quoted(path) + ": " + what + " accessor " + std::to_string(index);
  if (l.comps != comps)
    throw MeshIoError(at + " has the wrong type (" + std::to_string(l.comps) + " components, expected " +
                      std::to_string(comps) + ")");
  if (l.count > max_count)
    throw MeshIoError(at + " has " + num(l.count) + " elements, more than the " + num(max_count) +
                      " that may be read here");
  std::vector<double> out(l.count * comps, 0.0);
  if (l.data)
    for (std::size_t i = 0; i < l.count; ++i)
      for (int c = 0; c < comps; ++c)
        out[i * comps + c] = component(l.data + l.stride * i + c * l.component_size, l.component_type, l.normalized);
  if (sparse && l.sparse_count > 0) {
    const std::size_t isize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(l.sparse_index_type)));
    const std::size_t elem = static_cast<std::size_t>(l.component_size) * comps;
    for (std::size_t k = 0; k < l.sparse_count; ++k) {
      const std::uint32_t id = index_value(l.sparse_indices + isize * k, l.sparse_index_type);
      if (id >= l.count)
        throw MeshIoError(at + ": sparse index " + std::to_string(id) + " out of range (count " + num(l.count) + ")");
      for (int c = 0; c < comps; ++c)
        out[static_cast<std::size_t>(id) * comps + c] =
            component(l.sparse_values + elem * k + c * l.component_size, l.component_type, l.normalized);
    }
  }
  return out;
}

std::vector<std::uint32_t> read_indices(const tinygltf::Model& model, int index, const fs::path& path,
                                        std::size_t max_count) {
  const AccessorLayout l = accessor_layout(model, index, "index", path);
  const std::string at = quoted(path) + ": index accessor " + std::to_string(index);
  if (l.comps != 1 || !l.data) throw MeshIoError(at + " must be a scalar with a buffer view");
  if (!unsigned_index_type(l.component_type))
    throw MeshIoError(at + " must have unsigned byte, short or int components");
  if (l.count > max_count)
    throw MeshIoError(at + " has " + num(l.count) + " indices, more than the " + num(max_count) +
                      " that may be read here");
  std::vector<std::uint32_t> out(l.count);
  for (std::size_t i = 0; i < l.count; ++i) out[i] = index_value(l.data + l.stride * i, l.component_type);
  return out;
}

std::vector<std::uint8_t> external_image_bytes(const fs::path& gltf, const std::string& uri, std::uintmax_t max_bytes) {
  return read_model_side_file(gltf, relative_uri(uri, "image URI '" + uri + "'"), max_bytes);
}

std::vector<std::uint8_t> image_bytes(const tinygltf::Model& model, int image, const fs::path& path) {
  const tinygltf::Image& im = model.images.at(static_cast<std::size_t>(image));
  if (im.bufferView < 0) return {im.image.begin(), im.image.end()};
  const auto& view = checked_view(model, im.bufferView, "image " + std::to_string(image), path);
  const unsigned char* p = model.buffers[view.buffer].data.data() + view.byteOffset;
  return {p, p + view.byteLength};
}

}  // namespace trispline::core::gltf_read
