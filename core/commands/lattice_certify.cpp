#include "core/commands/lattice_certify.h"

#include <algorithm>
#include <chrono>

namespace trispline::core {

auto LatticeCertifyCommand::declare() -> Schema {
  return Schema("lattice.certify", "Certify that a deformed object's lattice does not fold (det J > 0 everywhere)")
      .field("object", &P::object, {.required = true, .help = "A deformed object (with an FFD)"})
      .field("max_depth", &P::max_depth,
             {.range = ParamRange{0, 12},
              .help = "Halvings of a Bézier cell before a box that is neither certified nor folded is called "
                      "undecided; the work is also bounded by 512 K Bernstein boxes, what is left after every "
                      "cell's first box shared out over the cells still mixed (a cell that spends its share is "
                      "undecided, counted in budget_cells)"})
      .label([](const P& p) { return "Certify lattice of '" + p.object + "'"; });
}

void LatticeCertifyCommand::redo(Scene& scene) {
  const SceneObject& object = require_deformed_object(scene, p_.object);
  // Budget: a tri-cubic cell costs ~50 µs (two cores), so 64³ cells is about ten seconds; a larger lattice is refused
  // before any work (a replay must not hang on a hostile line).
  std::size_t cell_count = 1;
  for (int a = 0; a < 3; ++a) {
    const KnotVector& k = object.ffd->lattice.knots(a);
    std::size_t spans = 0;
    for (int i = k.order() - 1; i < k.control_count(); ++i) spans += k[i + 1] > k[i] ? 1 : 0;
    cell_count *= std::max<std::size_t>(spans, 1);
  }
  constexpr std::size_t kMaxCells = std::size_t(64) * 64 * 64;
  if (cell_count > kMaxCells)
    throw CommandError("field 'object': the lattice of '" + p_.object + "' has " + std::to_string(cell_count) +
                           " Bézier cells, over the certificate's budget of " + std::to_string(kMaxCells),
                       "object");
  FoldCertificateOptions options;
  options.max_depth = p_.max_depth;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    certificate_ = certify_fold_free(object.ffd->lattice, options);
  } catch (const std::invalid_argument& e) {
    throw CommandError(std::string("field 'object': ") + e.what(), "object");
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json cells = nlohmann::json::array(), points = nlohmann::json::array(), params = nlohmann::json::array(),
                 undecided = nlohmann::json::array();
  for (std::size_t i = 0; i < certificate_.fold_cells.size(); ++i) {
    const glm::ivec3& c = certificate_.fold_cells[i];
    const glm::dvec3 &x = certificate_.fold_points[i], &t = certificate_.fold_params[i];
    cells.push_back({c.x, c.y, c.z});
    points.push_back({x.x, x.y, x.z});
    params.push_back({t.x, t.y, t.z});
  }
  for (const glm::ivec3& c : certificate_.undecided_cells) undecided.push_back({c.x, c.y, c.z});
  stats_ = {{"certificate", fold_verdict_name(certificate_.verdict)},
            {"fold_cells", cells},
            {"fold_points", points},
            {"fold_params", params},
            {"undecided_cells", undecided},
            {"cells", certificate_.cells},
            {"boxes", certificate_.boxes},
            {"budget_cells", certificate_.budget_cells},
            {"min_det_coefficient", certificate_.min_det_coefficient},
            {"ms", ms}};
}

}  // namespace trispline::core
