#include "core/scene/camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

namespace trispline::core {

glm::dvec3 Camera::forward() const { return glm::normalize(target - eye); }
glm::dvec3 Camera::right() const { return glm::normalize(glm::cross(forward(), up)); }
glm::dvec3 Camera::true_up() const { return glm::cross(right(), forward()); }

glm::dmat4 Camera::view_matrix() const { return glm::lookAt(eye, target, up); }

glm::dmat4 Camera::projection_matrix() const {
  return glm::perspective(glm::radians(fov_deg), aspect(), near_plane, far_plane);
}

glm::dvec3 Camera::ray_direction(const glm::dvec2& px) const {
  const double tan_half = std::tan(glm::radians(fov_deg) * 0.5);
  const double ndc_x = 2.0 * px.x / viewport.x - 1.0;
  const double ndc_y = 1.0 - 2.0 * px.y / viewport.y;
  const glm::dvec3 d = forward() + right() * (ndc_x * tan_half * aspect()) + true_up() * (ndc_y * tan_half);
  return glm::normalize(d);
}

glm::dvec3 Camera::project(const glm::dvec3& world) const {
  const glm::dvec3 rel = world - eye;
  const double depth = glm::dot(rel, forward());
  const double tan_half = std::tan(glm::radians(fov_deg) * 0.5);
  const double ndc_x = glm::dot(rel, right()) / (depth * tan_half * aspect());
  const double ndc_y = glm::dot(rel, true_up()) / (depth * tan_half);
  return {(ndc_x + 1.0) * 0.5 * viewport.x, (1.0 - ndc_y) * 0.5 * viewport.y, depth};
}

void Camera::validate() const {
  auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(eye) || !finite(target) || !finite(up)) throw std::invalid_argument("camera: non-finite eye/target/up");
  if (glm::length(target - eye) <= 0.0) throw std::invalid_argument("camera: eye and target coincide");
  if (glm::length(glm::cross(glm::normalize(target - eye), up)) < 1e-9)
    throw std::invalid_argument("camera: up is parallel to the view direction");
  if (!(fov_deg > 0.0 && fov_deg < 180.0)) throw std::invalid_argument("camera: fov_deg must be in (0, 180)");
  if (viewport.x <= 0 || viewport.y <= 0) throw std::invalid_argument("camera: viewport must be positive");
}

}  // namespace trispline::core
