// trispline::python::PyLattice — trispline.Lattice: a control lattice F (core::TrivariateBSpline<glm::dvec3>, seed
// Eq. 2.1) with the affine embedding E that takes the points it deforms into F's parameter domain (core::Embedding,
// core/ffd/ffd.h): a point x maps to F(E(x)). E is the identity when the points are parameters themselves.
#pragma once

#include "core/ffd/ffd.h"
#include "core/spline/trivariate_bspline.h"

namespace trispline::python {

struct PyLattice {
  core::TrivariateBSpline<glm::dvec3> spline;
  core::Embedding embedding;  // world → parameter domain (A x + b)
};

}  // namespace trispline::python
