// Contact grid: miss filling and contact-surface parameters. See contact_grid.h.
#include "core/placement/contact_grid.h"

#include <algorithm>

#include "core/spline/fitting.h"

namespace trispline::core {

int fill_missing_depths(std::vector<double>& depth, const std::vector<unsigned char>& known_in, int nu, int nv) {
  std::vector<unsigned char> known = known_in;
  if (std::find(known.begin(), known.end(), 1) == known.end()) return -1;
  int passes = 0;
  std::vector<std::pair<int, double>> found;
  for (;;) {
    found.clear();
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const int g = i + nu * j;
        if (known[g]) continue;
        double sum = 0;
        int count = 0;
        const int nb[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
        for (const auto& [a, b] : nb)
          if (a >= 0 && b >= 0 && a < nu && b < nv && known[a + nu * b]) {
            sum += depth[a + nu * b];
            ++count;
          }
        if (count > 0) found.emplace_back(g, sum / count);
      }
    if (found.empty()) break;
    for (const auto& [g, d] : found) {
      depth[g] = d;
      known[g] = 1;
    }
    ++passes;
  }
  return passes;
}

std::vector<double> contact_params_v(const std::vector<glm::dvec3>& grid, int nu, int nv) {
  std::vector<double> pv(static_cast<std::size_t>(nv), 0.0);
  std::vector<glm::dvec3> row(static_cast<std::size_t>(nv));
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) row[j] = grid[i + nu * j];
    const std::vector<double> p = parametrize(row, Parametrization::ChordLength);
    for (int j = 0; j < nv; ++j) pv[j] += p[j];
  }
  for (auto& x : pv) x /= nu;
  pv.front() = 0.0;
  pv.back() = 1.0;
  return pv;
}

std::vector<double> contact_params_u(const std::vector<glm::dvec3>& grid, int nu, int nv) {
  std::vector<glm::dvec3> mid(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i)
    mid[i] = nv % 2 ? grid[i + nu * (nv / 2)] : 0.5 * (grid[i + nu * (nv / 2 - 1)] + grid[i + nu * (nv / 2)]);
  std::vector<double> pu = parametrize(mid, Parametrization::ChordLength);
  pu.front() = 0.0;
  pu.back() = 1.0;
  return pu;
}

}  // namespace trispline::core
