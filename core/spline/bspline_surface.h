// trispline::core::BSplineSurface<T> — S(u,v) = Σ_i Σ_j P_ij B_i(u) B_j(v), T = double, glm::dvec2 or glm::dvec3.
// Control points are stored u-fastest: index(i, j) = i + nu * j, i in [0,nu), j in [0,nv).
// Source: Piegl & Tiller ch. 3.4 (A3.5, A3.6), ch. 5.3 (surface knot insertion).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "core/spline/knot_vector.h"

namespace trispline::core {

template <class T>
class BSplineSurface {
 public:
  // control_points: #(nu·nv), u fastest. Throws std::invalid_argument on count mismatch / non-finite points.
  BSplineSurface(KnotVector knots_u, KnotVector knots_v, std::vector<T> control_points);

  const KnotVector& knots(int axis) const { return axis == 0 ? ku_ : kv_; }  // axis 0 = u, 1 = v
  int control_count(int axis) const { return knots(axis).control_count(); }
  const std::vector<T>& control_points() const { return cps_; }
  std::vector<T>& control_points() { return cps_; }
  const T& control_point(int i, int j) const { return cps_[i + control_count(0) * j]; }
  T& control_point(int i, int j) { return cps_[i + control_count(0) * j]; }

  // (u, v) are clamped to the domain; a NaN parameter throws std::invalid_argument.
  T eval(double u, double v) const;
  struct FirstDerivatives {
    T value, du, dv;
  };
  FirstDerivatives eval_first(double u, double v) const;
  struct SecondDerivatives {
    T value, du, dv, duu, duv, dvv;
  };  // value and 1st/2nd partials
  SecondDerivatives eval_second(double u, double v) const;
  // Unit normal du × dv / |du × dv| (only for T = glm::dvec3, else throws std::logic_error); returns (0,0,0)
  // where the surface is degenerate.
  glm::dvec3 normal(double u, double v) const;

  // Boehm knot insertion along axis (0 = u, 1 = v). Function unchanged.
  void insert_knot(int axis, double t, int times = 1);
  // Every domain knot of both axes at multiplicity = order, knots outside the domain dropped (clamped result);
  // each non-empty cell is one Bézier patch. Function unchanged.
  BSplineSurface<T> bezier_extracted() const;

 private:
  KnotVector ku_, kv_;
  std::vector<T> cps_;
};

extern template class BSplineSurface<double>;
extern template class BSplineSurface<glm::dvec2>;  // fit_surface<glm::dvec2> returns it
extern template class BSplineSurface<glm::dvec3>;

}  // namespace trispline::core
