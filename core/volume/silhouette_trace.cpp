#include "core/volume/silhouette_trace.h"

#include <cmath>
#include <unordered_map>

namespace trispline::core::silhouette_detail {

std::vector<Chain> join_traces(const std::vector<Trace>& traces) {
  const std::size_t n = traces.size();
  // Face ends filed in a hash grid of 1/256 index units; two ends match within 1e-3 index units. Both solve the same
  // three equations, but the stopping test is on the residuals, so where the curve meets the face at a shallow angle
  // the two solutions can differ by ~1e-5; distinct curves are never that close on a face at these residuals.
  constexpr double kCell = 1.0 / 256.0, kMatch = 1e-3;
  auto key_of = [](const glm::i64vec3& q) {
    return static_cast<std::uint64_t>(q.x) * 0x9E3779B97F4A7C15ull ^
           static_cast<std::uint64_t>(q.y) * 0xC2B2AE3D27D4EB4Full ^
           static_cast<std::uint64_t>(q.z) * 0x165667B19E3779F9ull;
  };
  auto quantise = [](const glm::dvec3& x) {
    return glm::i64vec3(std::floor(x.x / kCell), std::floor(x.y / kCell), std::floor(x.z / kCell));
  };
  auto end_point = [&](std::size_t e) -> const glm::dvec3& {
    const Trace& t = traces[e / 2];
    return e % 2 == 0 ? t.points.front().x : t.points.back().x;
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::size_t e = 0; e < 2 * n; ++e)
    if (traces[e / 2].on_face[e % 2]) grid[key_of(quantise(end_point(e)))].push_back(static_cast<std::uint32_t>(e));
  std::vector<std::int64_t> partner(2 * n, -1);
  for (std::size_t e = 0; e < 2 * n; ++e) {
    if (!traces[e / 2].on_face[e % 2] || partner[e] >= 0) continue;
    const glm::dvec3& p = end_point(e);
    const glm::i64vec3 q = quantise(p);
    std::int64_t best = -1;
    double best_d = kMatch;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = grid.find(key_of(q + glm::i64vec3(dx, dy, dz)));
          if (it == grid.end()) continue;
          for (std::uint32_t f : it->second) {
            if (f == e || partner[f] >= 0) continue;
            const double d = glm::length(end_point(f) - p);
            if (d < best_d || (d == best_d && static_cast<std::int64_t>(f) < best)) best_d = d, best = f;
          }
        }
    if (best >= 0) partner[e] = best, partner[best] = static_cast<std::int64_t>(e);
  }
  std::vector<char> used(n, 0);
  std::vector<Chain> chains;
  auto walk = [&](std::size_t start, int entry) {
    Chain chain;
    std::size_t cur = start;
    while (!used[cur]) {
      used[cur] = 1;
      chain.pieces.push_back({static_cast<std::uint32_t>(cur), entry == 1});
      const std::int64_t next = partner[2 * cur + (1 - entry)];
      if (next < 0) break;
      if (static_cast<std::size_t>(next / 2) == start && used[start]) {
        chain.closed = true;
        break;
      }
      cur = static_cast<std::size_t>(next / 2), entry = static_cast<int>(next % 2);
    }
    return chain;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (used[i]) continue;
    if (traces[i].closed) {
      used[i] = 1;
      chains.push_back({{{static_cast<std::uint32_t>(i), false}}, true});
    } else if (partner[2 * i] < 0) {
      chains.push_back(walk(i, 0));
    } else if (partner[2 * i + 1] < 0) {
      chains.push_back(walk(i, 1));
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!used[i]) chains.push_back(walk(i, 0));
  return chains;
}

}  // namespace trispline::core::silhouette_detail
