#include "editor/replay/record.h"

#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <locale>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "core/commands/anim_record.h"
#include "core/image/image_codec.h"
#include "core/image/image_io.h"
#include "core/mesh/gltf_anim_io.h"
#include "core/scene/scene_export.h"
#include "editor/replay/elapsed.h"
#include "editor/replay/process.h"
#include "editor/replay/render_scene.h"

namespace trispline::editor {
namespace fs = std::filesystem;
namespace {

// sRGB-encoded 8-bit value → linear (IEC 61966-2-1), for EXR frames.
const std::array<float, 256>& srgb_to_linear_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      t[i] = static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table;
}

// Half-float RGBA EXR, linear: colour channels decoded from sRGB, alpha as is. "<stem>.tmp.exr" then renamed.
void write_exr_linear(const fs::path& path, int width, int height, const std::vector<unsigned char>& rgba) {
  const auto& lut = srgb_to_linear_table();
  std::vector<float> px(rgba.size());
  for (std::size_t i = 0; i < rgba.size(); ++i) px[i] = (i % 4 == 3) ? rgba[i] / 255.0f : lut[rgba[i]];
  const fs::path tmp = path.parent_path() / (path.stem().string() + ".tmp.exr");
  core::ImageWriteSpec spec;
  spec.width = width;
  spec.height = height;
  spec.stored = core::PixelType::kHalf;
  // OpenImageIO stamps EXRs with the current time (capDate) unless DateTime is set: frames must not vary by run.
  spec.text_attributes = {{"compression", "zip"}, {"DateTime", ""}};
  const std::string err = core::image_codec().write_file(tmp.string(), spec, core::PixelType::kFloat, px.data());
  std::error_code ec;
  if (err.empty()) fs::rename(tmp, path, ec);
  if (!err.empty() || ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("'" + path.string() + "': cannot write EXR: " + (err.empty() ? ec.message() : err));
  }
}

}  // namespace

fs::path find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path candidate = fs::path(dir) / name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

namespace {

std::string read_text(const fs::path& p, std::size_t max_chars) {
  std::ifstream in(p, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  if (s.size() > max_chars) s = "…" + s.substr(s.size() - max_chars);
  return s;
}

// "%" in a folder name would be read by ffmpeg's image2 pattern: "%%" is a literal percent sign.
std::string escape_percent(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

std::string number_text(double v) {
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace

nlohmann::json RecordResult::to_json() const {
  nlohmann::json names = nlohmann::json::array();
  for (const fs::path& f : files) names.push_back(f.string());
  nlohmann::json j = {{"frames_written", frames_written},
                      {"frame_first", frame_first},
                      {"frame_last", frame_last},
                      {"cancelled", cancelled},
                      {"files", names},
                      {"ms", ms}};
  j["glb"] = glb.empty() ? nlohmann::json() : nlohmann::json(glb);
  j["mp4"] = mp4.empty() ? nlohmann::json() : nlohmann::json(mp4);
  if (!mp4_note.empty()) j["mp4_note"] = mp4_note;
  return j;
}

std::string frame_file_name(int frame, const std::string& format) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "frame_%04d.%s", frame, format.c_str());
  return buf;
}

std::pair<int, int> record_range(const core::Scene& scene, const RecordOptions& options) {
  if (options.frame_first == 0 && options.frame_last == 0)
    return {scene.timeline.frame_start, scene.timeline.frame_end};
  return {options.frame_first, options.frame_last};
}

RecordOptions record_options(const core::RecordRequest& request, std::filesystem::path out_dir) {
  RecordOptions ro;
  static_cast<core::RecordOutputs&>(ro) = request;
  ro.out_dir = std::move(out_dir);
  return ro;
}

void validate_record_options(const core::Scene& scene, const RecordOptions& options) {
  if (options.out_dir.empty()) throw std::invalid_argument("no output folder given for the recording");
  if (options.format != "png" && options.format != "exr")
    throw std::invalid_argument("unknown image format '" + options.format + "': use png or exr");
  const auto [first, last] = record_range(scene, options);
  const std::string err = core::frame_range_error(scene.timeline, first, last);
  if (!err.empty()) throw std::invalid_argument(err);
  if (options.piece_base >= 0 && (options.piece_base < scene.timeline.frame_start || options.piece_base > first))
    throw std::invalid_argument("piece base frame " + std::to_string(options.piece_base) + " is not in [" +
                                std::to_string(scene.timeline.frame_start) + ", " + std::to_string(first) + "]");
  const bool sized = options.width != 0 || options.height != 0;
  if (sized && (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384))
    throw std::invalid_argument("frame size " + std::to_string(options.width) + "×" + std::to_string(options.height) +
                                " is not in [1, 16384]² pixels");
}

struct Recorder::Impl {
  core::Scene scene;
  RecordOptions options;
  int first = 0, last = 0, next = 0;
  bool cancelled = false;
  std::optional<RecordResult> finished;
  std::unique_ptr<HeadlessRenderer> renderer;
  core::Camera camera;  // fixed for every frame; clip planes refitted per frame
  std::optional<core::MorphAnimationBuilder> glb;
  RecordResult result;
  double frames_ms = 0;  // wall time of the frames rendered so far
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
};

Recorder::Recorder(const core::Scene& scene, RecordOptions options) : impl_(std::make_unique<Impl>()) {
  validate_record_options(scene, options);
  Impl& d = *impl_;
  d.scene = core::render_visible_scene(scene);  // render-hidden objects and volumes cost nothing below
  d.options = std::move(options);
  std::tie(d.first, d.last) = record_range(d.scene, d.options);
  d.next = d.first;
  d.camera = d.options.camera     ? *d.options.camera
             : d.scene.camera_set ? d.scene.camera
                                  : framing_camera(d.scene, d.options.width, d.options.height);
  if (d.options.width > 0) d.camera.viewport = {d.options.width, d.options.height};
  if (d.options.images) {
    d.renderer = std::make_unique<HeadlessRenderer>();
    d.renderer->check_frame_size(d.camera.viewport.x, d.camera.viewport.y);  // before any file is written
  }
  std::error_code ec;
  fs::create_directories(d.options.out_dir, ec);
  if (ec) throw std::runtime_error("cannot create '" + d.options.out_dir.string() + "': " + ec.message());
  if (d.options.glb && d.options.piece_base < 0) d.glb.emplace(d.scene.timeline.fps, d.first);
  if (d.options.glb && d.options.piece_base >= 0) {
    d.glb.emplace(d.scene.timeline.fps, d.options.piece_base);
    if (d.options.piece_base < d.first) {  // the base pose, as the recording of the whole range starts with it
      const double t = d.scene.timeline.time_of_frame(d.options.piece_base);
      d.glb->add_frame(core::scene_export_nodes(core::scene_at_time(d.scene, t)).nodes);
    }
  }
  d.result.frame_first = d.first;
  d.result.frame_last = d.last;
}

Recorder::~Recorder() = default;

bool Recorder::step() {
  Impl& d = *impl_;
  if (d.cancelled || d.finished || d.next > d.last) return false;
  const auto t0 = std::chrono::steady_clock::now();
  const int frame = d.next;
  // Everything below depends on the frame number only: the pose is evaluated from the document on the CPU
  // reference path. The renderer keeps the GPU copies of what this frame shares with the last one (immutable data,
  // cached by address and held while cached: tile maps, meshes, textures) and drops the rest in its draw.
  const core::Scene posed = core::scene_at_time(d.scene, d.scene.timeline.time_of_frame(frame));
  if (d.renderer) {
    core::Camera cam = d.camera;
    fit_clip_planes(cam, posed);
    RenderSettings settings;
    settings.ffd_backend = d.options.ffd_backend;
    settings.time_s = 0;  // posed is a still: its offsets already are those of `frame`
    settings.show_grid = false;
    d.renderer->draw(posed, cam, settings);
    const RenderedImage image = d.renderer->read_image();
    const fs::path file = d.options.out_dir / frame_file_name(frame, d.options.format);
    try {
      if (d.options.format == "exr")
        write_exr_linear(file, image.width, image.height, image.rgba);
      else
        core::write_image_rgba8(file, image.width, image.height, image.rgba);
    } catch (const core::ImageIoError& e) {
      throw std::runtime_error(e.what());
    }
    d.result.files.push_back(file);
  }
  if (d.glb) {
    const core::SceneExport exported = core::scene_export_nodes(posed);  // objects and their live tile layers
    d.glb->add_frame(exported.nodes);
  }
  ++d.result.frames_written;
  ++d.next;
  d.frames_ms += ms_since(t0);
  return true;
}

void Recorder::cancel() { impl_->cancelled = true; }
int Recorder::frames_done() const { return impl_->result.frames_written; }
int Recorder::frames_total() const { return impl_->last - impl_->first + 1; }
int Recorder::current_frame() const { return impl_->next; }

double Recorder::seconds_left() const {
  const Impl& d = *impl_;
  if (d.result.frames_written == 0) return -1;
  const double mean_s = d.frames_ms / 1000.0 / d.result.frames_written;
  return mean_s * (frames_total() - d.result.frames_written);
}

RecordResult Recorder::finish() {
  Impl& d = *impl_;
  if (d.finished) return *d.finished;
  RecordResult r = d.result;
  r.cancelled = d.cancelled;
  const fs::path& dir = d.options.out_dir;
  if (d.cancelled) {
    if (d.options.mp4) r.mp4_note = "recording cancelled: no MP4";
  } else if (r.frames_written > 0) {
    if (d.glb) {
      const bool piece = d.options.piece_base >= 0;
      const fs::path glb = dir / (piece ? "animation.piece" : "animation.glb");
      try {
        piece ? d.glb->write_piece(glb) : d.glb->write_glb(glb);
      } catch (const std::exception& e) {
        throw std::runtime_error("cannot write " + glb.filename().string() + ": " + e.what());
      }
      r.glb = glb.string();
      r.files.push_back(glb);
    }
    if (d.options.mp4) {
      if (d.options.format != "png") {
        r.mp4_note = "MP4 is made from PNG frames (format is " + d.options.format + ")";
      } else {
        r.mp4_note = write_mp4(dir, r.frame_first, r.frames_written, d.scene.timeline.fps, d.camera.viewport.x,
                               d.camera.viewport.y);
        if (r.mp4_note.empty()) {
          r.mp4 = (dir / "animation.mp4").string();
          r.files.push_back(dir / "animation.mp4");
        }
      }
    }
  }
  r.ms = ms_since(d.t0);
  d.finished = r;
  return r;
}

std::string write_mp4(const fs::path& dir, int first, int frames, double fps, int width, int height) {
  const fs::path ffmpeg = find_on_path("ffmpeg");
  if (ffmpeg.empty()) return "ffmpeg not found on PATH";
  const fs::path mp4 = dir / "animation.mp4";
  const fs::path log = dir / "animation.mp4.log";
  std::vector<std::string> argv = {ffmpeg.string(),
                                   "-hide_banner",
                                   "-loglevel",
                                   "error",
                                   "-nostdin",
                                   "-framerate",
                                   number_text(fps),
                                   "-start_number",
                                   std::to_string(first),
                                   "-i",
                                   escape_percent((dir / "frame_").string()) + "%04d.png"};
  // H.264 in 4:2:0 needs even sizes: pad an odd one with a black row or column.
  if (width % 2 || height % 2) argv.insert(argv.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"});
  argv.insert(argv.end(),
              {"-frames:v", std::to_string(frames), "-c:v", "libx264", "-pix_fmt", "yuv420p", "-y", mp4.string()});
  const int status = run_process(argv, log);
  std::error_code ec;
  std::string note;
  if (!(status == 0 && fs::is_regular_file(mp4, ec) && fs::file_size(mp4, ec) > 0)) {
    const std::string text = read_text(log, 600);
    note = "ffmpeg failed (" + (status < 0 ? std::string("did not run") : "exit " + std::to_string(status)) + ")" +
           (text.empty() ? "" : ": " + text);
    fs::remove(mp4, ec);
  }
  fs::remove(log, ec);
  return note;
}

RecordResult record_frames(const core::Scene& scene, const RecordOptions& options,
                           const std::function<bool(int, int)>& progress) {
  Recorder recorder(scene, options);
  while (recorder.step()) {
    if (progress && !progress(recorder.frames_done(), recorder.frames_total())) {
      recorder.cancel();
      break;
    }
  }
  return recorder.finish();
}

}  // namespace trispline::editor
