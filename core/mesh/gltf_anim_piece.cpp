// Pieces of an animated-GLB recording split by frames: MorphAnimationBuilder::write_piece, read_piece, append_piece
// (core/mesh/gltf_anim_io.h). The file is the builder's state, little-endian as the machine writes it:
//   "TSPIECE3", fps (f64), first_frame (i32), frames (i32), objects (u32), then per object: name (u32 length +
//   bytes), colour (3 × f32), its materials (below), segments (u32), per segment: first, frames (i32), changed (u8),
//   the base mesh (positions, normals, uvs as f64 arrays, triangles as u32, face materials as u16; each an u64 count
//   first), and per following frame the position and normal deltas (u64 count + f32; count 0 = all zero).
// Materials: has_set (u8); with a set, images (u32) each as name, uri, mime type, error (texts) and its encoded bytes
// (u64 count + u8) — decoded again on reading (OpenImageIO, deterministic), never stored as pixels — then materials
// (u32) field by field as core/mesh/material.h declares them. So a farm-assembled animation.glb carries the
// materials and images one recording writes, byte for byte.
// Every count is checked against the bytes left in the file before anything is allocated (a farm folder is
// untrusted input).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/mesh/gltf_anim_io.h"
#include "core/mesh/material_image.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

constexpr char kMagic[8] = {'T', 'S', 'P', 'I', 'E', 'C', 'E', '3'};

class Writer {
 public:
  explicit Writer(std::ofstream& out) : out_(out) {}
  template <class T>
  void value(const T& v) {
    out_.write(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void array(const std::vector<T>& v) {
    value(static_cast<std::uint64_t>(v.size()));
    out_.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  }
  void text(const std::string& s) {
    value(static_cast<std::uint32_t>(s.size()));
    out_.write(s.data(), static_cast<std::streamsize>(s.size()));
  }

 private:
  std::ofstream& out_;
};

class Reader {
 public:
  Reader(std::ifstream& in, const std::filesystem::path& path, std::uint64_t file_size)
      : in_(in), path_(path), left_(file_size) {}
  template <class T>
  T value() {
    T v{};
    take(sizeof v);
    in_.read(reinterpret_cast<char*>(&v), sizeof v);
    check();
    return v;
  }
  // A count read from the file is checked against the bytes the file still holds before the vector is sized.
  template <class T>
  std::vector<T> array() {
    const auto n = value<std::uint64_t>();
    if (n > left_ / sizeof(T))
      fail("an array of " + std::to_string(n) + " values in " + std::to_string(left_) + " bytes left");
    take(n * sizeof(T));
    std::vector<T> v(n);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    check();
    return v;
  }
  std::string text() {
    const auto n = value<std::uint32_t>();
    if (n > (1u << 20) || n > left_) fail("a name of " + std::to_string(n) + " bytes");
    take(n);
    std::string s(n, '\0');
    in_.read(s.data(), n);
    check();
    return s;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw MeshIoError("'" + path_.string() + "': not an animation piece (" + what + ")");
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  void take(std::uint64_t bytes) {
    if (bytes > left_) fail("truncated");
    left_ -= bytes;
  }
  void check() const {
    if (!in_) fail("truncated");
  }
  std::ifstream& in_;
  std::filesystem::path path_;
  std::uint64_t left_;  // bytes of the file not read yet
};

void write_mesh(Writer& w, const TriMesh& m) {
  w.array(m.positions);
  w.array(m.normals);
  w.array(m.uvs);
  w.array(m.triangles);
  w.array(m.face_material);
}

TriMesh read_mesh(Reader& r) {
  TriMesh m;
  m.positions = r.array<glm::dvec3>();
  m.normals = r.array<glm::dvec3>();
  m.uvs = r.array<glm::dvec2>();
  m.triangles = r.array<glm::uvec3>();
  m.face_material = r.array<MaterialSlot>();
  return m;
}

void write_texture(Writer& w, const MaterialTexture& t) {
  w.value(static_cast<std::int32_t>(t.image));
  w.value(static_cast<std::int32_t>(t.texcoord));
  w.value(static_cast<std::int32_t>(t.sampler.wrap_s));
  w.value(static_cast<std::int32_t>(t.sampler.wrap_t));
  w.value(static_cast<std::int32_t>(t.sampler.mag_filter));
  w.value(static_cast<std::int32_t>(t.sampler.min_filter));
  w.value(t.scale);
}

MaterialTexture read_texture(Reader& r, std::size_t images) {
  MaterialTexture t;
  t.image = r.value<std::int32_t>();
  t.texcoord = r.value<std::int32_t>();
  const auto wrap = [&r](std::int32_t v) {
    if (v != int(TextureWrap::Repeat) && v != int(TextureWrap::ClampToEdge) && v != int(TextureWrap::MirroredRepeat))
      r.fail("texture wrap " + std::to_string(v));
    return static_cast<TextureWrap>(v);
  };
  const auto filter = [&r](std::int32_t v) {
    if (v != 0 && (v < int(TextureFilter::Nearest) || v > int(TextureFilter::Linear)) &&
        (v < int(TextureFilter::NearestMipmapNearest) || v > int(TextureFilter::LinearMipmapLinear)))
      r.fail("texture filter " + std::to_string(v));
    return static_cast<TextureFilter>(v);
  };
  t.sampler.wrap_s = wrap(r.value<std::int32_t>());
  t.sampler.wrap_t = wrap(r.value<std::int32_t>());
  t.sampler.mag_filter = filter(r.value<std::int32_t>());
  t.sampler.min_filter = filter(r.value<std::int32_t>());
  t.scale = r.value<double>();
  if (t.image < -1 || t.image >= static_cast<std::int64_t>(images) || t.texcoord < 0 || !std::isfinite(t.scale))
    r.fail("texture");
  return t;
}

void write_materials(Writer& w, const std::shared_ptr<const MaterialSet>& set) {
  w.value(static_cast<std::uint8_t>(set != nullptr));
  if (!set) return;
  w.value(static_cast<std::uint32_t>(set->images.size()));
  for (const auto& image : set->images) {
    w.text(image->name);
    w.text(image->uri);
    w.text(image->mime_type);
    w.text(image->error);
    w.array(image->encoded);
  }
  w.value(static_cast<std::uint32_t>(set->materials.size()));
  for (const Material& m : set->materials) {
    w.text(m.name);
    w.value(m.base_color);
    write_texture(w, m.base_color_texture);
    w.value(m.metallic);
    w.value(m.roughness);
    write_texture(w, m.metallic_roughness_texture);
    write_texture(w, m.normal_texture);
    write_texture(w, m.occlusion_texture);
    w.value(m.emissive);
    write_texture(w, m.emissive_texture);
    w.value(static_cast<std::int32_t>(m.alpha_mode));
    w.value(m.alpha_cutoff);
    w.value(static_cast<std::uint8_t>(m.double_sided));
  }
}

std::shared_ptr<const MaterialSet> read_materials(Reader& r) {
  if (r.value<std::uint8_t>() == 0) return nullptr;
  auto set = std::make_shared<MaterialSet>();
  const auto images = r.value<std::uint32_t>();
  for (std::uint32_t i = 0; i < images; ++i) {
    std::string name = r.text(), uri = r.text(), mime = r.text(), error = r.text();
    std::vector<std::uint8_t> encoded = r.array<std::uint8_t>();
    MaterialImage image;
    if (error.empty()) {
      image = decode_material_image(std::move(encoded), mime, name, uri);
      // The writer decoded these bytes once; failing now means the piece was altered.
      if (!image.readable()) r.fail("image " + std::to_string(i) + ": " + image.error);
    } else {
      image.name = std::move(name);
      image.uri = std::move(uri);
      image.mime_type = std::move(mime);
      image.encoded = std::move(encoded);
      image.error = std::move(error);
    }
    set->images.push_back(std::make_shared<const MaterialImage>(std::move(image)));
  }
  const auto materials = r.value<std::uint32_t>();
  if (materials > kMaxMaterialsPerMesh) r.fail(std::to_string(materials) + " materials");
  for (std::uint32_t i = 0; i < materials; ++i) {
    Material m;
    m.name = r.text();
    m.base_color = r.value<glm::dvec4>();
    m.base_color_texture = read_texture(r, images);
    m.metallic = r.value<double>();
    m.roughness = r.value<double>();
    m.metallic_roughness_texture = read_texture(r, images);
    m.normal_texture = read_texture(r, images);
    m.occlusion_texture = read_texture(r, images);
    m.emissive = r.value<glm::dvec3>();
    m.emissive_texture = read_texture(r, images);
    const auto mode = r.value<std::int32_t>();
    if (mode < 0 || mode > int(AlphaMode::Blend)) r.fail("alpha mode " + std::to_string(mode));
    m.alpha_mode = static_cast<AlphaMode>(mode);
    m.alpha_cutoff = r.value<double>();
    m.double_sided = r.value<std::uint8_t>() != 0;
    bool finite = std::isfinite(m.metallic) && std::isfinite(m.roughness) && std::isfinite(m.alpha_cutoff);
    for (int k = 0; k < 4; ++k)
      finite = finite && std::isfinite(m.base_color[k]) && (k == 3 || std::isfinite(m.emissive[k]));
    if (!finite) r.fail("material " + std::to_string(i) + ": a non-finite factor");
    set->materials.push_back(std::move(m));
  }
  return set;
}

bool same_mesh(const TriMesh& a, const TriMesh& b) {
  return a.positions == b.positions && a.normals == b.normals && a.uvs == b.uvs && a.triangles == b.triangles &&
         a.face_material == b.face_material;
}

}  // namespace

void MorphAnimationBuilder::write_piece(const std::filesystem::path& path) const {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    Writer w(out);
    out.write(kMagic, sizeof kMagic);
    w.value(fps_);
    w.value(static_cast<std::int32_t>(first_frame_));
    w.value(static_cast<std::int32_t>(frames_));
    w.value(static_cast<std::uint32_t>(objects_.size()));
    for (const Object& o : objects_) {
      w.text(o.name);
      w.value(o.color);
      write_materials(w, o.materials);
      w.value(static_cast<std::uint32_t>(o.segments.size()));
      for (const Segment& s : o.segments) {
        w.value(static_cast<std::int32_t>(s.first));
        w.value(static_cast<std::int32_t>(s.frames));
        w.value(static_cast<std::uint8_t>(s.changed));
        write_mesh(w, s.base);
        for (int k = 0; k + 1 < s.frames; ++k) {
          w.array(s.pos_delta[k]);
          w.array(s.nrm_delta[k]);
        }
      }
    }
    out.flush();
    if (!out) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw MeshIoError("'" + path.string() + "': cannot write the animation piece");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw MeshIoError("'" + path.string() + "': cannot rename the temporary file: " + ec.message());
  }
}

MorphAnimationBuilder MorphAnimationBuilder::read_piece(const std::filesystem::path& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  if (ec || !in) throw MeshIoError("'" + path.string() + "': cannot open the animation piece");
  Reader r(in, path, size);
  char magic[sizeof kMagic];
  for (char& c : magic) c = static_cast<char>(r.value<std::uint8_t>());
  if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("no TSPIECE3 header");
  const double fps = r.value<double>();
  if (!(fps > 0) || !std::isfinite(fps)) r.fail("fps");
  MorphAnimationBuilder b(fps, r.value<std::int32_t>());
  if (b.first_frame_ < 0 || b.first_frame_ >= kMaxRecordedFrames) r.fail("first frame outside the timeline");
  b.frames_ = r.value<std::int32_t>();
  if (b.frames_ < 1) r.fail("no frames");
  if (b.frames_ > kMaxRecordedFrames - b.first_frame_) r.fail("frames beyond the timeline's last frame");
  const auto objects = r.value<std::uint32_t>();
  for (std::uint32_t i = 0; i < objects; ++i) {
    Object o;
    o.name = r.text();
    o.color = r.value<glm::vec3>();
    o.materials = read_materials(r);
    const auto segments = r.value<std::uint32_t>();
    int covered = 0;
    for (std::uint32_t k = 0; k < segments; ++k) {
      Segment s;
      s.first = r.value<std::int32_t>();
      s.frames = r.value<std::int32_t>();
      s.changed = r.value<std::uint8_t>() != 0;
      if (s.first != covered || s.frames < 1 || s.first + s.frames > b.frames_) r.fail("segment frames");
      covered += s.frames;
      s.base = read_mesh(r);
      if (!s.base.face_material.empty() && s.base.face_material.size() != s.base.triangles.size())
        r.fail("face materials");
      validate_mesh(s.base, "'" + path.string() + "': object '" + o.name + "'");
      const std::size_t floats = s.base.positions.size() * 3;
      for (int f = 0; f + 1 < s.frames; ++f) {
        s.pos_delta.push_back(r.array<float>());
        s.nrm_delta.push_back(r.array<float>());
        const std::size_t np = s.pos_delta.back().size(), nn = s.nrm_delta.back().size();
        if ((np != 0 && np != floats) || (nn != 0 && nn != floats)) r.fail("delta size");
      }
      o.segments.push_back(std::move(s));
    }
    if (segments > 0 && covered != b.frames_) r.fail("segments do not cover the frames");
    b.objects_.push_back(std::move(o));
  }
  return b;
}

bool MorphAnimationBuilder::append_piece(const MorphAnimationBuilder& piece) {
  if (frames_ == 0 || piece.fps_ != fps_ || piece.first_frame_ != first_frame_ ||
      piece.objects_.size() != objects_.size())
    return false;
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    const Object &a = objects_[i], &b = piece.objects_[i];
    if (a.name != b.name || a.color != b.color || a.segments.size() != b.segments.size()) return false;
    if ((a.materials == nullptr) != (b.materials == nullptr)) return false;
    if (a.segments.empty()) continue;
    if (a.segments.size() != 1 || !same_mesh(a.segments[0].base, b.segments[0].base)) return false;
  }
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    if (objects_[i].segments.empty()) continue;
    Segment& s = objects_[i].segments[0];
    const Segment& p = piece.objects_[i].segments[0];
    s.pos_delta.insert(s.pos_delta.end(), p.pos_delta.begin(), p.pos_delta.end());
    s.nrm_delta.insert(s.nrm_delta.end(), p.nrm_delta.begin(), p.nrm_delta.end());
    s.frames += p.frames - 1;
    s.changed = s.changed || p.changed;
  }
  frames_ += piece.frames_ - 1;
  return true;
}

}  // namespace trispline::core
