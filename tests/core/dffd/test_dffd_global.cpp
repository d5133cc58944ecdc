// Global DFFD around obstacles (core/dffd/dffd_global.h, dffd_rig.h; seed §6.3.1–6.3.2): a closed sphere pierced
// by a cylinder splits around it — open (boundary loops exactly on the discontinuity), capped and stitched (closed
// 2-manifolds, OpenMesh-checked), no face straddles a break, the deformed surface stays out of the obstacle; the
// fold-over check (Theorem 6) rejects a kernel too narrow for the displacement; bad input names its parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include "core/dffd/dffd_global.h"
#include "core/scene/primitives.h"
#include "core/scene/scene.h"
#include "tests/mesh_topology.h"

namespace trispline::core {
namespace {

// A unit sphere pierced along y by a cylinder of radius 0.3 through its centre (slightly off-centre in x, z so no
// vertex lies exactly on a break).
struct Pierced {
  TriMesh sphere = make_primitive(PrimitiveKind::Sphere);
  DffdObstacle cylinder;
  Pierced() {
    Transform t;
    t.scale = {0.3, 1.6, 0.3};
    t.translate = {0.013, 0.0, 0.017};
    cylinder.name = "tool";
    cylinder.world_mesh = transformed(make_primitive(PrimitiveKind::Cylinder), t);
  }
  GlobalDffdParams params(DffdOpenings openings) const {
    GlobalDffdParams p;
    p.axis = 0;
    p.w_axis = 1;
    p.controls = {16, 12, 12};
    p.kernel_width = 0.7;
    p.openings = openings;
    return p;
  }
};

TEST(DffdKernel, OneAtZeroZeroAtWidthMonotone) {
  for (DffdKernel k : {DffdKernel::gaussian, DffdKernel::bspline}) {
    EXPECT_DOUBLE_EQ(dffd_kernel(k, 0.0, 2.0), 1.0);
    EXPECT_DOUBLE_EQ(dffd_kernel(k, 2.0, 2.0), 0.0);
    EXPECT_DOUBLE_EQ(dffd_kernel(k, -3.0, 2.0), 0.0);
    double prev = 1.0;
    for (int i = 1; i <= 20; ++i) {
      const double v = dffd_kernel(k, 0.1 * i, 2.0);
      EXPECT_LT(v, prev);
      prev = v;
    }
  }
  EXPECT_THROW(dffd_kernel(DffdKernel::gaussian, 0.0, 0.0), std::invalid_argument);
}

TEST(DffdGlobal, LatticeIsTheIdentityOfItsBoxOnTheFaces) {
  Pierced s;
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::open));
  const glm::dmat3 Ainv = glm::inverse(g.rig.embedding.linear);
  for (double a : {0.0, 0.3, 0.77, 1.0})
    for (double b : {0.0, 0.5, 1.0})
      for (const glm::dvec3 p : {glm::dvec3(0.0, a, b), glm::dvec3(1.0, a, b)}) {  // u = 0 and u = 1 faces
        const glm::dvec3 x = Ainv * (p - g.rig.embedding.offset);
        EXPECT_LT(glm::length(g.rig.lattice.eval(p) - x), 1e-12) << p.x << " " << a << " " << b;
      }
  EXPECT_EQ(g.rig.discontinuities.size(), 1u);
  EXPECT_EQ(g.v_knots, 4u);  // order − 1 = 2 knots at each of the cylinder's two v-extremes
  EXPECT_GT(g.projected_points, 0u);
  EXPECT_GT(g.max_displacement, 0.2);
}

TEST(DffdGlobal, OpenSplitHasBoundaryLoopsExactlyOnTheDiscontinuity) {
  Pierced s;
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::open));
  const DffdRig& rig = g.rig;
  DffdApplyStats st;
  const MeshSplit split = dffd_split(rig, s.sphere, glm::dvec3(0.0), &st);
  EXPECT_GT(st.cut_edges, 10u);
  const double u0 = rig.discontinuities[0].u0;
  // No face straddles the break; every boundary vertex sits at u0 ∓ eps.
  for (const glm::uvec3& f : split.mesh.triangles) {
    const bool minus = split.params[f[0]].x < u0;
    for (int c = 1; c < 3; ++c) EXPECT_EQ(split.params[f[c]].x < u0, minus);
  }
  std::map<std::pair<unsigned, unsigned>, int> edges;
  for (const glm::uvec3& f : split.mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{std::min(f[e], f[(e + 1) % 3]), std::max(f[e], f[(e + 1) % 3])}];
  std::size_t boundary = 0;
  for (const auto& [e, n] : edges)
    if (n == 1) {
      ++boundary;
      for (unsigned v : {e.first, e.second}) EXPECT_NEAR(std::abs(split.params[v].x - u0), rig.eps, 1e-12);
    }
  EXPECT_GT(boundary, 20u);
  const TriMesh out = dffd_apply(rig, s.sphere, glm::dvec3(0.0));
  const test::Topology t = test::topology(out);
  EXPECT_TRUE(is_manifold(t));
  EXPECT_EQ(t.boundary_edges, boundary);
}

TEST(DffdGlobal, DeformedSurfaceWrapsTheObstacle) {
  Pierced s;
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::cap));
  const TriMesh out = dffd_apply(g.rig, s.sphere, glm::dvec3(0.0));
  // Without the DFFD, many sphere vertices lie inside the cylinder; after it, none lies deep inside (the B-spline
  // approximates C±(v), so allow a skin of 0.15 × radius).
  auto deep_inside = [&](const TriMesh& m) {
    std::size_t n = 0;
    for (const glm::dvec3& p : m.positions)
      if (std::hypot(p.x - 0.013, p.z - 0.017) < 0.85 * 0.3) ++n;
    return n;
  };
  EXPECT_GT(deep_inside(s.sphere), 50u);
  EXPECT_EQ(deep_inside(out), 0u);
}

TEST(DffdGlobal, CappedAndStitchedAreClosedTwoManifolds) {
  Pierced s;
  for (DffdOpenings o : {DffdOpenings::cap, DffdOpenings::stitch}) {
    const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(o));
    DffdApplyStats st;
    const TriMesh out = dffd_apply(g.rig, s.sphere, glm::dvec3(0.0), &st);
    EXPECT_GT(st.cap_triangles, 0u);
    EXPECT_EQ(st.open_chains, 0u);
    const test::Topology t = test::topology(out);
    EXPECT_EQ(t.openmesh_rejected, 0u) << dffd_openings_name(o);
    EXPECT_EQ(t.boundary_edges, 0u) << dffd_openings_name(o);
    EXPECT_EQ(t.nonmanifold_edges, 0u) << dffd_openings_name(o);
    EXPECT_EQ(t.duplicate_faces, 0u) << dffd_openings_name(o);
    std::size_t inside = 0;
    for (std::size_t f = 0; f < out.triangle_count(); ++f) inside += out.material(f) == kMaterialInside;
    EXPECT_EQ(inside, st.cap_triangles);
  }
  // Stitching moves the control points of both discontinuity planes to the level w_s (seed §6.3.2) in the rows the
  // obstacle opened (F⁻ ≠ F⁺); the other rows are closed already and keep their levels.
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::stitch));
  const GlobalDffd c = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::cap));
  ASSERT_EQ(g.w_s.size(), 1u);
  EXPECT_GT(g.w_s[0], 0.2);
  EXPECT_LT(g.w_s[0], 0.8);
  const Discontinuity& d = g.rig.discontinuities[0];
  const glm::ivec3 n = g.rig.lattice.control_counts();
  int stitched_rows = 0, kept_rows = 0;
  double first_level = std::nan("");
  for (int j = 0; j < n.y; ++j) {
    bool opened = false;
    for (int k = 0; k < n.z; ++k)
      opened = opened ||
               c.rig.lattice.control_point(d.minus_plane, j, k).x != c.rig.lattice.control_point(d.plus_plane, j, k).x;
    for (int k = 0; k < n.z; ++k) {
      const double ym = g.rig.lattice.control_point(d.minus_plane, j, k).y;
      const double yp = g.rig.lattice.control_point(d.plus_plane, j, k).y;
      if (opened) {
        if (std::isnan(first_level)) first_level = ym;
        EXPECT_EQ(ym, first_level) << j << " " << k;
        EXPECT_EQ(yp, first_level) << j << " " << k;
      } else {
        EXPECT_EQ(ym, c.rig.lattice.control_point(d.minus_plane, j, k).y) << j << " " << k;
      }
    }
    (opened ? stitched_rows : kept_rows) += 1;
  }
  EXPECT_GT(stitched_rows, 0);
  EXPECT_GT(kept_rows, 0);
}

TEST(DffdGlobal, OutsideTheBoxTheObjectIsOnlyTranslatedByItsOffset) {
  Pierced s;
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::cap));
  const glm::dvec3 offset(-1.5, 0.0, 0.0);  // the whole sphere before the box (walking in)
  DffdApplyStats st;
  const TriMesh out = dffd_apply(g.rig, s.sphere, offset, &st);
  ASSERT_EQ(out.vertex_count(), s.sphere.vertex_count());
  EXPECT_EQ(st.outside_vertices, s.sphere.vertex_count());
  const double du = 1.5 * g.box.size().x;
  for (std::size_t v = 0; v < out.vertex_count(); ++v)
    EXPECT_NEAR(glm::length(out.positions[v] - (s.sphere.positions[v] - glm::dvec3(du, 0, 0))), 0.0, 1e-12);
  // Deterministic: the same rig and offset give the same mesh bit for bit.
  const TriMesh a = dffd_apply(g.rig, s.sphere, glm::dvec3(0.1, 0, 0));
  const TriMesh b = dffd_apply(g.rig, s.sphere, glm::dvec3(0.1, 0, 0));
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(DffdGlobal, FoldOverIsRejectedOrReportedWhereItHappens) {
  Pierced s;
  GlobalDffdParams p = s.params(DffdOpenings::open);
  p.kernel_width = 0.05;  // far narrower than the 0.3 displacement: F⁻ passes its neighbours (Theorem 6 broken)
  try {
    build_global_dffd(s.sphere, {s.cylinder}, p);
    FAIL() << "a folding kernel was accepted";
  } catch (const DffdBuildError& e) {
    EXPECT_EQ(e.field, "kernel_width");
    EXPECT_NE(std::string(e.what()).find("fold-over"), std::string::npos) << e.what();
  }
  p.reject_fold = false;
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, p);
  ASSERT_FALSE(g.folds.empty());
  ASSERT_EQ(g.rig.fold_points.size(), g.folds.size());
  for (const DffdFold& f : g.folds) {
    const glm::dvec3 a = g.rig.lattice.control_point(f.index.x, f.index.y, f.index.z);
    const glm::dvec3 b = g.rig.lattice.control_point(f.index.x + 1, f.index.y, f.index.z);
    EXPECT_LE(b.x, a.x + 1e-9);  // really out of order along u
    EXPECT_EQ(f.position, a);
  }
}

TEST(DffdGlobal, BadInputNamesTheParameter) {
  Pierced s;
  auto field_of = [&](GlobalDffdParams p, std::vector<DffdObstacle> obstacles) -> std::string {
    try {
      build_global_dffd(s.sphere, obstacles, p);
    } catch (const DffdBuildError& e) {
      return e.field;
    }
    return "(accepted)";
  };
  const GlobalDffdParams ok = s.params(DffdOpenings::open);
  GlobalDffdParams p = ok;
  p.w_axis = p.axis;
  EXPECT_EQ(field_of(p, {s.cylinder}), "w_axis");
  p = ok;
  p.order = {7, 3, 3};
  EXPECT_EQ(field_of(p, {s.cylinder}), "order");
  p = ok;
  p.controls = {2, 12, 12};
  EXPECT_EQ(field_of(p, {s.cylinder}), "controls");
  p = ok;
  p.kernel_width = -1;
  EXPECT_EQ(field_of(p, {s.cylinder}), "kernel_width");
  EXPECT_EQ(field_of(ok, {}), "obstacles");
  EXPECT_EQ(field_of(ok, {{"empty", TriMesh{}}}), "obstacles");
  p = ok;
  Aabb small;  // the obstacle (y in ±1.6) is larger than this lattice box
  small.lo = {-1.5, -1.2, -1.2};
  small.hi = {1.5, 1.2, 1.2};
  p.box = small;
  EXPECT_EQ(field_of(p, {s.cylinder}), "box");
}

TEST(DffdGlobal, SceneObjectEvaluatesItsRigAndAnimatesThroughTheBox) {
  Pierced s;
  SceneObject o;
  o.name = "ball";
  o.rest_mesh = std::make_shared<const TriMesh>(s.sphere);
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::cap));
  o.dffd = std::make_shared<const DffdRig>(g.rig);
  o.offset_keys = {{0.0, {-1.5, 0, 0}, KeyInterpolation::linear}, {2.0, {1.5, 0, 0}, KeyInterpolation::linear}};
  o.refresh();
  EXPECT_TRUE(o.dffd_animated());
  EXPECT_TRUE(o.cpu_animated());
  EXPECT_FALSE(o.offset_animated());  // the renderer cannot play it: the CPU evaluates every frame
  EXPECT_EQ(o.world_mesh->vertex_count(), s.sphere.vertex_count());  // t = 0: before the box, not cut
  Scene scene;
  scene.insert(o);
  const Scene mid = scene_at_time(scene, 1.0);  // offset 0: pierced, split and capped
  const TriMesh& m = *mid.find("ball")->world_mesh;
  EXPECT_GT(m.vertex_count(), s.sphere.vertex_count());
  EXPECT_EQ(test::topology(m).boundary_edges, 0u);
  const Scene mid2 = scene_with_posed_clips(scene, 1.0);
  EXPECT_EQ(mid2.find("ball")->world_mesh->positions, m.positions);
}

}  // namespace
}  // namespace trispline::core

namespace trispline::core {
namespace {

// The overlapped evaluation (input vertices deformed while the split runs; what dffd_apply and a reused
// DffdFrameEvaluator do) gives the sequential pipeline's mesh (dffd_split, then dffd_deform) bit for bit, frame
// after frame with one evaluator, for offsets outside, across and inside the box, and when an input vertex lies
// exactly on a break (its parameter moves to u0 ∓ eps during the split and must be re-evaluated).
TEST(DffdGlobal, FrameEvaluatorEqualsDffdApplyBitForBit) {
  Pierced s;
  for (DffdOpenings o : {DffdOpenings::open, DffdOpenings::cap}) {
    const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(o));
    ASSERT_FALSE(g.rig.discontinuities.empty());
    const Discontinuity& d = g.rig.discontinuities[0];
    const std::size_t on = s.sphere.vertex_count() / 3;  // this vertex lands on the break
    const double onto = d.u0 - g.rig.params[on][d.axis];
    ASSERT_EQ(d.axis, 0);
    const MeshSplit probe = dffd_split(g.rig, s.sphere, {onto, 0, 0});
    ASSERT_TRUE(std::find(probe.cut_vertices.begin(), probe.cut_vertices.end(), on) != probe.cut_vertices.end());
    DffdFrameEvaluator evaluator;
    for (const glm::dvec3 offset : {glm::dvec3(0.0), glm::dvec3(-1.5, 0, 0), glm::dvec3(0.13, 0, 0),
                                    glm::dvec3(onto, 0, 0), glm::dvec3(-0.21, 0.05, 0), glm::dvec3(0.0)}) {
      DffdApplyStats a_st, b_st, c_st;
      MeshSplit split = dffd_split(g.rig, s.sphere, offset, &a_st);
      TriMesh a;
      dffd_deform(g.rig, split, a, &a_st);
      const TriMesh& b = evaluator.evaluate(g.rig, s.sphere, offset, &b_st);
      const TriMesh c = dffd_apply(g.rig, s.sphere, offset, &c_st);
      EXPECT_EQ(c.positions, b.positions);
      EXPECT_EQ(c.triangles, b.triangles);
      const std::string at = std::string(dffd_openings_name(o)) + " offset " + std::to_string(offset.x);
      EXPECT_EQ(a.positions, b.positions) << at;
      EXPECT_EQ(a.normals, b.normals) << at;
      EXPECT_EQ(a.triangles, b.triangles) << at;
      EXPECT_EQ(a.face_material, b.face_material) << at;
      EXPECT_EQ(a.uvs, b.uvs) << at;
      EXPECT_EQ(a_st.cut_edges, b_st.cut_edges) << at;
      EXPECT_EQ(a_st.cap_triangles, b_st.cap_triangles) << at;
      EXPECT_EQ(a_st.outside_vertices, b_st.outside_vertices) << at;
    }
  }
}

// Textured caps (cap_texturing) through the frame evaluator: the same mesh bit for bit as dffd_split + dffd_deform;
// the caps refined inside (more triangles than the plain caps) and their loop deformed onto the surface's points (the
// copies are evaluated at the same parameters).
TEST(DffdGlobal, TexturedCapsEvaluateLikeTheSurfaceTheyCopy) {
  Pierced s;
  const GlobalDffd g = build_global_dffd(s.sphere, {s.cylinder}, s.params(DffdOpenings::cap));
  const CapTexturing tex = cap_texturing(g.rig, 0.25);
  for (int k = 0; k < 3; ++k) EXPECT_GT(tex.uv_per_param[k], 0.0);
  EXPECT_GT(tex.max_edge, 0.0);
  EXPECT_THROW(cap_texturing(g.rig, 0.0), std::invalid_argument);
  DffdFrameEvaluator evaluator;
  for (const glm::dvec3 offset : {glm::dvec3(0.0), glm::dvec3(0.13, 0, 0), glm::dvec3(0.0, 0.05, -0.04)}) {
    MeshSplit split = dffd_split(g.rig, s.sphere, offset, nullptr, tex);
    // The uvs are the plane's parameters without the offset (the texture stays on the object).
    const int ua = (g.rig.discontinuities[0].axis + 1) % 3, ub = (g.rig.discontinuities[0].axis + 2) % 3;
    std::set<std::uint32_t> cap_vertices;
    for (std::size_t f = 0; f < split.mesh.triangle_count(); ++f)
      if (split.mesh.material(f) == kMaterialInside)
        for (int c = 0; c < 3; ++c) cap_vertices.insert(split.mesh.triangles[f][c]);
    ASSERT_FALSE(cap_vertices.empty());
    for (const std::uint32_t v : cap_vertices) {
      const glm::dvec3 q = split.params[v] - offset;
      EXPECT_NEAR(split.mesh.uvs[v].x, q[ua] * tex.uv_per_param[ua], 1e-9) << v;
      EXPECT_NEAR(split.mesh.uvs[v].y, q[ub] * tex.uv_per_param[ub], 1e-9) << v;
    }
    TriMesh a;
    dffd_deform(g.rig, split, a);
    const TriMesh& b = evaluator.evaluate(g.rig, s.sphere, offset, nullptr, tex);
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.uvs, b.uvs);
    const TriMesh plain = dffd_apply(g.rig, s.sphere, offset);
    EXPECT_GT(b.vertex_count(), plain.vertex_count());
    EXPECT_GT(b.triangle_count(), plain.triangle_count());
    std::set<std::tuple<double, double, double>> surface;
    std::map<std::pair<unsigned, unsigned>, int> cap_edges;
    for (std::size_t f = 0; f < b.triangle_count(); ++f)
      for (int c = 0; c < 3; ++c) {
        const unsigned v = b.triangles[f][c], w = b.triangles[f][(c + 1) % 3];
        if (b.material(f) == kMaterialInside) {
          ++cap_edges[{std::min(v, w), std::max(v, w)}];
        } else {
          const glm::dvec3 p = b.positions[v];
          surface.insert({p.x, p.y, p.z});
        }
      }
    std::size_t loop = 0, off = 0;
    for (const auto& [e, n] : cap_edges) {
      EXPECT_LE(n, 2);
      if (n != 1) continue;
      for (const unsigned v : {e.first, e.second}) {
        const glm::dvec3 p = b.positions[v];
        ++loop;
        off += surface.count({p.x, p.y, p.z}) == 0;
      }
    }
    EXPECT_GT(loop, 0u);
    EXPECT_EQ(off, 0u);
  }
}

}  // namespace
}  // namespace trispline::core
