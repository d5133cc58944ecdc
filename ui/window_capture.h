// trispline::ui window capture — reads the window's default framebuffer (3-D view + panels) for screenshots.
#pragma once

#include <vector>

namespace trispline::ui {

// RGBA8 of the back buffer of the current context's default framebuffer, #(w·h·4), top row first, alpha = 255.
// Call after drawing the frame and before swapping. width, height: framebuffer pixels.
std::vector<unsigned char> capture_back_buffer(int width, int height);

}  // namespace trispline::ui
