// bench_shading — frame time of the renderer with Material against Solid shading (ViewOptions::shading,
// docs/performance.md "Viewport shading") on a textured scene, offscreen through EGL:
//   five UV spheres of 256 × 128 quads (≈ 65 k triangles each, 0.33 M in all) side by side, each with a glTF
//   material whose base colour texture is a generated 2048² RGBA image (mipmapped, sRGB) and, on two of them, a
//   2048² normal map; one of them alpha MASK. Camera framing all five, the ground grid on.
// Per shading: 3 warm-up frames, then --frames frames each timed as draw + glFinish (wall clock), median and mean ms.
// First, the load of one 4096² texture (a photo-like generated image, as PNG and as JPEG q90): the OpenImageIO decode
// of the encoded bytes (core::decode_material_image, what scene.load does per image) and the GL upload with mipmaps
// (the first Material frame's MaterialTextures::texture), each the median of 5.
// Prints figures; never asserts timings.
//   build/bench/bench_shading [--frames N] [--width W] [--height H] [--samples S]
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "core/mesh/material_image.h"
#include "core/scene/camera.h"
#include "core/scene/scene.h"
#include "gpu/gl/gl_context.h"
#include "gpu/render/material_textures.h"
#include "gpu/render/renderer.h"

using namespace trispline;

namespace {

core::TriMesh sphere(const glm::dvec3& c, double r, int slices, int stacks) {
  core::TriMesh m;
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i <= slices; ++i) {
      const double u = double(i) / slices, v = double(j) / stacks;
      const double th = 2.0 * M_PI * u, ph = M_PI * v;
      const glm::dvec3 n(std::sin(ph) * std::cos(th), std::cos(ph), std::sin(ph) * std::sin(th));
      m.positions.push_back(c + r * n);
      m.normals.push_back(n);
      m.uvs.push_back({u * 4.0, v * 2.0});
    }
  const unsigned row = unsigned(slices + 1);
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      const unsigned a = unsigned(j) * row + unsigned(i), b = a + row;
      m.triangles.push_back({a, a + 1, b});
      m.triangles.push_back({a + 1, b + 1, b});
    }
  return m;
}

std::shared_ptr<const core::MaterialImage> checker(int n, bool normal_map) {
  auto im = std::make_shared<core::MaterialImage>();
  im->width = im->height = n;
  im->rgba8.resize(std::size_t(n) * std::size_t(n) * 4);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      std::uint8_t* p = &im->rgba8[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4];
      const bool odd = ((x >> 6) ^ (y >> 6)) & 1;
      if (normal_map) {
        const double s = std::sin(x * 0.05), t = std::cos(y * 0.05);
        p[0] = std::uint8_t(128 + 60 * s), p[1] = std::uint8_t(128 + 60 * t), p[2] = 230, p[3] = 255;
      } else {
        p[0] = odd ? 220 : 40, p[1] = std::uint8_t(x * 255 / n), p[2] = std::uint8_t(y * 255 / n);
        p[3] = ((x >> 5) & 3) == 0 ? 0 : 255;  // cut-out stripes for the MASK material
      }
    }
  return im;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A photo-like n² RGB image: smooth gradients with high-frequency texture (neither compresses to nothing).
std::vector<std::uint8_t> photo_like(int n) {
  std::vector<std::uint8_t> rgba(std::size_t(n) * std::size_t(n) * 4);
  std::uint32_t noise = 12345;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      noise = noise * 1664525u + 1013904223u;
      std::uint8_t* p = &rgba[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 4];
      const int grain = int(noise >> 28);
      p[0] = std::uint8_t(std::clamp(int(128 + 100 * std::sin(x * 0.003) * std::cos(y * 0.002)) + grain, 0, 255));
      p[1] = std::uint8_t(std::clamp(int(x * 200 / n) + grain, 0, 255));
      p[2] = std::uint8_t(std::clamp(int(y * 180 / n + 30 * std::sin(x * 0.05)) + grain, 0, 255));
      p[3] = 255;
    }
  return rgba;
}

std::vector<std::uint8_t> encode_jpeg(int n, const std::vector<std::uint8_t>& rgba) {
  std::vector<std::uint8_t> out;
  OIIO::Filesystem::IOVecOutput proxy(out);
  auto jpg = OIIO::ImageOutput::create("image.jpg");
  if (!jpg) throw std::runtime_error("no JPEG writer");
  jpg->set_ioproxy(&proxy);
  OIIO::ImageSpec spec(n, n, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("CompressionQuality", 90);
  std::vector<std::uint8_t> rgb(std::size_t(n) * std::size_t(n) * 3);
  for (std::size_t i = 0; i < rgb.size() / 3; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + std::size_t(c)] = rgba[4 * i + std::size_t(c)];
  if (!jpg->open("image.jpg", spec) || !jpg->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !jpg->close())
    throw std::runtime_error("cannot encode JPEG");
  return out;
}

// Decode and upload of one n² texture, PNG and JPEG: median ms of `runs` each.
void texture_load(int n, int runs) {
  const std::vector<std::uint8_t> rgba = photo_like(n);
  const std::pair<const char*, std::vector<std::uint8_t>> files[] = {{"PNG", core::encode_png_rgba8(n, n, rgba)},
                                                                     {"JPEG", encode_jpeg(n, rgba)}};
  for (const auto& [kind, bytes] : files) {
    std::vector<double> decode, upload;
    for (int r = 0; r < runs; ++r) {
      auto t0 = std::chrono::steady_clock::now();
      auto image = std::make_shared<const core::MaterialImage>(core::decode_material_image(bytes, "", "bench", ""));
      decode.push_back(ms_since(t0));
      if (!image->readable()) throw std::runtime_error(std::string(kind) + ": " + image->error);
      gpu::MaterialTextures textures;
      t0 = std::chrono::steady_clock::now();
      textures.texture(image, gpu::TextureColorSpace::srgb);
      glFinish();
      upload.push_back(ms_since(t0));
    }
    std::printf("texture %d² %-4s (%6.1f MB encoded): decode median %7.1f ms, GL upload + mipmaps median %7.1f ms\n", n,
                kind, double(bytes.size()) / 1e6, median(decode), median(upload));
  }
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 30, width = 1280, height = 720, samples = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const int v = std::atoi(argv[i + 1]);
    if (a == "--frames")
      frames = std::max(1, v);
    else if (a == "--width")
      width = std::max(16, v);
    else if (a == "--height")
      height = std::max(16, v);
    else if (a == "--samples")
      samples = std::max(1, v);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  try {
    gpu::HeadlessContext ctx;
    texture_load(4096, 5);
    core::Scene scene;
    auto set = std::make_shared<core::MaterialSet>();
    set->images = {checker(2048, false), checker(2048, true)};
    core::Material plain, bumpy, cut;
    plain.metallic = bumpy.metallic = cut.metallic = 0.0;
    plain.roughness = bumpy.roughness = cut.roughness = 0.5;
    plain.base_color_texture.image = bumpy.base_color_texture.image = cut.base_color_texture.image = 0;
    bumpy.normal_texture.image = 1;
    cut.alpha_mode = core::AlphaMode::Mask;
    cut.double_sided = true;
    const core::Material kinds[5] = {plain, bumpy, cut, plain, bumpy};
    std::size_t triangles = 0;
    for (int k = 0; k < 5; ++k) {
      core::SceneObject o;
      o.name = "ball" + std::to_string(k);
      o.source = "bench";
      o.color = {0.6f, 0.5f, 0.4f};
      core::TriMesh m = sphere({2.2 * (k - 2), 1.0, 0.0}, 1.0, 256, 128);
      triangles += m.triangles.size();
      o.rest_mesh = std::make_shared<const core::TriMesh>(m);
      o.world_mesh = std::make_shared<const core::TriMesh>(std::move(m));
      auto own = std::make_shared<core::MaterialSet>(*set);
      own->materials = {kinds[k]};
      o.materials = own;
      scene.insert(std::move(o));
    }
    core::Camera cam;
    cam.viewport = {width, height};
    cam.eye = {0.0, 3.0, 9.5};
    cam.target = {0.0, 1.0, 0.0};
    gpu::Renderer renderer;
    gpu::OffscreenTarget target(width, height, samples);
    std::printf("renderer: %s\n%d × %d, %d sample(s), %zu triangles, 2 textures of 2048², %d frames per shading\n",
                ctx.renderer().c_str(), width, height, target.samples(), triangles, frames);
    double solid_median = 0.0;
    for (const gpu::Shading s :
         {gpu::Shading::solid, gpu::Shading::material, gpu::Shading::solid, gpu::Shading::material}) {
      gpu::ViewOptions opt;
      opt.shading = s;
      std::vector<double> ms;
      for (int f = 0; f < frames + 3; ++f) {
        target.bind();
        const auto t0 = std::chrono::steady_clock::now();
        renderer.draw(scene, cam, opt);
        glFinish();
        const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (f >= 3) ms.push_back(t);
      }
      double mean = 0.0;
      for (double t : ms) mean += t;
      mean /= double(ms.size());
      const double med = median(ms);
      const bool solid = s == gpu::Shading::solid;
      if (solid) solid_median = med;
      std::printf("%-8s median %7.2f ms  mean %7.2f ms%s\n", solid ? "solid" : "material", med, mean,
                  solid ? "" : ("  (" + std::to_string(med / solid_median).substr(0, 4) + "× solid)").c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_shading: %s\n", e.what());
    return 1;
  }
  return 0;
}
