// trispline::core DDM P/N maps — a base surface sampled into P/N maps (seed §5.3.1), the data the GPU evaluator reads
// (seed §5.3.2), and DdmMapsBase: the CPU reference of that evaluation, so GPU and CPU give the same positions for
// tests, baking and export.
//
// A map holds, per chart that carries tiles (a "slot"), a R_u × R_v grid of samples of S and its first-order frame:
//   P = S, N = n, S_u, S_v, N_u = ∂n/∂u, N_v = ∂n/∂v  (18 float32 per sample; the seed's P and N textures plus the
// derivatives that make the tile normals exact, §5.3.2 last paragraph, instead of its ε trick). Sample (i, j) sits at
// (u, v) = (i / (R_u − 1), j / (R_v − 1)) of its chart. Between samples every quantity is bilinear (GL_LINEAR on the
// texel centres), N then renormalised; this interpolation is done with float weights in GLSL (texelFetch) and in
// double here, so the two agree to float precision.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "core/ddm/ddm_base.h"
#include "core/mesh/tri_mesh.h"

namespace trispline::core {

struct DdmMaps {
  static constexpr int kFloatsPerSample = 18;  // P, N, S_u, S_v, N_u, N_v — each x, y, z
  glm::ivec2 resolution{9, 9};                 // samples per chart along u and v, each ≥ 2
  glm::bvec2 periodic{false, false};           // u (v) wraps modulo 1 on every chart (the base's periodic())
  std::vector<int> slot_of_chart;              // #charts: the chart's slot in `samples`, −1 = not sampled
  std::vector<int> chart_of_slot;              // #slots: the inverse
  // #slots × R_v × R_u × 18 floats: slot, then row j (v), then column i (u). World (object) units; per parameter
  // unit of the chart for the derivatives.
  std::vector<float> samples;
  // Empty, or #slots × R_v × R_u: 1 where the sample lies on the surface, 0 where it was filled in (UV-mapped bases,
  // seed §5.4.1: the diffusion fill of texels no triangle covers). Tiles whose cell holds no valid sample are pruned.
  std::vector<std::uint8_t> valid;
  double base_size = 1.0;  // bounding-box diagonal of the sampled P (world / object units): the parity scale

  int slot_count() const { return static_cast<int>(chart_of_slot.size()); }
  std::size_t samples_per_slot() const { return static_cast<std::size_t>(resolution.x) * resolution.y; }
  // Pointer to the 18 floats of sample (i, j) of `slot`.
  const float* sample(int slot, int i, int j) const {
    return samples.data() + ((static_cast<std::size_t>(slot) * resolution.y + j) * resolution.x + i) * kFloatsPerSample;
  }
};

// Samples `base` on every chart in `charts` (sorted, distinct, each in [0, chart_count)) at `resolution` samples per
// chart edge (TBB over charts; deterministic). Appends to `previous` when given (its resolution must match; charts
// already sampled are kept, not resampled): painting extends a layer's maps by the charts it reaches.
// Throws std::invalid_argument: resolution < 2 or > 4097 per axis, a chart out of range, more than 2³¹ floats.
DdmMaps ddm_sample_maps(const DdmBase& base, const std::vector<int>& charts, glm::ivec2 resolution,
                        const DdmMaps* previous = nullptr);

// The sampled charts of `maps` as a base surface: eval is the bilinear interpolation described above (what the GPU
// evaluator computes). chart_count() = maps.slot_of_chart.size(); a chart without a slot throws std::out_of_range.
class DdmMapsBase final : public DdmBase {
 public:
  explicit DdmMapsBase(std::shared_ptr<const DdmMaps> maps);
  int chart_count() const override { return static_cast<int>(maps_->slot_of_chart.size()); }
  glm::bvec2 periodic() const override { return maps_->periodic; }
  DdmSurfacePoint eval(int chart, double u, double v) const override;
  const DdmMaps& maps() const { return *maps_; }

 private:
  std::shared_ptr<const DdmMaps> maps_;
};

// A mesh with texture coordinates as a base (seed §5.3.1, §5.4.1): P and N rasterised in UV space into one chart
// of resolution R × R (sample (i, j) at uv = (i, j)/(R − 1)), S_u, S_v from each triangle's UV Jacobian, N_u, N_v by
// central differences of the N map; samples no triangle covers are filled by the seed's 8-neighbour diffusion and
// marked invalid (DdmMaps::valid). Where UV islands overlap the triangle drawn last wins.
// Throws std::invalid_argument ("base: …"): no uvs (#V ≠ #uv), no triangles, a non-finite position or uv, no sample
// covered, resolution < 2 or > 4097.
DdmMaps ddm_rasterize_uv_maps(const TriMesh& mesh, int resolution);

// True when a tile cell [origin, origin + size] of `chart` holds at least one valid sample (always true for maps
// without a validity bitmap; false for a chart without a slot).
bool ddm_cell_valid(const DdmMaps& maps, const DdmInstance& cell);
// True when the sample nearest the cell's centre is valid (always true for maps without a validity bitmap; false for a
// chart without a slot): the stricter pruning of automatic UV atlases, whose many small charts leave many cells
// mostly in the gaps between them, drawn over diffused samples.
// True when the surface is continuous over the cell: P sampled at 5 × 5 points of it has no step between neighbours
// above twice the step S_u·Δu (S_v·Δv) at the cell's centre predicts. A cell of an automatic UV atlas that straddles a
// seam (its charts' neighbours in UV space are far apart on the surface) fails: its tile's vertices would land on two
// distant parts of the surface. False for a chart without a slot.
bool ddm_cell_continuous(const DdmMaps& maps, const DdmInstance& cell);
bool ddm_cell_centre_valid(const DdmMaps& maps, const DdmInstance& cell);

}  // namespace trispline::core
