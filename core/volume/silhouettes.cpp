#include "core/volume/silhouettes.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

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
      const double t = first_crossing(pb_.spline, pb_.table, pb_.iso, from, dir, t0, t1);
      if (t >= 0.0) depth_[std::size_t(j) * kN + std::size_t(i)] = t;
    }
  });
}

}  // namespace silhouette_detail

SilhouetteResult extract_silhouettes(const VolumeSpline& spline, const SingletonTable& table, double iso,
                                     const SilhouetteView& view, const SilhouetteParams& params) {
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
  const IndexView& iv = pb.view;
  // The directions w can take over the grid box: one cone (axis, half-angle) for the bin filter.
  glm::dvec3 w_axis = iv.v;
  double w_half = 0.0;
  if (iv.perspective) {
    const glm::dvec3 hi(spline.dims()[0] - 1, spline.dims()[1] - 1, spline.dims()[2] - 1);
    const glm::dvec3 centre = hi * 0.5;
    const double radius = glm::length(hi) * 0.5 + 1.0;
    const glm::dvec3 d = centre - iv.eye;
    const double dist = glm::length(d);
    w_axis = dist > 0.0 ? d / dist : glm::dvec3(0.0, 0.0, 1.0);
    w_half = dist > radius ? std::asin(radius / dist) : kPi;
  }
  std::optional<HiddenCells> hidden;
  if (!params.seed_hidden) {
    hidden.emplace(pb, w_axis, w_half);
    if (hidden->usable())
      pb.hidden = &*hidden;
    else
      hidden.reset();
  }
  const std::vector<std::uint32_t> bins = table.cells_holding(iso, w_axis, w_half, SingletonTable::CellOrder::by_bin);
  // The candidates by block (in the table's order within a block: the bucketing is stable).
  const auto& dims = table.cells();
  const glm::ivec3 blocks((dims[0] + kBlock - 1) / kBlock, (dims[1] + kBlock - 1) / kBlock,
                          (dims[2] + kBlock - 1) / kBlock);
  const std::size_t block_count = static_cast<std::size_t>(blocks.x) * blocks.y * blocks.z;
  auto cell_coords = [&](std::uint32_t cell) {
    return glm::ivec3(static_cast<int>(cell % dims[0]), static_cast<int>((cell / dims[0]) % dims[1]),
                      static_cast<int>(cell / (static_cast<std::size_t>(dims[0]) * dims[1])));
  };
  auto block_of = [&](const glm::ivec3& c) {
    return static_cast<std::size_t>(c.x / kBlock) +
           blocks.x * (static_cast<std::size_t>(c.y / kBlock) + blocks.y * static_cast<std::size_t>(c.z / kBlock));
  };
  std::vector<std::uint32_t> block_begin(block_count + 1, 0), by_block(bins.size()), block_id(bins.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, bins.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t e = r.begin(); e != r.end(); ++e)
                        block_id[e] = static_cast<std::uint32_t>(block_of(cell_coords(bins[e])));
                    });
  // Blocks wholly behind the surface (seed_hidden false) take no candidates.
  std::vector<unsigned char> block_hidden(block_count, 0);
  if (hidden)
    tbb::parallel_for(std::size_t(0), block_count, [&](std::size_t blk) {
      const glm::ivec3 bc(static_cast<int>(blk % blocks.x), static_cast<int>((blk / blocks.x) % blocks.y),
                          static_cast<int>(blk / (static_cast<std::size_t>(blocks.x) * blocks.y)));
      const glm::ivec3 first = bc * kBlock;
      block_hidden[blk] = hidden->hides(first, glm::min(first + kBlock, glm::ivec3(dims[0], dims[1], dims[2])));
    });
  std::size_t in_hidden_blocks = 0;
  for (std::uint32_t b : block_id) {
    if (block_hidden[b]) {
      ++in_hidden_blocks;
      continue;
    }
    ++block_begin[b + 1];
  }
  for (std::size_t b = 0; b < block_count; ++b) block_begin[b + 1] += block_begin[b];
  {
    std::vector<std::uint32_t> fill(block_begin.begin(), block_begin.end() - 1);
    for (std::size_t e = 0; e < bins.size(); ++e)
      if (!block_hidden[block_id[e]]) by_block[fill[block_id[e]]++] = bins[e];
  }
  // Each block: the exact per-singleton cone test (cell-sized view cone in perspective), then seeds, Newton and
  // tracing, skipping cells a trace has already crossed. Blocks write to their own slots (deterministic for any
  // thread count).
  std::vector<std::vector<Trace>> block_traces(block_count);
  std::vector<std::size_t> cand(block_count, 0), seeds(block_count, 0), hidden_cells(block_count, 0);
  const auto& singles = table.singletons();
  tbb::enumerable_thread_specific<BlockScratch> scratch;
#if defined(__SSE2__)
  std::optional<CubicHullTest> cubic;
  if (spline.order() == 4) cubic.emplace(spline, iv);
#endif
  tbb::parallel_for(std::size_t(0), block_count, [&](std::size_t blk) {
    if (block_begin[blk] == block_begin[blk + 1]) return;
    const glm::ivec3 bc(static_cast<int>(blk % blocks.x), static_cast<int>((blk / blocks.x) % blocks.y),
                        static_cast<int>(blk / (static_cast<std::size_t>(blocks.x) * blocks.y)));
    const glm::ivec3 first = bc * kBlock;
    const glm::ivec3 last = glm::min(first + kBlock, glm::ivec3(dims[0], dims[1], dims[2]));
    BlockTracer tracer(pb, first, last, scratch.local());
    for (std::uint32_t e = block_begin[blk]; e < block_begin[blk + 1]; ++e) {
      // The singletons are read in bin order, far apart in memory: fetch a few ahead.
      if (e + 8 < block_begin[blk + 1]) __builtin_prefetch(&singles[by_block[e + 8]]);
      const std::uint32_t cell = by_block[e];
      const glm::ivec3 c = cell_coords(cell);
      if (tracer.visited(c)) continue;
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
        // A seed heading into a cell a trace has crossed is given up early (what it would find there is known).
        auto known = [&](const glm::dvec3& x) { return tracer.inside(x) && tracer.visited(tracer.cell_of(x)); };
        if (!solve_point(pb, centre, cell_lo - 0.5, cell_lo + 1.5, kSeedIterations, p, -1, known)) return false;
        // A converged point anywhere in the block starts a trace, unless a trace already passed there.
        if (!tracer.inside(p.x) || tracer.visited(tracer.cell_of(p.x)) || tracer.near_trace(p.x, kJoinRadius))
          return false;
        tracer.trace_from(p);
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
    for (Trace& t : block_traces[b]) traces.push_back(std::move(t));
  }
  result.hidden_cells += in_hidden_blocks;
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
      pl.points.push_back(glm::dvec3(spline.index_to_world() * glm::dvec4(p.x, 1.0)));
      pl.gradient_norm.push_back(p.gradient_norm);
      result.max_value_residual = std::max(result.max_value_residual, p.value_residual);
      result.max_dot_residual = std::max(result.max_dot_residual, p.dot_residual);
      if (i > 0) result.length_mm += glm::length(pl.points[i] - pl.points[i - 1]);
    }
    if (pl.closed) result.length_mm += glm::length(pl.points.front() - pl.points.back());
    pl.visible.assign(n, 1);
    result.points += n;
    result.polylines.push_back(std::move(pl));
  }
  result.extract_ms = ms_since(t0);
  if (params.hidden_test) {
    const auto t1 = std::chrono::steady_clock::now();
    // Every 4th point (and the last) is tested; the points between two tested ones of the same visibility take it,
    // those between two that differ are tested one by one. A visibility change is located exactly; only a hidden
    // stretch shorter than 4 points between two visible ones (or the reverse) could be missed.
    constexpr std::size_t kStride = 4;
    auto occluded = [&](const SilhouettePolyline& pl, std::size_t i) {
      const glm::dvec3 x(spline.world_to_index() * glm::dvec4(pl.points[i], 1.0));
      if (hidden && hidden->hides(x, 0.0)) return 0;  // well behind the map's first crossings
      return iso_occluded(spline, table, iso, view, x) ? 0 : 1;
    };
    // The tested points of all polylines as one list (a few polylines hold most points: splitting by polyline would
    // leave one thread with the longest), then the stretches between two tested points that differ, per polyline.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> tested;  // (polyline, point)
    for (std::size_t k = 0; k < result.polylines.size(); ++k) {
      const std::size_t n = result.polylines[k].points.size();
      for (std::size_t i = 0; i < n; i += kStride) tested.emplace_back(std::uint32_t(k), std::uint32_t(i));
      if ((n - 1) % kStride != 0) tested.emplace_back(std::uint32_t(k), std::uint32_t(n - 1));
    }
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tested.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t e = r.begin(); e != r.end(); ++e) {
                          SilhouettePolyline& pl = result.polylines[tested[e].first];
                          pl.visible[tested[e].second] = static_cast<unsigned char>(occluded(pl, tested[e].second));
                        }
                      });
    tbb::parallel_for(std::size_t(0), result.polylines.size(), [&](std::size_t k) {
      SilhouettePolyline& pl = result.polylines[k];
      const std::size_t n = pl.points.size();
      for (std::size_t prev = 0; prev + 1 < n;) {
        const std::size_t next = std::min(prev + kStride, n - 1);
        for (std::size_t i = prev + 1; i < next; ++i)
          pl.visible[i] =
              pl.visible[prev] == pl.visible[next] ? pl.visible[prev] : static_cast<unsigned char>(occluded(pl, i));
        prev = next;
      }
    });
    result.hidden_ms = ms_since(t1);
  }
  return result;
}

namespace silhouette_detail {

double first_crossing(const VolumeSpline& spline, const SingletonTable& table, double iso, const glm::dvec3& from,
                      const glm::dvec3& dir, double t, double t_end) {
  const double step = 0.4;
  if (!(t < t_end)) return -1.0;
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
    const Singleton& sg = table.singletons()[table.cell_index(c[0], c[1], c[2])];
    if (!(double(sg.lo) <= iso && iso <= double(sg.hi))) {
      t = std::max(exit_of(c, 1.0) + 1e-6, t + 1e-6);
      prev = double(sg.hi) < iso ? -1.0 : 1.0;
      continue;
    }
    const double tn = std::min(t + step, t_end);
    const double f = spline.value(from + tn * dir) - iso;
    if ((prev < 0.0) != (f < 0.0)) return tn;
    prev = f;
    t = tn;
    if (tn >= t_end) break;
  }
  return -1.0;
}

}  // namespace silhouette_detail

bool iso_occluded(const VolumeSpline& spline, const SingletonTable& table, double iso, const SilhouetteView& view,
                  const glm::dvec3& from, double skip) {
  const IndexView iv = index_view(spline, view);
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
  return first_crossing(spline, table, iso, from, dir, skip, t_end) >= 0.0;
}

}  // namespace trispline::core
