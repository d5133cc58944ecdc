// Internal to the silhouette extraction (silhouettes.cpp): tracing the silhouette curves of one block of cells, and
// joining the blocks' traces at their shared face points. Not a public API.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/volume/silhouette_seeds.h"

namespace trispline::core::silhouette_detail {

// One piece of curve traced inside one block. Its ends are either free (the curve ended, or tracing failed) or lie on
// a face of the block, found exactly (solve_point on the face plane) so that the neighbour block's trace of the same
// curve ends at the same point.
struct Trace {
  std::vector<CurvePoint> points;
  bool closed = false;
  bool on_face[2] = {false, false};  // first, last point
};

// Per-thread memory of a block: which cells a trace has crossed, and the traced points filed by cell.
struct BlockScratch {
  struct Entry {
    glm::dvec3 x;
    std::int32_t trace, next;
    std::int32_t order;  // the point's number in its trace (in the order traced)
  };
  std::vector<std::int32_t> head;          // per local cell: first Entry of the cell, −1 none
  std::vector<unsigned char> visited;      // per local cell: a trace crossed it
  std::vector<unsigned char> hidden;       // per local cell: 0 not asked yet, 1 seen, 2 hidden (Problem::hidden)
  std::vector<unsigned char> hidden_tile;  // per local tile of kHiddenTile³ cells: as `hidden`, 2 = all its cells
  std::vector<std::uint32_t> touched;      // local cells to reset
  std::vector<Entry> entries;
  void reset() {
    for (std::uint32_t c : touched) head[c] = -1, visited[c] = 0;
    touched.clear();
    entries.clear();
  }
};

// Traces the silhouette curves of one block of cells (predictor–corrector continuation from each seed, both ways,
// until the curve closes, leaves the block, runs into another trace or cannot be followed).
class BlockTracer {
 public:
  BlockTracer(const Problem& pb, const glm::ivec3& first, const glm::ivec3& last, BlockScratch& scratch,
              const TraceLimits& limits = {})
      : pb_(pb), first_(first), last_(last), limits_(limits), s_(scratch) {
    const auto& dims = pb.spline.dims();
    for (int a = 0; a < 3; ++a) {
      extent_[a] = last[a] - first[a];
      lo_[a] = std::max(pb.spline.span_begin(first[a]), 0.0);
      hi_[a] = std::min(pb.spline.span_begin(last[a]), double(dims[a] - 1));
    }
    const std::size_t cells = static_cast<std::size_t>(kBlock) * kBlock * kBlock;
    if (s_.head.size() != cells) s_.head.assign(cells, -1), s_.visited.assign(cells, 0);
    s_.reset();
    if (pb.hidden) {
      constexpr int t = kBlock / kHiddenTile;
      s_.hidden.assign(cells, 0);
      s_.hidden_tile.assign(static_cast<std::size_t>(t) * t * t, 0);
    }
  }
  ~BlockTracer() { s_.reset(); }

  std::vector<Trace> traces;

  const TraceLimits& limits() const { return limits_; }

  bool visited(const glm::ivec3& cell) const { return s_.visited[local(cell)] != 0; }

  // Whether Problem::hidden hides the whole tile of kHiddenTile³ cells holding `cell` (asked once per tile and
  // block). The ball holding the tile holds each cell's, so a hidden tile hides each of its cells (a nearer ball over
  // more of the map); most cells of a view are decided so, before anything else is read about them.
  bool tile_hidden(const glm::ivec3& cell) {
    if (!pb_.hidden) return false;
    constexpr int t = kBlock / kHiddenTile;
    const glm::ivec3 tile = (cell - first_) / kHiddenTile;
    unsigned char& ht = s_.hidden_tile[static_cast<std::size_t>(tile.x + t * (tile.y + t * tile.z))];
    if (ht == 0) {
      const glm::ivec3 lo = first_ + tile * kHiddenTile;
      ht = pb_.hidden->hides(lo, glm::min(lo + kHiddenTile, last_)) ? 2 : 1;
    }
    return ht == 2;
  }

  // Whether Problem::hidden hides `cell` (a cell of this block; asked once per cell and block). False without it.
  bool hidden(const glm::ivec3& cell) {
    if (!pb_.hidden) return false;
    if (tile_hidden(cell)) return true;
    unsigned char& h = s_.hidden[local(cell)];
    if (h == 0) h = pb_.hidden->hides(cell, cell + 1) ? 2 : 1;
    return h == 2;
  }

  // A traced point within r (≤ 1) index units of x — of another trace than `own`, or of trace `own` numbered below
  // `own_before` — or null.
  const BlockScratch::Entry* near_trace(const glm::dvec3& x, double r, std::int32_t own = -1,
                                        std::int32_t own_before = 0) const {
    const glm::ivec3 c = cell_of(x);
    const glm::ivec3 lo = glm::max(c - 1, first_) - first_, hi = glm::min(c + 1, last_ - 1) - first_;
    const double r2 = r * r;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y) {
        const std::size_t row = kBlock * (static_cast<std::size_t>(y) + kBlock * static_cast<std::size_t>(z));
        for (int xi = lo.x; xi <= hi.x; ++xi)
          for (std::int32_t e = s_.head[row + xi]; e >= 0; e = s_.entries[e].next) {
            const BlockScratch::Entry& en = s_.entries[e];
            const glm::dvec3 d = en.x - x;
            if ((en.trace != own || en.order < own_before) && glm::dot(d, d) < r2) return &en;
          }
      }
    return nullptr;
  }

  bool inside(const glm::dvec3& x) const {
    return !glm::any(glm::lessThan(x, lo_)) && !glm::any(glm::greaterThan(x, hi_));
  }

  glm::ivec3 cell_of(const glm::dvec3& x) const {
    glm::ivec3 c;
    const double shift = pb_.spline.span_begin(0);
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor(x[a] - shift)), first_[a], last_[a] - 1);
    return c;
  }

  // Traces the curve through p both ways and keeps it when it is more than a point.
  void trace_from(const CurvePoint& p) {
    const auto id = static_cast<std::int32_t>(traces.size());
    next_order_ = 0;
    add_point(p.x, id);
    std::vector<CurvePoint> ahead, behind;
    const End e1 = march(p, 1.0, id, &p.x, ahead);
    Trace tr;
    if (e1 == End::closed) {
      tr.closed = true;
      tr.points.reserve(ahead.size() + 1);
      tr.points.push_back(p);
      tr.points.insert(tr.points.end(), ahead.begin(), ahead.end());
    } else {
      // Backwards, a loop the forward march could not close ends where the forward march stopped.
      const End e0 = march(p, -1.0, id, ahead.empty() ? nullptr : &ahead.back().x, behind);
      tr.points.reserve(behind.size() + ahead.size() + 1);
      tr.points.insert(tr.points.end(), behind.rbegin(), behind.rend());
      tr.points.push_back(p);
      tr.points.insert(tr.points.end(), ahead.begin(), ahead.end());
      tr.closed = e0 == End::closed;
      tr.on_face[0] = e0 == End::face;
      tr.on_face[1] = e1 == End::face;
    }
    if (tr.points.size() >= 2) traces.push_back(std::move(tr));
  }

 private:
  enum class End { failed, face, closed, joined };

  std::size_t local(const glm::ivec3& c) const {
    return static_cast<std::size_t>(c.x - first_.x) +
           kBlock * (static_cast<std::size_t>(c.y - first_.y) + kBlock * static_cast<std::size_t>(c.z - first_.z));
  }

  void visit(const glm::ivec3& c) {
    const std::size_t l = local(c);
    if (!s_.visited[l] && s_.head[l] < 0) s_.touched.push_back(static_cast<std::uint32_t>(l));
    s_.visited[l] = 1;
  }

  void add_point(const glm::dvec3& x, std::int32_t trace) {
    const std::int32_t order = next_order_++;
    const glm::ivec3 c = cell_of(x);
    const std::size_t l = local(c);
    if (!s_.visited[l] && s_.head[l] < 0) s_.touched.push_back(static_cast<std::uint32_t>(l));
    s_.visited[l] = 1;
    s_.entries.push_back({x, trace, s_.head[l], order});
    s_.head[l] = static_cast<std::int32_t>(s_.entries.size() - 1);
  }

  // Marks the cells the segment a→b crosses (samples every ¼ index unit).
  void visit_segment(const glm::dvec3& a, const glm::dvec3& b) {
    const int n = 1 + static_cast<int>(glm::length(b - a) * 4.0);
    for (int i = 0; i <= n; ++i) visit(cell_of(a + (b - a) * (double(i) / n)));
  }

  // Follows the curve from `start` along sign·tangent, appending the points after it to `out`; the march closes when it
  // comes back to *close_to (may be null) after going some way.
  End march(const CurvePoint& start, double sign, std::int32_t id, const glm::dvec3* close_to,
            std::vector<CurvePoint>& out) {
    const double min_turn_cos = limits_.min_turn_cos;
    const glm::dvec3 margin(1.0);
    glm::dvec3 x = start.x, t = sign * start.tangent;
    glm::dvec3 bend(0.0);  // dt/ds from the last step: the predictor follows the curve's bending
    double h = limits_.step_max, travelled = 0.0;
    int easy = 0;
    // A curve in one block is far shorter than kMaxSteps steps; the bound only stops a runaway march.
    for (int n = 0; n < kMaxSteps; ++n) {
      CurvePoint q;
      const glm::dvec3 predicted = x + h * t + (0.5 * h * h) * bend;
      bool ok = solve_point(pb_, predicted, lo_ - margin, hi_ + margin, kCorrectorIterations, q);
      double dl = 0.0;
      if (ok) {
        const glm::dvec3 d = q.x - x;
        dl = glm::length(d);
        // A step goes forward by about h, lands near the predictor (not on a neighbouring branch) and turns little.
        ok = dl >= 0.25 * h && dl <= 2.0 * h && glm::dot(d, t) >= 0.5 * dl &&
             glm::length(q.x - predicted) <= limits_.predictor_reach * h &&
             std::abs(glm::dot(q.tangent, t)) >= min_turn_cos;
      }
      if (!ok) {
        h *= 0.5, easy = 0;
        if (h < kStepMin) return End::failed;
        continue;
      }
      if (glm::dot(q.tangent, t) < 0.0) q.tangent = -q.tangent;
      if (!inside(q.x)) {
        // Leaving the block: the crossing of the face the segment x→q leaves through, solved on the face plane.
        double s = 1.0;
        int axis = -1;
        double plane = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double bound = q.x[a] > hi_[a] ? hi_[a] : (q.x[a] < lo_[a] ? lo_[a] : NAN);
          if (std::isnan(bound)) continue;
          const double sa = (bound - x[a]) / (q.x[a] - x[a]);
          if (sa < s) s = sa, axis = a, plane = bound;
        }
        if (axis < 0) return End::failed;
        glm::dvec3 y = x + s * (q.x - x);
        y[axis] = plane;
        CurvePoint f;
        const glm::dvec3 tol(1e-9);
        if (!solve_point(pb_, y, lo_ - margin, hi_ + margin, kCorrectorIterations, f, axis) ||
            glm::length(f.x - y) > h || glm::any(glm::lessThan(f.x, lo_ - tol)) ||
            glm::any(glm::greaterThan(f.x, hi_ + tol)))
          return End::failed;
        if (glm::dot(f.tangent, t) < 0.0) f.tangent = -f.tangent;
        visit_segment(x, f.x);
        out.push_back(f);
        return End::face;
      }
      // Another trace, or this one (not its last few points): the curve is known from here on. Back at close_to, the
      // curve is a closed loop.
      if (const BlockScratch::Entry* en = near_trace(q.x, limits_.join_radius, id, next_order_ - 8)) {
        if (close_to && en->trace == id && en->x == *close_to) {
          visit_segment(x, *close_to);
          return End::closed;
        }
        return End::joined;
      }
      // Behind the surface (Problem::hidden): the curve is not drawn from here on, so it is not traced further.
      if (hidden(cell_of(q.x))) return End::failed;
      visit_segment(x, q.x);
      add_point(q.x, id);
      out.push_back(q);
      travelled += dl;
      bend = (q.tangent - t) / dl;
      x = q.x, t = q.tangent;
      if (q.iterations <= 3 && ++easy >= 2) h = std::min(limits_.step_max, 1.5 * h);
    }
    return End::failed;
  }

  const Problem& pb_;
  glm::ivec3 first_, last_;  // cells first…last − 1 per axis
  TraceLimits limits_;
  glm::ivec3 extent_{0};
  glm::dvec3 lo_{0.0}, hi_{0.0};  // the block's box in index space, clipped to the domain
  std::int32_t next_order_ = 0;   // number of the next point of the trace being traced
  BlockScratch& s_;
};

// Joins the traces of all blocks at their shared face points into polylines (index lists of traces with direction),
// in the traces' order: open chains first (from a free end), then cycles.
struct ChainPiece {
  std::uint32_t trace;
  bool reversed;
};
struct Chain {
  std::vector<ChainPiece> pieces;
  bool closed = false;
};

std::vector<Chain> join_traces(const std::vector<Trace>& traces);

}  // namespace trispline::core::silhouette_detail
