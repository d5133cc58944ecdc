#include "gpu/gl/gl_debug.h"

namespace trispline::gpu {
namespace {

const char* source_name(GLenum s) {
  switch (s) {
    case GL_DEBUG_SOURCE_API:
      return "API";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM:
      return "window system";
    case GL_DEBUG_SOURCE_SHADER_COMPILER:
      return "shader compiler";
    case GL_DEBUG_SOURCE_THIRD_PARTY:
      return "third party";
    case GL_DEBUG_SOURCE_APPLICATION:
      return "application";
    default:
      return "other";
  }
}

const char* type_name(GLenum t) {
  switch (t) {
    case GL_DEBUG_TYPE_ERROR:
      return "error";
    case GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR:
      return "deprecated";
    case GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR:
      return "undefined behaviour";
    case GL_DEBUG_TYPE_PORTABILITY:
      return "portability";
    case GL_DEBUG_TYPE_PERFORMANCE:
      return "performance";
    case GL_DEBUG_TYPE_MARKER:
      return "marker";
    case GL_DEBUG_TYPE_PUSH_GROUP:
      return "push group";
    case GL_DEBUG_TYPE_POP_GROUP:
      return "pop group";
    default:
      return "other";
  }
}

GlDebugMessage::Severity severity_of(GLenum s) {
  switch (s) {
    case GL_DEBUG_SEVERITY_HIGH:
      return GlDebugMessage::Severity::high;
    case GL_DEBUG_SEVERITY_MEDIUM:
      return GlDebugMessage::Severity::medium;
    case GL_DEBUG_SEVERITY_LOW:
      return GlDebugMessage::Severity::low;
    default:
      return GlDebugMessage::Severity::notification;
  }
}

}  // namespace

GlDebugOutput::GlDebugOutput(GlDebugSink sink, GlDebugMessage::Severity min_severity)
    : state_(std::make_unique<State>(State{std::move(sink), min_severity})) {
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 43 && !epoxy_has_gl_extension("GL_KHR_debug")) return;
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(
      [](GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length, const GLchar* message,
         const void* user) {
        const auto* st = static_cast<const State*>(user);
        GlDebugMessage m;
        m.severity = severity_of(severity);
        if (m.severity < st->min_severity || !st->sink) return;
        m.source = source_name(source);
        m.type = type_name(type);
        m.id = id;
        m.text = length >= 0 ? std::string(message, std::size_t(length)) : std::string(message);
        st->sink(m);
      },
      state_.get());
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  active_ = true;
}

GlDebugOutput::~GlDebugOutput() {
  if (!active_) return;
  glDebugMessageCallback(nullptr, nullptr);
  glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
}

std::string format_gl_debug_message(const GlDebugMessage& m) {
  static const char* const kSeverity[] = {"note", "low", "medium", "high"};
  return "GL " + std::string(kSeverity[int(m.severity)]) + " " + m.type + " (" + m.source + ") #" +
         std::to_string(m.id) + ": " + m.text;
}

}  // namespace trispline::gpu
