#include "core/mesh/gltf_anim_io.h"

#include <algorithm>

#include "core/base/text.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/path_quote.h"

// As gltf_io.cpp: the Debian tinygltf library is built with its defaults; include the header without configuration
// macros and never define TINYGLTF_IMPLEMENTATION.
#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <stdexcept>

#include "core/mesh/gltf_materials.h"
#include "core/mesh/gltf_model.h"
#include "core/mesh/gltf_read.h"

namespace trispline::core {
namespace {

std::string target_name(int frame) { return printf_string("frame_%04d", frame); }

using gltf_model::add_view;

// A float accessor over `values` (#count × comps) in a new view, with min/max when `bounds`.
int add_floats(tinygltf::Model& model, const std::vector<float>& values, int type, int comps, int target, bool bounds) {
  tinygltf::Accessor acc;
  acc.bufferView = add_view(model, values.data(), values.size() * sizeof(float), target);
  acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  acc.type = type;
  acc.count = values.size() / comps;
  if (bounds) {
    acc.minValues.assign(comps, std::numeric_limits<double>::infinity());
    acc.maxValues.assign(comps, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < acc.count; ++i)
      for (int c = 0; c < comps; ++c) {
        acc.minValues[c] = std::min(acc.minValues[c], double(values[i * comps + c]));
        acc.maxValues[c] = std::max(acc.maxValues[c], double(values[i * comps + c]));
      }
  }
  model.accessors.push_back(acc);
  return static_cast<int>(model.accessors.size()) - 1;
}

std::vector<float> to_floats(const std::vector<glm::dvec3>& v) {
  std::vector<float> out(v.size() * 3);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(v[i][c]);
  return out;
}

// float(b − a) per component, or empty when every component is exactly equal.
std::vector<float> delta(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  bool any = false;
  std::vector<float> out(a.size() * 3);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      out[3 * i + c] = static_cast<float>(b[i][c] - a[i][c]);
      any = any || b[i][c] != a[i][c];
    }
  if (!any) out.clear();
  return out;
}

tinygltf::Model load(const std::filesystem::path& path) { return gltf_read::read_model(path); }

// Float VEC3 accessor `index` as #count vectors (a view-less accessor is all zeros), at most kMaxMeshFileVertices.
std::vector<glm::dvec3> read_vec3(const tinygltf::Model& model, int index, const std::filesystem::path& path) {
  if (gltf_read::accessor_layout(model, index, "VEC3", path).component_type != TINYGLTF_COMPONENT_TYPE_FLOAT)
    throw MeshIoError(quoted(path) + ": expected a float VEC3 accessor");
  const std::vector<double> v =
      gltf_read::read_accessor(model, index, 3, "VEC3", path, gltf_read::kMaxMeshFileVertices, /*sparse=*/false);
  std::vector<glm::dvec3> out(v.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::dvec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
  return out;
}

}  // namespace

MorphAnimationBuilder::MorphAnimationBuilder(double fps, int first_frame) : fps_(fps), first_frame_(first_frame) {
  if (!std::isfinite(fps) || fps <= 0) throw std::invalid_argument("animation fps must be finite and > 0");
}

int MorphAnimationBuilder::animated_objects() const {
  int n = 0;
  for (const Object& o : objects_) n += o.segments.size() > 1 || (o.segments.size() == 1 && o.segments[0].changed);
  return n;
}

int MorphAnimationBuilder::segment_count(const std::string& object) const {
  for (const Object& o : objects_)
    if (o.name == object) return static_cast<int>(o.segments.size());
  return 0;
}

namespace {

// Morph targets need the same vertex count and the same triangles.
bool same_topology(const TriMesh& a, const TriMesh& b) {
  return a.positions.size() == b.positions.size() && a.triangles == b.triangles &&
         (a.normals.size() == a.positions.size()) == (b.normals.size() == b.positions.size());
}

}  // namespace

void MorphAnimationBuilder::add_frame(const std::vector<GltfNode>& nodes) {
  if (frames_ == 0) {
    objects_.clear();
    for (const GltfNode& n : nodes) {
      Object o;
      o.name = n.name;
      o.color = n.color;
      o.materials = n.materials;
      o.inside_color = n.inside_color;
      o.inside_material = n.inside_material;
      if (n.mesh && !n.mesh->empty()) {
        validate_mesh(*n.mesh, "object '" + n.name + "'");
        o.segments.push_back(Segment{0, 1, *n.mesh, {}, {}, false});
      }
      objects_.push_back(std::move(o));
    }
    frames_ = 1;
    return;
  }
  if (nodes.size() != objects_.size())
    throw MeshIoError("animation frame " + std::to_string(frames_) + " has " + std::to_string(nodes.size()) +
                      " objects, the first frame had " + std::to_string(objects_.size()));
  // Check every object before storing anything, so a bad frame leaves the builder as it was.
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const GltfNode& n = nodes[i];
    const Object& o = objects_[i];
    const bool has_mesh = n.mesh && !n.mesh->empty();
    const auto mismatch = [&](const std::string& what) {
      return MeshIoError("object '" + n.name + "' in animation frame " + std::to_string(frames_) + ": " + what);
    };
    if (n.name != o.name) throw mismatch("expected object '" + o.name + "' at this position");
    if (has_mesh != !o.segments.empty()) throw mismatch("has a mesh in one frame and none in another");
    if (has_mesh) validate_mesh(*n.mesh, "object '" + n.name + "'");
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    Object& o = objects_[i];
    if (o.segments.empty()) continue;
    const TriMesh& m = *nodes[i].mesh;
    Segment& last = o.segments.back();
    if (!same_topology(last.base, m)) {  // a new mesh from this frame on (a DFFD split opened or closed, say)
      o.segments.push_back(Segment{frames_, 1, m, {}, {}, false});
      continue;
    }
    std::vector<float> dp = delta(last.base.positions, m.positions), dn;
    if (last.base.normals.size() == last.base.positions.size() && m.normals.size() == m.positions.size())
      dn = delta(last.base.normals, m.normals);
    last.changed = last.changed || !dp.empty() || !dn.empty();
    last.pos_delta.push_back(std::move(dp));
    last.nrm_delta.push_back(std::move(dn));
    ++last.frames;
  }
  ++frames_;
}

namespace {

// One TRIANGLES primitive of `m` (POSITION with bounds, NORMAL, TEXCOORD_0, uint32 indices) with the material.
tinygltf::Primitive add_primitive(tinygltf::Model& model, const TriMesh& m, const std::string& name,
                                  const glm::vec3& color) {
  const std::size_t nv = m.positions.size();
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] =
      add_floats(model, to_floats(m.positions), TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
  if (m.normals.size() == nv)
    prim.attributes["NORMAL"] =
        add_floats(model, to_floats(m.normals), TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  if (m.uvs.size() == nv) {
    std::vector<float> uv(nv * 2);
    for (std::size_t i = 0; i < nv; ++i)
      for (int c = 0; c < 2; ++c) uv[2 * i + c] = static_cast<float>(m.uvs[i][c]);
    prim.attributes["TEXCOORD_0"] = add_floats(model, uv, TINYGLTF_TYPE_VEC2, 2, TINYGLTF_TARGET_ARRAY_BUFFER, false);
  }
  std::vector<std::uint32_t> idx(m.triangles.size() * 3);
  for (std::size_t f = 0; f < m.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) idx[3 * f + c] = m.triangles[f][c];
  prim.indices = gltf_model::add_index_accessor(model, idx);
  prim.material = gltf_model::add_material(model, name, color);
  return prim;
}

// `prim` (all faces of `m`, with its targets) as one primitive per material slot the faces use, in slot order (slots
// past `set`'s end, or all without a set, in "<name>" of `color`), then one of the kMaterialInside faces, appended to
// `mesh`: same attributes and targets, their own indices.
// The kMaterialInside faces get `inside` (its first material) when given, else "<name>.inside" of `inside_color`.
void split_by_material(tinygltf::Model& model, gltf_materials::GltfMaterialWriter& writer, const std::string& name,
                       const glm::vec3& color, const std::shared_ptr<const MaterialSet>& set,
                       const glm::vec3& inside_color, const std::shared_ptr<const MaterialSet>& inside,
                       const TriMesh& m, const tinygltf::Primitive& prim, tinygltf::Mesh& mesh) {
  std::map<MaterialSlot, std::vector<std::uint32_t>> faces;  // slot → indices, in face order
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    std::vector<std::uint32_t>& idx = faces[m.material(f)];
    for (int c = 0; c < 3; ++c) idx.push_back(m.triangles[f][c]);
  }
  static const std::vector<int> kNone;
  const std::vector<int>& materials = set && !set->empty() ? writer.materials(set) : kNone;
  int fallback = prim.material;  // "<name>" of `color`, made with the primitive
  for (const auto& [slot, idx] : faces) {
    tinygltf::Primitive p = prim;
    p.indices = gltf_model::add_index_accessor(model, idx);
    if (slot == kMaterialInside) {
      p.material = inside && !inside->empty() ? writer.materials(inside)[0]
                                              : gltf_model::add_material(model, name + ".inside", inside_color);
    } else if (slot < materials.size()) {
      p.material = materials[slot];
    } else {
      if (fallback < 0) fallback = gltf_model::add_material(model, name, color);
      p.material = fallback;
    }
    mesh.primitives.push_back(std::move(p));
  }
}

}  // namespace

std::uint64_t MorphAnimationBuilder::glb_data_bytes() const {
  const std::uint64_t frames = static_cast<std::uint64_t>(frames_);
  std::uint64_t bytes = 4 * frames;  // key times
  for (const Object& o : objects_)
    for (const Segment& seg : o.segments) {
      const std::uint64_t nv = seg.base.positions.size(), nt = seg.base.triangles.size();
      const bool normals = seg.base.normals.size() == nv;
      // positions, normals, uvs and the indices (twice when split by material)
      bytes += nv * (12 + (normals ? 12 : 0) + (seg.base.uvs.size() == nv ? 8 : 0)) + nt * 12 * 2;
      const std::uint64_t targets = static_cast<std::uint64_t>(seg.frames - 1);
      if (seg.changed && targets > 0) bytes += targets * nv * (normals ? 24 : 12) + frames * targets * 4;
      if (o.segments.size() > 1) bytes += frames * 12;  // scale keys
    }
  return bytes;
}

namespace {

// An animation.glb being built (layout: gltf_anim_io.h): the model with its material writer and scene, the animation
// "recording" whose STEP channels all share one input (the #frames key times k/fps seconds, written with the first
// channel), and the node names used so far. The add_* members are templates over MorphAnimationBuilder's Object and
// Segment, which are private to the builder.
class MorphGlbModel {
 public:
  MorphGlbModel(int frames, double fps, int first_frame) : frames_(frames), first_frame_(first_frame), times_(frames) {
    model_.asset.version = "2.0";
    model_.asset.generator = "trispline";
    model_.buffers.resize(1);
    scene_.name = "Scene";  // named, so a scene without nodes is still written as an object (tinygltf drops `{}`)
    for (int k = 0; k < frames; ++k) times_[k] = static_cast<float>(k / fps);
    anim_.name = "recording";
  }
  MorphGlbModel(const MorphGlbModel&) = delete;
  MorphGlbModel& operator=(const MorphGlbModel&) = delete;

  // An object's node, named by the object: with one segment it holds the segment's mesh; otherwise (no mesh, or a
  // topology that changed during the recording) none, but one child node per segment (run of frames with one
  // topology).
  template <class Object>
  void add_object(const Object& o) {
    const int index = static_cast<int>(model_.nodes.size());
    model_.nodes.emplace_back();
    model_.nodes[index].name = unique(o.name);
    scene_.nodes.push_back(index);
    if (o.segments.size() == 1) {
      const int mesh = add_segment_mesh(o, o.segments[0], o.name, index);
      model_.nodes[index].mesh = mesh;
      return;
    }
    std::vector<int> children;
    for (const auto& seg : o.segments) children.push_back(add_segment_node(o, seg));
    model_.nodes[index].children = children;
  }

  // Adds the animation (when it has a channel) and the scene, then writes the .glb ("<path>.tmp" then renamed).
  void write(const std::filesystem::path& path) {
    if (!anim_.channels.empty()) model_.animations.push_back(std::move(anim_));
    model_.scenes.push_back(scene_);
    model_.defaultScene = 0;
    gltf_model::write_glb_atomically(model_, path);
  }

 private:
  // A STEP channel of `node`'s `path_name` ("weights", "scale") with `output` (#frames keys of `comps` floats).
  void add_channel(int node, const char* path_name, const std::vector<float>& output, int type, int comps) {
    if (times_accessor_ < 0) times_accessor_ = add_floats(model_, times_, TINYGLTF_TYPE_SCALAR, 1, 0, true);  // min/max
    tinygltf::AnimationSampler sampler;
    sampler.input = times_accessor_;
    sampler.output = add_floats(model_, output, type, comps, 0, false);
    sampler.interpolation = "STEP";
    anim_.samplers.push_back(sampler);
    tinygltf::AnimationChannel ch;
    ch.sampler = static_cast<int>(anim_.samplers.size()) - 1;
    ch.target_node = node;
    ch.target_path = path_name;
    anim_.channels.push_back(ch);
  }

  // Node names are unique in the file (a segment's "<object>/frames_NNNN-MMMM" cannot meet another name, but check):
  // `name`, or `name` + ".k" with the first k ≥ 1 not used yet.
  std::string unique(const std::string& name) {
    std::string out = name;
    for (int k = 1; used_.count(out); ++k) out = name + "." + std::to_string(k);
    used_[out] = 1;
    return out;
  }

  // A segment's child node "<object>/frames_NNNN-MMMM" (extras.frames = [NNNN, MMMM], timeline frames) with the
  // segment's mesh, shown (scale 1) on its frames and hidden (scale 0) on the others by STEP scale keys, as Blender
  // imports them; its rest scale is that of the recording's first frame. Returns the node index.
  template <class Object, class Segment>
  int add_segment_node(const Object& o, const Segment& seg) {
    char range[64];
    std::snprintf(range, sizeof range, "/frames_%04d-%04d", first_frame_ + seg.first,
                  first_frame_ + seg.first + seg.frames - 1);
    const int child = static_cast<int>(model_.nodes.size());
    model_.nodes.emplace_back();
    model_.nodes[child].name = unique(o.name + range);
    const int mesh = add_segment_mesh(o, seg, model_.nodes[child].name, child);
    model_.nodes[child].mesh = mesh;
    const bool shown_first = seg.first == 0;
    if (!shown_first) model_.nodes[child].scale = {0.0, 0.0, 0.0};
    tinygltf::Value::Object extras;
    extras["frames"] = tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(first_frame_ + seg.first), tinygltf::Value(first_frame_ + seg.first + seg.frames - 1)});
    model_.nodes[child].extras = tinygltf::Value(std::move(extras));
    std::vector<float> scale(static_cast<std::size_t>(frames_) * 3, 0.0f);
    for (int k = seg.first; k < seg.first + seg.frames; ++k)
      for (int c = 0; c < 3; ++c) scale[static_cast<std::size_t>(k) * 3 + c] = 1.0f;
    add_channel(child, "scale", scale, TINYGLTF_TYPE_VEC3, 3);
    return child;
  }

  // A segment as a mesh named `name` whose morph targets are its frames after the first (when any differs from its
  // first), one primitive per material slot when the object has materials or cut surfaces; `node` gets the weights
  // channel. Returns the mesh index.
  template <class Object, class Segment>
  int add_segment_mesh(const Object& o, const Segment& seg, const std::string& name, int node) {
    tinygltf::Primitive prim = add_primitive(model_, seg.base, o.name, o.color);
    tinygltf::Mesh mesh;
    mesh.name = name;
    if (seg.changed && seg.frames - 1 > 0) add_morph_targets(seg, node, prim, mesh);
    const auto& fm = seg.base.face_material;
    if ((o.materials && !o.materials->empty()) || std::find(fm.begin(), fm.end(), kMaterialInside) != fm.end())
      split_by_material(model_, writer_, o.name, o.color, o.materials, o.inside_color, o.inside_material, seg.base,
                        prim, mesh);
    else
      mesh.primitives.push_back(std::move(prim));
    model_.meshes.push_back(std::move(mesh));
    return static_cast<int>(model_.meshes.size()) - 1;
  }

  // The segment's #frames − 1 morph targets on `prim` (float POSITION and NORMAL deltas to its first frame, all
  // zeros for a frame equal to it), their names "frame_NNNN" and zero weights on `mesh`, and `node`'s weights channel:
  // at key k (of the recording) inside the segment target k − first − 1 weighs 1 and the others 0; elsewhere all 0.
  template <class Segment>
  void add_morph_targets(const Segment& seg, int node, tinygltf::Primitive& prim, tinygltf::Mesh& mesh) {
    const int targets = seg.frames - 1;
    const std::size_t nv = seg.base.positions.size();
    const bool normals = seg.base.normals.size() == nv;
    const std::vector<float> zeros(nv * 3, 0.0f);
    tinygltf::Value::Array names;
    for (int k = 0; k < targets; ++k) {
      const std::vector<float>& dp = seg.pos_delta[k].empty() ? zeros : seg.pos_delta[k];
      std::map<std::string, int> target;
      // Morph target POSITION accessors need min/max (glTF 2.0 §3.7.2.2).
      target["POSITION"] = add_floats(model_, dp, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, true);
      if (normals) {
        const std::vector<float>& dn = seg.nrm_delta[k].empty() ? zeros : seg.nrm_delta[k];
        target["NORMAL"] = add_floats(model_, dn, TINYGLTF_TYPE_VEC3, 3, TINYGLTF_TARGET_ARRAY_BUFFER, false);
      }
      prim.targets.push_back(std::move(target));
      names.emplace_back(target_name(first_frame_ + seg.first + k + 1));
    }
    mesh.weights.assign(targets, 0.0);
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(std::move(names));
    mesh.extras = tinygltf::Value(std::move(extras));
    std::vector<float> weights(static_cast<std::size_t>(frames_) * targets, 0.0f);
    for (int k = seg.first + 1; k < seg.first + seg.frames; ++k)
      weights[static_cast<std::size_t>(k) * targets + (k - seg.first - 1)] = 1.0f;
    add_channel(node, "weights", weights, TINYGLTF_TYPE_SCALAR, 1);
  }

  int frames_;
  int first_frame_;
  tinygltf::Model model_;
  gltf_materials::GltfMaterialWriter writer_{model_};
  tinygltf::Scene scene_;
  std::vector<float> times_;  // the key times, seconds
  tinygltf::Animation anim_;
  int times_accessor_ = -1;  // times_'s accessor once a channel was added
  std::map<std::string, int> used_;
};

}  // namespace

void MorphAnimationBuilder::write_glb(const std::filesystem::path& path) const {
  if (frames_ == 0) throw MeshIoError(quoted(path) + ": no frames recorded");
  if (const std::uint64_t bytes = glb_data_bytes(); bytes > kMaxAnimationGlbBytes)
    throw MeshIoError(quoted(path) + ": an animation of " + std::to_string(frames_) + " frames would take " +
                      std::to_string(bytes >> 20) + " MiB, over the " + std::to_string(kMaxAnimationGlbBytes >> 20) +
                      " MiB an animation.glb may take (morph targets grow with the square of the frames): record a "
                      "shorter range, or fewer changing objects");
  MorphGlbModel glb(frames_, fps_, first_frame_);
  for (const Object& o : objects_) glb.add_object(o);
  glb.write(path);
}

MorphAnimationInfo read_morph_animation_info(const std::filesystem::path& path) {
  const tinygltf::Model model = load(path);
  MorphAnimationInfo info;
  for (const tinygltf::Mesh& m : model.meshes) {
    MorphAnimationInfo::Mesh mi;
    mi.name = m.name;
    if (!m.primitives.empty()) {
      const tinygltf::Primitive& p = m.primitives.front();
      const auto pos = p.attributes.find("POSITION");
      if (pos != p.attributes.end() && pos->second >= 0 && pos->second < static_cast<int>(model.accessors.size()))
        mi.vertices = model.accessors[pos->second].count;
      mi.targets = static_cast<int>(p.targets.size());
    }
    if (m.extras.IsObject() && m.extras.Has("targetNames")) {
      const tinygltf::Value& names = m.extras.Get("targetNames");
      for (std::size_t i = 0; names.IsArray() && i < names.ArrayLen(); ++i)
        if (names.Get(static_cast<int>(i)).IsString())
          mi.target_names.push_back(names.Get(static_cast<int>(i)).Get<std::string>());
    }
    info.meshes.push_back(std::move(mi));
  }
  info.animations = static_cast<int>(model.animations.size());
  for (const tinygltf::Animation& a : model.animations)
    for (const tinygltf::AnimationChannel& ch : a.channels) {
      info.weight_channels += ch.target_path == "weights";
      info.scale_channels += ch.target_path == "scale";
    }
  if (!model.animations.empty() && !model.animations.front().samplers.empty()) {
    const tinygltf::AnimationSampler& s = model.animations.front().samplers.front();
    info.interpolation = s.interpolation;
    if (s.input >= 0 && s.input < static_cast<int>(model.accessors.size())) {
      const tinygltf::Accessor& in = model.accessors[s.input];
      info.keyframes = static_cast<int>(in.count);
      if (!in.maxValues.empty()) info.duration_s = in.maxValues.front();
    }
  }
  return info;
}

std::vector<glm::dvec3> read_morph_frame_positions(const std::filesystem::path& path, const std::string& mesh_name,
                                                   int frame) {
  const tinygltf::Model model = load(path);
  for (const tinygltf::Mesh& m : model.meshes) {
    if (m.name != mesh_name || m.primitives.empty()) continue;
    const tinygltf::Primitive& p = m.primitives.front();
    const auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) throw MeshIoError(quoted(path) + ": mesh '" + mesh_name + "' has no POSITION");
    std::vector<glm::dvec3> out = read_vec3(model, pos->second, path);
    if (frame == 0) return out;
    if (frame < 0 || frame > static_cast<int>(p.targets.size()))
      throw MeshIoError(quoted(path) + ": mesh '" + mesh_name + "' has no frame " + std::to_string(frame) + " (" +
                        std::to_string(p.targets.size()) + " morph targets)");
    const auto d = p.targets[frame - 1].find("POSITION");
    if (d == p.targets[frame - 1].end()) return out;
    const std::vector<glm::dvec3> delta_pos = read_vec3(model, d->second, path);
    if (delta_pos.size() != out.size()) throw MeshIoError(quoted(path) + ": morph target size mismatch");
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::dvec3(glm::vec3(out[i]) + glm::vec3(delta_pos[i]));
    return out;
  }
  throw MeshIoError(quoted(path) + ": no mesh named '" + mesh_name + "'");
}

}  // namespace trispline::core
