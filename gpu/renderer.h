// trispline::gpu::Renderer — draws a core::Scene with OpenGL 4.3 core into the currently bound framebuffer.
// GPU buffers are cached per object and re-uploaded only when the object's world_mesh pointer changes.
// Shaders are .glsl files under gpu/shaders/, embedded at build time.
#pragma once

#include "core/scene/scene.h"

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace trispline::gpu {

struct ViewOptions {
  bool show_lattice = false;          // control lattice of deformed objects (points + polylines)
  bool show_contact_surface = false;  // contact samples / F(u,v,0) of placed objects
  bool show_grid = true;              // ground grid on y = 0
  bool wireframe = false;
  std::string selected;               // highlighted object name (outline colour)
  std::vector<glm::dvec2> stroke_px;  // stroke being sketched, viewport pixels (top-left origin)
  glm::vec3 background_top{0.23f, 0.23f, 0.25f};
  glm::vec3 background_bottom{0.13f, 0.13f, 0.14f};
};

class Renderer {
 public:
  Renderer();  // needs a current GL context; compiles shaders (throws std::runtime_error with the GLSL log)
  ~Renderer();
  // Draws into the bound framebuffer with viewport (0,0,camera.viewport). Clears colour and depth.
  void draw(const core::Scene& scene, const core::Camera& camera, const ViewOptions& options);
  // Forget cached buffers of objects no longer in the scene (called by draw automatically).
  void release_unused(const core::Scene& scene);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// An FBO with colour (RGBA8) and depth attachments, for headless rendering and screenshots.
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height, int samples = 4);  // samples > 1: multisampled, resolved on read
  ~OffscreenTarget();
  void bind();  // binds as GL_FRAMEBUFFER and sets the viewport
  int width() const;
  int height() const;
  // RGBA8, #(w·h·4), top row first (ready to write as PNG).
  std::vector<unsigned char> read_rgba();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace trispline::gpu
