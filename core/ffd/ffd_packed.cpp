// FfdPackedLattice::build — flattens a control lattice into the float tables of ffd_packed.h (the spec the float
// backends, GLSL included, implement).
#include "core/ffd/ffd_packed.h"

#include <stdexcept>
#include <string>

#include "core/mesh/tri_mesh.h"
#include "core/spline/span_basis.h"

namespace trispline::core {

namespace {

FfdPackedAxis pack_axis(const KnotVector& kv, int axis) {
  if (kv.order() < 2 || kv.order() > 4)
    throw std::invalid_argument("FfdPackedLattice: order along axis " + std::to_string(axis) + " is " +
                                std::to_string(kv.order()) + "; the float backends support orders 2..4 (degree 1..3)");
  const SpanBasis<float> b(kv);
  FfdPackedAxis a;
  a.order = kv.order();
  a.count = kv.stored_control_count();
  a.periodic = kv.is_periodic();
  a.uniform_spans = b.uniform();
  a.domain_min = b.domain_min();
  a.domain_max = b.domain_max();
  a.inv_uniform_len = b.inv_uniform_length();
  a.span_begin = b.span_begins();
  a.inv_span_len = b.inv_span_lengths();
  a.first_index = b.first_indices();
  a.coef = b.coefficient_table();
  return a;
}

}  // namespace

FfdPackedLattice FfdPackedLattice::build(const TrivariateBSpline<glm::dvec3>& lattice, const Embedding& embedding) {
  FfdPackedLattice p;
  for (int a = 0; a < 3; ++a) p.axes[a] = pack_axis(lattice.knots(a), a);
  const std::vector<glm::dvec3>& cps = lattice.control_points();
  const std::size_t expected =
      static_cast<std::size_t>(p.axes[0].count) * p.axes[1].count * static_cast<std::size_t>(p.axes[2].count);
  if (cps.size() != expected)
    throw std::invalid_argument("FfdPackedLattice: " + std::to_string(cps.size()) +
                                " control points, the knot vectors need " + std::to_string(expected));
  Aabb box;
  for (const auto& q : cps) box.extend(q);
  p.bbox_min = box.lo;
  p.bbox_max = box.hi;
  p.centre = box.center();
  p.control_points.resize(4 * cps.size());
  for (std::size_t i = 0; i < cps.size(); ++i) {
    const glm::dvec3 q = cps[i] - p.centre;
    p.control_points[4 * i + 0] = static_cast<float>(q.x);
    p.control_points[4 * i + 1] = static_cast<float>(q.y);
    p.control_points[4 * i + 2] = static_cast<float>(q.z);
    p.control_points[4 * i + 3] = 0.0f;
  }
  p.embedding_linear = glm::mat3(embedding.linear);
  return p;
}

}  // namespace trispline::core
