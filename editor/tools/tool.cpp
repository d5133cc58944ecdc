#include "editor/tools/tool.h"

#include "editor/session/session.h"

namespace trispline::editor {

void ToolContext::execute_deferred(std::string what, nlohmann::json line) const {
  EditorSession& s = session;  // outlives the deferred work; the context may not
  defer(std::move(what), [&s, line = std::move(line)]() { s.execute(line); });
}

void ToolContext::execute_long(nlohmann::json line, std::string what, const std::string& verb) const {
  if (background) return background(line, std::move(what), verb);
  execute_deferred(std::move(what), std::move(line));
}

}  // namespace trispline::editor
