// trispline::core singletons of a VolumeSpline and their lookup table (seed §7.3.2, Def. 8, Fig. 7.1).
//
// Every knot span (cell) of D is a singleton: its Bézier form (knot insertion at every interior knot) bounds its
// values, [lo, hi] = [min, max] of its Bézier coefficients, and its gradients: the Bézier coefficients of ∂D/∂x,
// ∂D/∂y, ∂D/∂z, degree-raised to a common degree, are vectors whose convex hull holds every gradient in the cell
// (seed: "the control points of G ... completely bound the possible gradients"); their bounding cone (axis, half-angle
// α) bounds the gradient directions. A cone that would hold the zero vector is the whole sphere (α = 180°). Cones are
// in index space (gradients per index unit), where every silhouette test is made.
//
// The lookup table: rows are iso-level ranges (the dynamic range cut in `rows` equal bins), columns are `columns`
// direction cones covering the unit sphere (a Fibonacci set; each column's radius is the largest angle from a sphere
// point to its nearest column axis). A singleton is filed once, in the row holding its lo and the column nearest its
// cone axis; within a bin singletons are sorted by hi, largest first. A query for level c then visits the rows up to
// c's and stops in each bin at the first hi < c: every singleton whose range holds c is found and nothing is filed
// twice (the seed files a singleton in every row its range overlaps). Each bin keeps the largest cone of its members
// widened by the column radius, so whole bins are skipped when no gradient they hold can be orthogonal to the view.
// Macro-cells (8³ cells each) keep the min/max of their singletons for empty-space skipping along rays.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/spline/progress.h"
#include "core/volume/preparation_budget.h"
#include "core/volume/volume_spline.h"

namespace trispline::core {

// A singleton's bounds (24 bytes): value range and gradient cone, index space.
struct Singleton {
  float lo = 0.0f, hi = 0.0f;          // min / max of D over the cell (from its Bézier coefficients)
  float axis[3] = {0.0f, 0.0f, 0.0f};  // unit cone axis (zero when the cone is the whole sphere)
  float sin_half = 1.0f;  // sin α when α ≤ 90°, else 1: a direction ⊥ w is in the cone iff |axis·ŵ| ≤ sin_half
};

// The lookup table's default shape and bounds: rows (iso bins) and columns (direction cones), and the Fibonacci
// directions sampled to measure the column radius.
inline constexpr int kSingletonTableRows = 256, kSingletonTableColumns = 64;
inline constexpr int kSingletonTableMaxRows = 4096, kSingletonTableMaxColumns = 1024;
inline constexpr int kSingletonColumnProbes = 20000;

class SingletonTable {
 public:
  static constexpr int kMacro = 8;  // cells per macro-cell axis

  const std::array<int, 3>& cells() const { return cells_; }  // span counts per axis
  std::size_t cell_count() const { return singletons_.size(); }
  std::size_t cell_index(int a, int b, int c) const {
    return static_cast<std::size_t>(a) + static_cast<std::size_t>(cells_[0]) *
                                             (static_cast<std::size_t>(b) + static_cast<std::size_t>(cells_[1]) * c);
  }
  const std::vector<Singleton>& singletons() const { return singletons_; }
  double range_min() const { return range_min_; }  // smallest lo
  double range_max() const { return range_max_; }  // largest hi
  int rows() const { return rows_; }
  int columns() const { return static_cast<int>(column_axes_.size()); }

  // Cells whose value range holds `iso`, ascending (the lookup table's answer for one iso-level).
  std::vector<std::uint32_t> cells_holding(double iso) const;
  // As cells_holding, keeping only cells whose bin cone can hold a direction orthogonal to some direction of the cone
  // (w_axis unit, half-angle with sine/cosine w_sin, w_cos) of view directions — a bin-level filter; callers test
  // each singleton after it.
  // `order`: ascending, or by_bin (the table's own order: no sort, for callers that regroup the cells anyway).
  enum class CellOrder { ascending, by_bin };
  std::vector<std::uint32_t> cells_holding(double iso, const glm::dvec3& w_axis, double w_half_angle,
                                           CellOrder order = CellOrder::ascending) const;

  // Macro-cell bounds for ray skipping: macro (a, b, c) covers cells [8a, 8a+8) × ...
  const std::array<int, 3>& macro_cells() const { return macro_dims_; }
  glm::vec2 macro_range(int a, int b, int c) const {
    return macro_range_[static_cast<std::size_t>(a) +
                        static_cast<std::size_t>(macro_dims_[0]) *
                            (static_cast<std::size_t>(b) + static_cast<std::size_t>(macro_dims_[1]) * c)];
  }

  // Bytes held (singletons, bins, macro-cells).
  std::size_t memory_bytes() const;

 private:
  friend SingletonTable build_singleton_table(const VolumeSpline&, const ProgressSink&, int, int);
  void set_columns(int columns);  // column axes and radius
  void file_bins();               // range, bins and macro-cells from singletons_, rows_ and the columns

  std::array<int, 3> cells_{0, 0, 0};
  std::vector<Singleton> singletons_;
  double range_min_ = 0.0, range_max_ = 0.0;
  int rows_ = 0;
  std::vector<glm::vec3> column_axes_;
  double column_radius_ = 0.0;            // radians
  std::vector<std::uint32_t> bin_begin_;  // rows·columns + 1 offsets into bin_cells_
  std::vector<std::uint32_t> bin_cells_;  // cell indices, per bin sorted by hi descending
  std::vector<float> bin_half_angle_;     // rows·columns, radians: widened cone of the bin (≥ π/2 = any)
  std::array<int, 3> macro_dims_{0, 0, 0};
  std::vector<glm::vec2> macro_range_;  // (min lo, max hi) per macro-cell
};

// The bounds of cell (a, b, c) of `spline` (0 ≤ a < span_count(0), …), as build_singleton_table files them.
Singleton singleton_of_cell(const VolumeSpline& spline, int a, int b, int c);

// Preprocesses `spline` into singletons and their table (tbb-parallel over z-slabs; deterministic). rows: iso bins
// (1…kSingletonTableMaxRows), columns: direction cones (1…kSingletonTableMaxColumns); std::invalid_argument outside.
// Throws OperationCancelled through `progress`.
SingletonTable build_singleton_table(const VolumeSpline& spline, const ProgressSink& progress = {},
                                     int rows = kSingletonTableRows, int columns = kSingletonTableColumns);

}  // namespace trispline::core
