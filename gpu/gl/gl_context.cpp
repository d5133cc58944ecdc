#include "gpu/gl/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <string_view>
#include <vector>

#include "core/base/enum_names.h"
#include "core/base/text.h"

namespace trispline::gpu {
namespace {

std::string egl_error_name(EGLint e) {
  const char* name = core::code_name<EGLint>(e,
                                             {{EGL_SUCCESS, "EGL_SUCCESS"},
                                              {EGL_NOT_INITIALIZED, "EGL_NOT_INITIALIZED"},
                                              {EGL_BAD_ACCESS, "EGL_BAD_ACCESS"},
                                              {EGL_BAD_ALLOC, "EGL_BAD_ALLOC"},
                                              {EGL_BAD_ATTRIBUTE, "EGL_BAD_ATTRIBUTE"},
                                              {EGL_BAD_CONFIG, "EGL_BAD_CONFIG"},
                                              {EGL_BAD_CONTEXT, "EGL_BAD_CONTEXT"},
                                              {EGL_BAD_CURRENT_SURFACE, "EGL_BAD_CURRENT_SURFACE"},
                                              {EGL_BAD_DISPLAY, "EGL_BAD_DISPLAY"},
                                              {EGL_BAD_MATCH, "EGL_BAD_MATCH"},
                                              {EGL_BAD_NATIVE_PIXMAP, "EGL_BAD_NATIVE_PIXMAP"},
                                              {EGL_BAD_NATIVE_WINDOW, "EGL_BAD_NATIVE_WINDOW"},
                                              {EGL_BAD_PARAMETER, "EGL_BAD_PARAMETER"},
                                              {EGL_BAD_SURFACE, "EGL_BAD_SURFACE"},
                                              {EGL_CONTEXT_LOST, "EGL_CONTEXT_LOST"}},
                                             nullptr);
  if (name) return name;
  char buf[32];
  std::snprintf(buf, sizeof buf, "EGL error 0x%x", unsigned(e));
  return buf;
}

std::string last_egl_error() { return egl_error_name(eglGetError()); }

bool has_extension(const char* list, std::string_view name) {
  if (!list) return false;
  std::string_view s(list);
  std::size_t pos = 0;
  while (pos < s.size()) {
    std::size_t end = s.find(' ', pos);
    if (end == std::string_view::npos) end = s.size();
    if (s.substr(pos, end - pos) == name) return true;
    pos = end + 1;
  }
  return false;
}

// eglTerminate must not run while another HeadlessContext still uses the same display.
std::mutex g_display_mutex;
std::map<EGLDisplay, int> g_display_refs;

}  // namespace

struct HeadlessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  std::string platform;
};

HeadlessContext::HeadlessContext() : HeadlessContext(ContextOptions{}) {}

HeadlessContext::HeadlessContext(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
  std::vector<std::string> tried;  // every failed step, for the error message
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!client_ext) eglGetError();  // EGL < 1.5 without EGL_EXT_client_extensions: clear the error
  const bool platform_base = has_extension(client_ext, "EGL_EXT_platform_base");

  auto try_init = [&](EGLDisplay d, const char* platform) {
    if (d == EGL_NO_DISPLAY) {
      tried.push_back(std::string(platform) + ": no display (" + last_egl_error() + ")");
      return false;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) {
      tried.push_back(std::string(platform) + ": eglInitialize failed (" + last_egl_error() + ")");
      return false;
    }
    impl_->display = d;
    impl_->platform = platform;
    return true;
  };

  // 1. Mesa surfaceless (llvmpipe or a Mesa GPU driver, no X server needed).
  if (platform_base && has_extension(client_ext, "EGL_MESA_platform_surfaceless")) {
    try_init(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), "surfaceless");
  } else {
    tried.push_back("surfaceless: EGL_MESA_platform_surfaceless not in client extensions");
  }
  // 2. EGL devices (NVIDIA's EGL exposes GPUs this way).
  if (impl_->display == EGL_NO_DISPLAY && platform_base && has_extension(client_ext, "EGL_EXT_platform_device") &&
      has_extension(client_ext, "EGL_EXT_device_enumeration")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count)) {
      for (EGLint i = 0; i < count && impl_->display == EGL_NO_DISPLAY; ++i)
        try_init(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), "device");
      if (count == 0) tried.push_back("device: eglQueryDevicesEXT found no device");
    } else {
      tried.push_back("device: eglQueryDevicesEXT failed (" + last_egl_error() + ")");
    }
  } else if (impl_->display == EGL_NO_DISPLAY) {
    tried.push_back("device: EGL_EXT_platform_device / EGL_EXT_device_enumeration not in client extensions");
  }
  // 3. Whatever the default display is.
  if (impl_->display == EGL_NO_DISPLAY) try_init(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default");

  auto fail = [&](const std::string& why) {
    std::string msg = "cannot create a headless OpenGL context: " + why;
    for (const std::string& t : tried) msg += "\n  tried " + t;
    if (impl_->display != EGL_NO_DISPLAY) {
      std::lock_guard lock(g_display_mutex);
      if (g_display_refs.count(impl_->display) == 0) eglTerminate(impl_->display);  // not shared with a live context
    }
    throw GlContextError(msg);
  };
  if (impl_->display == EGL_NO_DISPLAY) fail("no EGL display could be initialised");

  const char* dpy_ext = eglQueryString(impl_->display, EGL_EXTENSIONS);
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed (" + last_egl_error() + ")");

  EGLConfig config = nullptr;
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                   EGL_PBUFFER_BIT,
                                   EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT,
                                   EGL_RED_SIZE,
                                   8,
                                   EGL_GREEN_SIZE,
                                   8,
                                   EGL_BLUE_SIZE,
                                   8,
                                   EGL_ALPHA_SIZE,
                                   8,
                                   EGL_NONE};
  EGLint n_configs = 0;
  if (!eglChooseConfig(impl_->display, config_attribs, &config, 1, &n_configs) || n_configs < 1) {
    if (!has_extension(dpy_ext, "EGL_KHR_no_config_context"))
      fail("no EGL config with EGL_PBUFFER_BIT|EGL_OPENGL_BIT and no EGL_KHR_no_config_context");
    config = EGL_NO_CONFIG_KHR;
  }
  if (!has_extension(dpy_ext, "EGL_KHR_surfaceless_context"))
    fail("the " + impl_->platform + " EGL display lacks EGL_KHR_surfaceless_context");

  // 4.5 core, then 4.3 core; with the debug flag first when asked for, then without.
  const int versions[][2] = {{4, 5}, {4, 3}};
  for (const auto& v : versions) {
    for (int debug = options.debug ? 1 : 0; debug >= 0 && impl_->context == EGL_NO_CONTEXT; --debug) {
      std::vector<EGLint> attribs = {EGL_CONTEXT_MAJOR_VERSION,       v[0],
                                     EGL_CONTEXT_MINOR_VERSION,       v[1],
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT};
      if (debug) attribs.insert(attribs.end(), {EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE});
      attribs.push_back(EGL_NONE);
      impl_->context = eglCreateContext(impl_->display, config, EGL_NO_CONTEXT, attribs.data());
      if (impl_->context == EGL_NO_CONTEXT)
        tried.push_back("eglCreateContext " + std::to_string(v[0]) + "." + std::to_string(v[1]) + " core" +
                        (debug ? " debug" : "") + " (" + last_egl_error() + ")");
    }
    if (impl_->context != EGL_NO_CONTEXT) break;
  }
  if (impl_->context == EGL_NO_CONTEXT)
    fail("no OpenGL 4.5 or 4.3 core context on the " + impl_->platform + " display");
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context)) {
    const std::string err = last_egl_error();
    eglDestroyContext(impl_->display, impl_->context);
    fail("eglMakeCurrent without a surface failed (" + err + ")");
  }
  std::lock_guard lock(g_display_mutex);
  ++g_display_refs[impl_->display];
}

HeadlessContext::~HeadlessContext() {
  if (!impl_ || impl_->display == EGL_NO_DISPLAY) return;
  if (eglGetCurrentContext() == impl_->context)
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(impl_->display, impl_->context);
  std::lock_guard lock(g_display_mutex);
  if (--g_display_refs[impl_->display] == 0) {
    g_display_refs.erase(impl_->display);
    eglTerminate(impl_->display);
  }
}

void HeadlessContext::make_current() {
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw GlContextError("eglMakeCurrent failed (" + last_egl_error() + ")");
}

std::string HeadlessContext::renderer() const { return current_gl_renderer(); }

std::string HeadlessContext::version() const {
  const GLubyte* s = glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "";
}

std::string HeadlessContext::platform() const { return impl_->platform; }

std::string current_gl_renderer() {
  const GLubyte* s = glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "";
}

bool is_software_renderer() {
  const std::string r = core::ascii_lower(current_gl_renderer());
  for (const char* name : {"llvmpipe", "softpipe", "swrast", "software rasterizer", "swiftshader"})
    if (r.find(name) != std::string::npos) return true;
  return false;
}

}  // namespace trispline::gpu
