// core::MeshClip: synthetic clips written here with tinygltf (CUBICSPLINE, STEP, default weights, errors) and, when
// the asset script has fetched them at configure time, the real clips from Debian's assimp-testmodels
// (AnimatedMorphCube: morph weights; simple_skin: the glTF tutorial skin). Expected values are computed from the
// files' accessor data with a reader independent of mesh_clip.cpp.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/mesh/gltf_io.h"
#include "core/mesh/mesh_clip.h"
#include "core/mesh/mesh_io.h"
#include "mesh_test_util.h"

namespace trispline::core {
namespace {

using test::TempDir;

double max_dist(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
  return d;
}

// Float accessor → doubles (tightly packed or strided), the test's own reader.
std::vector<double> floats(const tinygltf::Model& m, int index) {
  const auto& a = m.accessors.at(index);
  const auto& v = m.bufferViews.at(a.bufferView);
  const int comps = tinygltf::GetNumComponentsInType(a.type);
  const std::size_t stride = v.byteStride ? v.byteStride : 4 * comps;
  std::vector<double> out;
  for (std::size_t i = 0; i < a.count; ++i)
    for (int c = 0; c < comps; ++c) {
      float f;
      std::memcpy(&f, m.buffers.at(v.buffer).data.data() + v.byteOffset + a.byteOffset + stride * i + 4 * c, 4);
      out.push_back(f);
    }
  return out;
}

// ---- synthetic clips -----------------------------------------------------------------------------------------------

struct Builder {
  tinygltf::Model m;
  Builder() {
    m.asset.version = "2.0";
    m.buffers.resize(1);
  }
  int accessor(const std::vector<float>& data, int type) {
    auto& buf = m.buffers[0].data;
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buf.size();
    view.byteLength = data.size() * 4;
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    buf.insert(buf.end(), p, p + data.size() * 4);
    m.bufferViews.push_back(view);
    tinygltf::Accessor acc;
    acc.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
    acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    acc.type = type;
    acc.count = data.size() / tinygltf::GetNumComponentsInType(type);
    if (type == TINYGLTF_TYPE_SCALAR) {
      acc.minValues = {*std::min_element(data.begin(), data.end())};
      acc.maxValues = {*std::max_element(data.begin(), data.end())};
    }
    if (type == TINYGLTF_TYPE_VEC3) acc.minValues = {-10, -10, -10}, acc.maxValues = {10, 10, 10};
    m.accessors.push_back(acc);
    return static_cast<int>(m.accessors.size()) - 1;
  }
  int joints_u16(const std::vector<std::uint16_t>& data) {  // VEC4 unsigned short (JOINTS_0)
    const int a = accessor(std::vector<float>(data.size() / 2, 0.0f), TINYGLTF_TYPE_VEC4);  // reserve the bytes
    std::memcpy(m.buffers[0].data.data() + m.bufferViews[m.accessors[a].bufferView].byteOffset, data.data(),
                data.size() * 2);
    m.bufferViews[m.accessors[a].bufferView].byteLength = data.size() * 2;
    m.accessors[a].componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    m.accessors[a].count = data.size() / 4;
    return a;
  }
  void animation(const std::string& name, int node, const std::string& path, const std::string& interp,
                 const std::vector<float>& times, const std::vector<float>& values, int type) {
    tinygltf::Animation a;
    a.name = name;
    tinygltf::AnimationSampler s;
    s.input = accessor(times, TINYGLTF_TYPE_SCALAR);
    s.output = accessor(values, type);
    s.interpolation = interp;
    a.samplers.push_back(s);
    tinygltf::AnimationChannel c;
    c.sampler = 0;
    c.target_node = node;
    c.target_path = path;
    a.channels.push_back(c);
    m.animations.push_back(a);
  }
  void write(const std::filesystem::path& p) {
    tinygltf::TinyGLTF w;
    ASSERT_TRUE(w.WriteGltfSceneToFile(&m, p.string(), false, true, true, false));
  }
};

// One triangle (node 0, translated by (1,2,3)) with one morph target moving it +z by 1; node 1 has no mesh.
Builder triangle(std::vector<double> default_weights) {
  Builder b;
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = b.accessor({0, 0, 0, 1, 0, 0, 0, 1, 0}, TINYGLTF_TYPE_VEC3);
  prim.targets.push_back({{"POSITION", b.accessor({0, 0, 1, 0, 0, 1, 0, 0, 1}, TINYGLTF_TYPE_VEC3)}});
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  mesh.weights = std::move(default_weights);
  b.m.meshes.push_back(mesh);
  tinygltf::Node n0, n1;
  n0.mesh = 0;
  n0.translation = {1, 2, 3};
  n1.name = "empty";
  b.m.nodes = {n0, n1};
  tinygltf::Scene scene;
  scene.nodes = {0, 1};
  b.m.scenes.push_back(scene);
  b.m.defaultScene = 0;
  return b;
}

TEST(MeshClip, CubicSplineTranslationAndStepWeights) {
  TempDir dir;
  Builder b = triangle({});
  // CUBICSPLINE keys at 0 and 2: (in-tangent, value, out-tangent) per key.
  b.animation("cubic", 0, "translation", "CUBICSPLINE", {0, 2},
              {9, 9, 9, 1, 2, 3, 0.5f, 0, -1, 0, 1, 0, 3, 2, 1, 9, 9, 9}, TINYGLTF_TYPE_VEC3);
  b.animation("", 0, "weights", "STEP", {0, 1, 2}, {0.25f, 1, 0.5f}, TINYGLTF_TYPE_SCALAR);
  b.write(dir / "tri.gltf");

  EXPECT_EQ(MeshClip::list(dir / "tri.gltf"), (std::vector<std::string>{"cubic", "animation_1"}));
  const auto cubic = MeshClip::load(dir / "tri.gltf");  // "" = the first
  EXPECT_EQ(cubic->name(), "cubic");
  EXPECT_EQ(cubic->duration_s(), 2.0);
  std::vector<glm::dvec3> p, n;
  for (double t : {0.0, 0.5, 1.3, 2.0}) {
    cubic->pose(t, p, n);
    const double s = t / 2, td = 2, s2 = s * s, s3 = s2 * s;  // glTF 2.0 Appendix C Hermite basis
    const glm::dvec3 v0(1, 2, 3), b0(0.5, 0, -1), a1(0, 1, 0), v1(3, 2, 1);
    const glm::dvec3 tr =
        (2 * s3 - 3 * s2 + 1) * v0 + (s3 - 2 * s2 + s) * td * b0 + (-2 * s3 + 3 * s2) * v1 + (s3 - s2) * td * a1;
    EXPECT_LT(glm::length(p[1] - (glm::dvec3(1, 0, 0) + tr)), 1e-12) << "t = " << t;
    EXPECT_LT(glm::length(n[0] - glm::dvec3(0, 0, 1)), 1e-12);  // recomputed: the file has no normals
  }
  cubic->pose(-5, p, n);  // clamped to the first key
  EXPECT_EQ(p[0], glm::dvec3(1, 2, 3));

  const auto step = MeshClip::load(dir / "tri.gltf", "#1");
  EXPECT_EQ(step->name(), "animation_1");
  EXPECT_EQ(MeshClip::load(dir / "tri.gltf", "animation_1")->duration_s(), 2.0);
  const std::vector<std::pair<double, double>> expect = {{0, 0.25}, {0.999, 0.25}, {1.0, 1.0}, {1.7, 1.0}, {2, 0.5}};
  for (auto [t, w] : expect) {
    step->pose(t, p, n);
    EXPECT_EQ(p[2], glm::dvec3(1, 3, 3 + w)) << "t = " << t;  // exact: STEP copies the key
  }
}

TEST(MeshClip, MorphIsRelativeToTheDefaultWeights) {
  // load_mesh ignores default weights (its mesh is the base POSITION); the clip keeps that mesh as its rest state
  // and applies (w − default)·delta, so the rest pose matches the object loaded from the same file.
  TempDir dir;
  Builder b = triangle({0.5});
  b.animation("w", 0, "weights", "LINEAR", {0, 1}, {0.5f, 1.5f}, TINYGLTF_TYPE_SCALAR);
  b.write(dir / "tri.gltf");
  const auto clip = MeshClip::load(dir / "tri.gltf", "w");
  const TriMesh rest = load_mesh(dir / "tri.gltf");
  std::vector<glm::dvec3> p, n;
  clip->pose(0, p, n);
  EXPECT_EQ(max_dist(p, rest.positions), 0.0);
  EXPECT_EQ(clip->rest_positions(), rest.positions);
  clip->pose(0.5, p, n);  // weight 1.0 = default + 0.5
  EXPECT_LT(glm::length(p[0] - glm::dvec3(1, 2, 3.5)), 1e-12);
}

TEST(MeshClip, SkinnedNodeTransformAsLoadMesh) {
  // The skinned mesh node carries a translation X = (1,2,3): load_mesh bakes it, the spec ignores it for skins. The
  // clip keeps load_mesh's frame: p = X · B(t) · v (bind pose = rest pose here), and the mesh node's own animation
  // does not move the skin.
  TempDir dir;
  Builder b = triangle({});
  auto& prim = b.m.meshes[0].primitives[0];
  prim.targets.clear();
  prim.attributes["JOINTS_0"] = b.joints_u16({0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  prim.attributes["WEIGHTS_0"] = b.accessor({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, TINYGLTF_TYPE_VEC4);
  tinygltf::Skin skin;
  skin.joints = {1};  // node 1 ("empty"), a scene root: no inverseBindMatrices = identity
  b.m.skins.push_back(skin);
  b.m.nodes[0].skin = 0;
  b.animation("turn", 1, "rotation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0, 0.70710678f, 0.70710678f},
              TINYGLTF_TYPE_VEC4);
  b.animation("mesh_node", 0, "translation", "LINEAR", {0, 1}, {1, 2, 3, 9, 9, 9}, TINYGLTF_TYPE_VEC3);
  b.write(dir / "skin.gltf");
  const TriMesh rest = load_mesh(dir / "skin.gltf");
  const auto clip = MeshClip::load(dir / "skin.gltf", "turn");
  std::vector<glm::dvec3> p, n;
  clip->pose(0, p, n);
  EXPECT_LT(max_dist(p, rest.positions), 1e-12);
  clip->pose(1, p, n);  // joint rotated 90° about +z: (1,0,0) → (0,1,0), then + X
  EXPECT_LT(glm::length(p[0] - glm::dvec3(1, 2, 3)), 1e-6);
  EXPECT_LT(glm::length(p[1] - glm::dvec3(1, 3, 3)), 1e-6);
  EXPECT_LT(glm::length(p[2] - glm::dvec3(0, 2, 3)), 1e-6);
  EXPECT_THROW(MeshClip::load(dir / "skin.gltf", "mesh_node"), std::invalid_argument);  // animates no mesh
}

TEST(MeshClip, Errors) {
  TempDir dir;
  EXPECT_THROW(MeshClip::load(dir / "missing.gltf"), MeshIoError);
  EXPECT_THROW(MeshClip::list(dir / "missing.gltf"), MeshIoError);

  TriMesh tet = test::tetrahedron();
  write_glb(dir / "still.glb", {{"tet", &tet}});
  EXPECT_TRUE(MeshClip::list(dir / "still.glb").empty());
  try {
    MeshClip::load(dir / "still.glb");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("still.glb"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no animations"), std::string::npos) << e.what();
  }

  Builder b = triangle({});
  b.animation("walk", 0, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.animation("empty_node", 1, "translation", "LINEAR", {0, 1}, {0, 0, 0, 1, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.animation("short", 0, "translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 1, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.animation("nan", 0, "translation", "LINEAR", {0, NAN}, {0, 0, 0, 1, 0, 0}, TINYGLTF_TYPE_VEC3);
  b.write(dir / "tri.gltf");
  auto message = [&](const std::string& clip) {
    try {
      MeshClip::load(dir / "tri.gltf", clip);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no std::invalid_argument");
  };
  for (const std::string clip : {"run", "#4"}) {
    const std::string msg = message(clip);
    EXPECT_NE(msg.find("'" + clip + "'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("tri.gltf"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'walk'"), std::string::npos) << msg;  // lists the clips there are
  }
  EXPECT_NE(message("empty_node").find("animates no mesh"), std::string::npos) << message("empty_node");
  EXPECT_NE(message("short").find("expected 18"), std::string::npos) << message("short");
  EXPECT_NE(message("nan").find("clip 'nan'"), std::string::npos) << message("nan");
  std::vector<glm::dvec3> p, n;
  EXPECT_THROW(MeshClip::load(dir / "tri.gltf", "walk")->pose(NAN, p, n), std::invalid_argument);
}

TEST(MeshClip, WrapClipTime) {
  EXPECT_EQ(wrap_clip_time(5, 1, 2, 3, true), 2.0);   // (5 − 1)·2 = 8 → 8 − 6
  EXPECT_EQ(wrap_clip_time(5, 1, 2, 3, false), 3.0);  // clamped
  EXPECT_EQ(wrap_clip_time(0, 1, 1, 3, true), 2.0);   // before the start wraps backwards
  EXPECT_EQ(wrap_clip_time(0, 1, 1, 3, false), 0.0);
  EXPECT_EQ(wrap_clip_time(7, 0, 1, 0, true), 0.0);  // zero-length clip
}

#ifdef TRISPLINE_HAVE_CLIP_ASSETS
const std::filesystem::path kData = std::filesystem::path(TRISPLINE_SOURCE_DIR) / "assets/data";

tinygltf::Model parse(const std::filesystem::path& p) {
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadASCIIFromFile(&m, &err, &warn, p.string())) << err;
  return m;
}

TEST(MeshClipAssets, AnimatedMorphCube) {
  const auto path = kData / "AnimatedMorphCube/AnimatedMorphCube.gltf";
  const TriMesh rest = load_mesh(path);
  const auto clip = MeshClip::load(path, "Square");
  EXPECT_EQ(MeshClip::list(path), std::vector<std::string>{"Square"});
  ASSERT_EQ(clip->vertex_count(), rest.vertex_count());
  EXPECT_EQ(clip->vertex_count(), 24u);

  const tinygltf::Model m = parse(path);
  const auto& sampler = m.animations[0].samplers[0];
  const std::vector<double> times = floats(m, sampler.input), weights = floats(m, sampler.output);
  EXPECT_EQ(clip->duration_s(), *std::max_element(times.begin(), times.end()));
  EXPECT_NEAR(clip->duration_s(), 4.2, 1e-5);
  const auto& prim = m.meshes[0].primitives[0];
  const std::vector<double> d0 = floats(m, prim.targets[0].at("POSITION")),
                            d1 = floats(m, prim.targets[1].at("POSITION"));
  const auto& node = m.nodes[0];  // rotation + scale 100, baked by load_mesh: deltas go through the same matrix
  const glm::dmat3 xf =
      glm::dmat3(glm::mat3_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]))) *
      100.0;
  ASSERT_EQ(weights[0], 0.0);  // key 0: both weights 0 = the rest state
  ASSERT_EQ(weights[1], 0.0);
  std::vector<glm::dvec3> p, n, p2, n2;
  clip->pose(0, p, n);
  EXPECT_LT(max_dist(p, rest.positions), 1e-6);
  EXPECT_LT(max_dist(n, rest.normals), 1e-6);

  auto expected = [&](std::size_t v, double w0, double w1) {
    return rest.positions[v] + xf * (w0 * glm::make_vec3(&d0[3 * v]) + w1 * glm::make_vec3(&d1[3 * v]));
  };
  int keys_with_both = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {  // every key, every vertex
    clip->pose(times[k], p, n);
    keys_with_both += weights[2 * k] > 0.1 && weights[2 * k + 1] > 0.1;
    for (std::size_t v = 0; v < p.size(); ++v)
      ASSERT_LT(glm::length(p[v] - expected(v, weights[2 * k], weights[2 * k + 1])), 1e-9) << k << " " << v;
  }
  EXPECT_GT(keys_with_both, 0);       // the check covered both targets at once
  for (std::size_t k : {24u, 80u}) {  // LINEAR, midway between keys
    clip->pose(0.5 * (times[k] + times[k + 1]), p, n);
    const double w0 = 0.5 * (weights[2 * k] + weights[2 * k + 2]), w1 = 0.5 * (weights[2 * k + 1] + weights[2 * k + 3]);
    EXPECT_GT(glm::length(p[5] - rest.positions[5]), 1e-3);
    EXPECT_LT(glm::length(p[5] - expected(5, w0, w1)), 1e-9);
    for (const auto& nv : n) EXPECT_NEAR(glm::length(nv), 1.0, 1e-12);
  }
  // Looping: one period later is the same pose; two evaluations are bit-identical.
  const double d = clip->duration_s();
  clip->pose(wrap_clip_time(d + 1.25, 0, 1, d, true), p, n);
  clip->pose(1.25, p2, n2);
  EXPECT_LT(max_dist(p, p2), 1e-9);
  clip->pose(1.25, p, n);
  EXPECT_EQ(std::memcmp(p.data(), p2.data(), p.size() * sizeof(glm::dvec3)), 0);
  EXPECT_EQ(std::memcmp(n.data(), n2.data(), n.size() * sizeof(glm::dvec3)), 0);
}

TEST(MeshClipAssets, SimpleSkin) {
  const auto path = kData / "simple_skin/simple_skin.gltf";
  const TriMesh rest = load_mesh(path);
  const auto clip = MeshClip::load(path);
  ASSERT_EQ(clip->vertex_count(), rest.vertex_count());
  EXPECT_EQ(clip->vertex_count(), 10u);
  EXPECT_EQ(clip->duration_s(), 5.5);
  std::vector<glm::dvec3> p, n;
  clip->pose(0, p, n);  // key 0: joint rotation = identity = the nodes' rest rotation
  EXPECT_LT(max_dist(p, rest.positions), 1e-6);
  EXPECT_LT(max_dist(n, rest.normals), 1e-6);

  const tinygltf::Model m = parse(path);
  const std::vector<double> ibm = floats(m, m.skins[0].inverseBindMatrices);
  const std::vector<double> q = floats(m, m.animations[0].samplers[0].output);
  // Joint 1 (node 2) pivots about its bind position inverse(IBM₁)·origin = (0.5, 1, 0), in load_mesh's frame.
  const glm::dvec3 pivot(glm::inverse(glm::make_mat4(&ibm[16])) * glm::dvec4(0, 0, 0, 1));
  EXPECT_LT(glm::length(pivot - glm::dvec3(0.5, 1, 0)), 1e-12);
  auto rotated = [&](const glm::dvec3& r, double angle) {
    return pivot + glm::dvec3(std::cos(angle) * (r.x - pivot.x) - std::sin(angle) * (r.y - pivot.y),
                              std::sin(angle) * (r.x - pivot.x) + std::cos(angle) * (r.y - pivot.y), r.z - pivot.z);
  };
  const glm::dquat q2(q[11], q[8], q[9], q[10]);  // key 2 (t = 1 s): about +z
  const double angle = 2 * std::atan2(glm::length(glm::dvec3(q2.x, q2.y, q2.z)), q2.w);
  EXPECT_NEAR(angle, glm::radians(90.0), 1e-3);
  clip->pose(1.0, p, n);
  for (std::size_t v : {8u, 9u}) EXPECT_LT(glm::length(p[v] - rotated(rest.positions[v], angle)), 1e-6) << v;
  for (std::size_t v : {0u, 1u}) EXPECT_LT(glm::length(p[v] - rest.positions[v]), 1e-6) << v;  // joint 0 only
  for (std::size_t v : {4u, 5u})  // 50 % / 50 %: linear blend of the two
    EXPECT_LT(glm::length(p[v] - 0.5 * (rest.positions[v] + rotated(rest.positions[v], angle))), 1e-6) << v;
  // LINEAR between key 0 (identity) and key 1 (t = 0.5) slerps: at t = 0.25 half key 1's angle.
  const glm::dquat q1(q[7], q[4], q[5], q[6]);
  const double half = std::atan2(glm::length(glm::dvec3(q1.x, q1.y, q1.z)), q1.w);
  clip->pose(0.25, p, n);
  EXPECT_LT(glm::length(p[8] - rotated(rest.positions[8], half)), 1e-6);
  clip->pose(0.125, p, n);  // a quarter of the way: slerp's constant angular speed (nlerp would be ~2e-3 off)
  EXPECT_LT(glm::length(p[8] - rotated(rest.positions[8], 0.5 * half)), 1e-6);
  // No file normals: recomputed from the posed triangles.
  TriMesh posed = rest;
  posed.positions = p;
  compute_vertex_normals(posed);
  EXPECT_EQ(max_dist(n, posed.normals), 0.0);
}
// Qt 3D's RiggedFigure keeps one animation per joint (19, two keys each): "*" plays them together, so the pose at
// mid-clip moves more of the figure than any one animation does, and equals the rest at no time in between.
TEST(MeshClipAssets, AllAnimationsOfAFilePlayTogether) {
  const auto path = kData / "qt3d/gltf/2.0/RiggedFigure/RiggedFigure.gltf";
  if (!std::filesystem::exists(path)) GTEST_FAIL() << "missing " << path << " (scripts/fetch_assets.sh)";
  ASSERT_EQ(MeshClip::list(path).size(), 19u);
  const auto all = MeshClip::load(path, kAllClips), one = MeshClip::load(path, "#0");
  EXPECT_EQ(all->name(), "*");
  EXPECT_NEAR(all->duration_s(), 1.25, 1e-6);
  std::vector<glm::dvec3> pa, na, p1, n1;
  all->pose(0.6, pa, na);
  one->pose(0.6, p1, n1);
  auto moved = [&](const std::vector<glm::dvec3>& p) {
    std::size_t n = 0;
    for (std::size_t v = 0; v < p.size(); ++v) n += glm::length(p[v] - all->rest_positions()[v]) > 1e-6;
    return n;
  };
  EXPECT_GT(moved(pa), moved(p1)) << "every joint's animation moves more vertices than the first joint's alone";
  EXPECT_GT(moved(pa), all->vertex_count() / 2);
  EXPECT_THROW(MeshClip::load(path, "no such clip"), std::invalid_argument);
}

#endif

}  // namespace
}  // namespace trispline::core
