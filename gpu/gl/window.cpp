#include "gpu/gl/window.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <epoxy/gl.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace trispline::gpu {
namespace {

std::mutex g_glfw_mutex;
int g_windows = 0;         // live windows; GLFW is terminated with the last one
std::string g_last_error;  // GLFW reports errors through a callback

void on_glfw_error(int code, const char* description) {
  char code_text[32];
  std::snprintf(code_text, sizeof code_text, " (GLFW error 0x%x)", unsigned(code));
  g_last_error = std::string(description ? description : "unknown") + code_text;
}

}  // namespace

Window::Window(const std::string& title, int width, int height, const WindowOptions& options) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("Window: size must be positive");
  std::lock_guard lock(g_glfw_mutex);
  glfwSetErrorCallback(on_glfw_error);
  g_last_error.clear();
  // On a loaded machine the X server now and then refuses a connection it takes a moment later (seen under Xvfb on
  // 2 cores: 2 starts in 15 failed, each X client started beside them connected): a display that is set but refused is
  // asked again, five times in about 3 s, before the window is given up.
  if (g_windows == 0) {
    bool ready = glfwInit();
    for (int attempt = 1; !ready && attempt <= 5 && std::getenv("DISPLAY") &&
                          g_last_error.find("Failed to open display") != std::string::npos;
         ++attempt) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200 * attempt));
      g_last_error.clear();
      ready = glfwInit();
    }
    if (!ready)
      throw GlContextError("cannot open a window: glfwInit failed: " + g_last_error +
                           " (no display? use HeadlessContext, or run under xvfb-run -a)");
  }
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_SAMPLES, options.samples);
  glfwWindowHint(GLFW_DEPTH_BITS, 24);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    const std::string err = g_last_error;
    if (g_windows == 0) glfwTerminate();
    throw GlContextError("cannot open a window with an OpenGL 4.3 core context: " + err);
  }
  ++g_windows;
  glfwSetWindowUserPointer(window_, this);
  auto damage = [](GLFWwindow* w) { static_cast<Window*>(glfwGetWindowUserPointer(w))->damaged_ = true; };
  glfwSetWindowRefreshCallback(window_, damage);
  glfwSetFramebufferSizeCallback(
      window_, [](GLFWwindow* w, int, int) { static_cast<Window*>(glfwGetWindowUserPointer(w))->damaged_ = true; });
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(options.vsync ? 1 : 0);
}

Window::~Window() {
  std::lock_guard lock(g_glfw_mutex);
  if (!window_) return;
  glfwDestroyWindow(window_);
  if (--g_windows == 0) glfwTerminate();
}

void Window::make_current() { glfwMakeContextCurrent(window_); }
bool Window::should_close() const { return glfwWindowShouldClose(window_) != 0; }
void Window::set_should_close(bool close) { glfwSetWindowShouldClose(window_, close ? GLFW_TRUE : GLFW_FALSE); }
void Window::swap() { glfwSwapBuffers(window_); }
void Window::poll_events() { glfwPollEvents(); }
void Window::wait_events(double timeout_s) { glfwWaitEventsTimeout(timeout_s); }
void Window::wait_events() { glfwWaitEvents(); }
bool Window::take_damage() { return std::exchange(damaged_, false); }
void Window::set_title(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

glm::ivec2 Window::framebuffer_size() const {
  glm::ivec2 s(0);
  glfwGetFramebufferSize(window_, &s.x, &s.y);
  return s;
}

glm::ivec2 Window::window_size() const {
  glm::ivec2 s(0);
  glfwGetWindowSize(window_, &s.x, &s.y);
  return s;
}

}  // namespace trispline::gpu
