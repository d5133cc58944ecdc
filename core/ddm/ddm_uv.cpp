// UV-mapped DDM bases: P/N maps rasterised in texture space. See ddm_pn_maps.h (ddm_rasterize_uv_maps).
// Source: seed §5.3.1 and §5.4.1 — the base's positions and normals drawn into its own texture space, texels no
// triangle covers filled by repeated 8-neighbour averaging (the seed's diffusion), and a bitmap of the valid texels.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/ddm/ddm_pn_maps.h"
#include "core/mesh/mesh_io.h"

namespace trispline::core {
namespace {

constexpr int kF = DdmMaps::kFloatsPerSample;

bool finite2(const glm::dvec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Area-weighted vertex normals (for meshes loaded without normals).
std::vector<glm::dvec3> vertex_normals(const TriMesh& m) {
  if (m.normals.size() == m.vertex_count()) return m.normals;
  std::vector<glm::dvec3> n(m.vertex_count(), glm::dvec3(0.0));
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 a = glm::cross(m.positions[t[1]] - m.positions[t[0]], m.positions[t[2]] - m.positions[t[0]]);
    n[t[0]] += a, n[t[1]] += a, n[t[2]] += a;
  }
  for (glm::dvec3& v : n) v = glm::length(v) > 0.0 ? glm::normalize(v) : glm::dvec3(0, 0, 1);
  return n;
}

}  // namespace

DdmMaps ddm_rasterize_uv_maps(const TriMesh& mesh, int resolution) {
  if (resolution < 2 || resolution > 4097)
    throw std::invalid_argument("map_resolution: " + std::to_string(resolution) + " (need 2 … 4097)");
  if (mesh.triangles.empty()) throw std::invalid_argument("base: the mesh has no triangles");
  if (mesh.uvs.size() != mesh.vertex_count())
    throw std::invalid_argument("base: the mesh has no texture coordinates (" + std::to_string(mesh.uvs.size()) +
                                " uvs for " + std::to_string(mesh.vertex_count()) + " vertices); use base \"limit\"");
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    if (!finite3(mesh.positions[v]) || !finite2(mesh.uvs[v]))
      throw std::invalid_argument("base: non-finite position or uv at vertex " + std::to_string(v));
  const int R = resolution;
  const std::size_t count = static_cast<std::size_t>(R) * R;
  DdmMaps maps;
  maps.resolution = {R, R};
  maps.slot_of_chart = {0};
  maps.chart_of_slot = {0};
  maps.samples.assign(count * kF, 0.0f);
  maps.valid.assign(count, 0);
  const std::vector<glm::dvec3> normals = vertex_normals(mesh);
  std::vector<glm::dvec3> P(count), N(count), Su(count), Sv(count);
  for (const glm::uvec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k)
      if (t[k] >= mesh.vertex_count()) throw std::invalid_argument("base: a triangle index ≥ #V");
    const glm::dvec2 a = mesh.uvs[t[0]], b = mesh.uvs[t[1]], c = mesh.uvs[t[2]];
    const glm::dvec2 e1 = b - a, e2 = c - a;
    const double det = e1.x * e2.y - e1.y * e2.x;
    if (!(std::abs(det) > 1e-14)) continue;  // a triangle with no UV area covers no sample
    // [S_u S_v] = [P1 − P0, P2 − P0] · M⁻¹ with M = [e1 e2] (the triangle's UV Jacobian).
    const glm::dvec3 d1 = mesh.positions[t[1]] - mesh.positions[t[0]], d2 = mesh.positions[t[2]] - mesh.positions[t[0]];
    const glm::dvec3 su = (d1 * e2.y - d2 * e1.y) / det, sv = (d2 * e1.x - d1 * e2.x) / det;
    const glm::dvec2 lo = glm::min(a, glm::min(b, c)) * double(R - 1), hi = glm::max(a, glm::max(b, c)) * double(R - 1);
    const int i0 = std::max(0, static_cast<int>(std::ceil(lo.x - 1e-9))),
              i1 = std::min(R - 1, static_cast<int>(std::floor(hi.x + 1e-9)));
    const int j0 = std::max(0, static_cast<int>(std::ceil(lo.y - 1e-9))),
              j1 = std::min(R - 1, static_cast<int>(std::floor(hi.y + 1e-9)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const glm::dvec2 q = glm::dvec2(i, j) / double(R - 1) - a;
        const double s = (q.x * e2.y - q.y * e2.x) / det, r = (e1.x * q.y - e1.y * q.x) / det;
        if (s < -1e-9 || r < -1e-9 || s + r > 1.0 + 1e-9) continue;
        const std::size_t k = static_cast<std::size_t>(j) * R + i;
        P[k] = mesh.positions[t[0]] * (1 - s - r) + mesh.positions[t[1]] * s + mesh.positions[t[2]] * r;
        const glm::dvec3 n = normals[t[0]] * (1 - s - r) + normals[t[1]] * s + normals[t[2]] * r;
        N[k] = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0, 0, 1);
        Su[k] = su, Sv[k] = sv;
        maps.valid[k] = 1;
      }
  }
  if (std::find(maps.valid.begin(), maps.valid.end(), 1) == maps.valid.end())
    throw std::invalid_argument("base: no sample of the " + std::to_string(R) + "² UV map is covered by a triangle");
  // Diffusion fill (seed §5.4.1): ring by ring, an empty sample takes the mean of its filled 8-neighbours of the
  // previous ring (Jacobi order: deterministic). A ring's candidates are the empty neighbours of the previous ring
  // (of the covered samples for the first), so a pass costs the ring's size, not R².
  std::vector<std::uint8_t> filled = maps.valid;
  auto for_neighbours = [R](std::size_t k, auto&& f) {
    const int i = static_cast<int>(k % R), j = static_cast<int>(k / R);
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        const int x = i + di, y = j + dj;
        if ((di == 0 && dj == 0) || x < 0 || y < 0 || x >= R || y >= R) continue;
        f(static_cast<std::size_t>(y) * R + x);
      }
  };
  std::vector<std::size_t> ring;  // the samples filled by the last pass
  for (std::size_t k = 0; k < count; ++k)
    if (filled[k]) ring.push_back(k);
  std::vector<std::uint8_t> queued(count, 0);
  while (!ring.empty()) {
    std::vector<std::size_t> next;
    for (const std::size_t k : ring)
      for_neighbours(k, [&](std::size_t q) {
        if (!filled[q] && !queued[q]) queued[q] = 1, next.push_back(q);
      });
    std::sort(next.begin(), next.end());
    for (const std::size_t k : next) {
      glm::dvec3 p(0.0), n(0.0), su(0.0), sv(0.0);
      int c = 0;
      for_neighbours(k, [&](std::size_t q) {
        if (filled[q] != 1) return;
        p += P[q], n += N[q], su += Su[q], sv += Sv[q], ++c;
      });
      P[k] = p / double(c), N[k] = glm::length(n) > 0.0 ? glm::normalize(n) : glm::dvec3(0, 0, 1);
      Su[k] = su / double(c), Sv[k] = sv / double(c);
    }
    for (const std::size_t k : next) filled[k] = 1;  // usable from the next ring on
    ring = std::move(next);
  }
  // N_u, N_v by central differences of the N map (one-sided on the border), per parameter unit.
  for (int j = 0; j < R; ++j)
    for (int i = 0; i < R; ++i) {
      const std::size_t k = static_cast<std::size_t>(j) * R + i;
      const int il = std::max(i - 1, 0), ir = std::min(i + 1, R - 1), jl = std::max(j - 1, 0),
                jr = std::min(j + 1, R - 1);
      const glm::dvec3 nu = (N[static_cast<std::size_t>(j) * R + ir] - N[static_cast<std::size_t>(j) * R + il]) *
                            (double(R - 1) / (ir - il));
      const glm::dvec3 nv = (N[static_cast<std::size_t>(jr) * R + i] - N[static_cast<std::size_t>(jl) * R + i]) *
                            (double(R - 1) / (jr - jl));
      float* s = maps.samples.data() + k * kF;
      const glm::dvec3 v6[6] = {P[k], N[k], Su[k], Sv[k], nu, nv};
      for (int m = 0; m < 6; ++m)
        for (int x = 0; x < 3; ++x) s[3 * m + x] = static_cast<float>(v6[m][x]);
    }
  maps.base_size = std::max(mesh_bounds(mesh).diagonal(), 1e-12);
  return maps;
}

}  // namespace trispline::core
