// `trispline farm assemble DIR`: after every task of a farm. Frames: the log and every chunk checked (its record,
// every frame decoded), the chunks' frames linked into DIR, their animation.piece files joined into DIR/animation.glb
// (the bytes one `replay --frames A-B` writes), the MP4, and DIR/report.json. Batch: every run's report.json
// collected into DIR/summary.json.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <ostream>
#include <stdexcept>

#include "core/mesh/gltf_anim_io.h"
#include "editor/commands/history.h"
#include "editor/farm/farm.h"
#include "editor/replay/record.h"
#include "editor/replay/replay.h"

namespace trispline::editor {
namespace fs = std::filesystem;
namespace {

nlohmann::json read_json_or_null(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) > (64u << 20)) return nullptr;
  std::ifstream in(path);
  if (!in) return nullptr;
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return nullptr;
  }
}

void write_json(const fs::path& path, const nlohmann::json& j) {
  write_file_atomically(path, j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

// dst becomes the same file as src: a hard link (a copy where the filesystem has none), made under a temporary name
// and renamed over dst, so a reader never sees a partial frame.
void link_atomically(const fs::path& src, const fs::path& dst) {
  const fs::path tmp = dst.parent_path() / (dst.stem().string() + ".link.tmp" + dst.extension().string());
  std::error_code ec;
  fs::remove(tmp, ec);
  fs::create_hard_link(src, tmp, ec);
  if (ec) fs::copy_file(src, tmp, fs::copy_options::overwrite_existing);
  fs::rename(tmp, dst);
}

// The chunks' pieces joined, or nullopt when one cannot be joined exactly (an object's topology changes).
std::optional<core::MorphAnimationBuilder> join_pieces(const FarmPlan& plan) {
  std::optional<core::MorphAnimationBuilder> joined;
  for (const FarmTask& t : plan.tasks) {
    const fs::path path = plan.dir / "chunks" / farm_task_name(t.index) / "animation.piece";
    core::MorphAnimationBuilder piece = core::MorphAnimationBuilder::read_piece(path);
    // A piece holds the range's first frame, then the chunk's frames (the first chunk starts with it).
    const int expected = t.last - t.first + 1 + (t.first > plan.frame_first ? 1 : 0);
    if (piece.frame_count() != expected)
      throw std::runtime_error(path.string() + " holds " + std::to_string(piece.frame_count()) + " frames, not " +
                               std::to_string(expected) + ": rerun the chunk (trispline farm resume)");
    if (!joined)
      joined.emplace(std::move(piece));
    else if (!joined->append_piece(piece))
      return std::nullopt;
  }
  return joined;
}

// One process's animation.glb when the pieces cannot be joined: replay the log and pose every frame (no rendering).
void pose_animation_glb(const FarmPlan& plan) {
  core::Scene scene;
  History history(scene);
  const ScratchFolder scratch;  // what the log exports goes there, not next to the log
  const ReplayResult r = replay_lines(history, plan.log, {}, scratch.path());
  if (!r.ok) throw std::runtime_error("the log does not replay: " + r.error);
  RecordOptions ro;
  ro.out_dir = plan.dir;
  ro.format = plan.format;
  ro.frame_first = plan.frame_first, ro.frame_last = plan.frame_last;
  ro.width = plan.width, ro.height = plan.height;
  ro.images = ro.mp4 = false;  // pose only: the frames are the chunks'; no MP4
  record_frames(scene, ro);
}

// Every chunk checked against its record, every frame decoded: "" when all hold, else the first problem.
std::string check_chunks(const FarmPlan& plan, int& bad_frames) {
  std::string first;
  bad_frames = 0;
  for (const FarmTask& t : plan.tasks) {
    const ChunkCheck c = check_chunk(plan, t, true);
    if (c.done) continue;
    bad_frames += static_cast<int>(c.bad_frames.size());
    if (first.empty()) first = "chunk " + farm_task_name(t.index) + ": " + c.problem;
  }
  return first;
}

int assemble_frames(const FarmPlan& plan, std::ostream& out, std::ostream& err) {
  const auto t0 = std::chrono::steady_clock::now();
  std::error_code ec;
  // A failed or refused assembly must not leave the outputs of an earlier one looking current.
  for (const char* name : {"report.json", "animation.glb", "animation.mp4"}) fs::remove(plan.dir / name, ec);
  if (const std::string changed = log_change(plan.log, plan.log_crc32, plan.log_bytes); !changed.empty()) {
    err << "farm assemble: " << changed << "; nothing assembled\n";
    return 2;
  }
  int bad_frames = 0;
  if (const std::string bad = check_chunks(plan, bad_frames); !bad.empty()) {
    err << "farm assemble: " << bad << " (" << bad_frames << " frames not verified); nothing assembled: "
        << "trispline farm resume " << plan.dir.string() << "\n";
    return 2;
  }
  nlohmann::json chunks = nlohmann::json::array();
  for (const FarmTask& t : plan.tasks) {
    const nlohmann::json report = read_json_or_null(plan.dir / "chunks" / farm_task_name(t.index) / "report.json");
    nlohmann::json c = {{"index", t.index}, {"first", t.first}, {"last", t.last}};
    if (report.is_object()) {
      c["replay_ms"] = report.value("replay_ms", 0.0);
      if (report.contains("record")) c["record_ms"] = report["record"].value("ms", 0.0);
    }
    chunks.push_back(c);
  }
  std::string glb_source = "pieces";
  try {
    std::optional<core::MorphAnimationBuilder> joined = join_pieces(plan);
    if (joined) {
      joined->write_glb(plan.dir / "animation.glb");
    } else {
      glb_source = "posed";  // exact too, at the cost of posing every frame once more
      out << "farm assemble: an object changes topology: posing every frame for animation.glb\n";
      pose_animation_glb(plan);
    }
    for (int f = plan.frame_first; f <= plan.frame_last; ++f) {
      const FarmTask& t = plan.tasks.at(static_cast<std::size_t>((f - plan.frame_first) / plan.chunk));
      link_atomically(plan.dir / "chunks" / farm_task_name(t.index) / frame_file_name(f, plan.format),
                      plan.dir / frame_file_name(f, plan.format));
    }
  } catch (const std::exception& e) {
    err << "farm assemble: " << e.what() << "\n";
    return 3;
  }
  const int frames = plan.frame_last - plan.frame_first + 1;
  const std::optional<FileSum> glb = file_sum(plan.dir / "animation.glb", 1ull << 40);
  if (!glb) {
    err << "farm assemble: animation.glb was not written\n";
    return 3;
  }
  nlohmann::json record = {{"frames_written", frames},
                           {"frame_first", plan.frame_first},
                           {"frame_last", plan.frame_last},
                           {"glb", (plan.dir / "animation.glb").string()},
                           {"glb_bytes", glb->bytes},
                           {"glb_crc32", glb->crc32},
                           {"log_crc32", plan.log_crc32},
                           {"glb_source", glb_source},
                           {"mp4", nullptr}};
  if (plan.format == "png") {
    const std::string note =
        write_mp4(plan.dir, plan.frame_first, frames, plan.fps, plan.frame_width, plan.frame_height);
    if (note.empty())
      record["mp4"] = (plan.dir / "animation.mp4").string();
    else
      record["mp4_note"] = note;
  } else {
    record["mp4_note"] = "MP4 is made from PNG frames (format is " + plan.format + ")";
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  record["assemble_ms"] = ms;
  try {
    write_json(plan.dir / "report.json", {{"farm", plan.to_json()}, {"record", record}, {"chunks", chunks}});
  } catch (const std::exception& e) {
    err << "farm assemble: " << e.what() << "\n";
    return 3;
  }
  out << "assembled frames " << plan.frame_first << "-" << plan.frame_last << " in " << plan.dir.string()
      << ": animation.glb (" << glb_source << ")"
      << (record["mp4"].is_null() ? ", no MP4: " + record.value("mp4_note", std::string()) : ", animation.mp4")
      << " in " << static_cast<int>(ms) << " ms\n";
  return 0;
}

int assemble_batch(const FarmPlan& plan, std::ostream& out, std::ostream& err) {
  nlohmann::json runs = nlohmann::json::array();
  int ok = 0;
  nlohmann::json failed = nlohmann::json::array();
  std::error_code ec;
  fs::remove(plan.dir / "summary.json", ec);
  if (const std::string changed = batch_logs_changed(plan); !changed.empty()) {
    err << "farm assemble: " << changed << "; nothing assembled\n";
    return 2;
  }
  for (const FarmTask& t : plan.tasks) {
    const bool valid = batch_report_valid(plan, t);
    const nlohmann::json report = valid ? read_json_or_null(plan.dir / "runs" / t.name / "report.json") : nullptr;
    const bool run_ok = valid && report["ok"].get<bool>();
    nlohmann::json r = {{"name", t.name}, {"log", t.log.string()}, {"ok", run_ok}, {"report", report}};
    if (report.is_null())
      r["error"] = "no replay report in runs/" + t.name +
                   "/report.json (the task did not run to the end, or the file "
                   "is not a report: logs/task_" +
                   farm_task_name(t.index) + ".log)";
    else if (!run_ok)
      r["error"] = report.value("error", std::string("an output could not be written"));
    ok += run_ok;
    if (!run_ok) failed.push_back(t.name);
    runs.push_back(r);
  }
  try {
    write_json(plan.dir / "summary.json",
               {{"logs", plan.tasks.size()}, {"ok", ok}, {"failed", failed}, {"runs", runs}});
  } catch (const std::exception& e) {
    err << "farm assemble: " << e.what() << "\n";
    return 3;
  }
  out << "summary: " << ok << " of " << plan.tasks.size()
      << " logs replayed without error: " << (plan.dir / "summary.json").string() << "\n";
  return 0;
}

}  // namespace

int farm_assemble(const fs::path& dir, std::ostream& out, std::ostream& err) {
  const std::optional<FarmPlan> plan = read_plan_or_report(dir, err, "farm assemble");
  if (!plan) return 2;
  try {
    return plan->kind == "batch" ? assemble_batch(*plan, out, err) : assemble_frames(*plan, out, err);
  } catch (const std::exception& e) {
    err << "farm assemble: " << e.what() << "\n";
    return 3;
  }
}

}  // namespace trispline::editor
