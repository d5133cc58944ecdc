#include "editor/session/background_command.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "editor/commands/command_registry.h"
#include "editor/commands/history.h"
#include "editor/session/session.h"
#include "ui/gui_probe.h"
#include "ui/param_widgets.h"
#include "ui/theme.h"

namespace trispline::editor {

namespace {
bool ready(const std::future<void>& f) {
  return f.valid() && f.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}
}  // namespace

BackgroundCommand::BackgroundCommand(EditorSession& session) : session_(session) {}

BackgroundCommand::~BackgroundCommand() {
  if (!job_) return;
  job_->cancel = true;
  wait();
  session_.set_busy({});
}

double BackgroundCommand::progress() const { return job_ ? job_->progress.load() : 0.0; }

const std::string& BackgroundCommand::what() const {
  static const std::string none;
  return job_ ? job_->what : none;
}

void BackgroundCommand::cancel() {
  if (job_) job_->cancel = true;
}

void BackgroundCommand::wait() const {
  if (job_ && job_->future.valid()) job_->future.wait();
}

bool BackgroundCommand::refused(const std::string& what) const {
  if (!job_ && session_.busy().empty()) return false;
  session_.messages().warning(what + " refused: " + (job_ ? job_->what : session_.busy()) +
                              " (wait for it or cancel it)");
  return true;
}

bool BackgroundCommand::start(const nlohmann::json& line, std::string what, std::string verb) {
  if (refused(what)) return false;
  core::CommandPtr cmd;
  try {
    core::CommandContext ctx;
    std::error_code ec;
    ctx.base_dir = std::filesystem::current_path(ec);
    cmd = CommandRegistry::builtin().parse(line, ctx);
  } catch (const std::exception&) {
    return session_.execute(line);  // reports the parse error as every command line does
  }
  if (!cmd->preparable()) return session_.execute(std::move(cmd));
  auto job = std::make_unique<Job>();
  job->command = std::move(cmd);
  job->what = std::move(what);
  job->verb = std::move(verb);
  job->changes = session_.change_count();
  job->started = std::chrono::steady_clock::now();
  Job* j = job.get();
  // The worker reads its own copy of the scene: the UI thread keeps drawing session_.scene() meanwhile.
  job->future = std::async(std::launch::async, [j, scene = session_.scene()] {
    core::ProgressSink sink;
    sink.report = [j](double f) { j->progress = std::clamp(f, 0.0, 1.0); };
    sink.cancel = &j->cancel;
    j->command->prepare(scene, sink);
  });
  session_.set_busy(job->what);
  job_ = std::move(job);
  return true;
}

bool BackgroundCommand::start_history(std::size_t target) {
  History& history = session_.history();
  target = std::min(target, history.size());
  const std::size_t from = history.applied();
  if (target == from) return false;
  const char* verb = target + 1 == from ? "Undo" : target == from + 1 ? "Redo" : "History jump";
  std::string what = target + 1 == from   ? "Undo " + history.at(target).label()
                     : target == from + 1 ? "Redo " + history.at(from).label()
                     : target == 0        ? std::string("History: back to the initial state")
                                          : "History: to step " + std::to_string(target);
  if (refused(what)) return false;
  auto job = std::make_unique<Job>();
  job->what = std::move(what);
  job->verb = verb;
  job->target = target;
  job->changes = session_.change_count();
  job->started = std::chrono::steady_clock::now();
  Job* j = job.get();
  // The history's commands are walked over a copy: the UI thread keeps drawing session_.scene(), and the session
  // refuses every other change (set_busy) until finish().
  job->future = std::async(std::launch::async, [j, &history, scene = session_.scene()]() mutable {
    history.walk(scene, *j->target, [j](std::size_t done, std::size_t total) {
      if (j->cancel) throw core::OperationCancelled();
      j->progress = double(done) / double(std::max<std::size_t>(total, 1));
    });
    j->walked = std::move(scene);
  });
  session_.set_busy(job->what);
  job_ = std::move(job);
  return true;
}

bool BackgroundCommand::start_open(const std::filesystem::path& log, std::function<void()> opened) {
  std::string what = "Opening " + log.filename().string();
  if (refused(what)) return false;
  std::size_t lines = 0;  // for the progress bar: the log's lines, comments included
  if (std::ifstream in(log); in) lines = std::size_t(std::count(std::istreambuf_iterator<char>(in), {}, '\n'));
  auto job = std::make_unique<Job>();
  job->what = std::move(what);
  job->verb = "Open";
  job->after_open = std::move(opened);
  job->changes = session_.change_count();
  job->started = std::chrono::steady_clock::now();
  Job* j = job.get();
  job->future = std::async(std::launch::async, [j, log, lines] {
    j->opened = EditorSession::prepare_open(log, [j, lines](const core::Command&, int line) {
      if (j->cancel) throw core::OperationCancelled();
      j->progress = std::min(1.0, double(line) / double(std::max<std::size_t>(lines, 1)));
    });
  });
  session_.set_busy(job->what);
  job_ = std::move(job);
  return true;
}

bool BackgroundCommand::finish() {
  if (!job_ || !ready(job_->future)) return false;
  const std::unique_ptr<Job> job = std::move(job_);
  session_.set_busy({});
  ui::MessageLog& log = session_.messages();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - job->started).count();
  try {
    job->future.get();
  } catch (const core::OperationCancelled&) {
    log.info(job->verb + " cancelled: the scene is unchanged");
    return false;
  } catch (const core::CommandError& e) {
    log.error(job->command ? command_error_text(job->command->id(), e)
                           : job->what + " failed: " + e.what() + " (the scene is unchanged)");
    return false;
  } catch (const std::exception& e) {
    log.error((job->command ? job->command->id() : job->what) + " failed: " + e.what() + " (the scene is unchanged)");
    return false;
  }
  if (job->cancel) {  // Cancel pressed after the last progress check: the built result is dropped all the same
    log.info(job->verb + " cancelled: the scene is unchanged");
    return false;
  }
  if (session_.change_count() != job->changes) {  // cannot happen while the session refuses changes; never apply
    log.error(job->what + ": the scene changed while it was built; nothing was applied");
    return false;
  }
  if (job->target) return session_.settle_history(std::move(*job->walked), *job->target);
  if (job->opened) {
    if (!session_.commit_open(std::move(job->opened))) return false;
    if (job->after_open) job->after_open();
    return true;
  }
  return session_.execute(std::move(job->command), ms);
}

void BackgroundCommand::draw_progress(const ui::Rect& viewport) {
  if (!job_) return;
  // Bottom centre of the viewport: the timing overlay holds its top left.
  ImGui::SetNextWindowPos(ImVec2(viewport.pos.x + viewport.size.x * 0.5f, viewport.pos.y + viewport.size.y - 12.0f),
                          ImGuiCond_Always, ImVec2(0.5f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.92f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoMove |
                                 ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav;
  if (ImGui::Begin("###background_command", nullptr, flags)) {
    const double f = progress();
    ImGui::TextUnformatted(job_->what.c_str());
    ImGui::TextColored(ui::colors::dim, "%s",
                       job_->cancel ? "cancelling..." : "the view stays live; other edits wait until this is done");
    char label[32];
    std::snprintf(label, sizeof label, "%.0f %%", 100.0 * f);
    ImGui::ProgressBar(float(f), ImVec2(320.0f, 0.0f), label);
    ui::probe::item("command.progress");
    ui::probe::value("command.progress", label);
    ImGui::SameLine();
    ImGui::BeginDisabled(job_->cancel.load());
    if (ImGui::Button("Cancel", ImVec2(90.0f, 0.0f))) cancel();
    ImGui::EndDisabled();
    ui::probe::item("command.cancel");
    ui::tooltip("Stop: nothing changes and nothing is logged");
  }
  ImGui::End();
}

}  // namespace trispline::editor
