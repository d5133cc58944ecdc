// Objects whose deformation carries their tile layers (core/scene/ddm_follow.h), shared by the CPU tests
// (tests/core/scene/test_ddm_follow.cpp) and the GLSL parity test (tests/gpu/test_ddm_gl.cpp): a sphere with a thorn
// layer on its Loop limit surface, moved by a transform and then (a) a bent FFD lattice with a parameter offset,
// (b) a moved host surface (its vertices warped, as a clip pose or an incision would), (c) a DFFD with one opened
// C⁻¹ break across the sphere.
#pragma once

#include <cmath>
#include <memory>
#include <vector>

#include "core/ddm/ddm_layer.h"
#include "core/ddm/ddm_pn_maps.h"
#include "core/dffd/dffd.h"
#include "core/dffd/dffd_rig.h"
#include "core/ffd/ffd.h"
#include "core/scene/primitives.h"
#include "core/scene/scene.h"

namespace trispline::test {

// The sphere (radius 1) with 2 × 2 thorns per limit chart of its 8 × 4 polygon, height 0.12, placed by a transform.
inline core::SceneObject thorny_sphere() {
  core::SceneObject o;
  o.name = "ball";
  o.rest_mesh = std::make_shared<const core::TriMesh>(core::make_sphere(8, 4));
  o.transform.translate = {0.3, -0.2, 0.1};
  o.transform.rotate_deg = {10.0, 25.0, 0.0};
  o.transform.scale = {1.2, 0.9, 1.0};
  auto layer = std::make_shared<core::DdmLayer>();
  layer->name = "thorns";
  layer->tiles = {core::make_ddm_tile("thorn")};
  layer->height = 0.12;
  layer->surface = std::make_shared<core::DdmSubdivBase>(*o.rest_mesh);
  layer->instances = core::ddm_layout_cells(core::DdmLayout::rect, {2, 2}, layer->surface->chart_count());
  layer->host_mesh = o.rest_mesh;
  core::ddm_layer_finish(*layer, {9, 9});
  o.ddm_layers = {layer};
  o.refresh();
  return o;
}

// The world box of the object and its tiles, and a lattice of `controls` per axis (order 3) that is the identity of
// that box (control points at the Greville abscissae).
inline core::FfdBinding identity_binding(const core::SceneObject& o, glm::ivec3 controls = {5, 5, 5}) {
  std::vector<glm::dvec3> pts = o.world_rest_mesh().positions;
  const glm::dmat4 m = o.transform.matrix();
  for (const auto& l : o.ddm_layers)
    for (const glm::dvec3& p : l->mesh->positions) pts.push_back(glm::dvec3(m * glm::dvec4(p, 1.0)));
  core::FfdBinding b{
      core::TrivariateBSpline<glm::dvec3>(core::KnotVector::clamped_uniform(3, controls.x),
                                          core::KnotVector::clamped_uniform(3, controls.y),
                                          core::KnotVector::clamped_uniform(3, controls.z),
                                          std::vector<glm::dvec3>(std::size_t(controls.x) * controls.y * controls.z)),
      core::embed_bounding_box(pts, {0, 1}),
      {}};
  const glm::dmat3 inv = glm::inverse(b.embedding.linear);
  const auto gu = b.lattice.knots(0).greville(), gv = b.lattice.knots(1).greville(), gw = b.lattice.knots(2).greville();
  for (int k = 0; k < controls.z; ++k)
    for (int j = 0; j < controls.y; ++j)
      for (int i = 0; i < controls.x; ++i)
        b.lattice.control_point(i, j, k) = inv * (glm::dvec3(gu[i], gv[j], gw[k]) - b.embedding.offset);
  b.params = core::embed_points(b.embedding, o.world_rest_mesh().positions);
  return b;
}

// (a) bent and twisted by an FFD, with a parameter offset.
inline core::SceneObject ffd_case() {
  core::SceneObject o = thorny_sphere();
  core::FfdBinding b = identity_binding(o);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 5; ++i) {
        glm::dvec3& p = b.lattice.control_point(i, j, k);
        p.y += 0.25 * std::sin(1.3 * i) + 0.1 * k;
        p.z += 0.15 * (j - 2) * (i - 2) * 0.2;
      }
  o.ffd = std::make_shared<const core::FfdBinding>(std::move(b));
  o.param_offset = {0.02, 0.0, -0.01};
  o.refresh();
  return o;
}

// (b) the host surface warped in place (vertex count and order kept), as a clip pose would.
inline core::SceneObject host_case() {
  core::SceneObject o = thorny_sphere();
  core::TriMesh warped = *o.rest_mesh;
  for (glm::dvec3& p : warped.positions)
    p = glm::dvec3(p.x * 1.3 + 0.2 * p.y * p.y, p.y + 0.3 * std::sin(2 * p.x), p.z);
  o.rest_mesh = std::make_shared<const core::TriMesh>(std::move(warped));  // the layer keeps the old one as host
  o.refresh();
  return o;
}

// (c) a DFFD with a break at u = 0.5 across the sphere, its two sides pulled apart.
inline core::SceneObject dffd_case() {
  core::SceneObject o = thorny_sphere();
  const core::FfdBinding b = identity_binding(o);
  auto rig = std::make_shared<core::DffdRig>(
      core::DffdRig{b.lattice, b.embedding, b.params, {}, core::DffdOpenings::open, 1e-6, true, {}, {}});
  const core::Discontinuity d = core::insert_discontinuity(rig->lattice, 0, 0.5);
  core::open_discontinuity(rig->lattice, d, {-0.3, 0.0, 0.0}, {0.3, 0.1, 0.0});
  rig->discontinuities = {d};
  o.dffd = rig;
  o.refresh();
  return o;
}

}  // namespace trispline::test
