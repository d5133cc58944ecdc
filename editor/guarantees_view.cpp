#include "editor/guarantees_view.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/ffd/deformation_bounds.h"
#include "core/ffd/ffd.h"
#include "editor/replay/elapsed.h"
#include "ui/overlays.h"

namespace trispline::editor {

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kDecades = 3.0;  // the ramp spans max/1000 … max
constexpr float kHeatAlpha = 0.82f;
const glm::vec4 kUnbounded{0.92f, 0.25f, 0.92f, kHeatAlpha};
const glm::vec4 kCertified{0.30f, 0.86f, 0.38f, 0.95f}, kFold{1.0f, 0.18f, 0.12f, 1.0f},
    kUndecided{0.62f, 0.62f, 0.64f, 0.95f};

// Display colour of t ∈ [0,1]: dark blue → blue → green → yellow → red.
glm::vec4 ramp(double t) {
  static const glm::vec3 stops[] = {{0.16f, 0.20f, 0.52f},
                                    {0.14f, 0.52f, 0.86f},
                                    {0.22f, 0.78f, 0.42f},
                                    {0.96f, 0.84f, 0.20f},
                                    {0.90f, 0.18f, 0.14f}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int i = std::min(static_cast<int>(t), 3);
  return {glm::mix(stops[i], stops[i + 1], static_cast<float>(t - i)), kHeatAlpha};
}

double ramp_position(double bound, double max_bound) {
  if (!(max_bound > 0.0) || !(bound > 0.0)) return 0.0;
  return std::log10(bound / max_bound) / kDecades + 1.0;
}

ImU32 to_imgui(const glm::vec4& c) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1.0f)); }

}  // namespace

GuaranteesView::~GuaranteesView() {
  if (job_.valid()) job_.wait();
}

GuaranteesView::Result GuaranteesView::compute(const Input& in) {
  Result r;
  r.input = in;
  const core::TrivariateBSpline<glm::dvec3>& F = *in.lattice;
  const core::TriMesh& rest = *in.rest;
  try {
    if (in.bounds) {
      const auto t0 = Clock::now();
      const core::SecondDerivativeBounds bounds(F);
      const std::vector<double> b = core::triangle_error_bounds(bounds, in.binding->params, rest.triangles, in.offset);
      std::vector<glm::dvec3> params = in.binding->params, deformed;
      for (glm::dvec3& p : params) p += in.offset;
      core::ffd_evaluate(F, params, deformed);
      r.triangles = b.size();
      std::vector<double> finite;
      finite.reserve(b.size());
      for (double x : b) {
        if (std::isfinite(x))
          finite.push_back(x);
        else
          ++r.unbounded;
      }
      r.max_bound = finite.empty() ? 0.0 : *std::max_element(finite.begin(), finite.end());
      if (!finite.empty()) {
        std::nth_element(finite.begin(), finite.begin() + finite.size() / 2, finite.end());
        r.median_bound = finite[finite.size() / 2];
      }
      auto corners = std::make_shared<std::vector<glm::vec3>>();
      auto colors = std::make_shared<std::vector<glm::vec4>>();
      corners->reserve(3 * b.size());
      colors->reserve(3 * b.size());
      for (std::size_t f = 0; f < b.size(); ++f) {
        const glm::vec4 c = std::isfinite(b[f]) ? ramp(ramp_position(b[f], r.max_bound)) : kUnbounded;
        for (int k = 0; k < 3; ++k) {
          corners->push_back(glm::vec3(deformed[rest.triangles[f][k]]));
          colors->push_back(c);
        }
      }
      r.corners = std::move(corners);
      r.colors = std::move(colors);
      r.bounds_ms = ms_since(t0);
    }
    if (in.certificate) {
      const auto t0 = Clock::now();
      r.certificate = core::certify_fold_free(F);
      r.certificate_ms = ms_since(t0);
      // The Bézier cells' edges through F, each segment in the worst verdict of the cells sharing it.
      const core::TrivariateBSpline<glm::dvec3> U = F.periodic_unwrapped();
      std::array<std::vector<double>, 3> breaks;
      for (int a = 0; a < 3; ++a) {
        const core::KnotVector& k = U.knots(a);
        for (double t : k.knots())
          if (t >= k.domain_min() && t <= k.domain_max() && (breaks[a].empty() || breaks[a].back() != t))
            breaks[a].push_back(t);
      }
      const glm::ivec3 cells(int(breaks[0].size()) - 1, int(breaks[1].size()) - 1, int(breaks[2].size()) - 1);
      if (static_cast<std::size_t>(cells.x) * cells.y * cells.z == r.certificate->cells) {
        std::vector<unsigned char> verdict(r.certificate->cells, 0);  // 0 certified, 1 undecided, 2 fold
        auto id = [&](const glm::ivec3& c) { return c.x + std::size_t(cells.x) * (c.y + std::size_t(cells.y) * c.z); };
        for (const glm::ivec3& c : r.certificate->undecided_cells) verdict[id(c)] = 1;
        for (const glm::ivec3& c : r.certificate->fold_cells) verdict[id(c)] = 2;
        constexpr int kPieces = 6;
        for (int a = 0; a < 3; ++a) {
          const int b = (a + 1) % 3, c = (a + 2) % 3;
          for (std::size_t j = 0; j < breaks[b].size(); ++j)
            for (std::size_t k = 0; k < breaks[c].size(); ++k)
              for (int i = 0; i < cells[a]; ++i) {
                unsigned char worst = 0;
                for (int dj = -1; dj <= 0; ++dj)
                  for (int dk = -1; dk <= 0; ++dk) {
                    glm::ivec3 cell;
                    cell[a] = i;
                    cell[b] = int(j) + dj;
                    cell[c] = int(k) + dk;
                    if (cell[b] < 0 || cell[b] >= cells[b] || cell[c] < 0 || cell[c] >= cells[c]) continue;
                    worst = std::max(worst, verdict[id(cell)]);
                  }
                const glm::vec4 colour = worst == 2 ? kFold : worst == 1 ? kUndecided : kCertified;
                glm::dvec3 t;
                t[b] = breaks[b][j];
                t[c] = breaks[c][k];
                for (int p = 0; p < kPieces; ++p) {
                  t[a] = breaks[a][i] + (breaks[a][i + 1] - breaks[a][i]) * p / kPieces;
                  r.cell_ends.push_back(F.eval(t));
                  t[a] = breaks[a][i] + (breaks[a][i + 1] - breaks[a][i]) * (p + 1) / kPieces;
                  r.cell_ends.push_back(F.eval(t));
                  r.cell_colors.push_back(colour);
                }
              }
        }
      }
    }
  } catch (const std::exception& e) {
    r = Result{};
    r.input = in;
    r.error = e.what();
  }
  return r;
}

bool GuaranteesView::Input::same(const Input& o) const {
  return object == o.object && lattice == o.lattice && rest == o.rest && binding == o.binding && offset == o.offset &&
         bounds == o.bounds && certificate == o.certificate;
}

void GuaranteesView::update(const core::Scene& scene, const std::string& object,
                            const std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>& lattice,
                            bool error_bounds, bool certificate) {
  // The newest finished computation is shown (a stale one until then, as the live silhouettes are).
  if (job_.valid() && job_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    Result r = job_.get();
    // Shown if it is still of the object and views wanted, even for an older lattice (a drag moves on meanwhile).
    if (wanted_ && r.input.object == wanted_->object && r.input.bounds == wanted_->bounds &&
        r.input.certificate == wanted_->certificate)
      shown_ = std::move(r), ++updates_;
  }
  const core::SceneObject* o = (error_bounds || certificate) ? scene.find(object) : nullptr;
  if (!o || !o->ffd || !o->rest_mesh || o->ffd->params.size() != o->rest_mesh->positions.size()) {
    wanted_.reset();
    shown_.reset();
    return;
  }
  Input in;
  in.object = object;
  // The lattice shown: the preview's, else the object's own (aliasing the binding keeps it alive).
  in.lattice = lattice ? lattice : std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>(o->ffd, &o->ffd->lattice);
  in.binding = o->ffd;
  in.rest = o->rest_mesh;
  in.offset = o->offset_at(0.0);
  in.live = lattice != nullptr;
  in.bounds = error_bounds;
  in.certificate = certificate;
  wanted_ = in;
  if (shown_ && !(shown_->input.object == in.object && shown_->input.bounds == in.bounds &&
                  shown_->input.certificate == in.certificate))
    shown_.reset();  // another object or other views: nothing stale of the wrong kind
  const bool current = shown_ && shown_->input.same(in);
  if (!current && !job_.valid()) job_ = std::async(std::launch::async, [in] { return compute(in); });
}

bool GuaranteesView::busy() const { return job_.valid(); }

void GuaranteesView::decorate(gpu::ViewOptions& options) const {
  if (!shown_) return;
  const Result& r = *shown_;
  if (r.corners) options.overlays.colored_triangles.push_back({r.corners, r.colors});
  if (!r.cell_ends.empty()) options.overlays.colored_lines.push_back({r.cell_ends, r.cell_colors});
  if (r.certificate && !r.certificate->fold_points.empty())
    options.overlays.points.push_back({r.certificate->fold_points, kFold, options.style.fold_point_px});
}

std::string GuaranteesView::summary() const {
  if (!shown_) return busy() ? "computing" : "";
  const Result& r = *shown_;
  char line[200];
  std::string s;
  if (r.corners) {
    std::snprintf(line, sizeof line, "bounds %.1f ms (%zu tris, max %.3g)", r.bounds_ms, r.triangles, r.max_bound);
    s += line;
  }
  if (r.certificate) {
    std::snprintf(line, sizeof line, "%scertificate %.1f ms (%s, %zu cells)", s.empty() ? "" : "; ", r.certificate_ms,
                  core::fold_verdict_name(r.certificate->verdict), r.certificate->cells);
    s += line;
  }
  if (busy()) s += "; computing";
  return s;
}

nlohmann::json GuaranteesView::probe() const {
  nlohmann::json p = {{"object", shown_ ? shown_->input.object : std::string()},
                      {"live", shown_ && shown_->input.live},
                      {"updates", updates_},
                      {"busy", busy()},
                      {"error_bounds", shown_ && shown_->corners != nullptr},
                      {"certificate", nullptr},
                      {"error", shown_ ? shown_->error : std::string()}};
  if (!shown_) return p;
  const Result& r = *shown_;
  if (r.corners) {
    p["triangles"] = r.triangles;
    p["max_bound"] = r.max_bound;
    p["median_bound"] = r.median_bound;
    p["unbounded"] = r.unbounded;
  }
  if (r.certificate) {
    p["certificate"] = core::fold_verdict_name(r.certificate->verdict);
    p["cells"] = r.certificate->cells;
    p["fold_cells"] = r.certificate->fold_cells.size();
    p["undecided_cells"] = r.certificate->undecided_cells.size();
    p["cell_segments"] = r.cell_colors.size();
  }
  return p;
}

void GuaranteesView::draw_legend(const ui::Rect& viewport) const {
  if (!shown_) return;
  const Result& r = *shown_;
  if (!ui::begin_viewport_overlay("##guarantees_legend", viewport.pos.x + viewport.size.x - 10,
                                  viewport.pos.y + viewport.size.y - 10, 1.0f, 1.0f, 0.85f))
    return;
  ImGui::Text("%s%s", r.input.object.c_str(), busy() ? "  (updating...)" : "");
  if (!r.error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", r.error.c_str());
  if (r.corners) {
    ImGui::TextUnformatted("Certified error bound (world units)");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "Per triangle: an upper bound on the distance between the true deformed surface F(T) and\n"
          "the flat triangle drawn through its deformed corners (seed ch. 3: Filip et al.'s right-\n"
          "triangle bound and the smallest-enclosing-circle bound, from the lattice's second\n"
          "differences). Logarithmic colours over three decades below the largest bound.");
    const float w = 220.0f, h = 12.0f;
    const ImVec2 at = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    constexpr int kSteps = 32;
    for (int i = 0; i < kSteps; ++i)
      dl->AddRectFilledMultiColor(ImVec2(at.x + w * i / kSteps, at.y), ImVec2(at.x + w * (i + 1) / kSteps, at.y + h),
                                  to_imgui(ramp(double(i) / kSteps)), to_imgui(ramp(double(i + 1) / kSteps)),
                                  to_imgui(ramp(double(i + 1) / kSteps)), to_imgui(ramp(double(i) / kSteps)));
    ImGui::Dummy(ImVec2(w, h));
    char lo[32], mid[32], hi[32];
    std::snprintf(lo, sizeof lo, "%.2g", r.max_bound * std::pow(10.0, -kDecades));
    std::snprintf(mid, sizeof mid, "%.2g", r.max_bound * std::pow(10.0, -kDecades / 2));
    std::snprintf(hi, sizeof hi, "%.3g", r.max_bound);
    const float x0 = ImGui::GetCursorPosX();
    ImGui::TextUnformatted(lo);
    ImGui::SameLine(x0 + 0.5f * w - 0.5f * ImGui::CalcTextSize(mid).x);
    ImGui::TextUnformatted(mid);
    ImGui::SameLine(x0 + w - ImGui::CalcTextSize(hi).x);
    ImGui::TextUnformatted(hi);
    ImGui::Text("median %.3g, %zu triangles", r.median_bound, r.triangles);
    if (r.unbounded > 0) {
      ImGui::TextColored(ImVec4(kUnbounded.x, kUnbounded.y, kUnbounded.z, 1.0f), "%zu unbounded", r.unbounded);
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "Triangles crossing a C0 knot plane (order 2) or leaving the lattice's domain: F is not\n"
            "smooth across them, so no bound holds. Refine (mesh.refine) to split them there.");
    }
  }
  if (r.certificate) {
    if (r.corners) ImGui::Separator();
    const core::FoldCertificate& c = *r.certificate;
    const glm::vec4 colour = c.verdict == core::FoldVerdict::fold        ? kFold
                             : c.verdict == core::FoldVerdict::undecided ? kUndecided
                                                                         : kCertified;
    const ImVec4 ic(colour.x, colour.y, colour.z, 1.0f);
    if (c.verdict == core::FoldVerdict::fold_free)
      ImGui::TextColored(ic, "Fold-free: certified (%zu cells)", c.cells);
    else if (c.verdict == core::FoldVerdict::fold)
      ImGui::TextColored(ic, "Folds in %zu of %zu cells", c.fold_cells.size(), c.cells);
    else
      ImGui::TextColored(ic, "Undecided in %zu of %zu cells", c.undecided_cells.size(), c.cells);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "det J of the lattice as an exact Bernstein polynomial per Bezier cell, subdivided:\n"
          "green cells are certified det J > 0 (no fold), red cells fold (det J <= 0 at the red\n"
          "points), grey cells are undecided after 6 halvings. %.1f ms.",
          r.certificate_ms);
  }
  ImGui::End();
}

}  // namespace trispline::editor
