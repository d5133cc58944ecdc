// trispline::gpu GL debug output — routes KHR_debug messages of the current context to a sink (the editor's Log
// panel). Meant for debug builds (gpu::kGlDebugBuild); contexts made with ContextOptions::debug report more.
#pragma once

#include <epoxy/gl.h>

#include <functional>
#include <memory>
#include <string>

namespace trispline::gpu {

struct GlDebugMessage {
  enum class Severity { notification, low, medium, high };
  Severity severity = Severity::notification;
  std::string source;  // "API", "shader compiler", "window system", "third party", "application", "other"
  std::string type;    // "error", "deprecated", "undefined behaviour", "portability", "performance", "other", ...
  GLuint id = 0;
  std::string text;
};

using GlDebugSink = std::function<void(const GlDebugMessage&)>;

// Installs `sink` as the current context's debug callback while alive (synchronous output, so messages arrive
// on the calling thread right after the offending call). Messages below `min_severity` are dropped.
// Must be destroyed with the same context current. If KHR_debug (GL 4.3 core) is unavailable, active() is false
// and nothing is installed.
class GlDebugOutput {
 public:
  explicit GlDebugOutput(GlDebugSink sink, GlDebugMessage::Severity min_severity = GlDebugMessage::Severity::low);
  ~GlDebugOutput();
  GlDebugOutput(const GlDebugOutput&) = delete;
  GlDebugOutput& operator=(const GlDebugOutput&) = delete;
  bool active() const { return active_; }

 private:
  struct State {
    GlDebugSink sink;
    GlDebugMessage::Severity min_severity;
  };
  std::unique_ptr<State> state_;  // stable address: the GL user parameter
  bool active_ = false;
};

// One line, e.g. "GL high error (API) #1280: GL_INVALID_ENUM in glEnable(...)".
std::string format_gl_debug_message(const GlDebugMessage& m);

}  // namespace trispline::gpu
