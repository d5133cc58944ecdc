// trispline::core DDM base surfaces — deformation displacement maps on the CPU (seed ch. 5): base surfaces as
// charts, tile layouts, and the reference evaluation T(u,v,w) = S(u,v) + n(u,v)·w (seed Eq. 5.1–5.2) with exact
// normals. The GPU path (seed §5.3.2) samples the same charts from P/N textures (ddm_pn_maps.h); this one is what
// tests and exports compare to.
//
// Conventions: chart parameters (u, v) ∈ [0,1]² (clamped); world units for S and height; tile space as ddm_tile.h.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/ddm/ddm_tile.h"
#include "core/mesh/tri_mesh.h"
#include "core/spline/bspline_surface.h"
#include "core/spline/progress.h"

namespace trispline::core {

// One base-surface point with what T and its Jacobian need: S, ∂S/∂u, ∂S/∂v (world units per parameter unit), the
// unit normal n = S_u × S_v / |S_u × S_v| and its partials ∂n/∂u, ∂n/∂v (Weingarten: the tangential part of
// ∂(S_u × S_v)/∂· divided by |S_u × S_v|).
struct DdmSurfacePoint {
  glm::dvec3 p{0.0}, du{0.0}, dv{0.0}, n{0.0}, dn_du{0.0}, dn_dv{0.0};
};

// A base surface made of charts, each parametrised over [0,1]² (seed §5.3.1).
class DdmBase {
 public:
  virtual ~DdmBase() = default;
  virtual int chart_count() const = 0;
  // (u, v) clamped to [0,1]² (taken modulo 1 on a periodic axis). Throws std::out_of_range for chart ∉
  // [0, chart_count()).
  virtual DdmSurfacePoint eval(int chart, double u, double v) const = 0;
  // Axes along which every chart closes on itself (S(0, v) = S(1, v) for u): tiles and offset animation wrap there.
  virtual glm::bvec2 periodic() const { return {false, false}; }
};

// B-spline / Bézier patches as charts (seed §5.3.1): chart c is patches[c] with its domain mapped onto [0,1]².
// Where S_u × S_v vanishes (a collapsed patch edge, the teapot's bottom centre) n is taken a little inside the patch.
// With grid = (c, r) (c·r = #patches) the patches instead form ONE chart: patch i + c·j covers
// [i/c, (i+1)/c] × [j/r, (j+1)/r] (the teapot's body: 4 patches around × 2 high, periodic around, so tiles and
// offset animation run round the pot across patch borders as in the seed's single texture space).
class DdmSplineBase final : public DdmBase {
 public:
  // Throws std::invalid_argument: no patches; grid with c·r ≠ #patches or c, r < 1.
  explicit DdmSplineBase(std::vector<BSplineSurface<glm::dvec3>> patches, glm::ivec2 grid = {0, 0},
                         glm::bvec2 periodic = {false, false});
  int chart_count() const override { return grid_.x > 0 ? 1 : static_cast<int>(patches_.size()); }
  glm::bvec2 periodic() const override { return periodic_; }
  DdmSurfacePoint eval(int chart, double u, double v) const override;
  const BSplineSurface<glm::dvec3>& patch(int i) const { return patches_.at(static_cast<std::size_t>(i)); }

 private:
  DdmSurfacePoint eval_patch(int patch, double u, double v) const;
  std::vector<BSplineSurface<glm::dvec3>> patches_;
  glm::ivec2 grid_{0, 0};
  glm::bvec2 periodic_{false, false};
};

// The limit surface of a triangle mesh (Loop scheme, OpenSubdiv Bfr, double precision; seed §5.4.1's base, without its
// global parametrisation): chart 3f + k is the quad of face f at its corner k — corners (in the face's triangular
// parameters) vertex k, the middle of edge (k, k+1), the face centre, the middle of edge (k+2, k) — mapped
// bilinearly from [0,1]², u along edge (k, k+1), v along edge (k, k+2). Neighbouring charts meet along their shared
// edges on the same limit curve, so tiles cross face borders without cracks. Boundaries: edges and corners
// interpolated (as mesh.subdivide).
// Throws std::invalid_argument ("base: …"): no triangles, an index ≥ #V, a non-finite position, an edge with more
// than two faces, a topology OpenSubdiv rejects, a face without limit surface.
class DdmSubdivBase final : public DdmBase {
 public:
  explicit DdmSubdivBase(const TriMesh& mesh);
  ~DdmSubdivBase() override;
  DdmSubdivBase(DdmSubdivBase&&) noexcept;
  int chart_count() const override;
  DdmSurfacePoint eval(int chart, double u, double v) const override;
  // The limit surface of face f at its own triangular parameters (s, t) (s, t ≥ 0, s + t ≤ 1; vertex 0 at (0,0),
  // vertex 1 at (1,0), vertex 2 at (0,1)).
  glm::dvec3 limit_point(int face, double s, double t) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One tile instance (seed §5.3.2: per-instance offsets): the cell [origin, origin + size] of chart `chart` that the
// tile's [0,1]² fills.
struct DdmInstance {
  int chart = 0;
  glm::dvec2 origin{0.0};
  glm::dvec2 size{1.0};
  int tile = 0;  // index into the layer's tiles (several tiles per layer, seed Fig. 5.12)
  bool operator==(const DdmInstance&) const = default;
};

// Per-layer transform in the tile's texture space (applied before the cell map): the tile point (x, y) goes to
//   (x', y') = R(rotate_deg) · diag(scale) · ((x, y) − ½) + ½ + shift,
// then (u, v) = origin + size ⊙ (x', y') + offset (offset: the layer's texture-space animation, seed §5.4.2).
struct DdmTileTransform {
  glm::dvec2 scale{1.0};      // tile units per cell (1 = the tile fills its cell)
  double rotate_deg = 0;      // degrees, counter-clockwise in (u, v)
  glm::dvec2 shift{0.0};      // cell units
  glm::dmat2 linear() const;  // R · diag(scale)
  glm::dvec2 apply(glm::dvec2 xy) const { return linear() * (xy - 0.5) + 0.5 + shift; }
  bool is_identity() const { return scale == glm::dvec2(1.0) && rotate_deg == 0 && shift == glm::dvec2(0.0); }
};

enum class DdmLayout { rect, hex, brick };
const char* ddm_layout_name(DdmLayout l);  // "rect" | "hex" | "brick"

// The cells of an n × m layout on every chart, chart by chart, row by row (v), then along u (tile 0 each):
//   rect   n × m cells of size (1/n, 1/m);
//   brick  m rows of height 1/m; even rows n cells, odd rows n − 1 cells shifted by half a cell (seed Fig. 5.12);
//   hex    m rows of the hex tile (its corners at y = ¼, ¾): cells of width 1/n and height 1/(0.75·(m − 1) + 1), rows
//          0.75 of a cell apart, odd rows n − 1 cells shifted by half a cell (seed Fig. 5.11).
// Throws std::invalid_argument ("counts: …") when n or m < 1 (or n < 2 for brick / hex, whose odd rows would be
// empty), or chart_count < 1.
std::vector<DdmInstance> ddm_layout_cells(DdmLayout layout, glm::ivec2 counts, int chart_count);
// The counts check of ddm_layout_cells alone, without making any cell (a log's counts may ask for 10¹⁰).
void ddm_check_layout_counts(DdmLayout layout, glm::ivec2 counts);
// The same layouts with counts of their own per chart: chart c gets chart_counts[c] (the order above). Throws as
// above for any chart's counts.
std::vector<DdmInstance> ddm_layout_cells(DdmLayout layout, const std::vector<glm::ivec2>& chart_counts);
// How many cells ddm_layout_cells makes on one chart with `counts` (valid counts), without making them.
std::size_t ddm_layout_cell_count(DdmLayout layout, glm::ivec2 counts);

// Counts on one chart of world size `chart_size` (its mean world length along u and v, world units) whose cells are
// `tile_size` world units across: n = round(size.x / tile_size); m = round(size.y / tile_size) for rect and brick, and
// for hex the m whose rows (0.75 of a cell apart, ddm_layout_cells) give cells tile_size high,
// m = round((size.y / tile_size − 1) / 0.75) + 1. At least 1 (n ≥ 2 for hex and brick), at most 2²⁰ per axis (the
// caller weighs the product against its budget). Throws std::invalid_argument ("tile_size: …") for tile_size not
// finite or ≤ 0.
glm::ivec2 ddm_counts_for_size(DdmLayout layout, glm::dvec2 chart_size, double tile_size);

// The reference evaluation (seed Eq. 5.1–5.2): every instance's copy of its tile (tiles[instance.tile]), instances
// one after another, each in its tile's vertex order (#V = Σ #tile vertices; triangles offset per instance; what
// ddm.bake writes). A tile point (x, y, w) of an instance maps to T(u, v, w·height) with (u, v) from
// DdmTileTransform above. Normals: the tile's normal through the cofactor of T's Jacobian
//   J = [S'_u, S'_v] · diag(size) · L | h·n],  S'_· = S_· + w·h·n_·,  L = transform.linear()
// (exact, seed §5.3.2 last paragraph, without its ε trick), renormalised. TBB over instances; deterministic.
// `progress` (may be null) is checked between chunks of instances (reported in [0, 1], on the calling thread): the
// chunks change nothing in the result. Throws std::invalid_argument: height not finite or ≤ 0, a chart or tile index
// out of range, a tile without normals (#V), no tiles; OperationCancelled through `progress`.
TriMesh ddm_evaluate(const DdmBase& base, const std::vector<DdmTile>& tiles, const std::vector<DdmInstance>& instances,
                     double height, const DdmTileTransform& transform = {}, glm::dvec2 offset = glm::dvec2(0.0),
                     const ProgressSink* progress = nullptr);
// One tile for every instance (instance.tile ignored).
TriMesh ddm_evaluate(const DdmBase& base, const DdmTile& tile, const std::vector<DdmInstance>& instances,
                     double height);

// Metamorphosis (seed Eq. 5.3): V = V1·(1 − α) + V2·α vertex by vertex, normals interpolated and renormalised; α
// outside [0,1] extrapolates. Throws std::invalid_argument: different topology (require_same_ddm_topology),
// non-finite α.
DdmTile ddm_morph(const DdmTile& a, const DdmTile& b, double alpha);

}  // namespace trispline::core
