// Headless rendering of a scene (replay's final.png, README screenshots) through an EGL surfaceless context.
#pragma once

#include "core/scene/scene.h"

#include <string>
#include <vector>

namespace trispline::editor {

struct RenderedImage {
  int width = 0, height = 0;        // pixels
  std::vector<unsigned char> rgba;  // #(w·h·4), top row first
  std::string renderer;             // GL_RENDERER of the context used
};

// A camera that frames the visible objects from the front-right-above, for scenes without camera.set.
core::Camera framing_camera(const core::Scene& scene, int width, int height);

// Renders with the scene's camera (or framing_camera when none was set). width/height 0 = the camera's viewport;
// otherwise the camera's viewport is replaced (aspect follows). Throws gpu::GlContextError / std::runtime_error.
RenderedImage render_scene_headless(const core::Scene& scene, int width = 0, int height = 0);

}  // namespace trispline::editor
