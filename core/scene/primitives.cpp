#include "core/scene/primitives.h"

#include <array>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <iterator>
#include <random>
#include <stdexcept>
#include <unordered_map>

#include "core/base/enum_names.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/uv_sphere.h"
#include "core/spline/bspline_surface.h"

namespace trispline::core {
namespace {

constexpr double kPi = glm::pi<double>();

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

// Quad (a, b, c, d), counter-clockwise seen from the side it faces, as two triangles.
void add_quad(TriMesh& m, unsigned a, unsigned b, unsigned c, unsigned d) {
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

// (n+1)² grid over [-1,1]² in xz at height h(x, z); vertex (i, j) = i + (n+1)·j, x = -1 + 2i/n, z = -1 + 2j/n.
// Triangles are CCW seen from +y.
template <class Height>
TriMesh xz_grid(int n, Height h) {
  TriMesh m;
  const auto row = static_cast<unsigned>(n + 1);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1.0 + 2.0 * i / n, z = -1.0 + 2.0 * j / n;
      m.positions.push_back({x, h(x, z), z});
      m.uvs.push_back({double(i) / n, double(j) / n});
    }
  for (unsigned j = 0; j < unsigned(n); ++j)
    for (unsigned i = 0; i < unsigned(n); ++i) {
      const unsigned a = i + row * j;
      add_quad(m, a, a + row, a + row + 1, a + 1);  // a → +z → +x+z → +x is CCW seen from +y
    }
  return m;
}

// Uniform double in [0,1) from the raw 64-bit output (53 high bits): identical on every platform.
double unit_double(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Exact-key welding with a 3×3×3 neighbourhood search, so points that round into neighbouring cells still meet.
class Welder {
 public:
  explicit Welder(double cell) : inv_cell_(1.0 / cell), tol2_(cell * cell) {}
  // Index of a previously added point within `cell` of p, or -1.
  long find(const glm::dvec3& p, const std::vector<glm::dvec3>& points) const {
    const Key k = key(p);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dz = -1; dz <= 1; ++dz) {
          const auto it = map_.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it != map_.end() && glm::dot(points[it->second] - p, points[it->second] - p) <= tol2_) return it->second;
        }
    return -1;
  }
  void insert(const glm::dvec3& p, long index) { map_.emplace(key(p), index); }

 private:
  using Key = std::array<long long, 3>;
  struct Hash {
    std::size_t operator()(const Key& k) const {
      return std::hash<long long>()(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  Key key(const glm::dvec3& p) const {
    return {std::llround(p.x * inv_cell_), std::llround(p.y * inv_cell_), std::llround(p.z * inv_cell_)};
  }
  double inv_cell_, tol2_;
  std::unordered_map<Key, long, Hash> map_;
};

}  // namespace

namespace {

constexpr const char* kPrimitiveKindNames[] = {"teapot", "plane", "sphere", "box", "cylinder", "terrain"};
static_assert(std::size(kPrimitiveKindNames) == std::size_t(PrimitiveKind::Terrain) + 1, "one name per kind");

}  // namespace

PrimitiveKind parse_primitive_kind(const std::string& name) {
  for (std::size_t i = 0; i < std::size(kPrimitiveKindNames); ++i)
    if (name == kPrimitiveKindNames[i]) return static_cast<PrimitiveKind>(i);
  throw std::invalid_argument("unknown primitive kind '" + name +
                              "' (valid kinds: teapot, plane, sphere, box, cylinder, terrain)");
}

std::string primitive_kind_name(PrimitiveKind kind) {
  const char* name = core::enum_name(kind, kPrimitiveKindNames, nullptr);
  if (!name) throw std::invalid_argument("invalid PrimitiveKind");
  return name;
}

TriMesh make_primitive(PrimitiveKind kind, std::uint64_t seed) {
  switch (kind) {
    case PrimitiveKind::Teapot:
      return make_teapot();
    case PrimitiveKind::Plane:
      return make_plane();
    case PrimitiveKind::Sphere:
      return make_sphere();
    case PrimitiveKind::Box:
      return make_box();
    case PrimitiveKind::Cylinder:
      return make_cylinder();
    case PrimitiveKind::Terrain:
      return make_terrain(seed);
  }
  throw std::invalid_argument("invalid PrimitiveKind");
}

TriMesh make_plane(int divisions) {
  require(divisions >= 1, "make_plane: divisions must be >= 1");
  TriMesh m = xz_grid(divisions, [](double, double) { return 0.0; });
  m.normals.assign(m.positions.size(), glm::dvec3(0, 1, 0));
  return m;
}

TriMesh make_sphere(int slices, int stacks) {
  require(slices >= 3 && stacks >= 2, "make_sphere: need slices >= 3 and stacks >= 2");
  // Unit sphere, φ toward +z, radial normals (= positions): core/mesh/uv_sphere.h.
  return make_uv_sphere(1.0, stacks, slices, SpherePhi::toward_plus_z, SphereNormals::radial);
}

TriMesh make_box() {
  constexpr int n = 8;  // quads per face edge, so that the box deforms
  TriMesh m;
  // Per face: outward normal and tangents (u, v) with u × v = normal.
  const glm::dvec3 X(1, 0, 0), Y(0, 1, 0), Z(0, 0, 1);
  const std::array<std::array<glm::dvec3, 3>, 6> faces = {
      {{X, Y, Z}, {-X, Z, Y}, {Y, Z, X}, {-Y, X, Z}, {Z, X, Y}, {-Z, Y, X}}};
  for (const auto& f : faces) {
    const auto base = static_cast<unsigned>(m.positions.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double s = double(i) / n, t = double(j) / n;
        m.positions.push_back(f[0] + (2 * s - 1) * f[1] + (2 * t - 1) * f[2]);
        m.normals.push_back(f[0]);
        m.uvs.push_back({s, t});
      }
    for (unsigned j = 0; j < unsigned(n); ++j)
      for (unsigned i = 0; i < unsigned(n); ++i) {
        const unsigned a = base + i + (n + 1) * j;
        add_quad(m, a, a + 1, a + n + 2, a + n + 1);
      }
  }
  return m;
}

TriMesh make_cylinder(int segments) {
  require(segments >= 3, "make_cylinder: segments must be >= 3");
  constexpr int rings = 16;  // quads along the height, so that the side deforms
  TriMesh m;
  for (int k = 0; k <= rings; ++k)
    for (int i = 0; i < segments; ++i) {
      const double ph = 2.0 * kPi * i / segments;
      m.positions.push_back({std::cos(ph), -1.0 + 2.0 * k / rings, std::sin(ph)});
      m.normals.push_back({std::cos(ph), 0.0, std::sin(ph)});
    }
  const auto segs = static_cast<unsigned>(segments);
  for (unsigned k = 0; k < unsigned(rings); ++k)
    for (unsigned i = 0; i < segs; ++i) {
      const unsigned a = k * segs + i, b = k * segs + (i + 1) % segs;
      add_quad(m, a, a + segs, b + segs, b);  // lower φ → upper φ → upper φ+dφ → lower φ+dφ: outwards
    }
  for (const double y : {1.0, -1.0}) {  // caps: centre + own ring (split from the side for a sharp rim)
    const auto centre = static_cast<unsigned>(m.positions.size());
    m.positions.push_back({0, y, 0});
    m.normals.push_back({0, y, 0});
    for (int i = 0; i < segments; ++i) {
      const double ph = 2.0 * kPi * i / segments;
      m.positions.push_back({std::cos(ph), y, std::sin(ph)});
      m.normals.push_back({0, y, 0});
    }
    for (unsigned i = 0; i < segs; ++i) {
      const unsigned r0 = centre + 1 + i, r1 = centre + 1 + (i + 1) % segs;
      if (y > 0)
        m.triangles.push_back({centre, r1, r0});  // CCW seen from +y
      else
        m.triangles.push_back({centre, r0, r1});  // CCW seen from -y
    }
  }
  return m;
}

TriMesh make_terrain(std::uint64_t seed, int divisions) {
  require(divisions >= 2, "make_terrain: divisions must be >= 2");
  // A sum of 14 Gaussian hills (centres slightly beyond the square so edges are not flat), rescaled to [0, 0.3].
  struct Hill {
    double x, z, inv2s2, amp;
  };
  std::mt19937_64 rng(seed);
  std::vector<Hill> hills(14);
  for (auto& h : hills) {
    h.x = -1.3 + 2.6 * unit_double(rng);
    h.z = -1.3 + 2.6 * unit_double(rng);
    const double sigma = 0.18 + 0.35 * unit_double(rng);
    h.inv2s2 = 1.0 / (2.0 * sigma * sigma);
    h.amp = (unit_double(rng) < 0.25 ? -0.5 : 1.0) * (0.3 + 0.7 * unit_double(rng));  // a few dips
  }
  auto f = [&](double x, double z) {
    double s = 0;
    for (const auto& h : hills) s += h.amp * std::exp(-((x - h.x) * (x - h.x) + (z - h.z) * (z - h.z)) * h.inv2s2);
    return s;
  };
  TriMesh m = xz_grid(divisions, f);
  double lo = 1e300, hi = -1e300;
  for (const auto& p : m.positions) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  const double range = hi > lo ? hi - lo : 1.0;
  for (auto& p : m.positions) p.y = 0.3 * ((p.y - lo) / range);
  compute_vertex_normals(m);
  return m;
}

TriMesh make_teapot(int segments) {
  require(segments >= 2, "make_teapot: segments must be >= 2");
  const int s = segments;
  const KnotVector bezier(4, {0, 0, 0, 0, 1, 1, 1, 1});  // one cubic Bézier span, clamped
  TriMesh m;
  std::vector<glm::dvec3> normal_sum;
  Welder welder(1e-9);  // Newell units (model ~3 units across); shared patch edges agree to ~1e-15
  std::vector<unsigned> grid(static_cast<std::size_t>((s + 1) * (s + 1)));
  for (int p = 0; p < detail::kTeapotPatchCount; ++p) {
    std::vector<glm::dvec3> cps(16);
    for (int k = 0; k < 16; ++k) {  // row-major (v, u) = u fastest, as BSplineSurface stores them
      const double* q = detail::kTeapotVertices[detail::kTeapotPatches[p][k]];
      cps[k] = {q[0], q[2], -q[1]};  // z up → y up, right-handed: (x, y, z) ↦ (x, z, −y)
    }
    const BSplineSurface<glm::dvec3> patch(bezier, bezier, std::move(cps));
    for (int j = 0; j <= s; ++j)
      for (int i = 0; i <= s; ++i) {
        const double u = double(i) / s, v = double(j) / s;
        const glm::dvec3 pos = patch.eval(u, v);
        glm::dvec3 n = patch.normal(u, v);
        if (glm::length(n) < 0.5) {
          // Degenerate edge (lid knob and bottom centre collapse a whole patch row): take the normal a little
          // inside the patch, towards its centre, where the surface is regular.
          for (double step : {1e-3, 1e-2, 0.5 / s}) {
            n = patch.normal(u + (0.5 - u) * step * 2, v + (0.5 - v) * step * 2);
            if (glm::length(n) > 0.5) break;
          }
        }
        long id = welder.find(pos, m.positions);
        if (id < 0) {
          id = static_cast<long>(m.positions.size());
          m.positions.push_back(pos);
          normal_sum.push_back(glm::dvec3(0.0));
          welder.insert(pos, id);
        }
        normal_sum[id] += n;
        grid[i + (s + 1) * j] = static_cast<unsigned>(id);
      }
    // With u along a patch row and v across rows, du × dv points out of the teapot: wind (u, v) quads CCW.
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) {
        const unsigned a = grid[i + (s + 1) * j], b = grid[i + 1 + (s + 1) * j];
        const unsigned c = grid[i + 1 + (s + 1) * (j + 1)], d = grid[i + (s + 1) * (j + 1)];
        for (const glm::uvec3 t : {glm::uvec3(a, b, c), glm::uvec3(a, c, d)})
          if (t.x != t.y && t.y != t.z && t.x != t.z) m.triangles.push_back(t);  // drop triangles collapsed at a pole
      }
  }
  m.normals.resize(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const double len = glm::length(normal_sum[i]);
    m.normals[i] = len > 0 ? normal_sum[i] / len : glm::dvec3(0, 1, 0);
  }
  // Stand on y = 0 with height 1, the body's axis of revolution on the y axis (Newell's data is built around
  // it, so the teapot turns about its body, as Blender's does); uniform scale keeps the normals.
  const Aabb box = mesh_bounds(m);
  const double scale = 1.0 / box.size().y;
  const glm::dvec3 origin(0.0, box.lo.y, 0.0);
  for (auto& q : m.positions) q = (q - origin) * scale;
  return m;
}

std::vector<BSplineSurface<glm::dvec3>> teapot_body_patches() {
  // make_teapot stands the tessellated teapot on y = 0 with height 1 (uniform scale). Its lowest and highest points
  // are patch corners (the bottom's and the lid knob's poles), which every tessellation samples, so its y range is
  // that of the patch corners; the same affine map applied to the control points moves the patches exactly.
  Aabb raw;  // Newell units, y up
  for (int p = 0; p < detail::kTeapotPatchCount; ++p)
    for (int k : {0, 3, 12, 15})
      raw.extend(glm::dvec3(0.0, detail::kTeapotVertices[detail::kTeapotPatches[p][k]][2], 0.0));
  const double scale = 1.0 / raw.size().y;
  const KnotVector bezier(4, {0, 0, 0, 0, 1, 1, 1, 1});
  std::vector<BSplineSurface<glm::dvec3>> out;
  for (int p = 4; p < 12; ++p) {
    std::vector<glm::dvec3> cps(16);
    for (int k = 0; k < 16; ++k) {  // as make_teapot: u fastest, (x, y, z) ↦ (x, z, −y)
      const double* q = detail::kTeapotVertices[detail::kTeapotPatches[p][k]];
      cps[k] = (glm::dvec3(q[0], q[2], -q[1]) - glm::dvec3(0.0, raw.lo.y, 0.0)) * scale;
    }
    out.emplace_back(bezier, bezier, std::move(cps));
  }
  return out;
}

}  // namespace trispline::core
