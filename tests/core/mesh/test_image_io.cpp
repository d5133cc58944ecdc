// PNG and EXR through OpenImageIO: exact round trip for PNG, 8-bit-exact after half-float EXR.
#include "core/image/image_io.h"
#include "mesh_test_util.h"

namespace trispline::core {
namespace {

using test::TempDir;

std::vector<unsigned char> gradient(int w, int h) {
  std::vector<unsigned char> px(static_cast<std::size_t>(w) * h * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      unsigned char* p = &px[(static_cast<std::size_t>(y) * w + x) * 4];
      p[0] = static_cast<unsigned char>(x * 255 / (w - 1));
      p[1] = static_cast<unsigned char>(y * 255 / (h - 1));
      p[2] = static_cast<unsigned char>((x + y) % 256);
      p[3] = y == 0 ? 255 : 128;  // top row opaque: checks row order
    }
  return px;
}

TEST(ImageIo, PngRoundTripIsExactTopRowFirst) {
  TempDir dir;
  const auto px = gradient(17, 9);
  write_image_rgba8(dir / "a.png", 17, 9, px);
  const ImageRgba8 img = read_image_rgba8(dir / "a.png");
  EXPECT_EQ(img.width, 17);
  EXPECT_EQ(img.height, 9);
  EXPECT_EQ(img.rgba, px);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.tmp.png"));
}

TEST(ImageIo, ExrRoundTrip) {
  TempDir dir;
  const auto px = gradient(8, 4);
  write_image_rgba8(dir / "a.exr", 8, 4, px);
  const ImageRgba8 img = read_image_rgba8(dir / "a.exr");
  ASSERT_EQ(img.rgba.size(), px.size());
  for (std::size_t i = 0; i < px.size(); ++i) EXPECT_NEAR(int(img.rgba[i]), int(px[i]), 1) << i;
}

TEST(ImageIo, Errors) {
  TempDir dir;
  const auto px = gradient(4, 4);
  EXPECT_THROW(write_image_rgba8(dir / "a.bmpx", 4, 4, px), ImageIoError);
  EXPECT_THROW(write_image_rgba8(dir / "a.png", 5, 4, px), ImageIoError);
  EXPECT_THROW(write_image_rgba8(dir / "a.png", 0, 0, {}), ImageIoError);
  EXPECT_THROW(write_image_rgba8(dir / "missing/dir/a.png", 4, 4, px), ImageIoError);
  EXPECT_THROW(read_image_rgba8(dir / "none.png"), ImageIoError);
  test::write_text(dir / "bad.png", "this is not a png");
  EXPECT_THROW(read_image_rgba8(dir / "bad.png"), ImageIoError);
}

}  // namespace
}  // namespace trispline::core
