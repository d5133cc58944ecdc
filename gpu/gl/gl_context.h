// trispline::gpu GL contexts: a headless EGL surfaceless context (Mesa llvmpipe without a GPU, or NVIDIA's EGL
// device platform) for replay/tests, and the GLFW window the editor uses. Both give OpenGL ≥ 4.3 core through
// libepoxy. Headless contexts have no default framebuffer: render into an OffscreenTarget.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

struct GLFWwindow;

namespace trispline::gpu {

// Thrown when no context can be made (message says which EGL/GLFW call failed and why).
class GlContextError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// True in builds without NDEBUG: contexts are created with the debug flag and KHR_debug messages are routed.
#ifdef NDEBUG
inline constexpr bool kGlDebugBuild = false;
#else
inline constexpr bool kGlDebugBuild = true;
#endif

struct ContextOptions {
  bool debug = kGlDebugBuild;  // request a debug context (KHR_debug output, see gpu/gl/gl_debug.h)
};

class HeadlessContext {
 public:
  // Creates and makes current a 4.5 (falling back to 4.3) core context. Throws GlContextError.
  HeadlessContext();
  explicit HeadlessContext(const ContextOptions& options);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;
  void make_current();
  std::string renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version() const;   // GL_VERSION
  // EGL platform that gave the display: "surfaceless" (Mesa), "device" (EGL_EXT_platform_device, NVIDIA) or
  // "default" (eglGetDisplay(EGL_DEFAULT_DISPLAY)).
  std::string platform() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Renderer string helpers for the current context.
std::string current_gl_renderer();
bool is_software_renderer();  // llvmpipe / softpipe / swrast: timer queries are unreliable there

}  // namespace trispline::gpu
