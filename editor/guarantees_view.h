// trispline::editor::GuaranteesView — the viewport's guarantees on a deformed object (seed ch. 3 and beyond):
//  * View > Error bounds: the object's triangles coloured by their certified deformation-error bound (the largest
//    distance between the true deformed surface and the drawn flat triangle, world units; core/ffd/
//    deformation_bounds.h) on a logarithmic colour ramp over three decades below the largest bound, magenta where a
//    triangle has no bound (it crosses a C⁰ knot plane or leaves the lattice's domain), with a legend in world units;
//  * View > Fold certificate: the lattice's Bézier cells drawn through F — green certified fold-free, red folding
//    (with the fold points), grey undecided (core/ffd/fold_certificate.h) — and the verdict in the legend.
// Shown for the object the Press tool is previewing during a drag (so both follow the drag live), else the selected
// deformed object (an FFD, not a DFFD rig). Recomputed only when that object's lattice, mesh or offset changes; the
// time it took goes to the timing overlay.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/ffd/fold_certificate.h"
#include "core/scene/scene.h"
#include "gpu/view_options.h"
#include "ui/layout.h"

namespace trispline::editor {

class GuaranteesView {
 public:
  // Brings the view up to date for `object` of `scene` (empty or not deformed: nothing shown), with `lattice` in
  // place of its own when given (the Press tool's live preview). Never throws: a failure is shown in the legend.
  void update(const core::Scene& scene, const std::string& object,
              const std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>>& lattice, bool error_bounds,
              bool certificate);
  void decorate(gpu::ViewOptions& options) const;
  // The legend (colour ramp in world units, certificate verdict) in the viewport's bottom-right corner.
  void draw_legend(const ui::Rect& viewport) const;

  // The last computation's cost, milliseconds (negative: none shown) and a one-line summary, for the timing overlay.
  double bounds_ms() const { return shown_bounds_ ? bounds_ms_ : -1.0; }
  double certificate_ms() const { return shown_certificate_ ? certificate_ms_ : -1.0; }
  std::string summary() const;
  // For GUI tests: what is shown (object, live, updates, triangles, max_bound, median_bound, unbounded, certificate,
  // cells, fold_cells, undecided_cells, cell_segments, error).
  nlohmann::json probe() const;

 private:
  std::string object_;
  std::shared_ptr<const core::TrivariateBSpline<glm::dvec3>> lattice_;  // what the figures were made for
  std::shared_ptr<const core::TriMesh> rest_;
  glm::dvec3 offset_{0.0};
  bool live_ = false;       // shown for a tool's live preview (a Press drag), not the object's own lattice
  std::size_t updates_ = 0;  // computations made (a test sees the view follow a drag)
  bool shown_bounds_ = false, shown_certificate_ = false;
  std::string error_;

  // Error bounds.
  std::shared_ptr<const std::vector<glm::vec3>> corners_;  // #3T world units
  std::shared_ptr<const std::vector<glm::vec4>> colors_;   // #3T
  std::size_t triangles_ = 0, unbounded_ = 0;
  double max_bound_ = 0.0, median_bound_ = 0.0;
  double bounds_ms_ = -1.0;

  // Certificate.
  std::optional<core::FoldCertificate> certificate_;
  std::vector<glm::dvec3> cell_ends_;  // #2S
  std::vector<glm::vec4> cell_colors_;  // #S
  double certificate_ms_ = -1.0;
};

}  // namespace trispline::editor
