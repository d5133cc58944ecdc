#include "editor/render_scene.h"

#include <algorithm>
#include <cmath>

#include "gpu/gl_context.h"
#include "gpu/renderer.h"

namespace trispline::editor {

core::Camera framing_camera(const core::Scene& scene, int width, int height) {
  core::Camera cam;
  cam.viewport = {width > 0 ? width : 1280, height > 0 ? height : 720};
  const core::Aabb box = scene.bounds();
  if (!box.valid()) return cam;
  const glm::dvec3 c = box.center();
  const double radius = std::max(0.5 * box.diagonal(), 1e-6);
  const double dist = radius / std::sin(glm::radians(cam.fov_deg) * 0.5) * 1.05;
  cam.target = c;
  cam.eye = c + glm::normalize(glm::dvec3(0.8, 0.6, 1.0)) * dist;
  cam.near_plane = dist * 0.01;
  cam.far_plane = dist * 10.0;
  return cam;
}

RenderedImage render_scene_headless(const core::Scene& scene, int width, int height) {
  gpu::HeadlessContext context;
  core::Camera cam = scene.camera_set ? scene.camera : framing_camera(scene, width, height);
  if (width > 0 && height > 0) cam.viewport = {width, height};
  // camera.set carries no clip planes: fit them to the scene so meshes in any units are neither clipped nor
  // lose depth precision.
  const core::Aabb box = scene.bounds();
  if (box.valid()) {
    const double reach = glm::length(box.center() - cam.eye) + 0.5 * box.diagonal();
    cam.far_plane = std::max(reach * 1.5, 1e-3);
    cam.near_plane = cam.far_plane * 1e-4;
  }
  gpu::Renderer renderer;
  gpu::OffscreenTarget target(cam.viewport.x, cam.viewport.y);
  target.bind();
  gpu::ViewOptions view;
  renderer.draw(scene, cam, view);
  RenderedImage image;
  image.width = target.width();
  image.height = target.height();
  image.rgba = target.read_rgba();
  image.renderer = context.renderer();
  return image;
}

}  // namespace trispline::editor
