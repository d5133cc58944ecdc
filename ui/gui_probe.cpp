#include "ui/gui_probe.h"

namespace trispline::ui::probe {

namespace {
bool g_enabled = false;
std::map<std::string, ItemRect> g_items;
std::map<std::string, std::string> g_values;
std::string g_active;
}  // namespace

void set_enabled(bool on) { g_enabled = on; }
bool enabled() { return g_enabled; }

void begin_frame() {
  g_items.clear();
  g_values.clear();
  g_active.clear();
}

void item(const std::string& name) {
  if (!g_enabled) return;
  g_items[name] = {ImGui::GetItemRectMin(), ImGui::GetItemRectMax()};
  if (ImGui::IsItemActive()) g_active = name;
}

void rect(const std::string& name, ImVec2 min, ImVec2 max) {
  if (g_enabled) g_items[name] = {min, max};
}

void value(const std::string& name, const std::string& text) {
  if (g_enabled) g_values[name] = text;
}

const std::map<std::string, ItemRect>& items() { return g_items; }
const std::map<std::string, std::string>& values() { return g_values; }
const std::string& active() { return g_active; }

}  // namespace trispline::ui::probe
