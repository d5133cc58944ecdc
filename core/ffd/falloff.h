// trispline::core falloff profiles of the spherical pressing tools (seed §2.4.1, Fig. 2.7) and the ones Blender
// users know from proportional editing / sculpt brushes. A profile maps the normalised distance t = d / radius
// (d world units from the tool's centre) to a weight in [0,1]; every profile is 0 for t ≥ 1 (outside the sphere).
//   gaussian  exp(−t² / (2σ²)), σ = 1/3 (seed's Gaussian; ≈ 0.011 at the rim, truncated there)
//   hat       1 − t                      (seed's hat = Blender "Linear")
//   box       1                          (seed's box = Blender "Constant"; both names accepted)
//   smooth    3s² − 2s³, s = 1 − t       (Blender "Smooth")
//   sphere    √(1 − t²)                  (Blender "Sphere")
//   root      √(1 − t)                   (Blender "Root")
//   sharp     (1 − t)²                   (Blender "Sharp")
//   constant  1                          (Blender "Constant")
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

namespace trispline::core {

enum class Falloff { gaussian, hat, box, smooth, sphere, root, sharp, constant };

inline constexpr std::array<std::string_view, 8> kFalloffNames{"gaussian", "hat",  "box",   "smooth",
                                                               "sphere",   "root", "sharp", "constant"};

inline std::string_view to_string(Falloff f) { return kFalloffNames[static_cast<std::size_t>(f)]; }

inline std::optional<Falloff> parse_falloff(std::string_view name) {
  for (std::size_t i = 0; i < kFalloffNames.size(); ++i)
    if (kFalloffNames[i] == name) return static_cast<Falloff>(i);
  return std::nullopt;
}

// Weight of `f` at normalised distance t ≥ 0 (t = d / radius); 0 for t ≥ 1 and for NaN.
inline double falloff_weight(Falloff f, double t) {
  if (!(t >= 0.0) || t >= 1.0) return 0.0;
  const double s = 1.0 - t;
  switch (f) {
    case Falloff::gaussian:
      return std::exp(-t * t * 4.5);  // σ = 1/3: 1/(2σ²) = 4.5
    case Falloff::hat:
      return s;
    case Falloff::smooth:
      return s * s * (3.0 - 2.0 * s);
    case Falloff::sphere:
      return std::sqrt(1.0 - t * t);
    case Falloff::root:
      return std::sqrt(s);
    case Falloff::sharp:
      return s * s;
    case Falloff::box:
    case Falloff::constant:
    default:
      return 1.0;
  }
}

}  // namespace trispline::core
