// Iso-surface meshes of a VolumeSpline (core/volume/iso_mesh.h) on analytic spheres sampled through an anisotropic,
// offset (and once mirrored) voxel-to-world map: closed manifold meshes, vertices on D = iso and on the sphere,
// outward normals and winding, caps where the sphere leaves the box, refusals, progress, files.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/mesh/mesh_io.h"
#include "core/volume/iso_mesh.h"
#include "core/volume/volume_spline.h"
#include "tests/mesh_topology.h"

namespace trispline::core {
namespace {

// A ball of `radius` mm at `centre` (world), D = radius − |p − centre| (> 0 inside: material above iso 0, like bone
// in CT) sampled on dims voxels with spacing `spacing` mm from `origin`; `mirror` flips the world x axis.
struct Ball {
  glm::dvec3 centre{4.0, -7.0, 11.0};
  double radius = 12.0;
  glm::dvec3 spacing{0.9, 1.15, 0.8};
  glm::dvec3 origin{-14.0, -22.0, -8.0};
  std::array<int, 3> dims{36, 30, 42};
  bool mirror = false;
  bool signed_distance = false;  // D = |p − centre| − radius instead (material below iso)

  ScalarVolume volume() const {
    ScalarVolume v;
    v.dims = dims;
    v.index_to_world = glm::dmat4(1.0);
    for (int a = 0; a < 3; ++a) v.index_to_world[a][a] = spacing[a];
    if (mirror) v.index_to_world[0][0] = -spacing[0];
    v.index_to_world[3] = glm::dvec4(origin, 1.0);
    v.values.resize(v.voxel_count());
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i) {
          const double d = radius - glm::distance(v.world(glm::dvec3(i, j, k)), centre);
          v.values[v.index(i, j, k)] = static_cast<float>(signed_distance ? -d : d);
        }
    return v;
  }
};

// Winding: every triangle's normal agrees with its vertices' normals; returns the worst cosine.
double worst_face_agreement(const TriMesh& m) {
  double worst = 1.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    const glm::dvec3 fn = glm::cross(b - a, c - a);
    const double len = glm::length(fn);
    if (len == 0.0) continue;
    const glm::dvec3 vn = m.normals[t.x] + m.normals[t.y] + m.normals[t.z];
    worst = std::min(worst, glm::dot(fn / len, glm::normalize(vn)));
  }
  return worst;
}

void expect_on_sphere(const TriMesh& mesh, const VolumeSpline& spline, const Ball& ball, double iso) {
  const double range = spline.control_max() - spline.control_min();
  const glm::dmat4 to_index = spline.world_to_index();
  double worst_value = 0.0, worst_radius = 0.0, worst_normal = 1.0;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::dvec3 p = mesh.positions[i];
    worst_value = std::max(worst_value, std::abs(spline.value(glm::dvec3(to_index * glm::dvec4(p, 1.0))) - iso));
    worst_radius = std::max(worst_radius, std::abs(glm::distance(p, ball.centre) - ball.radius));
    worst_normal = std::min(worst_normal, glm::dot(mesh.normals[i], glm::normalize(p - ball.centre)));
    EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0, 1e-12);
  }
  EXPECT_LE(worst_value, 1e-6 * range);
  EXPECT_LE(worst_radius, 1e-3 * 2.0 * ball.radius);
  EXPECT_GT(worst_normal, 0.999);  // outward, along the sphere's normal
}

TEST(IsoMesh, SphereIsClosedOnSplineWithOutwardNormals) {
  const Ball ball;
  const VolumeSpline spline(ball.volume(), 4, /*interpolate=*/true);
  IsoMeshStats st;
  const TriMesh mesh = extract_iso_mesh(spline, 0.0, {}, nullptr, &st);
  ASSERT_GT(mesh.triangle_count(), 1000u);
  validate_mesh(mesh, "sphere");
  test::expect_closed_manifold(mesh);
  EXPECT_TRUE(test::is_manifold(test::topology(mesh)));
  expect_on_sphere(mesh, spline, ball, 0.0);
  EXPECT_GT(worst_face_agreement(mesh), 0.5);
  const double v = 4.0 / 3.0 * std::numbers::pi * std::pow(ball.radius, 3);
  EXPECT_NEAR(signed_volume(mesh), v, 0.01 * v);  // CCW seen from outside: positive
  EXPECT_EQ(st.unconverged, 0u);
  EXPECT_EQ(st.cap_vertices, 0u);
  EXPECT_EQ(st.triangles, mesh.triangle_count());
  EXPECT_EQ(st.triangles, 2 * st.crossing_edges);  // one quad per crossing edge at adaptivity 0
  EXPECT_GT(st.sampled_voxels, 0u);
  EXPECT_LT(st.sampled_voxels, spline.control_points().size());  // sparse: not every voxel is stored
}

TEST(IsoMesh, MirroredWorldKeepsOutwardWinding) {
  Ball ball;
  ball.mirror = true;
  ball.origin.x = 18.0;  // world x runs from 18 down to 18 − 35·0.9
  const VolumeSpline spline(ball.volume(), 4, true);
  ASSERT_LT(glm::determinant(glm::dmat3(spline.index_to_world())), 0.0);
  const TriMesh mesh = extract_iso_mesh(spline, 0.0);
  test::expect_closed_manifold(mesh);
  expect_on_sphere(mesh, spline, ball, 0.0);
  EXPECT_GT(worst_face_agreement(mesh), 0.5);
  EXPECT_GT(signed_volume(mesh), 0.0);
}

TEST(IsoMesh, MaterialBelowIsoFlipsTheSide) {
  Ball ball;
  ball.signed_distance = true;  // D < 0 inside: the sphere is the material with material_above = false
  const VolumeSpline spline(ball.volume(), 4, true);
  IsoMeshOptions opt;
  opt.material_above = false;
  const TriMesh mesh = extract_iso_mesh(spline, 0.0, opt);
  test::expect_closed_manifold(mesh);
  expect_on_sphere(mesh, spline, ball, 0.0);
  EXPECT_GT(signed_volume(mesh), 0.0);
  EXPECT_GT(worst_face_agreement(mesh), 0.5);
}

TEST(IsoMesh, OtherIsoLevelAndFinerSampling) {
  const Ball ball;
  const VolumeSpline spline(ball.volume(), 4, true);
  const double iso = 3.0;  // the sphere of radius 9 mm
  Ball inner = ball;
  inner.radius = ball.radius - iso;
  const TriMesh coarse = extract_iso_mesh(spline, iso);
  IsoMeshOptions opt;
  opt.samples_per_voxel = 2;
  const TriMesh fine = extract_iso_mesh(spline, iso, opt);
  test::expect_closed_manifold(fine);
  expect_on_sphere(fine, spline, inner, iso);
  const double ratio = double(fine.triangle_count()) / double(coarse.triangle_count());
  EXPECT_GT(ratio, 3.0);
  EXPECT_LT(ratio, 5.0);
}

TEST(IsoMesh, UnprojectedVerticesAreOffTheSpline) {
  const Ball ball;
  const VolumeSpline spline(ball.volume(), 4, true);
  IsoMeshOptions opt;
  opt.project_to_spline = false;
  const TriMesh raw = extract_iso_mesh(spline, 0.0, opt);
  double worst = 0.0;
  for (const glm::dvec3& p : raw.positions)
    worst = std::max(worst, std::abs(spline.value(glm::dvec3(spline.world_to_index() * glm::dvec4(p, 1.0)))));
  const double range = spline.control_max() - spline.control_min();
  EXPECT_GT(worst, 1e-4 * range);  // OpenVDB's linear interpolation alone is not on D = iso
}

// Without Newton steps every vertex goes through the bracketed fallback (regula falsi towards a grid corner on the
// other side of iso), which brings each onto D = iso on its own.
TEST(IsoMesh, BracketedFallbackAloneReachesTheSurface) {
  const Ball ball;
  for (int order : {2, 4}) {
    SCOPED_TRACE(order);
    const VolumeSpline spline(ball.volume(), order, true);
    IsoMeshOptions opt;
    opt.max_newton_steps = 0;
    IsoMeshStats st;
    const TriMesh mesh = extract_iso_mesh(spline, 0.0, opt, nullptr, &st);
    EXPECT_EQ(st.unconverged, 0u);
    EXPECT_LE(st.max_residual, 1e-6);
    test::expect_closed_manifold(mesh);
    if (order == 4) expect_on_sphere(mesh, spline, ball, 0.0);
  }
}

TEST(IsoMesh, OrdersTwoAndThree) {
  const Ball ball;
  for (int order : {2, 3}) {
    SCOPED_TRACE(order);
    const VolumeSpline spline(ball.volume(), order, true);
    IsoMeshStats st;
    const TriMesh mesh = extract_iso_mesh(spline, 0.0, {}, nullptr, &st);
    test::expect_closed_manifold(mesh);
    EXPECT_LE(st.max_residual, 1e-6);
    EXPECT_EQ(st.unconverged, 0u);
    EXPECT_GT(signed_volume(mesh), 0.0);
  }
}

// The ball pokes out of the box's high-z face (and, mirrored, its low-x face): the mesh is closed by planar caps.
TEST(IsoMesh, CapsCloseTheMeshWhereMaterialLeavesTheBox) {
  Ball ball;
  ball.centre = glm::dvec3(4.0, -7.0, 20.0);  // box z ∈ [−8, 24.8]: 4.8 mm above the centre
  const VolumeSpline spline(ball.volume(), 4, true);
  const double top = ball.origin.z + (ball.dims[2] - 1) * ball.spacing.z;
  IsoMeshStats st;
  const TriMesh mesh = extract_iso_mesh(spline, 0.0, {}, nullptr, &st);
  test::expect_closed_manifold(mesh);
  EXPECT_TRUE(test::is_manifold(test::topology(mesh)));
  EXPECT_GT(st.cap_vertices, 0u);
  EXPECT_EQ(st.unconverged, 0u);
  const double r = ball.radius, h = r - (top - ball.centre.z);  // height of the cut-off cap
  const double expected = 4.0 / 3.0 * std::numbers::pi * r * r * r - std::numbers::pi * h * h * (3 * r - h) / 3.0;
  EXPECT_NEAR(signed_volume(mesh), expected, 0.01 * expected);
  EXPECT_GT(worst_face_agreement(mesh), 0.5);
  std::size_t on_top = 0;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const glm::dvec3 p = mesh.positions[i];
    if (std::abs(p.z - top) < 1e-6) {
      ++on_top;
      EXPECT_LE(glm::distance(p, ball.centre), r + 1e-3 * 2 * r);  // on the disc or its rim
    } else {
      EXPECT_NEAR(glm::distance(p, ball.centre), r, 1e-3 * 2 * r);
    }
  }
  EXPECT_EQ(on_top, st.cap_vertices);

  IsoMeshOptions open;
  open.close_at_boundary = false;
  const TriMesh opened = extract_iso_mesh(spline, 0.0, open);
  const test::Topology t = test::topology(opened);
  EXPECT_EQ(t.nonmanifold_edges, 0u);
  EXPECT_GT(t.boundary_edges, 0u);
  EXPECT_EQ(t.boundary_loops, 1u);
  const glm::dmat4 to_index = spline.world_to_index();
  for (const auto& [a, b] : t.boundary)
    for (unsigned v : {a, b}) {  // the rim: on the face and on D = 0
      EXPECT_NEAR(opened.positions[v].z, top, 1e-6);
      EXPECT_LE(std::abs(spline.value(glm::dvec3(to_index * glm::dvec4(opened.positions[v], 1.0)))), 1e-6 * 24.0);
    }
  EXPECT_LT(opened.triangle_count(), mesh.triangle_count());
}

TEST(IsoMesh, RefusesLevelsOutsideTheRangeAndOversizedMeshes) {
  const Ball ball;
  const VolumeSpline spline(ball.volume(), 4, true);
  EXPECT_THROW(extract_iso_mesh(spline, spline.control_max() + 1.0), std::invalid_argument);
  EXPECT_THROW(extract_iso_mesh(spline, spline.control_max()), std::invalid_argument);
  EXPECT_THROW(extract_iso_mesh(spline, spline.control_min() - 1.0), std::invalid_argument);
  EXPECT_THROW(extract_iso_mesh(spline, std::nan("")), std::invalid_argument);
  IsoMeshOptions small;
  small.max_triangles = 500;
  EXPECT_THROW(extract_iso_mesh(spline, 0.0, small), std::invalid_argument);
  IsoMeshOptions few;
  few.max_sampled_voxels = 1000;
  EXPECT_THROW(extract_iso_mesh(spline, 0.0, few), std::invalid_argument);
  for (int s : {0, 5}) {
    IsoMeshOptions bad;
    bad.samples_per_voxel = s;
    EXPECT_THROW(extract_iso_mesh(spline, 0.0, bad), std::invalid_argument);
  }
  IsoMeshOptions adapt;
  adapt.adaptivity = 1.5;
  EXPECT_THROW(extract_iso_mesh(spline, 0.0, adapt), std::invalid_argument);
  IsoMeshOptions steps;
  steps.max_newton_steps = -1;
  EXPECT_THROW(extract_iso_mesh(spline, 0.0, steps), std::invalid_argument);
}

TEST(IsoMesh, ReportsProgressAndCancels) {
  const Ball ball;
  const VolumeSpline spline(ball.volume(), 4, true);
  std::vector<double> seen;
  ProgressSink sink;
  sink.report = [&](double f) { seen.push_back(f); };
  extract_iso_mesh(spline, 0.0, {}, &sink);
  ASSERT_GE(seen.size(), 3u);
  for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
  EXPECT_EQ(seen.back(), 1.0);

  std::atomic<bool> cancel{true};
  ProgressSink cancelling;
  cancelling.cancel = &cancel;
  EXPECT_THROW(extract_iso_mesh(spline, 0.0, {}, &cancelling), OperationCancelled);
}

TEST(IsoMesh, WritesGlbObjPly) {
  const Ball ball;
  const VolumeSpline spline(ball.volume(), 4, true);
  const TriMesh mesh = extract_iso_mesh(spline, 0.0);
  const auto dir = std::filesystem::temp_directory_path() / "trispline_test_iso_mesh";
  std::filesystem::create_directories(dir);
  for (const char* ext : {".glb", ".obj", ".ply"}) {
    SCOPED_TRACE(ext);
    const auto path = dir / (std::string("ball") + ext);
    write_iso_mesh(path, mesh);
    const TriMesh back = load_mesh(path);
    EXPECT_EQ(back.triangle_count(), mesh.triangle_count());
    EXPECT_NEAR(signed_volume(back), signed_volume(mesh), 1e-3 * signed_volume(mesh));
  }
  EXPECT_THROW(write_iso_mesh(dir / "ball.stl", mesh), MeshIoError);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace trispline::core
