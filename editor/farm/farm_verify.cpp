// What a farm checks instead of trusting its folder: sizes and CRC-32s (zlib) of the logs and of every chunk's
// files, recorded by the task that wrote them (chunks/NNNN/chunk.json), and frames that decode (OpenImageIO).
#include <zlib.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "core/image/image_codec.h"
#include "editor/farm/farm.h"
#include "editor/replay/record.h"

namespace trispline::editor {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr std::uintmax_t kMaxChunkRecordBytes = 16u << 20;
constexpr std::uint64_t kMaxPieceBytes = 1ull << 36;

fs::path chunk_dir(const FarmPlan& plan, const FarmTask& task) {
  return plan.dir / "chunks" / farm_task_name(task.index);
}

// A frame file's upper bound: RGBA float pixels and 1 MiB of headers (PNG's and EXR's worst cases are below).
std::uint64_t max_frame_bytes(const FarmPlan& plan) {
  return static_cast<std::uint64_t>(plan.frame_width) * static_cast<std::uint64_t>(plan.frame_height) * 16 + (1u << 20);
}

json sum_json(const FileSum& s) { return {{"bytes", s.bytes}, {"crc32", s.crc32}}; }

// A {"bytes","crc32"} object of a chunk record; nullopt when it is not one.
std::optional<FileSum> sum_from_json(const json& j) {
  if (!j.is_object() || !j.contains("bytes") || !j.contains("crc32") || !j["bytes"].is_number_unsigned() ||
      !j["crc32"].is_number_unsigned() || j["crc32"].get<std::uint64_t>() > 0xFFFFFFFFull)
    return std::nullopt;
  return FileSum{j["bytes"].get<std::uint64_t>(), static_cast<std::uint32_t>(j["crc32"].get<std::uint64_t>())};
}

// "" when `path` is an RGBA image of width × height (and, when `pixels`, every scanline decodes to finite values).
std::string check_image(const fs::path& path, int width, int height, bool pixels) {
  std::string err;
  std::unique_ptr<core::ImageReader> in;
  try {
    in = core::image_codec().open_file(path.string(), false, err);
  } catch (const std::exception& e) {
    return std::string("cannot be checked: ") + e.what();
  }
  if (!in) return "does not decode: " + err;
  const core::ImageHeader& spec = in->header();
  if (spec.width != width || spec.height != height || spec.channels != 4 || spec.depth != 1)
    return "is " + std::to_string(spec.width) + "×" + std::to_string(spec.height) + " with " +
           std::to_string(spec.channels) + " channels, not the farm's " + std::to_string(width) + "×" +
           std::to_string(height) + " RGBA";
  if (!pixels) return "";
  std::vector<float> row(static_cast<std::size_t>(width) * 4);
  for (int y = 0; y < height; ++y) {
    if (!in->read_row_float(y, row.data())) return "row " + std::to_string(y) + " does not decode: " + in->error();
    for (const float v : row)
      if (!std::isfinite(v)) return "row " + std::to_string(y) + " holds a non-finite value";
  }
  return "";
}

}  // namespace

std::optional<FileSum> file_sum(const fs::path& path, std::uint64_t max_bytes, bool follow_symlink) {
  std::error_code ec;
  if (!fs::is_regular_file(follow_symlink ? fs::status(path, ec) : fs::symlink_status(path, ec))) return std::nullopt;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec || size > max_bytes) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  FileSum sum;
  uLong crc = crc32(0L, Z_NULL, 0);
  std::vector<char> buf(1 << 16);
  while (in) {
    in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
    const std::streamsize n = in.gcount();
    if (n <= 0) break;
    crc = crc32(crc, reinterpret_cast<const Bytef*>(buf.data()), static_cast<uInt>(n));
    sum.bytes += static_cast<std::uint64_t>(n);
    if (sum.bytes > max_bytes) return std::nullopt;  // grew while read
  }
  if (in.bad()) return std::nullopt;
  sum.crc32 = static_cast<std::uint32_t>(crc);
  return sum;
}

std::string log_change(const fs::path& log, std::uint32_t crc32, std::uint64_t bytes) {
  const std::optional<FileSum> now = file_sum(log, kFarmMaxLogBytes, true);
  if (!now) return "the log '" + log.string() + "' is gone or unreadable since submission";
  if (now->bytes != bytes || now->crc32 != crc32)
    return "the log '" + log.string() + "' changed since submission (" + std::to_string(now->bytes) +
           " bytes, CRC-32 " + std::to_string(now->crc32) + "; submitted: " + std::to_string(bytes) +
           " bytes, CRC-32 " + std::to_string(crc32) + "): submit it again into a new folder";
  return "";
}

std::string batch_logs_changed(const FarmPlan& plan) {
  std::string first;
  int changed = 0;
  for (const FarmTask& t : plan.tasks)
    if (std::string why = log_change(t.log, t.log_crc32, t.log_bytes); !why.empty()) {
      if (changed++ == 0) first = std::move(why);
    }
  if (changed > 1) first += " (and " + std::to_string(changed - 1) + " other logs of the batch)";
  return first;
}

bool batch_report_valid(const FarmPlan& plan, const FarmTask& task) {
  const fs::path path = plan.dir / "runs" / task.name / "report.json";
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(path, ec)) || !fs::is_regular_file(path, ec) ||
      fs::file_size(path, ec) > (64u << 20))
    return false;
  std::ifstream in(path);
  try {
    const nlohmann::json r = nlohmann::json::parse(in);
    return r.is_object() && r.contains("ok") && r["ok"].is_boolean();
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

void seal_chunk(const FarmPlan& plan, const FarmTask& task) {
  const fs::path dir = chunk_dir(plan, task);
  json frames = json::array();
  for (int f = task.first; f <= task.last; ++f) {
    const std::optional<FileSum> s = file_sum(dir / frame_file_name(f, plan.format), max_frame_bytes(plan));
    if (!s) throw std::runtime_error("frame " + std::to_string(f) + " is missing from " + dir.string());
    json e = sum_json(*s);
    e["frame"] = f;
    frames.push_back(e);
  }
  const std::optional<FileSum> piece = file_sum(dir / "animation.piece", kMaxPieceBytes);
  if (!piece) throw std::runtime_error("animation.piece is missing from " + dir.string());
  const json record = {{"task", task.index},          {"first", task.first}, {"last", task.last},
                       {"log_crc32", plan.log_crc32}, {"frames", frames},    {"piece", sum_json(*piece)}};
  write_file_atomically(dir / "chunk.json", record.dump(1) + "\n");
}

ChunkCheck check_chunk(const FarmPlan& plan, const FarmTask& task, bool decode_pixels) {
  ChunkCheck c;
  const fs::path dir = chunk_dir(plan, task);
  std::error_code ec;
  const auto all_bad = [&](const std::string& why) {
    c.bad_frames.clear();
    for (int f = task.first; f <= task.last; ++f) c.bad_frames.push_back(f);
    c.problem = why;
    return c;
  };
  const fs::file_status dir_status = fs::symlink_status(dir, ec);
  if (!fs::exists(dir_status)) return all_bad("no output yet (" + dir.string() + " does not exist)");
  if (!fs::is_directory(dir_status)) return all_bad(dir.string() + " is not a folder (a symlink or a file)");
  const fs::path record_path = dir / "chunk.json";
  const std::uintmax_t size = fs::file_size(record_path, ec);
  if (ec || !fs::is_regular_file(fs::symlink_status(record_path, ec)))
    return all_bad("no chunk.json (the task has not finished)");
  if (size > kMaxChunkRecordBytes) return all_bad("chunk.json is over 16 MiB");
  json r;
  try {
    std::ifstream in(record_path, std::ios::binary);
    r = json::parse(in);
  } catch (const json::exception& e) {
    return all_bad(std::string("chunk.json is not JSON: ") + e.what());
  }
  const std::size_t n = static_cast<std::size_t>(task.last - task.first + 1);
  if (!r.is_object() || r.value("task", json()) != task.index || r.value("first", json()) != task.first ||
      r.value("last", json()) != task.last || r.value("log_crc32", json()) != plan.log_crc32 || !r.contains("frames") ||
      !r["frames"].is_array() || r["frames"].size() != n)
    return all_bad("chunk.json is not the record of task " + std::to_string(task.index) + " of this plan");
  for (std::size_t k = 0; k < n; ++k) {
    const int f = task.first + static_cast<int>(k);
    const json& e = r["frames"][k];
    const std::optional<FileSum> want = sum_from_json(e);
    const fs::path file = dir / frame_file_name(f, plan.format);
    std::string why;
    if (!want || !e.is_object() || e.value("frame", json()) != f) {
      why = "has no record";
    } else if (fs::file_size(file, ec) != want->bytes || ec) {
      why = "is missing or not the recorded size";
    } else if (const std::optional<FileSum> got = file_sum(file, want->bytes); !got || !(*got == *want)) {
      why = "is not the file the task wrote (CRC-32)";
    } else {
      why = check_image(file, plan.frame_width, plan.frame_height, decode_pixels);
    }
    if (!why.empty()) {
      c.bad_frames.push_back(f);
      if (c.problem.empty()) c.problem = "frame " + std::to_string(f) + " " + why;
    }
  }
  const std::optional<FileSum> want_piece = sum_from_json(r.value("piece", json()));
  const std::optional<FileSum> piece =
      want_piece ? file_sum(dir / "animation.piece", want_piece->bytes) : std::optional<FileSum>();
  if (!want_piece || !piece || !(*piece == *want_piece)) {
    if (c.problem.empty()) c.problem = "animation.piece is missing or not the file the task wrote (CRC-32)";
    c.done = false;
    return c;
  }
  c.done = c.problem.empty();
  return c;
}

}  // namespace trispline::editor
