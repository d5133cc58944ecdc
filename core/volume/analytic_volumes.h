// trispline::core analytic volumes: sampled fields whose iso-surfaces and silhouettes are known in closed form, for
// tests and the silhouette bench (sphere and torus distance fields, a product of sines).
#pragma once

#include <string>

#include "core/volume/scalar_volume.h"

namespace trispline::core {

enum class AnalyticVolume { sphere, torus, sines };

// Geometry of the analytic volumes in world millimetres. The grid spans the box [−extent, extent]³ with n, n + n/4 and
// n − n/5 samples along x, y, z (anisotropic spacing on purpose), voxel (0,0,0) at the box's low corner.
struct AnalyticShape {
  double extent = 50.0;         // half-size of the sampled box, mm
  double sphere_radius = 30.0;  // sphere: D = radius − |p|, iso 0 is the sphere
  double torus_major = 28.0;    // torus about z: D = minor − dist(p, circle of `major` in z = 0)
  double torus_minor = 12.0;
  double sines_period = 40.0;  // sines: D = sin(2πx/P)·sin(2πy/P)·sin(2πz/P)
};

// Samples the field on the grid (x fastest). Units "" (the values are mm for the distance fields). Throws
// std::invalid_argument when n < 4 or n > 1024.
ScalarVolume make_analytic_volume(AnalyticVolume kind, int n, const AnalyticShape& shape = {});

// The field at a world point (what the samples are taken from).
double analytic_field(AnalyticVolume kind, const glm::dvec3& world, const AnalyticShape& shape = {});

// "sphere", "torus", "sines"; parse returns false on another name.
const char* analytic_volume_name(AnalyticVolume kind);
bool parse_analytic_volume(const std::string& name, AnalyticVolume& kind);

}  // namespace trispline::core
