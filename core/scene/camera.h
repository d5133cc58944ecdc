// trispline::core::Camera — a pinhole camera as given by the `camera.set` command.
// World is right-handed, Y up. Viewport pixels: (0,0) at the top-left corner, x right, y down, pixel centres at
// half-integers; a stroke point (px, py) maps to the ray through that image position.
#pragma once

#include <glm/glm.hpp>

namespace trispline::core {

struct Camera {
  glm::dvec3 eye{3.0, 2.0, 3.0};     // world units
  glm::dvec3 target{0.0, 0.5, 0.0};  // world units
  glm::dvec3 up{0.0, 1.0, 0.0};      // need not be orthogonal to the view direction
  double fov_deg = 45.0;             // vertical field of view, degrees
  glm::ivec2 viewport{1280, 720};    // pixels (width, height)
  double near_plane = 0.01;          // world units (rendering only)
  double far_plane = 1000.0;

  double aspect() const { return double(viewport.x) / double(viewport.y); }
  glm::dvec3 forward() const;  // unit view direction (eye → target)
  glm::dvec3 right() const;    // unit
  glm::dvec3 true_up() const;  // unit, orthogonal to forward and right
  glm::dmat4 view_matrix() const;
  glm::dmat4 projection_matrix() const;  // OpenGL clip space, depth in [-1,1]
  // World-space ray through viewport pixel `px`: origin = eye, returns unit direction.
  glm::dvec3 ray_direction(const glm::dvec2& px) const;
  // World point → viewport pixel (x, y) and view depth (distance along forward). Depth ≤ 0 means behind the eye.
  glm::dvec3 project(const glm::dvec3& world) const;
  // Throws std::invalid_argument if eye == target, up ∥ forward, fov outside (0,180), or viewport not positive.
  void validate() const;
};

// Same eye, target, up, field of view and viewport (the view a silhouette was extracted for).
inline bool same_view(const Camera& a, const Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fov_deg == b.fov_deg && a.viewport == b.viewport;
}

}  // namespace trispline::core
