// `lattice.certify` — whether a deformed object's FFD lattice is fold-free (det J > 0 on its whole domain), with a
// guarantee rather than samples (core/ffd/fold_certificate.h: Bernstein expansion of det J per Bézier cell,
// subdivided where undecided). Fields: declared in lattice_certify.cpp (ParamSchema), listed in docs/commands.md.
// A query: the scene is not modified and the line is never an undo step (it is logged so a replay reports it again).
// Errors beyond the declared ranges (CommandError, field named): unknown object / no lattice / more than 64³ Bézier
// cells (`object`).
// stats(): certificate ("fold_free" | "fold" | "undecided"), fold_cells ([[i,j,k],…]: knot spans), fold_points
// ([[x,y,z],…], world units: F at a parameter point of each folding cell where det J ≤ 0), fold_params (the
// parameter points, [0,1]³), undecided_cells, cells, boxes, min_det_coefficient, ms.
#pragma once

#include "core/commands/declared_command.h"
#include "core/ffd/fold_certificate.h"

namespace trispline::core {

struct LatticeCertifyParams {
  std::string object;
  int max_depth = 6;  // halvings of a cell before a mixed box is undecided
};

class LatticeCertifyCommand : public DeclaredCommand<LatticeCertifyCommand, LatticeCertifyParams> {
 public:
  static Schema declare();

  void redo(Scene& scene) override;  // computes the certificate; the scene is not modified
  void undo(Scene&) override {}
  bool undoable() const override { return false; }
  nlohmann::json stats() const override { return stats_; }

  const FoldCertificate& certificate() const { return certificate_; }

 private:
  FoldCertificate certificate_;
  nlohmann::json stats_ = nlohmann::json::object();
};

}  // namespace trispline::core
