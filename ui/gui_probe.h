// trispline::ui::probe — where GUI tests (tests/gui) find widgets without hard-coded pixels. Panels name the items a
// test needs right after submitting them (`probe::item("timeline.frame")`); the editor writes the names with their
// screen rectangles into its probe file every frame (`trispline edit --gui-probe FILE`). Off by default: then item()
// returns at once.
#pragma once

#include <imgui.h>

#include <map>
#include <string>

namespace trispline::ui::probe {

struct ItemRect {
  ImVec2 min, max;  // screen pixels, top-left origin
};

void set_enabled(bool on);
bool enabled();
void begin_frame();                  // forgets the previous frame's items
void item(const std::string& name);  // the last submitted ImGui item's rectangle, under `name` (last one wins)
void rect(const std::string& name, ImVec2 min, ImVec2 max);    // a rectangle ImGui's last item does not give
void value(const std::string& name, const std::string& text);  // a value a test reads (a text field's content)
const std::map<std::string, ItemRect>& items();
const std::map<std::string, std::string>& values();
const std::string& active();  // the named item that is active (being typed into, dragged, held) this frame, or ""

}  // namespace trispline::ui::probe
