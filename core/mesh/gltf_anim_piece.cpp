// Pieces of an animated-GLB recording split by frames: MorphAnimationBuilder::write_piece, read_piece, append_piece
// (core/mesh/gltf_anim_io.h). The file is the builder's state, little-endian as the machine writes it:
//   "TSPIECE2", fps (f64), first_frame (i32), frames (i32), objects (u32), then per object: name (u32 length +
//   bytes), colour (3 × f32), segments (u32), per segment: first, frames (i32), changed (u8), the base mesh
//   (positions, normals, uvs as f64 arrays, triangles as u32, face materials as u16; each an u64 count first), and per
//   following frame the position and normal deltas (u64 count + f32; count 0 = all zero).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <system_error>

#include "core/mesh/gltf_anim_io.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

constexpr char kMagic[8] = {'T', 'S', 'P', 'I', 'E', 'C', 'E', '2'};
// Larger counts mean a corrupt file: no recording holds that many values in one array.
constexpr std::uint64_t kMaxCount = std::uint64_t(1) << 34;

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
  Reader(std::ifstream& in, const std::filesystem::path& path) : in_(in), path_(path) {}
  template <class T>
  T value() {
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof v);
    check();
    return v;
  }
  template <class T>
  std::vector<T> array() {
    const auto n = value<std::uint64_t>();
    if (n > kMaxCount) fail("array of " + std::to_string(n) + " values");
    std::vector<T> v(n);
    in_.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
    check();
    return v;
  }
  std::string text() {
    const auto n = value<std::uint32_t>();
    if (n > (1u << 20)) fail("name of " + std::to_string(n) + " bytes");
    std::string s(n, '\0');
    in_.read(s.data(), n);
    check();
    return s;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw MeshIoError("'" + path_.string() + "': not an animation piece (" + what + ")");
  }

 private:
  void check() const {
    if (!in_) fail("truncated");
  }
  std::ifstream& in_;
  std::filesystem::path path_;
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
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshIoError("'" + path.string() + "': cannot open the animation piece");
  Reader r(in, path);
  char magic[sizeof kMagic];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("no TSPIECE2 header");
  const double fps = r.value<double>();
  if (!(fps > 0) || !std::isfinite(fps)) r.fail("fps");
  MorphAnimationBuilder b(fps, r.value<std::int32_t>());
  b.frames_ = r.value<std::int32_t>();
  if (b.frames_ < 1) r.fail("no frames");
  const auto objects = r.value<std::uint32_t>();
  for (std::uint32_t i = 0; i < objects; ++i) {
    Object o;
    o.name = r.text();
    o.color = r.value<glm::vec3>();
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
