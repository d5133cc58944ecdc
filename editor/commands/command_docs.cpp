#include "editor/commands/command_docs.h"

#include <algorithm>
#include <stdexcept>

namespace trispline::editor {
namespace {

constexpr const char* kBegin = "<!-- params: ";
constexpr const char* kEnd = "<!-- /params -->";

// A table cell: '|' escaped, and code-formatted when it is a value or a type.
std::string cell(const std::string& text, bool code = false) {
  if (text.empty()) return "";
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return code ? "`" + out + "`" : out;
}

}  // namespace

std::string params_table(const CommandRegistry& registry, const std::string& id) {
  std::string out = "| field | type | default | range | unit | meaning |\n|---|---|---|---|---|---|\n";
  for (const core::ParamDoc& d : registry.params(id)) {
    const bool code_default = d.default_text != "required" && d.default_text != "unset";
    out += "| " + cell(d.name, true) + " | " + cell(d.type, true) + " | " + cell(d.default_text, code_default) + " | " +
           cell(d.range) + " | " + cell(d.unit) + " | " + cell(d.help) + " |\n";
  }
  return out;
}

std::string with_generated_tables(const std::string& document, const CommandRegistry& registry) {
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t begin = document.find(kBegin, at);
    if (begin == std::string::npos) break;
    const std::size_t id_start = begin + std::string(kBegin).size();
    const std::size_t id_end = document.find(" -->", id_start);
    const std::size_t end = document.find(kEnd, id_start);
    if (id_end == std::string::npos || end == std::string::npos || id_end > end)
      throw std::runtime_error("commands docs: a '" + std::string(kBegin) + "' block has no '" + kEnd + "'");
    const std::string id = document.substr(id_start, id_end - id_start);
    const auto ids = registry.ids();
    if (std::find(ids.begin(), ids.end(), id) == ids.end())
      throw std::runtime_error("commands docs: no command '" + id + "'");
    out += document.substr(at, id_end + 4 - at) + "\n" + params_table(registry, id);
    at = end;
  }
  return out + document.substr(at);
}

}  // namespace trispline::editor
