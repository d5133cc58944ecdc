// trispline::gpu::Window — the editor's GLFW window with an OpenGL 4.3 core context (through libepoxy).
// Needs a display (X11/Wayland; Xvfb works: `xvfb-run -a -s "-screen 0 1280x720x24" ...`). Without one the
// constructor throws GlContextError; headless code uses HeadlessContext instead.
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "gpu/gl/gl_context.h"

struct GLFWwindow;

namespace trispline::gpu {

struct WindowOptions {
  int samples = 4;             // MSAA samples of the default framebuffer (0 = none)
  bool vsync = true;           // swap interval 1
  bool visible = true;         // false: hidden window (tests)
  bool debug = kGlDebugBuild;  // debug context (see gpu/gl/gl_debug.h)
};

class Window {
 public:
  // Opens a window of `width`×`height` screen coordinates titled `title` and makes its context current.
  // Throws GlContextError with GLFW's own description (e.g. "X11: The DISPLAY environment variable is missing")
  // if GLFW cannot initialise or no 4.3 core context can be created; std::invalid_argument for a non-positive size.
  Window(const std::string& title, int width, int height, const WindowOptions& options = {});
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  void make_current();
  bool should_close() const;
  void set_should_close(bool close);
  void swap();                                // swap buffers (vsync per WindowOptions)
  static void poll_events();                  // glfwPollEvents
  static void wait_events(double timeout_s);  // glfwWaitEventsTimeout: idle without spinning
  static void wait_events();                  // glfwWaitEvents: sleeps until an event arrives
  // True once after the window's contents were lost or its framebuffer resized (GLFW's refresh and framebuffer-size
  // callbacks): an editor that draws only on change must draw again.
  bool take_damage();
  glm::ivec2 framebuffer_size() const;  // pixels (differs from window_size() on HiDPI)
  glm::ivec2 window_size() const;       // screen coordinates
  void set_title(const std::string& title);
  GLFWwindow* native() const { return window_; }  // for ImGui_ImplGlfw_InitForOpenGL

 private:
  GLFWwindow* window_ = nullptr;
  bool damaged_ = true;  // set by the callbacks (glfwSetWindowUserPointer)
};

}  // namespace trispline::gpu
