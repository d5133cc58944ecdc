// trispline::ui keyboard shortcuts — maps the key presses since the last frame (ImGuiHost::key_presses) (Blender-like
// bindings, see the Keys window) to the same actions as the main menu. Nothing fires while ImGui wants the keyboard
// (typing in a field).
#pragma once

#include <string>

#include "ui/imgui_host.h"
#include "ui/main_menu.h"

namespace trispline::ui {

// The action whose shortcut was pressed this frame, or MenuAction::None.
MenuAction poll_shortcuts();
// True for a press that acts on its own (a shortcut, F12, a tool letter): ImGuiHost::set_batch_end hands out one of
// them per frame, so presses queued during a slow frame run in order.
bool ends_key_batch(const KeyPress& k);

// A letter key ("K") pressed this frame without modifiers that no MenuAction is bound to, for tools that declare
// it as their shortcut (ToolEntry::shortcut, e.g. the Incision tool's K, Blender's Knife); "" if none or typing.
std::string poll_tool_key();
// The letter of one such key press ("" if it has modifiers, is bound to a MenuAction or is not a letter).
std::string tool_key(const KeyPress& press);

// The action bound to one key press (GLFW key code and GLFW_MOD_* bits), ignoring whether ImGui wants the
// keyboard; MenuAction::None if unbound.
MenuAction shortcut_action(const KeyPress& press);

}  // namespace trispline::ui
