// Shared fixture and scenes of the gpu tests. GlTest makes (once per process) a headless EGL context; a test whose
// context cannot be made fails with the reason — GL tests never skip.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "gpu/gl/gl_context.h"
#include "gpu/render/renderer.h"

namespace trispline::gpu::test {

class GlTest : public ::testing::Test {
 protected:
  void SetUp() override;
  static HeadlessContext& context();
};

// UV sphere, world units, with unit normals; CCW seen from outside.
core::TriMesh uv_sphere(const glm::dvec3& center, double radius, int slices = 48, int stacks = 24);
// Object with `mesh` as its world mesh (no transform, no FFD).
core::SceneObject make_object(const std::string& name, core::TriMesh mesh, const glm::vec3& color);
// Camera at (0,0,4) looking at the origin, 160×120 pixels, 45° vertical field of view.
core::Camera front_camera(int width = 160, int height = 120);

struct Rgba {
  int r, g, b, a;
};
Rgba pixel(const std::vector<unsigned char>& img, int width, int x, int y);  // (x, y) top-left origin
bool reddish(const Rgba& p);  // clearly red: r > 90 and r > 2·g and r > 2·b

// Renders `scene` from `camera` into a fresh w×h (camera.viewport) 4× MSAA target, returns RGBA top row first.
std::vector<unsigned char> render(Renderer& renderer, const core::Scene& scene, const core::Camera& camera,
                                  const ViewOptions& options = {});

}  // namespace trispline::gpu::test
