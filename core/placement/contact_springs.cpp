// Mass-spring relaxation of the contact surface (seed §2.3.2); see contact_springs.h for the model.
#include "core/placement/contact_springs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/raycast/ray_caster.h"

namespace trispline::core {

namespace {

// Neighbour offsets in cyclic order +u, +v, −u, −v (the four springs of a mass).
constexpr int kSpringDi[4] = {1, 0, -1, 0};
constexpr int kSpringDj[4] = {0, 1, 0, -1};

bool finite3(const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("relax_contact_surface: " + what);
}

double angle_deg(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / std::numbers::pi;
}

}  // namespace

double contact_roughness_deg(const std::vector<glm::dvec3>& points, int l, int m, int i, int j) {
  const glm::dvec3& p = points[static_cast<size_t>(i + l * j)];
  bool has[4];
  glm::dvec3 d[4];
  for (int q = 0; q < 4; ++q) {
    const int ni = i + kSpringDi[q], nj = j + kSpringDj[q];
    has[q] = ni >= 0 && ni < l && nj >= 0 && nj < m;
    d[q] = has[q] ? points[static_cast<size_t>(ni + l * nj)] - p : glm::dvec3(0.0);
  }
  bool nhas[4];
  glm::dvec3 n[4];
  for (int q = 0; q < 4; ++q) {
    const int r = (q + 1) % 4;
    nhas[q] = has[q] && has[r];
    if (nhas[q]) {
      n[q] = glm::cross(d[q], d[r]);
      if (!(glm::length(n[q]) > 0.0)) nhas[q] = false;  // degenerate triangle: skipped
    }
  }
  double worst = 0.0;
  for (int q = 0; q < 4; ++q) {
    const int r = (q + 1) % 4;
    if (nhas[q] && nhas[r]) worst = std::max(worst, angle_deg(n[q], n[r]));
  }
  return worst;
}

namespace {

void validate_springs(const std::vector<glm::dvec3>& points, int l, int m, const std::vector<glm::dvec3>& directions,
                      const SpringParams& prm) {
  require(l >= 1 && m >= 1, "grid size l, m must be >= 1");
  const size_t N = static_cast<size_t>(l) * static_cast<size_t>(m);
  require(points.size() == N, "points must have l*m entries");
  require(directions.size() == N, "directions must have l*m entries");
  require(std::isfinite(prm.mass) && prm.mass > 0.0, "mass must be positive");
  require(std::isfinite(prm.stiffness) && prm.stiffness > 0.0, "stiffness must be positive");
  require(std::isfinite(prm.damping) && prm.damping >= 0.0, "damping must be >= 0");
  require(prm.angle_threshold_deg > 0.0 && prm.angle_threshold_deg < 180.0, "angle_threshold_deg must be in (0, 180)");
  require(prm.max_steps >= 0, "max_steps must be >= 0");
  require(std::isfinite(prm.ray_height) && prm.ray_height > 0.0, "ray_height must be positive");
  for (size_t a = 0; a < N; ++a) {
    require(finite3(points[a]), "non-finite point");
    require(finite3(directions[a]), "non-finite direction");
    require(std::abs(glm::length(directions[a]) - 1.0) <= 1e-6, "directions must be unit vectors");
  }
}

// Floors along V_P (first hit from above): per mass, the lowest offset s along its direction (−∞ = none).
std::vector<double> spring_floors(const std::vector<glm::dvec3>& P0, const std::vector<glm::dvec3>& directions,
                                  const RayCaster* scene, const SpringParams& prm, SpringStats& st) {
  const size_t N = P0.size();
  const double no_floor = -std::numeric_limits<double>::infinity();
  std::vector<double> floor_s(N, no_floor);
  if (scene != nullptr && !scene->empty()) {
    for (size_t a = 0; a < N; ++a) {
      const glm::dvec3& V = directions[a];
      const auto hit = scene->intersect(P0[a] + prm.ray_height * V, -V);
      if (hit) {
        floor_s[a] = glm::dot(hit->position - P0[a], V);
        ++st.floors;
      }
    }
  }
  return floor_s;
}

// Candidates (rougher than the threshold) and the active set around them, in ascending index order.
std::vector<size_t> active_masses(const std::vector<glm::dvec3>& points, int l, int m, const SpringParams& prm,
                                  SpringStats& st) {
  const size_t N = points.size();
  const auto idx = [l](int i, int j) { return static_cast<size_t>(i + l * j); };
  std::vector<unsigned char> cand(N, 0), active(N, 0);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < l; ++i)
      if (contact_roughness_deg(points, l, m, i, j) > prm.angle_threshold_deg) {
        cand[idx(i, j)] = 1;
        ++st.candidates;
      }
  if (prm.neighbourhood < 0) {
    std::fill(active.begin(), active.end(), 1);
  } else {
    const int r = prm.neighbourhood;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < l; ++i) {
        if (!cand[idx(i, j)]) continue;
        for (int jj = std::max(0, j - r); jj <= std::min(m - 1, j + r); ++jj)
          for (int ii = std::max(0, i - r); ii <= std::min(l - 1, i + r); ++ii) active[idx(ii, jj)] = 1;
      }
  }
  std::vector<size_t> act;
  for (size_t a = 0; a < N; ++a)
    if (active[a]) act.push_back(a);
  st.active = static_cast<int>(act.size());
  return act;
}

// Rest lengths per (mass, neighbour slot): 4·#masses, 0 where there is no neighbour or rest lengths are zero.
std::vector<double> rest_lengths(const std::vector<glm::dvec3>& P0, int l, int m, const SpringParams& prm) {
  const auto idx = [l](int i, int j) { return static_cast<size_t>(i + l * j); };
  std::vector<double> rest(4 * P0.size(), 0.0);
  if (prm.rest_length_initial)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < l; ++i)
        for (int q = 0; q < 4; ++q) {
          const int ni = i + kSpringDi[q], nj = j + kSpringDj[q];
          if (ni >= 0 && ni < l && nj >= 0 && nj < m)
            rest[4 * idx(i, j) + q] = glm::length(P0[idx(ni, nj)] - P0[idx(i, j)]);
        }
  return rest;
}

}  // namespace

SpringStats relax_contact_surface(std::vector<glm::dvec3>& points, int l, int m,
                                  const std::vector<glm::dvec3>& directions, const RayCaster* scene,
                                  const SpringParams& prm) {
  validate_springs(points, l, m, directions, prm);
  const size_t N = static_cast<size_t>(l) * static_cast<size_t>(m);

  SpringStats st;
  const double M = prm.mass, k = prm.stiffness, rho = prm.damping;
  const double w_max = std::sqrt(8.0 * k / M);
  st.dt = 1.0 / w_max;
  if (rho > 0.0) st.dt = std::min(st.dt, M / rho);
  const double dt = st.dt;

  const std::vector<glm::dvec3> P0 = points;
  const auto idx = [l](int i, int j) { return static_cast<size_t>(i + l * j); };
  const std::vector<double> floor_s = spring_floors(P0, directions, scene, prm, st);
  const std::vector<size_t> act = active_masses(points, l, m, prm, st);
  const std::vector<double> rest = rest_lengths(P0, l, m, prm);

  // If a mass starts below its floor, lift it onto it first (the constraint holds at all times).
  std::vector<double> s(N, 0.0), v(N, 0.0), acc(N, 0.0);
  for (size_t a : act)
    if (s[a] < floor_s[a]) {
      s[a] = floor_s[a];
      points[a] = P0[a] + s[a] * directions[a];
    }

  auto all_smooth = [&]() {
    for (size_t a : act) {
      const int i = static_cast<int>(a % static_cast<size_t>(l)), j = static_cast<int>(a / static_cast<size_t>(l));
      if (contact_roughness_deg(points, l, m, i, j) > prm.angle_threshold_deg) return false;
    }
    return true;
  };

  st.converged = all_smooth();
  while (!st.converged && st.steps < prm.max_steps) {
    // Accelerations from the old state (Jacobi order).
    for (size_t a : act) {
      const int i = static_cast<int>(a % static_cast<size_t>(l)), j = static_cast<int>(a / static_cast<size_t>(l));
      glm::dvec3 f(0.0);
      for (int q = 0; q < 4; ++q) {
        const int ni = i + kSpringDi[q], nj = j + kSpringDj[q];
        if (ni < 0 || ni >= l || nj < 0 || nj >= m) continue;
        const glm::dvec3 D = points[idx(ni, nj)] - points[a];
        if (prm.rest_length_initial) {
          const double len = glm::length(D);
          if (len > 0.0) f += k * (len - rest[4 * a + q]) / len * D;
        } else {
          f += k * D;
        }
      }
      acc[a] = glm::dot(f, directions[a]) / M - rho / M * v[a];
    }
    for (size_t a : act) {
      v[a] += dt * acc[a];
      s[a] += dt * v[a];
      if (s[a] <= floor_s[a]) {
        s[a] = floor_s[a];
        if (v[a] < 0.0) v[a] = 0.0;
      }
      points[a] = P0[a] + s[a] * directions[a];
    }
    ++st.steps;
    st.converged = all_smooth();
  }

  for (size_t a = 0; a < N; ++a) st.max_displacement = std::max(st.max_displacement, std::abs(s[a]));
  return st;
}

}  // namespace trispline::core
