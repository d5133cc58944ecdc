// trispline::editor::GuaranteesView — the viewport's guarantees on a deformed object (seed ch. 3 and beyond):
//  * View > Error bounds: the object's triangles coloured by their certified deformation-error bound (the largest
//    distance between the true deformed surface and the drawn flat triangle, world units; core/ffd/
//    deformation_bounds.h) on a logarithmic colour ramp over three decades below the largest bound, magenta where a
//    triangle has no bound (it crosses a C⁰ knot plane or leaves the lattice's domain), with a legend in world units;
//  * View > Fold certificate: the lattice's Bézier cells drawn through F — green certified fold-free, red folding
//    (with the fold points), grey undecided (core/ffd/fold_certificate.h) — and the verdict in the legend.
// Shown for the object the Press tool is previewing during a drag (so both follow the drag live), else the selected
// deformed object (an FFD, not a DFFD rig). Computed on a worker thread only when that object's lattice, mesh or
// offset changes (the newest finished result is drawn meanwhile, so a drag never waits for it); the time it took goes
// to the timing overlay.
#pragma once

#include <future>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/ffd/fold_certificate.h"
#include "core/scene/scene.h"
#include "gpu/view/view_options.h"
#include "ui/layout.h"

namespace trispline::editor {

class GuaranteesView {
 public:
  GuaranteesView() = default;
  GuaranteesView(const GuaranteesView&) = delete;
  GuaranteesView& operator=(const GuaranteesView&) = delete;
  ~GuaranteesView();  // waits for a computation still running

  // Brings the view up to date for `object` of `scene` (empty or not deformed: nothing shown), with `lattice` in
  // place of its own when given (the Press tool's live preview): adopts a finished computation, starts the next one
  // on a worker thread when the input changed and none is running (the newest finished one is shown meanwhile).
  // Never throws: a failure is shown in the legend.
  void update(const core::Scene& scene, const std::string& object,
              const std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>& lattice, bool error_bounds,
              bool certificate);
  void decorate(gpu::ViewOptions& options) const;
  // The legend (colour ramp in world units, certificate verdict) in the viewport's bottom-right corner.
  void draw_legend(const ui::Rect& viewport) const;

  // The shown computation's cost, milliseconds (negative: none shown) and a one-line summary, for the timing overlay.
  double bounds_ms() const { return shown_ && shown_->corners ? shown_->bounds_ms : -1.0; }
  double certificate_ms() const { return shown_ && shown_->certificate ? shown_->certificate_ms : -1.0; }
  std::string summary() const;
  bool busy() const;  // a computation is running
  // For GUI tests: what is shown (object, live, updates, busy, triangles, max_bound, median_bound, unbounded,
  // certificate, cells, fold_cells, undecided_cells, cell_segments, error).
  nlohmann::json probe() const;

 private:
  // What a computation is for: everything it reads is held, so the scene may change meanwhile.
  struct Input {
    std::string object;
    std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> lattice;
    std::shared_ptr<const core::FfdBinding> binding;  // params #V × 3
    std::shared_ptr<const core::TriMesh> rest;
    glm::dvec3 offset{0.0};
    bool live = false;  // a tool's live preview (a Press drag), not the object's own lattice
    bool bounds = false, certificate = false;
    bool same(const Input& other) const;  // the same figures would come out (live aside)
  };
  struct Result {
    Input input;
    std::string error;
    // Error bounds.
    std::shared_ptr<const std::vector<glm::vec3>> corners;  // #3T world units
    std::shared_ptr<const std::vector<glm::vec4>> colors;   // #3T
    std::size_t triangles = 0, unbounded = 0;
    double max_bound = 0.0, median_bound = 0.0, bounds_ms = -1.0;
    // Certificate.
    std::optional<core::FoldCertificate> certificate;
    std::vector<glm::dvec3> cell_ends;   // #2S world units
    std::vector<glm::vec4> cell_colors;  // #S
    double certificate_ms = -1.0;
  };
  static Result compute(const Input& in);

  std::optional<Input> wanted_;  // the last update's input
  std::optional<Result> shown_;  // the newest finished computation for it (possibly of an older lattice)
  std::future<Result> job_;      // the running computation
  std::size_t updates_ = 0;      // computations adopted (a test sees the view follow a drag)
};

}  // namespace trispline::editor
