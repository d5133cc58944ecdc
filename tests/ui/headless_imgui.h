// A Dear ImGui context for tests, without a window: a built font atlas and one frame open. render() ends the frame
// and returns its draw data; next_frame() ends it and opens the next; step() sets the mouse, opens the next frame and
// draws `ui` in it (Dear ImGui reads input at NewFrame, widgets react while drawn). The destructor ends the frame.
#pragma once

#include <imgui.h>

#include <functional>

namespace trispline::test {

class HeadlessImGui {
 public:
  HeadlessImGui() {
    ctx_ = ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(1280, 720);
    io.DeltaTime = 1.0f / 60.0f;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
    ImGui::NewFrame();
  }
  ~HeadlessImGui() {
    if (frame_open_) ImGui::Render();
    ImGui::DestroyContext(ctx_);
  }
  HeadlessImGui(const HeadlessImGui&) = delete;
  HeadlessImGui& operator=(const HeadlessImGui&) = delete;

  const ImDrawData& render() {
    ImGui::Render();
    frame_open_ = false;
    return *ImGui::GetDrawData();
  }
  void next_frame() {
    if (frame_open_) ImGui::Render();
    ImGui::NewFrame();
    frame_open_ = true;
  }
  void step(ImVec2 mouse, bool down, const std::function<void()>& ui, int button = 0) {
    if (frame_open_) ImGui::Render();
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = mouse;
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = down && b == button;
    ImGui::NewFrame();
    frame_open_ = true;
    ui();
  }
  // `frames` frames (a new window is hidden in its first) of a window `name` holding `draw`, the mouse off screen.
  void show_window(const char* name, const std::function<void()>& draw, int frames = 2) {
    for (int f = 0; f < frames; ++f)
      step({-10, -10}, false, [&] {
        ImGui::Begin(name);
        draw();
        ImGui::End();
      });
  }

 private:
  ImGuiContext* ctx_;
  bool frame_open_ = true;
};

}  // namespace trispline::test
