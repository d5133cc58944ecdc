// trispline::ui status bar — one line at the bottom of the window: document, objects, vertices, last command.
#pragma once

#include <cstddef>
#include <string>

namespace trispline::ui {

struct StatusInfo {
  std::string document;   // file name of the document, or "untitled"
  bool modified = false;  // unsaved changes
  std::size_t objects = 0;
  std::size_t vertices = 0;  // world-mesh vertices of all objects
  std::size_t triangles = 0;
  std::string last_command;     // label of the last executed command
  double last_command_ms = -1;  // < 0: none yet
  std::string hint;             // tool hint, e.g. "Drag to sketch a stroke"
};

float status_bar_height();                  // pixels
void draw_status_bar(const StatusInfo& s);  // a borderless window docked to the bottom edge

}  // namespace trispline::ui
