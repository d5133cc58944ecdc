#include "core/mesh/mesh_clip.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>
#include <stdexcept>

#include "core/mesh/gltf_model.h"
#include "core/mesh/mesh_clip_gltf.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {

double wrap_clip_time(double time_s, double start_s, double speed, double duration_s, bool loop) {
  if (!(duration_s > 0)) return 0.0;
  const double t = (time_s - start_s) * speed;
  if (!loop) return std::clamp(t, 0.0, duration_s);
  const double w = t - duration_s * std::floor(t / duration_s);
  return w >= duration_s ? 0.0 : w;  // rounding can give exactly duration_s
}

namespace {

using namespace clip_gltf;

enum class Path { Translation, Rotation, Scale, Weights };

struct Channel {
  int node = -1;
  Path path = Path::Translation;
  int sampler = -1;
};

struct NodeRest {
  int parent = -1;
  bool has_matrix = false;
  glm::dmat4 matrix{1.0};
  glm::dvec3 t{0.0}, s{1.0};
  glm::dquat r{1.0, 0.0, 0.0, 0.0};
};

struct Pose {  // node locals and weights at one time
  std::vector<glm::dvec3> t, s;
  std::vector<glm::dquat> r;
  std::vector<std::vector<double>> weights;  // per node, empty = not animated
};

// One mesh-carrying node as read_gltf_objects visits it: vertices [begin, end) of the concatenated mesh.
struct Instance {
  int node = -1, skin = -1;
  std::size_t begin = 0, end = 0;
  glm::dmat4 rest_xf{1.0};                // the node's world transform as load_mesh bakes it
  std::vector<double> default_weights;    // #targets: node.weights, else mesh.weights, else 0
  std::vector<glm::dvec3> dpos, dnrm;     // #targets × (end − begin) morph deltas, mesh-local
  std::vector<glm::dmat4> rest_skin_inv;  // #(end − begin) or empty when the rest pose is the bind pose
};

struct Skin {
  std::vector<int> joints;
  std::vector<glm::dmat4> ibm;
};

bool is_surface(const tinygltf::Primitive& prim) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

}  // namespace

struct MeshClip::Impl {
  std::vector<NodeRest> nodes;
  std::vector<int> node_order;  // parents before children
  std::vector<AnimSampler> samplers;
  std::vector<Channel> channels;
  std::vector<Skin> skins;
  std::vector<Instance> instances;
  std::vector<glm::dvec3> base_pos, base_nrm;  // #V mesh-local (before the node transform); base_nrm empty if none
  std::vector<std::size_t> infl_begin;         // #V + 1 offsets into infl (empty when no instance is skinned)
  std::vector<std::pair<int, double>> infl;    // (joint slot in the instance's skin, weight)
  std::vector<glm::uvec3> triangles;           // load_mesh's, for recomputed normals

  Pose rest_pose() const;
  void apply(double t, Pose& pose) const;
  std::vector<glm::dmat4> globals(const Pose& pose) const;
  void evaluate(const Pose& pose, std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) const;
};

Pose MeshClip::Impl::rest_pose() const {
  Pose p;
  p.t.resize(nodes.size());
  p.r.resize(nodes.size());
  p.s.resize(nodes.size());
  p.weights.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) p.t[i] = nodes[i].t, p.r[i] = nodes[i].r, p.s[i] = nodes[i].s;
  return p;
}

void MeshClip::Impl::apply(double t, Pose& pose) const {
  double buf[4];
  for (const auto& ch : channels) {
    const AnimSampler& smp = samplers[ch.sampler];
    if (ch.path == Path::Weights) {
      auto& w = pose.weights[ch.node];
      w.assign(smp.width, 0.0);
      sample_channel(smp, t, false, w.data());
      continue;
    }
    sample_channel(smp, t, ch.path == Path::Rotation, buf);
    if (ch.path == Path::Translation) pose.t[ch.node] = {buf[0], buf[1], buf[2]};
    if (ch.path == Path::Scale) pose.s[ch.node] = {buf[0], buf[1], buf[2]};
    if (ch.path == Path::Rotation) pose.r[ch.node] = glm::dquat(buf[3], buf[0], buf[1], buf[2]);
  }
}

std::vector<glm::dmat4> MeshClip::Impl::globals(const Pose& pose) const {
  std::vector<glm::dmat4> g(nodes.size());
  for (int i : node_order) {
    const NodeRest& n = nodes[i];
    const glm::dmat4 local = n.has_matrix ? n.matrix : node_trs(pose.t[i], pose.r[i], pose.s[i]);
    g[i] = n.parent < 0 ? local : g[n.parent] * local;
  }
  return g;
}

// Vertex pipeline, per instance: morph (rest-relative weights), then skin (rest-relative, see load()) or the node's
// animated world transform; normals by the inverse transpose of the same linear map, renormalised.
void MeshClip::Impl::evaluate(const Pose& pose, std::vector<glm::dvec3>& positions,
                              std::vector<glm::dvec3>& normals) const {
  const std::size_t nv = base_pos.size();
  positions.resize(nv);
  const bool file_normals = !base_nrm.empty();
  normals.resize(nv);
  const std::vector<glm::dmat4> g = globals(pose);
  for (const Instance& in : instances) {
    const std::size_t count = in.end - in.begin, nt = in.default_weights.size();
    const std::vector<double>& w = pose.weights[in.node].empty() ? in.default_weights : pose.weights[in.node];
    std::vector<glm::dmat4> joint_m;
    if (in.skin >= 0) {
      const Skin& sk = skins[in.skin];
      joint_m.resize(sk.joints.size());
      for (std::size_t j = 0; j < sk.joints.size(); ++j) joint_m[j] = g[sk.joints[j]] * sk.ibm[j];
    }
    const glm::dmat4& node_m = g[in.node];
    const glm::dmat3 node_n = glm::inverseTranspose(glm::dmat3(node_m));
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t v = in.begin + i;
      glm::dvec3 p = base_pos[v];
      glm::dvec3 n = file_normals ? base_nrm[v] : glm::dvec3(0.0);
      for (std::size_t k = 0; k < nt; ++k) {
        const double f = (k < w.size() ? w[k] : in.default_weights[k]) - in.default_weights[k];
        if (f == 0) continue;
        p += f * in.dpos[k * count + i];
        if (file_normals) n += f * in.dnrm[k * count + i];
      }
      const bool skinned = in.skin >= 0 && infl_begin[v] < infl_begin[v + 1];
      if (!skinned) {
        positions[v] = glm::dvec3(node_m * glm::dvec4(p, 1.0));
        if (file_normals) n = node_n * n;
      } else {
        glm::dmat4 b(0.0);
        for (std::size_t q = infl_begin[v]; q < infl_begin[v + 1]; ++q) b += infl[q].second * joint_m[infl[q].first];
        const glm::dmat4 m = in.rest_skin_inv.empty() ? in.rest_xf * b : in.rest_xf * in.rest_skin_inv[i] * b;
        positions[v] = glm::dvec3(m * glm::dvec4(p, 1.0));
        if (file_normals) n = glm::inverseTranspose(glm::dmat3(m)) * n;
      }
      if (file_normals) {
        const double len = glm::length(n);
        normals[v] = len > 0 && std::isfinite(len) ? n / len : glm::dvec3(0, 1, 0);
      }
    }
  }
  if (!file_normals) {
    TriMesh m;
    m.positions = positions;
    m.triangles = triangles;
    compute_vertex_normals(m);
    normals = std::move(m.normals);
  }
}

namespace {
std::vector<std::string> animation_names(const tinygltf::Model& model) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < model.animations.size(); ++i)
    names.push_back(model.animations[i].name.empty() ? "animation_" + std::to_string(i) : model.animations[i].name);
  return names;
}
}  // namespace

std::vector<std::string> MeshClip::list(const std::filesystem::path& path) {
  return animation_names(gltf_read::read_model(path));
}

void MeshClip::pose(double t_s, std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& normals) const {
  if (!std::isfinite(t_s))
    throw std::invalid_argument(quoted_path(path_) + " clip '" + name_ + "': non-finite clip time");
  Pose p = impl_->rest_pose();
  impl_->apply(std::clamp(t_s, 0.0, duration_s_), p);
  impl_->evaluate(p, positions, normals);
}

namespace {

void require_finite(const std::vector<double>& v, const std::string& msg) {
  for (double x : v)
    if (!std::isfinite(x)) throw MeshIoError(msg);
}

// Picks the animation: "" = first, "#i" = i-th, else its name (or "animation_<i>" for an unnamed one).
int pick_animation(const std::vector<std::string>& names, const std::string& clip, const std::string& file) {
  if (names.empty()) throw std::invalid_argument(file + ": the file has no animations");
  if (clip.empty()) return 0;
  if (clip == kAllClips) return -1;
  if (clip[0] == '#' && clip.size() > 1 && clip.size() < 10 &&
      std::all_of(clip.begin() + 1, clip.end(), [](unsigned char c) { return std::isdigit(c); })) {
    const int i = std::stoi(clip.substr(1));
    if (i < static_cast<int>(names.size())) return i;
  }
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == clip) return static_cast<int>(i);
  std::string all;
  for (const auto& n : names) all += (all.empty() ? "'" : ", '") + n + "'";
  throw std::invalid_argument(file + ": no clip '" + clip + "' (the file's clips: " + all + ")");
}

// Mesh-carrying nodes in read_gltf_objects' order: the default scene's roots (else every scene's), depth first
// (read_model checked that the nodes form a forest, so this ends).
std::vector<int> mesh_nodes_in_load_order(const tinygltf::Model& model, const std::string& file) {
  const std::vector<int> roots = gltf_model::root_nodes(model);
  std::vector<int> stack(roots.rbegin(), roots.rend());
  std::vector<int> out;
  while (!stack.empty()) {
    const int node = stack.back();
    stack.pop_back();
    if (node < 0 || node >= static_cast<int>(model.nodes.size())) throw MeshIoError(file + ": invalid node hierarchy");
    if (model.nodes[node].mesh >= 0) out.push_back(node);
    const auto& ch = model.nodes[node].children;
    stack.insert(stack.end(), ch.rbegin(), ch.rend());
  }
  return out;
}

}  // namespace

namespace {

// The steps of MeshClip::load, in order; each throws as load() documents. Everything decoded or held besides the
// vertices is charged to one budget (values_left), before it is allocated.
struct ClipReader {
  const tinygltf::Model& model;
  const std::filesystem::path& path;
  const std::string file;   // quoted path, for messages
  const std::string where;  // file and clip, for messages about the clip
  MeshClip::Impl& im;
  std::size_t values_left = gltf_read::kMaxClipValues;
  bool file_normals = true;
  std::size_t total_vertices = 0;

  MeshIoError over_budget(const std::string& what) const {
    return MeshIoError(file + ": the clip's " + what + " need more than " + std::to_string(gltf_read::kMaxClipValues) +
                       " numbers (the limit for a clip)");
  }
  void charge(std::size_t items, std::size_t per_item, const std::string& what) {
    if (per_item != 0 && items > values_left / per_item) throw over_budget(what);
    values_left -= items * per_item;
  }

  void read_nodes();
  void read_skins();
  void read_vertices();
  void read_instance(int node);
  std::size_t read_primitive(const tinygltf::Mesh& gm, const tinygltf::Primitive& prim, Instance& in, std::size_t nt,
                             std::size_t count, std::size_t off);
  void bind_rest(const Pose& rest_pose);
  double read_channels(const std::vector<int>& ais);
};

// Nodes: rest TRS (or fixed matrix), parents, and an order with parents first.
void ClipReader::read_nodes() {
  const std::size_t nn = model.nodes.size();
  im.nodes.resize(nn);
  std::vector<std::vector<int>> kids(nn);
  for (std::size_t i = 0; i < nn; ++i) {
    const auto& n = model.nodes[i];
    NodeRest& r = im.nodes[i];
    r.has_matrix = n.matrix.size() == 16;
    if (r.has_matrix) r.matrix = glm::make_mat4(n.matrix.data());
    if (n.translation.size() == 3) r.t = glm::make_vec3(n.translation.data());
    if (n.rotation.size() == 4) r.r = glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
    if (n.scale.size() == 3) r.s = glm::make_vec3(n.scale.data());
    for (int c : n.children) {
      if (c < 0 || c >= static_cast<int>(nn) || im.nodes[c].parent >= 0 || c == static_cast<int>(i))
        throw MeshIoError(file + ": invalid node hierarchy (child index out of range or node with two parents)");
      im.nodes[c].parent = static_cast<int>(i);
      kids[i].push_back(c);
    }
  }
  for (std::size_t i = 0; i < nn; ++i)
    if (im.nodes[i].parent < 0) {
      std::vector<int> stack{static_cast<int>(i)};
      while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        im.node_order.push_back(n);
        stack.insert(stack.end(), kids[n].begin(), kids[n].end());
      }
    }
  if (im.node_order.size() != nn) throw MeshIoError(file + ": invalid node hierarchy (cycle)");
}

void ClipReader::read_skins() {
  const std::size_t nn = model.nodes.size();
  for (const auto& s : model.skins) {
    Skin sk;
    sk.joints = s.joints;
    for (int j : sk.joints)
      if (j < 0 || j >= static_cast<int>(nn)) throw MeshIoError(file + ": skin joint index out of range");
    sk.ibm.assign(sk.joints.size(), glm::dmat4(1.0));  // §3.7.3.1: identity when inverseBindMatrices is absent
    if (s.inverseBindMatrices >= 0) {
      const std::size_t count =
          gltf_read::accessor_layout(model, s.inverseBindMatrices, "inverseBindMatrices", path).count;
      if (count < sk.joints.size()) throw MeshIoError(file + ": fewer inverse bind matrices than joints");
      charge(count, 16, "inverse bind matrices");
      const auto m = gltf_read::read_accessor(model, s.inverseBindMatrices, 16, "inverseBindMatrices", path, count);
      require_finite(m, file + ": non-finite inverse bind matrix");
      for (std::size_t j = 0; j < sk.joints.size(); ++j) sk.ibm[j] = glm::make_mat4(m.data() + 16 * j);
    }
    im.skins.push_back(std::move(sk));
  }
}

// Vertices, exactly as read_gltf_objects concatenates them: mesh nodes in load order, surface primitives in order.
void ClipReader::read_vertices() {
  im.infl_begin.push_back(0);
  for (int node : mesh_nodes_in_load_order(model, file)) read_instance(node);
  if (!file_normals) im.base_nrm.clear();
}

void ClipReader::read_instance(int node) {
  const auto& gn = model.nodes[node];
  if (gn.mesh >= static_cast<int>(model.meshes.size())) throw MeshIoError(file + ": node refers to a missing mesh");
  const auto& gm = model.meshes[gn.mesh];
  Instance in;
  in.node = node;
  in.skin = gn.skin;
  if (in.skin >= static_cast<int>(im.skins.size())) throw MeshIoError(file + ": node refers to a missing skin");
  in.begin = im.base_pos.size();
  std::size_t nt = 0, count = 0;
  bool first = true;
  for (const auto& prim : gm.primitives) {
    if (!is_surface(prim)) continue;
    if (!first && prim.targets.size() != nt)
      throw MeshIoError(file + ": mesh '" + gm.name + "' primitives have different morph target counts");
    nt = prim.targets.size(), first = false;
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) throw MeshIoError(file + ": primitive without POSITION");
    const std::size_t n = gltf_read::accessor_layout(model, pos->second, "POSITION", path).count;
    if (n > gltf_read::kMaxMeshFileVertices - total_vertices)
      throw MeshIoError(file + ": the file's meshes have more than " + std::to_string(gltf_read::kMaxMeshFileVertices) +
                        " vertices (the limit for mesh files)");
    total_vertices += n;
    count += n;
  }
  charge(nt, count * 6, "morph targets");  // dpos and dnrm: 2 × 3 doubles per target and vertex
  in.dpos.assign(nt * count, glm::dvec3(0.0));
  in.dnrm.assign(nt * count, glm::dvec3(0.0));
  in.default_weights.assign(nt, 0.0);
  const auto& dw = gn.weights.empty() ? gm.weights : gn.weights;
  for (std::size_t k = 0; k < nt && k < dw.size(); ++k) in.default_weights[k] = dw[k];
  std::size_t off = 0;
  for (const auto& prim : gm.primitives) {
    if (!is_surface(prim)) continue;
    off += read_primitive(gm, prim, in, nt, count, off);
  }
  in.end = im.base_pos.size();
  im.instances.push_back(std::move(in));
}

// One surface primitive of `in` at vertex offset `off` (of `count`) in the instance: positions, normals, nt morph
// deltas, skin influences. Returns its vertex count.
std::size_t ClipReader::read_primitive(const tinygltf::Mesh& gm, const tinygltf::Primitive& prim, Instance& in,
                                       std::size_t nt, std::size_t count, std::size_t off) {
  auto attr = [&](const std::map<std::string, int>& attrs, const std::string& key) {
    const auto it = attrs.find(key);
    return it == attrs.end() ? -1 : it->second;
  };
  const int pi = attr(prim.attributes, "POSITION");
  const std::size_t n = gltf_read::accessor_layout(model, pi, "POSITION", path).count;  // counted above
  // An attribute, morph delta, joint or weight accessor of this primitive: exactly n elements.
  auto require_n = [&](int index, const std::string& what) {
    const std::size_t c = gltf_read::accessor_layout(model, index, what, path).count;
    if (c != n)
      throw MeshIoError(file + ": mesh '" + gm.name + "': " + what + " has " + std::to_string(c) +
                        " elements, POSITION has " + std::to_string(n));
  };
  const auto pos = gltf_read::read_accessor(model, pi, 3, "POSITION", path, n, false);
  require_finite(pos, file + ": non-finite POSITION value");
  for (std::size_t i = 0; i < n; ++i) im.base_pos.push_back(glm::make_vec3(pos.data() + 3 * i));
  const int ni = attr(prim.attributes, "NORMAL");
  if (ni >= 0 && file_normals) {
    require_n(ni, "NORMAL");
    const auto nrm = gltf_read::read_accessor(model, ni, 3, "NORMAL", path, n, false);
    require_finite(nrm, file + ": non-finite NORMAL value");
    for (std::size_t i = 0; i < n; ++i) im.base_nrm.push_back(glm::make_vec3(nrm.data() + 3 * i));
  }
  file_normals = file_normals && ni >= 0 && im.base_nrm.size() == im.base_pos.size();
  for (std::size_t k = 0; k < nt; ++k) {
    for (const char* key : {"POSITION", "NORMAL"}) {
      const int ti = attr(prim.targets[k], key);
      if (ti < 0) continue;
      const std::string what = std::string("morph target ") + key;
      require_n(ti, what);
      const auto d = gltf_read::read_accessor(model, ti, 3, what, path, n);
      require_finite(d, file + ": non-finite morph target " + key);
      auto& dst = key[0] == 'P' ? in.dpos : in.dnrm;
      for (std::size_t i = 0; i < n; ++i) dst[k * count + off + i] = glm::make_vec3(d.data() + 3 * i);
    }
  }
  std::vector<std::vector<std::pair<int, double>>> vi(n);
  for (int set = 0; in.skin >= 0; ++set) {
    const int ji = attr(prim.attributes, "JOINTS_" + std::to_string(set));
    const int wi = attr(prim.attributes, "WEIGHTS_" + std::to_string(set));
    if (ji < 0 || wi < 0) break;
    require_n(ji, "JOINTS_" + std::to_string(set));
    require_n(wi, "WEIGHTS_" + std::to_string(set));
    charge(n, 16, "skin influences");  // 4 joints + 4 weights decoded, up to 4 influences of 2 numbers kept
    const auto jv = gltf_read::read_accessor(model, ji, 4, "JOINTS", path, n);
    const auto wv = gltf_read::read_accessor(model, wi, 4, "WEIGHTS", path, n);
    require_finite(wv, file + ": non-finite skin weight");
    for (std::size_t q = 0; q < 4 * n; ++q) {
      if (wv[q] == 0) continue;
      if (!(jv[q] >= 0 && jv[q] < static_cast<double>(im.skins[in.skin].joints.size())))
        throw MeshIoError(file + ": skin joint index out of range in JOINTS_" + std::to_string(set));
      vi[q / 4].push_back({static_cast<int>(jv[q]), wv[q]});
    }
  }
  for (const auto& list : vi) {
    im.infl.insert(im.infl.end(), list.begin(), list.end());
    im.infl_begin.push_back(im.infl.size());
  }
  return n;
}

// Rest transforms (node TRS): load_mesh's node transforms, and the rest skin matrices that skinning is made
// relative to, so the clip's rest pose is load_mesh's mesh even when the rest pose is not the bind pose.
void ClipReader::bind_rest(const Pose& rest_pose) {
  const std::vector<glm::dmat4> g0 = im.globals(rest_pose);
  for (Instance& in : im.instances) {
    in.rest_xf = g0[in.node];
    if (in.skin < 0) continue;
    const Skin& sk = im.skins[in.skin];
    bool bind_is_rest = true;
    for (std::size_t v = in.begin; v < in.end; ++v) {
      glm::dmat4 b(0.0);
      for (std::size_t q = im.infl_begin[v]; q < im.infl_begin[v + 1]; ++q)
        b += im.infl[q].second * (g0[sk.joints[im.infl[q].first]] * sk.ibm[im.infl[q].first]);
      double scale = 0;  // singular relative to the matrix's size
      for (int c = 0; c < 3; ++c) scale = std::max(scale, glm::length(glm::dvec3(b[c])));
      if (!(std::abs(glm::determinant(glm::dmat3(b))) > 1e-12 * scale * scale * scale) &&
          im.infl_begin[v] < im.infl_begin[v + 1])
        throw std::invalid_argument(where + ": vertex " + std::to_string(v) + " has a singular rest skin matrix");
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) bind_is_rest = bind_is_rest && std::abs(b[c][r] - (c == r)) < 1e-12;
      in.rest_skin_inv.push_back(im.infl_begin[v] < im.infl_begin[v + 1] ? glm::inverse(b) : glm::dmat4(1.0));
    }
    if (bind_is_rest) in.rest_skin_inv.clear();
  }
}

// Channels (§3.11) of the animations `ais`, one after another: only translation/rotation/scale/weights; a channel
// without a node is ignored (spec). Returns the clip's duration in seconds.
double ClipReader::read_channels(const std::vector<int>& ais) {
  const std::size_t nn = model.nodes.size();
  std::vector<char> moves(nn, 0), morphs(nn, 0);
  auto mark_up = [&](int n) {
    for (; n >= 0 && !moves[n]; n = im.nodes[n].parent) moves[n] = 1;
  };
  for (const Instance& in : im.instances) {
    if (!in.default_weights.empty()) morphs[in.node] = 1;
    if (in.skin < 0)
      mark_up(in.node);
    else
      for (int j : im.skins[in.skin].joints) mark_up(j);
  }
  bool animates_mesh = false;
  double duration = 0;
  // Each channel decodes its sampler (several may share one): the sum is checked before the first is read.
  std::size_t keys_and_values = 0;
  for (int ai : ais)
    for (const auto& ch : model.animations[ai].channels) {
      const auto& anim = model.animations[ai];
      const std::string& p = ch.target_path;
      if (ch.target_node < 0 || ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size()) ||
          (p != "translation" && p != "rotation" && p != "scale" && p != "weights"))
        continue;
      const auto in = gltf_read::accessor_layout(model, anim.samplers[ch.sampler].input, "sampler input", path);
      const auto out = gltf_read::accessor_layout(model, anim.samplers[ch.sampler].output, "sampler output", path);
      keys_and_values += std::min(in.count, values_left + 1) + std::min(out.count, values_left + 1) * out.comps;
      if (keys_and_values > values_left) throw over_budget("keys and other animation data");
    }  // read_sampler takes them from values_left as it reads
  for (int ai : ais)
    for (std::size_t c = 0; c < model.animations[ai].channels.size(); ++c) {
      const auto& anim = model.animations[ai];
      const auto& ch = anim.channels[c];
      const std::string at = where + ": " + (ais.size() > 1 ? "animation " + std::to_string(ai) + " " : std::string()) +
                             "channel " + std::to_string(c);
      Channel out;
      out.node = ch.target_node;
      const std::string& p = ch.target_path;
      if (out.node < 0) continue;
      if (out.node >= static_cast<int>(nn)) throw std::invalid_argument(at + " targets a missing node");
      if (p == "translation")
        out.path = Path::Translation;
      else if (p == "rotation")
        out.path = Path::Rotation;
      else if (p == "scale")
        out.path = Path::Scale;
      else if (p == "weights")
        out.path = Path::Weights;
      else
        continue;
      if (out.path != Path::Weights && im.nodes[out.node].has_matrix)
        throw std::invalid_argument(at + " animates a node that has a matrix (glTF 2.0 §3.5.3 forbids it)");
      if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size()))
        throw std::invalid_argument(at + " refers to a missing sampler");
      const auto& as = anim.samplers[ch.sampler];
      int width = out.path == Path::Rotation ? 4 : 3;
      if (out.path == Path::Weights) {
        const int m = model.nodes[out.node].mesh;
        width = m >= 0 && m < static_cast<int>(model.meshes.size()) && !model.meshes[m].primitives.empty()
                    ? static_cast<int>(model.meshes[m].primitives.front().targets.size())
                    : 0;
        if (width == 0) throw std::invalid_argument(at + " animates weights of a node without morph targets");
      }
      const int comps = out.path == Path::Weights ? 1 : width;
      AnimSampler smp = read_sampler(model, as, width, comps, out.path == Path::Rotation, at, path, values_left);
      duration = std::max(duration, smp.times.back());
      animates_mesh = animates_mesh || (out.path == Path::Weights ? morphs[out.node] : moves[out.node]);
      out.sampler = static_cast<int>(im.samplers.size());
      im.samplers.push_back(std::move(smp));
      im.channels.push_back(out);
    }
  if (!animates_mesh) throw std::invalid_argument(where + ": the clip animates no mesh that load_mesh includes");
  return duration;
}

}  // namespace

std::shared_ptr<const MeshClip> MeshClip::load(const std::filesystem::path& path, const std::string& clip) {
  const TriMesh rest = load_mesh(path);  // MeshIoError for file problems; the vertices the clip must reproduce
  const tinygltf::Model model = gltf_read::read_model(path);  // checked: indices in range, nodes a forest
  const std::string file = quoted_path(path);
  const std::vector<std::string> names = animation_names(model);
  const int ai = pick_animation(names, clip, file);
  std::vector<int> ais{ai};
  if (ai < 0) {  // every animation, played together
    ais.resize(names.size());
    for (std::size_t i = 0; i < ais.size(); ++i) ais[i] = static_cast<int>(i);
  }
  const std::string name = ai < 0 ? std::string(kAllClips) : names[ai];
  const std::string where = file + " clip '" + name + "'";
  if (model.nodes.empty()) throw std::invalid_argument(where + ": the file has no nodes to animate");

  auto im = std::make_shared<Impl>();
  ClipReader reader{model, path, file, where, *im};
  reader.read_nodes();
  reader.read_skins();
  reader.read_vertices();
  if (im->base_pos.size() != rest.positions.size())
    throw MeshIoError(file + ": clip mesh has " + std::to_string(im->base_pos.size()) + " vertices, load_mesh " +
                      std::to_string(rest.positions.size()));
  im->triangles = rest.triangles;
  const Pose rest_pose = im->rest_pose();
  reader.bind_rest(rest_pose);
  const double duration = reader.read_channels(ais);

  // Self-check: the rest pose must reproduce load_mesh (guards the two readers against drifting apart).
  std::vector<glm::dvec3> pos, nrm;
  im->evaluate(rest_pose, pos, nrm);
  const double tol = 1e-9 * (1.0 + mesh_bounds(rest).diagonal());
  for (std::size_t v = 0; v < pos.size(); ++v)
    if (!(glm::length(pos[v] - rest.positions[v]) <= tol))
      throw MeshIoError(where + ": rest pose differs from load_mesh at vertex " + std::to_string(v));

  auto out = std::make_shared<MeshClip>();
  out->name_ = name;
  out->path_ = path;
  out->duration_s_ = duration;
  out->rest_positions_ = rest.positions;
  out->impl_ = std::move(im);
  return out;
}
}  // namespace trispline::core
