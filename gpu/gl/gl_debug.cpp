#include "gpu/gl/gl_debug.h"

#include "core/base/enum_names.h"

namespace trispline::gpu {
namespace {

const char* source_name(GLenum s) {
  return core::code_name<GLenum>(s,
                                 {{GL_DEBUG_SOURCE_API, "API"},
                                  {GL_DEBUG_SOURCE_WINDOW_SYSTEM, "window system"},
                                  {GL_DEBUG_SOURCE_SHADER_COMPILER, "shader compiler"},
                                  {GL_DEBUG_SOURCE_THIRD_PARTY, "third party"},
                                  {GL_DEBUG_SOURCE_APPLICATION, "application"}},
                                 "other");
}

const char* type_name(GLenum t) {
  return core::code_name<GLenum>(t,
                                 {{GL_DEBUG_TYPE_ERROR, "error"},
                                  {GL_DEBUG_TYPE_DEPRECATED_BEHAVIOR, "deprecated"},
                                  {GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR, "undefined behaviour"},
                                  {GL_DEBUG_TYPE_PORTABILITY, "portability"},
                                  {GL_DEBUG_TYPE_PERFORMANCE, "performance"},
                                  {GL_DEBUG_TYPE_MARKER, "marker"},
                                  {GL_DEBUG_TYPE_PUSH_GROUP, "push group"},
                                  {GL_DEBUG_TYPE_POP_GROUP, "pop group"}},
                                 "other");
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
