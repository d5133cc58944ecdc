#include "core/volume/silhouettes.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <utility>

#include "core/volume/silhouette_seeds.h"
#include "core/volume/silhouette_trace.h"

namespace trispline::core {

using namespace silhouette_detail;

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_params(double iso, const SilhouetteView& view, const SilhouetteParams& params) {
  if (!std::isfinite(iso)) throw std::invalid_argument("the iso-level must be a finite number");
  if (params.subdivision < 1 || params.subdivision > 4)
    throw std::invalid_argument("subdivision must be 1…4 sub-cells per singleton axis, got " +
                                std::to_string(params.subdivision));
  if (!(params.accuracy >= 1e-12 && params.accuracy <= 1e-2))
    throw std::invalid_argument("accuracy must be in [1e-12, 1e-2], got " + std::to_string(params.accuracy));
  if (!(params.pixel_step >= 0.0 && params.pixel_step <= 16.0))
    throw std::invalid_argument("pixel_step must be in [0, 16] pixels, got " + std::to_string(params.pixel_step));
  if (!(view.pixel_size >= 0.0) || !std::isfinite(view.pixel_size))
    throw std::invalid_argument("the pixel size must be a finite number ≥ 0 (0: not on a screen)");
  if (view.perspective) {
    if (!std::isfinite(view.eye.x) || !std::isfinite(view.eye.y) || !std::isfinite(view.eye.z))
      throw std::invalid_argument("the eye position must be finite");
  } else if (!(glm::length(view.direction) > 0.0) || !std::isfinite(glm::length(view.direction))) {
    throw std::invalid_argument("the viewing direction must be a finite non-zero vector");
  }
}

}  // namespace

namespace silhouette_detail {

HiddenCells::HiddenCells(const Problem& pb, const glm::dvec3& axis, double half_angle) : pb_(pb) {
  const glm::dvec3 hi(pb.spline.dims()[0] - 1, pb.spline.dims()[1] - 1, pb.spline.dims()[2] - 1);
  const glm::dvec3 centre = 0.5 * hi;
  const double radius = 0.5 * glm::length(hi) + 1.0;
  a_ = pb.view.perspective ? axis : pb.view.v;
  const glm::dvec3 other = std::abs(a_.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  u_ = glm::normalize(glm::cross(a_, other));
  v_ = glm::cross(a_, u_);
  if (pb.view.perspective) {
    if (!(half_angle < 0.45 * kPi)) return;  // the eye inside or next to the box: no map
    scale_ = std::tan(half_angle);
    origin_ = pb.view.eye;
  } else {
    scale_ = radius;
    origin_ = centre - (radius + 1.0) * a_;
  }
  depth_.assign(std::size_t(kN) * kN, INFINITY);
  tbb::parallel_for(0, kN, [&](int j) {
    for (int i = 0; i < kN; ++i) {
      const double x = ((i + 0.5) / kN * 2.0 - 1.0) * scale_, y = ((j + 0.5) / kN * 2.0 - 1.0) * scale_;
      glm::dvec3 from = origin_, dir = a_;
      if (pb_.view.perspective)
        dir = glm::normalize(a_ + x * u_ + y * v_);
      else
        from = origin_ + x * u_ + y * v_;
      // The ray's span inside the grid box (slabs).
      double t0 = 0.0, t1 = INFINITY;
      for (int c = 0; c < 3; ++c) {
        if (dir[c] == 0.0) {
          if (from[c] < 0.0 || from[c] > hi[c]) t1 = -1.0;
          continue;
        }
        const double ta = (0.0 - from[c]) / dir[c], tb = (hi[c] - from[c]) / dir[c];
        t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
      }
      if (!(t0 < t1)) continue;
      const double t = first_crossing(pb_.spline, pb_.table, pb_.iso, from, dir, t0, t1, pb_.sides);
      if (t >= 0.0) depth_[std::size_t(j) * kN + std::size_t(i)] = t;
    }
  });
}

}  // namespace silhouette_detail

namespace {

// Cells filed by block of kBlock³: cells[begin[b] … begin[b + 1]) in the order given (a stable counting sort).
struct BlockCells {
  glm::ivec3 blocks{0};
  std::vector<std::uint32_t> begin, cells;
};

glm::ivec3 block_grid(const SingletonTable& table) {
  const auto& dims = table.cells();
  return {(dims[0] + kBlock - 1) / kBlock, (dims[1] + kBlock - 1) / kBlock, (dims[2] + kBlock - 1) / kBlock};
}

glm::ivec3 cell_coords(const SingletonTable& table, std::uint32_t cell) {
  const auto& dims = table.cells();
  return {static_cast<int>(cell % dims[0]), static_cast<int>((cell / dims[0]) % dims[1]),
          static_cast<int>(cell / (static_cast<std::size_t>(dims[0]) * dims[1]))};
}

std::size_t block_of(const glm::ivec3& blocks, const glm::ivec3& c) {
  return static_cast<std::size_t>(c.x / kBlock) +
         blocks.x * (static_cast<std::size_t>(c.y / kBlock) + blocks.y * static_cast<std::size_t>(c.z / kBlock));
}

BlockCells file_by_block(const SingletonTable& table, const std::vector<std::uint32_t>& cells) {
  BlockCells out;
  out.blocks = block_grid(table);
  const std::size_t block_count = static_cast<std::size_t>(out.blocks.x) * out.blocks.y * out.blocks.z;
  std::vector<std::uint32_t> block_id(cells.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t e = r.begin(); e != r.end(); ++e)
                        block_id[e] = static_cast<std::uint32_t>(block_of(out.blocks, cell_coords(table, cells[e])));
                    });
  out.begin.assign(block_count + 1, 0);
  for (std::uint32_t b : block_id) ++out.begin[b + 1];
  for (std::size_t b = 0; b < block_count; ++b) out.begin[b + 1] += out.begin[b];
  out.cells.resize(cells.size());
  std::vector<std::uint32_t> fill(out.begin.begin(), out.begin.end() - 1);
  for (std::size_t e = 0; e < cells.size(); ++e) out.cells[fill[block_id[e]]++] = cells[e];
  return out;
}

// The view cone of the grid box: the directions w takes over it (axis, half-angle; orthographic: the view, 0).
std::pair<glm::dvec3, double> view_cone(const VolumeSpline& spline, const IndexView& iv) {
  if (!iv.perspective) return {iv.v, 0.0};
  const glm::dvec3 hi(spline.dims()[0] - 1, spline.dims()[1] - 1, spline.dims()[2] - 1);
  const glm::dvec3 d = hi * 0.5 - iv.eye;
  const double radius = glm::length(hi) * 0.5 + 1.0, dist = glm::length(d);
  return {dist > 0.0 ? d / dist : glm::dvec3(0.0, 0.0, 1.0), dist > radius ? std::asin(radius / dist) : kPi};
}

// Pixels a cell covers at `distance` millimetres from the eye (orthographic: anywhere); +∞ without a pixel size.
struct ScreenScale {
  double cell_mm = 0.0;     // the longest cell edge, millimetres
  double pixel_size = 0.0;  // SilhouetteView::pixel_size
  bool perspective = true;
  bool on_screen() const { return pixel_size > 0.0; }
  double pixels(double mm, double distance) const {
    return mm / (pixel_size * (perspective ? std::max(distance, 1e-9) : 1.0));
  }
};

// One extraction; `filed`: the candidate cells by block (null: the table's query for this view), `previous`: points
// (index space) of curves to trace first.
SilhouetteResult extract(const VolumeSpline& spline, const SingletonTable& table, double iso,
                         const SilhouetteView& view, const SilhouetteParams& params, const BlockCells* filed,
                         const std::vector<glm::dvec3>* previous, const LevelSides* sides) {
  check_params(iso, view, params);
  for (int a = 0; a < 3; ++a)
    if (table.cells()[a] != spline.span_count(a))
      throw std::invalid_argument("the singleton table was built for another volume spline");
  const auto t0 = std::chrono::steady_clock::now();
  SilhouetteResult result;
  Problem pb{spline,
             table,
             index_view(spline, view),
             iso,
             std::max(spline.control_max() - spline.control_min(), 1e-30),
             params.accuracy,
             glm::dmat3(spline.index_to_world())};
  if (sides && sides->iso() == iso) pb.sides = sides;
  const IndexView& iv = pb.view;
  const auto [w_axis, w_half] = view_cone(spline, iv);
  std::optional<HiddenCells> hidden;
  if (!params.seed_hidden) {
    hidden.emplace(pb, w_axis, w_half);
    if (hidden->usable())
      pb.hidden = &*hidden;
    else
      hidden.reset();
  }
  const auto& dims = table.cells();
  // The candidates by block (in the table's order within a block).
  BlockCells own;
  if (!filed) {
    own = file_by_block(table, table.cells_holding(iso, w_axis, w_half, SingletonTable::CellOrder::by_bin));
    filed = &own;
  }
  const glm::ivec3 blocks = filed->blocks;
  const std::size_t block_count = static_cast<std::size_t>(blocks.x) * blocks.y * blocks.z;
  auto block_box = [&](std::size_t blk) {
    const glm::ivec3 bc(static_cast<int>(blk % blocks.x), static_cast<int>((blk / blocks.x) % blocks.y),
                        static_cast<int>(blk / (static_cast<std::size_t>(blocks.x) * blocks.y)));
    const glm::ivec3 first = bc * kBlock;
    return std::pair{first, glm::min(first + kBlock, glm::ivec3(dims[0], dims[1], dims[2]))};
  };
  // The previous curves' points by block.
  std::vector<std::uint32_t> seed_begin(block_count + 1, 0);
  std::vector<glm::dvec3> seed_points;
  if (previous) {
    const double shift = spline.span_begin(0);
    std::vector<std::uint32_t> seed_block;
    seed_block.reserve(previous->size());
    for (const glm::dvec3& x : *previous) {
      glm::ivec3 c;
      for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor(x[a] - shift)), 0, dims[a] - 1);
      seed_block.push_back(static_cast<std::uint32_t>(block_of(blocks, c)));
      ++seed_begin[seed_block.back() + 1];
    }
    for (std::size_t b = 0; b < block_count; ++b) seed_begin[b + 1] += seed_begin[b];
    seed_points.resize(previous->size());
    std::vector<std::uint32_t> fill(seed_begin.begin(), seed_begin.end() - 1);
    for (std::size_t e = 0; e < previous->size(); ++e) seed_points[fill[seed_block[e]]++] = (*previous)[e];
  }
  // The screen density: blocks whose cells cover fewer than pixel_step pixels are traced coarsely.
  ScreenScale screen;
  screen.perspective = iv.perspective;
  if (params.pixel_step > 0.0 && view.pixel_size > 0.0 && std::isfinite(view.pixel_size)) {
    screen.pixel_size = view.pixel_size;
    for (int a = 0; a < 3; ++a) screen.cell_mm = std::max(screen.cell_mm, glm::length(pb.to_world[a]));
  }
  // Each block: the previous curves, then the exact per-singleton cone test (cell-sized view cone in perspective),
  // seeds, Newton and tracing, skipping cells a trace has already crossed. Blocks wholly behind the surface
  // (seed_hidden false) do nothing. Blocks write to their own slots (deterministic for any thread count).
  std::vector<std::vector<Trace>> block_traces(block_count);
  std::vector<std::size_t> cand(block_count, 0), seeds(block_count, 0), hidden_cells(block_count, 0),
      from_previous(block_count, 0);
  const auto& singles = table.singletons();
  tbb::enumerable_thread_specific<BlockScratch> scratch;
#if defined(__SSE2__)
  std::optional<CubicHullTest> cubic;
  if (spline.order() == 4) cubic.emplace(spline, iv);
#endif
  tbb::parallel_for(std::size_t(0), block_count, [&](std::size_t blk) {
    const std::uint32_t cells_begin = filed->begin[blk], cells_end = filed->begin[blk + 1];
    if (cells_begin == cells_end) return;

    const auto [first, last] = block_box(blk);
    if (hidden && hidden->hides(first, last)) {
      hidden_cells[blk] = cells_end - cells_begin;
      return;
    }
    TraceLimits limits;
    if (screen.on_screen()) {
      const glm::dvec3 lo(spline.span_begin(first.x), spline.span_begin(first.y), spline.span_begin(first.z));
      const glm::dvec3 hi = lo + glm::dvec3(last - first);
      const double nearest = glm::length(pb.to_world * (glm::clamp(iv.eye, lo, hi) - iv.eye));
      if (screen.pixels(screen.cell_mm, nearest) < params.pixel_step) limits = TraceLimits::coarse();
    }
    BlockTracer tracer(pb, first, last, scratch.local(), limits);
    // A point heading into a cell a trace has crossed is given up early (what it would find there is known).
    auto known = [&](const glm::dvec3& x) { return tracer.inside(x) && tracer.visited(tracer.cell_of(x)); };
    auto trace_new = [&](const CurvePoint& p) {
      if (!tracer.inside(p.x) || tracer.visited(tracer.cell_of(p.x)) || tracer.near_trace(p.x, limits.join_radius))
        return false;
      tracer.trace_from(p);
      return true;
    };
    for (std::uint32_t e = seed_begin[blk]; e < seed_begin[blk + 1]; ++e) {
      const glm::dvec3& x = seed_points[e];
      const glm::ivec3 c = tracer.cell_of(x);
      if (tracer.visited(c) || tracer.hidden(c)) continue;
      CurvePoint p;
      if (!solve_point(pb, x, x - 1.5, x + 1.5, kCorrectorIterations, p, -1, known)) continue;
      from_previous[blk] += trace_new(p);
    }
    for (std::uint32_t e = cells_begin; e < cells_end; ++e) {
      // The singletons are read in bin order, far apart in memory: fetch a few ahead.
      if (e + 8 < cells_end) __builtin_prefetch(&singles[filed->cells[e + 8]]);
      const std::uint32_t cell = filed->cells[e];
      const glm::ivec3 c = cell_coords(table, cell);
      if (tracer.visited(c)) continue;
      // Behind the surface by its tile: decided before the singleton is read.
      if (tracer.tile_hidden(c)) {
        ++hidden_cells[blk];
        continue;
      }
      const Singleton& s = singles[cell];
      glm::dvec3 w = iv.v;
      double s_w = 0.0, c_w = 1.0;
      if (iv.perspective) {
        const glm::dvec3 centre(spline.span_begin(c.x) + 0.5, spline.span_begin(c.y) + 0.5,
                                spline.span_begin(c.z) + 0.5);
        w = centre - iv.eye;
        const double dist = glm::length(w);
        const double r = std::sqrt(3.0) * 0.5;
        if (dist <= r) {
          s_w = 1.0, c_w = 0.0;
        } else {
          w /= dist;
          s_w = r / dist, c_w = std::sqrt(1.0 - s_w * s_w);
        }
      }
      if (s_w < 1.0 && !cones_admit_orthogonal(s, w, s_w, c_w)) continue;
      if (tracer.hidden(c)) {
        ++hidden_cells[blk];
        continue;
      }
      ++cand[blk];
      const glm::dvec3 cell_lo(spline.span_begin(c.x), spline.span_begin(c.y), spline.span_begin(c.z));
      bool whole_cell_tested = false;
#if defined(__SSE2__)
      if (cubic) {
        if (!cubic->may_hold_zero(c.x, c.y, c.z)) continue;
        whole_cell_tested = true;
      }
#endif
      seed_cell(pb, c.x, c.y, c.z, params.subdivision, whole_cell_tested, [&](const glm::dvec3& centre) {
        ++seeds[blk];
        CurvePoint p;
        if (!solve_point(pb, centre, cell_lo - 0.5, cell_lo + 1.5, kSeedIterations, p, -1, known)) return false;
        // A converged point anywhere in the block starts a trace, unless a trace already passed there.
        if (!trace_new(p)) return false;
        return tracer.visited(c);  // this cell is covered: its other seeds would find the same curve
      });
    }
    block_traces[blk] = std::move(tracer.traces);
  });
  std::vector<Trace> traces;
  for (std::size_t b = 0; b < block_count; ++b) {
    result.candidates += cand[b];
    result.seeds += seeds[b];
    result.hidden_cells += hidden_cells[b];
    result.traced_from_previous += from_previous[b];
    for (Trace& t : block_traces[b]) traces.push_back(std::move(t));
  }
  const glm::dvec3 eye_world = view.eye;
  for (const Chain& chain : join_traces(traces)) {
    SilhouettePolyline pl;
    std::vector<const CurvePoint*> pts;
    for (const ChainPiece& piece : chain.pieces) {
      const auto& tp = traces[piece.trace].points;
      const std::size_t m = tp.size();
      // The first point of every piece after the first repeats the face point the previous piece ended on.
      for (std::size_t i = pts.empty() ? 0 : 1; i < m; ++i) pts.push_back(&tp[piece.reversed ? m - 1 - i : i]);
    }
    if (chain.closed && chain.pieces.size() > 1 && !pts.empty()) pts.pop_back();  // back at the first face point
    if (pts.size() < 2) continue;  // isolated points are not strokes of a curve
    pl.closed = chain.closed && pts.size() >= 3;
    const std::size_t n = pts.size();
    pl.points.reserve(n);
    pl.gradient_norm.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      const CurvePoint& p = *pts[i];
      const glm::dvec3 x(spline.index_to_world() * glm::dvec4(p.x, 1.0));
      // On a screen, a point within a pixel of the last one kept is merged into it (never the first or last).
      if (screen.on_screen() && i > 0 && i + 1 < n &&
          screen.pixels(glm::length(x - pl.points.back()), glm::length(x - eye_world)) < 1.0)
        continue;
      pl.points.push_back(x);
      pl.gradient_norm.push_back(p.gradient_norm);
      result.max_value_residual = std::max(result.max_value_residual, p.value_residual);
      result.max_dot_residual = std::max(result.max_dot_residual, p.dot_residual);
    }
    const std::size_t kept = pl.points.size();
    for (std::size_t i = 1; i < kept; ++i) result.length_mm += glm::length(pl.points[i] - pl.points[i - 1]);
    if (pl.closed && kept < 3) pl.closed = false;
    if (pl.closed) result.length_mm += glm::length(pl.points.front() - pl.points.back());
    pl.visible.assign(kept, 1);
    result.points += kept;
    result.polylines.push_back(std::move(pl));
  }
  result.extract_ms = ms_since(t0);
  if (params.hidden_test) {
    const auto t1 = std::chrono::steady_clock::now();
    // Every 4th point (and the last) is tested; the points between two tested ones of the same visibility take it,
    // those between two that differ are tested one by one. A visibility change is located exactly; only a hidden
    // stretch shorter than 4 points between two visible ones (or the reverse) could be missed.
    constexpr std::size_t kStride = 4;
    auto seen_from_eye = [&](const SilhouettePolyline& pl, std::size_t i) {
      const glm::dvec3 x(spline.world_to_index() * glm::dvec4(pl.points[i], 1.0));
      if (hidden && hidden->hides(x, 0.0)) return 0;  // well behind the map's first crossings
      return occluded(spline, table, iso, iv, x, 1.5, pb.sides) ? 0 : 1;
    };
    // The tested points of all polylines as one list (a few polylines hold most points: splitting by polyline would
    // leave one thread with the longest), then the stretches between two tested points that differ, per polyline.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> tested;  // (polyline, point)
    for (std::size_t k = 0; k < result.polylines.size(); ++k) {
      const std::size_t n = result.polylines[k].points.size();
      for (std::size_t i = 0; i < n; i += kStride) tested.emplace_back(std::uint32_t(k), std::uint32_t(i));
      if ((n - 1) % kStride != 0) tested.emplace_back(std::uint32_t(k), std::uint32_t(n - 1));
    }
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, tested.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t e = r.begin(); e != r.end(); ++e) {
            SilhouettePolyline& pl = result.polylines[tested[e].first];
            pl.visible[tested[e].second] = static_cast<unsigned char>(seen_from_eye(pl, tested[e].second));
          }
        });
    tbb::parallel_for(std::size_t(0), result.polylines.size(), [&](std::size_t k) {
      SilhouettePolyline& pl = result.polylines[k];
      const std::size_t n = pl.points.size();
      for (std::size_t prev = 0; prev + 1 < n;) {
        const std::size_t next = std::min(prev + kStride, n - 1);
        for (std::size_t i = prev + 1; i < next; ++i)
          pl.visible[i] = pl.visible[prev] == pl.visible[next] ? pl.visible[prev]
                                                               : static_cast<unsigned char>(seen_from_eye(pl, i));
        prev = next;
      }
    });
    result.hidden_ms = ms_since(t1);
  }
  return result;
}

// Points of `r`'s curves about every `spacing` index units (index space): the next view's first seeds.
std::vector<glm::dvec3> curve_samples(const VolumeSpline& spline, const SilhouetteResult& r, double spacing) {
  std::vector<glm::dvec3> out;
  for (const SilhouettePolyline& pl : r.polylines) {
    double since = spacing;  // the first point seeds
    glm::dvec3 last(0.0);
    for (std::size_t i = 0; i < pl.points.size(); ++i) {
      const glm::dvec3 x(spline.world_to_index() * glm::dvec4(pl.points[i], 1.0));
      if (i > 0) since += glm::length(x - last);
      last = x;
      if (since >= spacing) out.push_back(x), since = 0.0;
    }
  }
  return out;
}

}  // namespace

SilhouetteResult extract_silhouettes(const VolumeSpline& spline, const SingletonTable& table, double iso,
                                     const SilhouetteView& view, const SilhouetteParams& params) {
  return extract(spline, table, iso, view, params, nullptr, nullptr, nullptr);
}

struct SilhouetteSequence::Filed {
  Filed(const SingletonTable& table, double iso)
      : iso(iso), cells(file_by_block(table, table.cells_holding(iso))), sides(table, iso) {}
  double iso;
  BlockCells cells;
  LevelSides sides;
};

SilhouetteSequence::SilhouetteSequence(std::shared_ptr<const VolumeSpline> spline,
                                       std::shared_ptr<const SingletonTable> table)
    : spline_(std::move(spline)), table_(std::move(table)) {
  if (!spline_ || !table_) throw std::invalid_argument("a silhouette sequence needs a volume spline and its table");
  for (int a = 0; a < 3; ++a)
    if (table_->cells()[a] != spline_->span_count(a))
      throw std::invalid_argument("the singleton table was built for another volume spline");
}

SilhouetteSequence::~SilhouetteSequence() = default;

void SilhouetteSequence::restart() { previous_.clear(); }

SilhouetteResult SilhouetteSequence::next(double iso, const SilhouetteView& view, const SilhouetteParams& params) {
  check_params(iso, view, params);
  if (!filed_ || filed_->iso != iso) {
    filed_ = std::make_unique<Filed>(*table_, iso);
    previous_.clear();
  }
  SilhouetteResult r = extract(*spline_, *table_, iso, view, params, &filed_->cells, &previous_, &filed_->sides);
  previous_ = curve_samples(*spline_, r, 2.0);
  return r;
}

namespace silhouette_detail {

LevelSides::LevelSides(const SingletonTable& table, double iso) : iso_(iso) {
  const auto& singles = table.singletons();
  const auto& dims = table.cells();
  for (int a = 0; a < 3; ++a) tiles_[a] = static_cast<std::size_t>((dims[a] + kTile - 1) / kTile);
  words_.assign(2 * tiles_[0] * tiles_[1] * tiles_[2], 0);
  // Cells past the grid's end (in its last tiles) repeat the last cell's side: a tile is uniform as its cells are.
  tbb::parallel_for(std::size_t(0), tiles_[2], [&](std::size_t tz) {
    for (std::size_t ty = 0; ty < tiles_[1]; ++ty)
      for (std::size_t tx = 0; tx < tiles_[0]; ++tx) {
        std::uint64_t w[2] = {0, 0};
        for (unsigned k = 0; k < 64; ++k) {
          const int x = std::min(int(4 * tx + (k & 3)), dims[0] - 1),
                    y = std::min(int(4 * ty + ((k >> 2) & 3)), dims[1] - 1),
                    z = std::min(int(4 * tz + (k >> 4)), dims[2] - 1);
          const Singleton& sg = singles[table.cell_index(x, y, z)];
          const std::uint64_t side = double(sg.hi) < iso ? below : (double(sg.lo) > iso ? above : holds);
          w[k >> 5] |= side << (2 * (k & 31));
        }
        const std::size_t t = tx + tiles_[0] * (ty + tiles_[1] * tz);
        words_[2 * t] = w[0], words_[2 * t + 1] = w[1];
      }
  });
}

double first_crossing(const VolumeSpline& spline, const SingletonTable& table, double iso, const glm::dvec3& from,
                      const glm::dvec3& dir, double t, double t_end, const LevelSides* sides) {
  const double step = 0.4;
  if (!(t < t_end)) return -1.0;
  if (sides && sides->iso() != iso) sides = nullptr;
  double prev = spline.value(from + t * dir) - iso;
  const auto& md = table.macro_cells();
  const auto& cells = table.cells();
  const double shift = spline.span_begin(0);  // cell c starts at c + shift on every axis
  // Where the ray leaves the box of `size` index units starting at index `first`·size + shift on each axis.
  auto exit_of = [&](const int* first, double size) {
    double exit = INFINITY;
    for (int a = 0; a < 3; ++a) {
      const double lo = first[a] * size + shift, up = lo + size;
      if (dir[a] > 0.0)
        exit = std::min(exit, (up - from[a]) / dir[a]);
      else if (dir[a] < 0.0)
        exit = std::min(exit, (lo - from[a]) / dir[a]);
    }
    return exit;
  };
  while (t < t_end) {
    // Skip macro-cells, then cells, whose range cannot hold the level: jump to where the ray leaves them. The sign of
    // D − c there is the box's (its whole range is on one side of c), so no value is needed.
    const glm::dvec3 x = from + t * dir;
    int m[3], c[3];
    for (int a = 0; a < 3; ++a) {
      c[a] = std::clamp(static_cast<int>(std::floor(x[a] - shift)), 0, cells[a] - 1);
      m[a] = std::min(c[a] / SingletonTable::kMacro, md[a] - 1);
    }
    const glm::vec2 r = table.macro_range(m[0], m[1], m[2]);
    if (!(double(r.x) <= iso && iso <= double(r.y))) {
      t = std::max(exit_of(m, SingletonTable::kMacro) + 1e-6, t + 1e-6);
      prev = double(r.y) < iso ? -1.0 : 1.0;
      continue;
    }
    LevelSides::Side side;
    if (sides) {
      if (const LevelSides::Side whole = sides->tile_side(c[0], c[1], c[2]); whole != LevelSides::holds) {
        const int tile[3] = {c[0] / LevelSides::kTile, c[1] / LevelSides::kTile, c[2] / LevelSides::kTile};
        t = std::max(exit_of(tile, LevelSides::kTile) + 1e-6, t + 1e-6);
        prev = whole == LevelSides::below ? -1.0 : 1.0;
        continue;
      }
      side = sides->side(c[0], c[1], c[2]);
    } else {
      const Singleton& sg = table.singletons()[table.cell_index(c[0], c[1], c[2])];
      side = double(sg.hi) < iso ? LevelSides::below : (double(sg.lo) > iso ? LevelSides::above : LevelSides::holds);
    }
    if (side != LevelSides::holds) {
      t = std::max(exit_of(c, 1.0) + 1e-6, t + 1e-6);
      prev = side == LevelSides::below ? -1.0 : 1.0;
      continue;
    }
    // Through this cell in steps of `step`, its lookups made once (the last step may end in the next cell).
    const double cell_end = std::min(exit_of(c, 1.0), t_end);
    do {
      const double tn = std::min(t + step, t_end);
      const double f = spline.value(from + tn * dir) - iso;
      if ((prev < 0.0) != (f < 0.0)) return tn;
      prev = f;
      t = tn;
    } while (t < cell_end);
    if (t >= t_end) break;
  }
  return -1.0;
}

bool occluded(const VolumeSpline& spline, const SingletonTable& table, double iso, const IndexView& iv,
              const glm::dvec3& from, double skip, const LevelSides* sides) {
  glm::dvec3 dir = iv.perspective ? iv.eye - from : -iv.v;
  double t_end = iv.perspective ? glm::length(dir) : INFINITY;
  if (!(glm::length(dir) > 0.0)) return false;
  dir /= glm::length(dir);
  // Clip to the grid box.
  const glm::dvec3 hi(spline.dims()[0] - 1, spline.dims()[1] - 1, spline.dims()[2] - 1);
  for (int a = 0; a < 3; ++a) {
    if (dir[a] > 0.0)
      t_end = std::min(t_end, (hi[a] - from[a]) / dir[a]);
    else if (dir[a] < 0.0)
      t_end = std::min(t_end, (0.0 - from[a]) / dir[a]);
  }
  return first_crossing(spline, table, iso, from, dir, skip, t_end, sides) >= 0.0;
}

}  // namespace silhouette_detail

bool iso_occluded(const VolumeSpline& spline, const SingletonTable& table, double iso, const SilhouetteView& view,
                  const glm::dvec3& from, double skip) {
  return silhouette_detail::occluded(spline, table, iso, index_view(spline, view), from, skip, nullptr);
}

}  // namespace trispline::core
