// `place.sketch` — places an object along a stroke sketched over the scene (seed §2.3.1, Eq. 2.1–2.5). Fields:
// declared in place_sketch.cpp (ParamSchema), listed in docs/commands.md. What the declaration cannot say:
// the stroke is in viewport pixels (top-left origin) of the line's "camera", else of the last camera.set; the
// profiles scale the half-width and height piecewise linearly along u (or over (u, v)) (seed §2.4.1, Eq. 2.5);
// "springs" relaxes the contact surface as a mass-spring net before the volume is built. fit stretch: the object covers
// u ∈ [0, extent] of the path (extent 1: the whole stroke, however long). fit keep: it keeps its proportions — its
// length is scaled by the factor its height is (h ÷ the object's height along up_axis), so it covers
// u ∈ [0, min(extent, u_L)] with u_L where the contact curve F(u, ½, 0) has run that length (by arc length: the
// lattice's speed along u is not uniform near its ends). Below the whole path an offset along u (anim.keyframe)
// walks the object along the stroke (seed §2.4.3). The report gives the extent used ("extent") and the fit. An
// object with a glTF clip (anim.clip) is embedded by the bounding box of its poses over the clip (64 samples), so no
// pose leaves the lattice. The rays see every visible object except the one being placed and those listed in
// "ignore" (the editor lists the objects hidden in its viewport). Re-placing an already placed object starts again
// from its undeformed (transformed) rest mesh. Undo restores the object as it was.
#pragma once

#include <cstdint>
#include <optional>

#include "core/commands/declared_command.h"
#include "core/commands/snapshot_command.h"
#include "core/placement/contact_springs.h"

namespace trispline::core {

// Contact samples (rays) a placement may ask for, samples[0] × samples[1]: refused above, naming `samples`.
inline constexpr std::int64_t kMaxContactSamples = std::int64_t(1) << 20;

struct PlaceSketchParams {
  std::string object;
  std::vector<glm::dvec2> stroke;     // #S × 2 pixels
  double width = 0.15;                // half-width d, world units
  double height = 0.2;                // h, world units
  std::string fit = "keep";           // keep (the object's proportions) | stretch (the extent as given)
  double extent = 1.0;                // stretch: fraction of the path (u) the object covers, (0, 1]; keep: at most
  std::vector<double> width_profile;  // d(u) factors over u (seed Eq. 2.5); empty = constant
  std::vector<std::vector<double>> height_profile;  // h(u) or h(u,v) factors: rows over v; empty = constant
  std::optional<SpringParams> springs;              // mass-spring contact surface (seed §2.3.2); unset = off
  glm::ivec2 samples{32, 8};                        // contact sampling nu × nv rays
  std::string volume = "extrude";                   // extrude (F1, Eq. 2.3) | offset (F2, Eq. 2.4)
  glm::ivec3 order{4, 4, 3};                        // per axis, degree + 1
  glm::ivec3 controls{10, 4, 3};                    // control points per axis
  std::string length_axis = "x";
  std::string up_axis = "y";
  std::optional<Camera> camera;     // view the stroke was drawn in (else the scene camera)
  std::vector<std::string> ignore;  // objects the rays pass through (hidden in the editor's view)
};

// The "springs" object of place.sketch: the mass-spring contact surface (seed §2.3.2).
const ParamSchema<SpringParams>& spring_schema();

class PlaceSketchCommand : public ObjectSnapshotCommand<PlaceSketchCommand, PlaceSketchParams> {
 public:
  static Schema declare();

 protected:
  std::optional<SceneObject> build(const Scene& scene) override;

 private:
  double applied_extent_ = 1.0;   // the extent used (report.json "extent")
  double fit_path_length_ = 0.0;  // keep: the contact curve's length, world units
};

}  // namespace trispline::core
