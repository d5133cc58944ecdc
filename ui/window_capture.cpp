#include "ui/window_capture.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstddef>

namespace trispline::ui {

std::vector<unsigned char> capture_back_buffer(int width, int height) {
  const std::size_t stride = std::size_t(width) * 4;
  std::vector<unsigned char> rows(stride * height), rgba(rows.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  for (int y = 0; y < height; ++y)  // GL rows are bottom-up
    std::copy_n(rows.data() + stride * (height - 1 - y), stride, rgba.data() + stride * y);
  for (std::size_t i = 3; i < rgba.size(); i += 4) rgba[i] = 255;  // the UI leaves blended alpha behind
  return rgba;
}

}  // namespace trispline::ui
