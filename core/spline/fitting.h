// Least-squares fitting of B-spline curves and surfaces to points with given parameters.
// Source: Piegl & Tiller ch. 9.4 (least-squares approximation); seed §2.3.1 (contact-surface re-fit).
#pragma once

#include <vector>

#include "core/spline/bspline_curve.h"
#include "core/spline/bspline_surface.h"

namespace trispline::core {

enum class Parametrization { Uniform, ChordLength, Centripetal };

// Parameters in [0,1] for an ordered point sequence (#P). Uniform: i/(P-1); ChordLength (= arc length of the
// polyline): cumulative |P_i - P_{i-1}| normalised; Centripetal: cumulative sqrt of that. Coincident points
// get equal parameters; a sequence of zero total length falls back to Uniform. Throws if #P < 2.
template <class T>
std::vector<double> parametrize(const std::vector<T>& points, Parametrization kind);

// Least-squares curve with clamped knots (KnotVector::clamped_for_fit) of `order` and `control_count`, through
// points (#P) at params (#P, non-decreasing, from 0 to 1); end points interpolated exactly (P&T 9.4.1: the
// endpoint-constrained least-squares problem, normal equations NᵀN·P = R).
// Throws std::invalid_argument if #P < control_count, order > control_count, control_count < 2, sizes differ,
// params do not run from 0 to 1, or the input is not finite.
template <class T>
BSplineCurve<T> fit_curve(const std::vector<T>& points, const std::vector<double>& params, int order,
                          int control_count);
// Same with given knots: knots must be clamped, params must start at knots.domain_min() and end at
// knots.domain_max() (within 1e-12 of the domain length), #P >= knots.control_count() >= 2. Throws
// std::invalid_argument on any violation, on non-finite input, and when the normal equations are singular
// (some basis function has no parameter in its support). The solver is a band Cholesky (band_cholesky.h).
template <class T>
BSplineCurve<T> fit_curve(const std::vector<T>& points, const std::vector<double>& params, const KnotVector& knots);

// Least-squares tensor-product surface through a grid of points (#(pu·pv), u fastest) with parameters
// params_u (#pu) and params_v (#pv); orders and control counts per axis; corners interpolated.
// Separable: fits every row in u, then every resulting control column in v (exact tensor-product LSQ on grids).
// Throws std::invalid_argument if grid.size() != pu·pv or a per-axis condition of fit_curve fails.
// Instantiated for T = double, glm::dvec2, glm::dvec3 (parametrize and fit_curve too).
template <class T>
BSplineSurface<T> fit_surface(const std::vector<T>& grid, int pu, int pv, const std::vector<double>& params_u,
                              const std::vector<double>& params_v, int order_u, int order_v, int control_count_u,
                              int control_count_v);
// Same with given clamped knot vectors per axis (conditions as for fit_curve with knots).
template <class T>
BSplineSurface<T> fit_surface(const std::vector<T>& grid, int pu, int pv, const std::vector<double>& params_u,
                              const std::vector<double>& params_v, const KnotVector& knots_u,
                              const KnotVector& knots_v);

}  // namespace trispline::core
