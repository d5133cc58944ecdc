#include "gl_test.h"

#include <cmath>
#include <cstdio>

#include "tests/test_shapes.h"

namespace trispline::gpu::test {

HeadlessContext& GlTest::context() {
  static HeadlessContext ctx;  // throws GlContextError (with the reason) if none can be made; retried next time
  return ctx;
}

void GlTest::SetUp() {
  try {
    context().make_current();
  } catch (const std::exception& e) {
    FAIL() << "no headless OpenGL context (GL tests must not skip): " << e.what();
  }
}

core::TriMesh uv_sphere(const glm::dvec3& center, double radius, int slices, int stacks) {
  core::TriMesh m;
  for (int j = 0; j <= stacks; ++j) {
    const double theta = M_PI * double(j) / stacks;  // from +y down
    for (int i = 0; i <= slices; ++i) {
      const double phi = 2.0 * M_PI * double(i) / slices;
      const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
    }
  }
  const unsigned row = unsigned(slices + 1);
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const unsigned a = unsigned(j) * row + unsigned(i), b = a + row;
      m.triangles.push_back({a, b, a + 1});
      m.triangles.push_back({a + 1, b, b + 1});
    }
  return m;
}

core::SceneObject make_object(const std::string& name, core::TriMesh mesh, const glm::vec3& color) {
  core::SceneObject o;
  o.name = name;
  o.source = "test";
  o.color = color;
  o.rest_mesh = std::make_shared<const core::TriMesh>(mesh);
  o.world_mesh = std::make_shared<const core::TriMesh>(std::move(mesh));
  return o;
}

core::Camera front_camera(int width, int height) { return trispline::test::front_camera(4.0, 45.0, {width, height}); }

Rgba pixel(const std::vector<unsigned char>& img, int width, int x, int y) {
  const std::size_t i = (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
  return {img[i], img[i + 1], img[i + 2], img[i + 3]};
}

bool reddish(const Rgba& p) { return p.r > 90 && p.r > 2 * p.g && p.r > 2 * p.b; }

std::vector<unsigned char> render(Renderer& renderer, const core::Scene& scene, const core::Camera& camera,
                                  const ViewOptions& options) {
  OffscreenTarget target(camera.viewport.x, camera.viewport.y, 4);
  target.bind();
  renderer.draw(scene, camera, options);
  return target.read_rgba();
}

}  // namespace trispline::gpu::test
