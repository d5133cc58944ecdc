#include "gpu/brush_geometry.h"

#include <cmath>
#include <glm/gtc/constants.hpp>

namespace trispline::gpu {

void append_brush_sphere(const BrushSphere& s, const glm::vec3& eye, std::vector<OverlayVertex>& out, int slices,
                         int stacks) {
  if (!(s.radius > 0.0) || slices < 3 || stacks < 2) return;
  const glm::vec3 c(s.centre);
  const float r = float(s.radius);
  // Unit normal at (slice a, stack b): b = 0 is the north pole (+y), b = stacks the south pole.
  auto normal = [&](int a, int b) {
    const float theta = glm::pi<float>() * float(b) / float(stacks);
    const float phi = glm::two_pi<float>() * float(a) / float(slices);
    return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  auto vertex = [&](const glm::vec3& n) {
    const glm::vec3 p = c + r * n;
    const glm::vec3 to_eye = glm::normalize(eye - p);
    const float facing = std::abs(glm::dot(n, to_eye));
    const float rim = 1.0f - facing;
    const glm::vec3 rgb = glm::vec3(s.color) * (0.55f + 0.45f * facing) + 0.25f * rim * glm::vec3(1.0f);
    const float alpha = glm::min(1.0f, s.color.w * (1.0f + 1.5f * rim * rim));
    return OverlayVertex{p, glm::vec4(glm::min(rgb, glm::vec3(1.0f)), alpha)};
  };
  for (int b = 0; b < stacks; ++b) {
    for (int a = 0; a < slices; ++a) {
      const glm::vec3 n00 = normal(a, b), n10 = normal(a + 1, b), n01 = normal(a, b + 1), n11 = normal(a + 1, b + 1);
      // Seen from outside, increasing phi runs clockwise around +y: (00, 10, 11) is CCW from outside.
      if (b > 0) out.insert(out.end(), {vertex(n00), vertex(n10), vertex(n11)});
      if (b < stacks - 1) out.insert(out.end(), {vertex(n00), vertex(n11), vertex(n01)});
    }
  }
}

}  // namespace trispline::gpu
