#include "editor/app_state.h"

namespace trispline::editor {
namespace {
// A window with 4x MSAA, reopened without it on a software renderer (llvmpipe: MSAA doubles the frame time).
// TRISPLINE_MSAA=N forces N samples.
std::unique_ptr<gpu::Window> make_window(int width, int height) {
  gpu::WindowOptions o;
  const char* forced = std::getenv("TRISPLINE_MSAA");
  if (forced) o.samples = std::atoi(forced);
  auto window = std::make_unique<gpu::Window>("trispline", width, height, o);
  if (forced || o.samples == 0 || !gpu::is_software_renderer()) return window;
  window.reset();
  o.samples = 0;
  return std::make_unique<gpu::Window>("trispline", width, height, o);
}

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// This frame's panel rectangles, the Timeline drawn: it spans the window's width above the status bar (Blender); the
// other panels share the rest.
ui::DockLayout layout_with_timeline(const ui::ViewToggles& toggles, const ImGuiIO& io, AnimationUi& anim,
                                    const core::Camera& view) {
  const float timeline_h = toggles.show_timeline ? ui::timeline_panel_height() : 0.0f;
  ui::DockLayout layout =
      ui::compute_layout(io.DisplaySize, ImGui::GetFrameHeight(), ui::status_bar_height() + timeline_h, {},
                         toggles.show_tool_panel, toggles.show_side_panels, toggles.show_log_panel);
  if (toggles.show_timeline) {
    const ui::Rect rect{{0, io.DisplaySize.y - ui::status_bar_height() - timeline_h}, {io.DisplaySize.x, timeline_h}};
    anim.draw_timeline(rect, view.viewport);
  }
  return layout;
}

// The History panel's requests: undo, redo and jumps walk the history on a worker (a redo may load a volume or fill a
// mesh again); "Run again" writes a file an opened log did not write. restore_context makes the window's GL context
// current again.
void run_history_request(const ui::HistoryPanelResult& hr, EditorSession& session, BackgroundCommand& background,
                         AnimationUi& anim, const std::function<void()>& restore_context) {
  const std::size_t at = session.history().applied();
  if (hr.jump_to) background.start_history(*hr.jump_to);
  if (hr.undo && at > 0) background.start_history(at - 1);
  if (hr.redo) background.start_history(at + 1);
  if (hr.run_again) session.run_again(*hr.run_again);  // a file an opened log did not write
  if (hr.run_again_output) anim.run_again(*hr.run_again_output, restore_context);
}

// The modal transform's state (`text`: its header) in a box at the bottom left of the viewport's free part `free`
// (Blender: in its header); the timing overlay holds the top left.
void draw_transform_header(const std::string& text, const ui::Rect& free) {
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  const ImVec2 at(free.pos.x + 8.0f, free.pos.y + free.size.y - size.y - 8.0f);
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddRectFilled({at.x - 4, at.y - 2}, {at.x + size.x + 4, at.y + size.y + 2}, IM_COL32(20, 20, 22, 210), 3.0f);
  dl->AddText(at, IM_COL32(255, 220, 120, 255), text.c_str());
}

}  // namespace

App::App(const AppOptions& options)
    : options_(options),
      window_(make_window(options.width, options.height)),
      host_(window_->native(), std::string()),  // fixed docked layout: nothing worth an imgui.ini
      gl_renderer_(gpu::current_gl_renderer()),
      session_(messages_),
      tool_ctx_{session_,
                view_,
                selected_,
                [this](std::string what, std::function<void()> work) { work_.push(std::move(what), std::move(work)); },
                [this](const nlohmann::json& line, std::string what, std::string verb) {
                  background_.start(line, std::move(what), std::move(verb));
                },
                [this](std::string title, std::string extension, std::string name,
                       std::function<void(const fs::path&)> chosen) {
                  tool_save_ = {std::move(title), std::move(extension), std::move(name), std::move(chosen)};
                  ask_file(FilePurpose::ToolSave);
                }},
      tools_(tool_ctx_) {
  try {
    renderer_ = std::make_unique<gpu::Renderer>();
  } catch (const std::exception& e) {
    messages_.error(std::string("the 3-D view is off: ") + e.what());
  }
  try {
    ui_timer_ = std::make_unique<gpu::GpuTimer>();
  } catch (const std::exception& e) {
    messages_.warning(std::string("the UI pass is not timed: ") + e.what());
  }
  messages_.info("OpenGL renderer: " + gl_renderer_);
  ui::probe::set_enabled(!options.gui_probe.empty());
  ui::ImGuiHost::set_batch_end(ui::ends_key_batch);  // shortcuts pressed during a slow frame run one a frame, in order
  if (gpu::is_software_renderer()) {
    // On a software rasteriser the CPU fast path evaluates FFDs ~20× faster than GLSL (docs/performance.md): the
    // Press tool's live preview then stays interactive. View ▸ FFD evaluator switches back.
    toggles_.ffd_backend = core::FfdBackend::cpu_fast;
    messages_.info("software OpenGL: FFD evaluator set to " + std::string(ui::ffd_backend_label(toggles_.ffd_backend)));
  }
  view_ = nav_.camera(window_->framebuffer_size());

  if (!options.bench_out.empty()) bench_.emplace();
  if (options.screenshot.empty() && !bench_) recovery_ = session_.start(options.recover_prompt);
  if (!options.open_log.empty() && !recovery_) open_later(options.open_log);
}

bool App::transform_input() {
  const ImGuiIO& io = ImGui::GetIO();
  const std::vector<ui::KeyPress>& keys = ui::ImGuiHost::key_presses();
  std::size_t first = 0;
  if (!transform_.active()) {
    if (io.WantCaptureKeyboard || io.WantTextInput || !work_.empty() || background_.running() || anim_.recording() ||
        tools_.owns_mouse() || file_dialog_.is_open() || recovery_ || prompt_for_ != Pending::None)
      return false;
    const core::SceneObject* o = session_.scene().find(selected_);
    if (!o || !o->world_mesh || !o->visible) return false;
    const auto start = std::find_if(keys.begin(), keys.end(),
                                    [](const ui::KeyPress& k) { return TransformModal::start_key(k).has_value(); });
    if (start == keys.end()) return false;
    transform_.begin(*TransformModal::start_key(*start), *o, view_, nav_input_from_imgui().mouse_px);
    first = std::size_t(start - keys.begin()) + 1;  // the keys typed after G in the same frame belong to it
  }
  TransformModalInput in;
  in.keys = keys;
  in.mouse_px = nav_input_from_imgui().mouse_px;
  in.left_clicked = io.MouseClicked[0] && first == 0;
  in.right_clicked = io.MouseClicked[1];
  if (transform_.update(in, first) == TransformModal::Outcome::confirmed) session_.execute(transform_.confirmed_line());
  return true;
}

void App::viewport_input() {
  const ImGuiIO& io = ImGui::GetIO();
  if (transform_frame_) {  // the modal transform owns the mouse: no navigation, no tool, no picking
    tools_.mouse_away();
    return;
  }
  if (io.WantCaptureMouse || !work_.empty()) {
    // A drag that began in the view ends there too: ImGui wants the mouse again on the frame the button comes up over
    // a panel or an overlay window, and that release must still reach the tool (else its stroke stays open).
    if (tools_.owns_mouse() && work_.empty() && !background_.running())
      tools_.handle_mouse(nav_input_from_imgui().mouse_px);
    else if (!tools_.owns_mouse())
      tools_.mouse_away();
    return;
  }
  const NavInput nav = nav_input_from_imgui();
  if (background_.running()) {  // a command is being built: the view navigates, the tools wait (they would edit)
    nav_.update(nav, view_.viewport);
    tools_.mouse_away();
    return;
  }
  if (tools_.owns_mouse()) {  // a stroke is being drawn: its pixels belong to the view at mouse-down, keep it
    tools_.handle_mouse(nav.mouse_px);
    return;
  }
  const bool nav_owns_left = nav_.update(nav, view_.viewport);
  if (!nav_owns_left && !(io.KeyAlt && io.MouseClicked[0]))
    tools_.handle_mouse(nav.mouse_px);
  else
    tools_.mouse_away();
}

void App::render_view() {
  volumes_.update(anim_.drawn_scene(), view_);  // live silhouettes for this view, on a worker thread
  const glm::ivec2 fb = window_->framebuffer_size();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fb.x, fb.y);
  if (!renderer_ || fb.x <= 0 || fb.y <= 0) {
    glClearColor(0.15f, 0.15f, 0.16f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    return;
  }
  gpu::ViewOptions vo = ui::view_options(toggles_);
  vo.selected = selected_;
  vo.time_s = anim_.time_s();
  vo.volume_budget_ms = kVolumeBudgetMs;
  if (!core::same_view(view_, moved_view_) || view_.near_plane != moved_view_.near_plane)
    moved_view_ = view_, moved_at_ = Clock::now();
  vo.ddm.cull = toggles_.fast_tiles;
  vo.ddm.moving = toggles_.fast_tiles && Clock::now() - moved_at_ < std::chrono::duration<double>(kMotionHoldSeconds);
  vo.ddm.motion_budget_vertices =
      gpu::is_software_renderer() ? gpu::kDdmMotionBudgetVerticesSoftware : gpu::kDdmMotionBudgetVertices;
  if (toggles_.fast_tiles) vo.ddm.pixels_per_unit = view_.projection_matrix()[1][1] * view_.viewport.y * 0.5;
  tools_.decorate(vo);
  volumes_.decorate(vo);
  if (const core::SceneObject* o = session_.scene().find(selected_);
      o && o->ffd && control_point_.highlight && vo.overlays.spheres.empty()) {
    // The control point edited in the Tool panel: a small sphere at P_ijk, 2 % of the lattice's extent.
    const auto& lattice = o->ffd->lattice;
    core::Aabb box;
    for (const glm::dvec3& p : lattice.control_points()) box.extend(p);
    const glm::ivec3 n = lattice.control_counts();
    int i[3];
    for (int a = 0; a < 3; ++a) i[a] = std::clamp(control_point_.index[a], 0, n[a] - 1);
    vo.overlays.spheres.push_back(
        {lattice.control_point(i[0], i[1], i[2]), 0.02 * box.diagonal(), {1.0f, 0.85f, 0.3f, 0.6f}});
  }
  // The Press tool's drag preview: the pressed object drawn with the lattice pressed so far (its own world_mesh is
  // the unpressed one until the command runs at mouse-up), evaluated by the FFD backend, never the stale CPU mesh.
  if (live_preview_) vo.overlays.lattices_in_place.push_back({live_preview_->object, live_preview_->lattice});
  guarantees_.decorate(vo);
  const gpu::Overlays& ov = vo.overlays;
  overlay_counts_ = {ov.strokes.size(),  ov.curves.size(),  ov.meshes.size(),
                     ov.lattices.size(), ov.spheres.size(), ov.points.size()};
  try {
    if (transform_.active()) {  // the live preview: a shallow copy with the object moved, the document untouched
      core::Scene shown = anim_.drawn_scene();
      if (shown.find(transform_.object())) shown.replace(transform_.preview_object());
      renderer_->draw(shown, view_, vo);
    } else {
      renderer_->draw(anim_.drawn_scene(), view_, vo);
    }
  } catch (const std::exception& e) {
    if (vo.ffd_backend != core::FfdBackend::cpu_ref) {
      // E.g. a lattice order the fast backends do not support (they take 2..4): the reference takes any.
      messages_.error(std::string("FFD evaluator ") + ui::ffd_backend_label(vo.ffd_backend) + " failed (" + e.what() +
                      "); switched to " + ui::ffd_backend_label(core::FfdBackend::cpu_ref));
      toggles_.ffd_backend = core::FfdBackend::cpu_ref;
      return;
    }
    messages_.error(std::string("drawing failed, the 3-D view is off: ") + e.what());
    renderer_.reset();
  }
}

bool App::animating() const { return toggles_.play_animation; }

void App::draw_control_point() {
  const core::SceneObject* o = session_.scene().find(selected_);
  if (!o || !o->ffd) return;
  if (ui::begin_docked("Tool", layout_.tool))  // the same window again: ImGui appends to it
    if (auto line = ui::draw_control_point_section(*o, control_point_)) session_.execute(*line);
  ImGui::End();
}

void App::frame() {
  // Shortcuts pressed while a job runs wait in order for its end (an undo typed during a slow redo follows it).
  ui::ImGuiHost::hold_batches(background_.running());
  host_.new_frame();
  ui::probe::begin_frame();
  nav_.follow(session_.scene().camera, session_.scene().camera_set, window_->framebuffer_size());
  const ImGuiIO& io = ImGui::GetIO();
  view_ = nav_.camera(window_->framebuffer_size());
  background_.finish();  // a Fill / Bake built on its worker: applied (one history entry) or reported
  if (const std::string loaded = volumes_.finish_load(); !loaded.empty()) {
    selected_ = loaded;
    frame_selected();  // a volume in millimetres would otherwise fill or vanish from the view
    view_ = nav_.camera(window_->framebuffer_size());
  }
  if (!session_.scene().find(selected_) && !session_.scene().find_volume(selected_)) selected_.clear();

  ui::MenuState menu = session_.menu_state();
  menu.material_shading = gpu::material_shading(session_.scene(), toggles_.shading);
  handle_menu(ui::draw_main_menu(toggles_, menu));
  // The modal transform (G / R / S) takes every key while it runs: X is then an axis, not Delete.
  transform_frame_ = transform_input();
  // While working or recording only F12 (screenshot) is taken from the keyboard.
  ui::MenuAction key = ui::poll_shortcuts();
  if (transform_frame_ && key != ui::MenuAction::Screenshot) key = ui::MenuAction::None;
  handle_menu(key == ui::MenuAction::Screenshot || (work_.empty() && !anim_.recording()) ? key : ui::MenuAction::None);
  if (!transform_frame_ && work_.empty() && !background_.running() && !anim_.recording() &&
      !tools_.owns_mouse())  // tool keys (K: Incision)
    if (const std::string k = ui::poll_tool_key(); !k.empty()) tools_.activate_shortcut(k);

  // The Timeline spans the window's width above the status bar (Blender); the other panels share the rest.
  anim_.begin_frame(selected_, toggles_.play_animation);
  anim_.set_view(view_);
  layout_ = layout_with_timeline(toggles_, io, anim_, view_);
  const ui::DockLayout& layout = layout_;
  toggles_.play_animation = anim_.playback().playing;  // the Play button
  control_point_.highlight = false;                    // set again while the Control point section is hovered
  // While a command is built on its worker the panels that edit the document are greyed (the session refuses
  // changes anyway); the view, the timeline's playback and the Log stay live.
  ImGui::BeginDisabled(background_.running());
  if (toggles_.show_tool_panel) {
    // A selected volume's panel takes the lower part of the Tool column (the tools work on meshes).
    const core::VolumeObject* volume = session_.scene().find_volume(selected_);
    const ui::RectPair column = ui::split_rect(layout.tool, volume ? 0.36f : 1.0f);
    tools_.draw_panel(column.top);
    draw_control_point();
    if (volume)
      if (const ui::VolumeExportKind* kind = volumes_.draw_panel(column.bottom, *volume)) {
        export_request_ = {volume->name, kind};
        ask_file(FilePurpose::ExportVolume);
      }
  }
  if (toggles_.show_side_panels) {
    ui::ScenePanelState sps{selected_, session_.has_command("scene.remove"), &transform_fields_, &text_params_};
    handle_scene(ui::draw_scene_panel(layout.scene, session_.scene(), sps));
    const ui::HistoryPanelResult hr = ui::draw_history_panel(layout.history, session_.history_view());
    run_history_request(hr, session_, background_, anim_, [this] { window_->make_current(); });
  }
  ImGui::EndDisabled();
  if (toggles_.show_log_panel) log_panel_.draw(layout.log, messages_);

  ui::StatusInfo st = session_.status();
  st.hint = transform_.active() ? transform_.header() : tools_.hint();
  ui::draw_status_bar(st);

  if (auto chosen = file_dialog_.draw()) handle_file(*chosen);
  volumes_.draw_load_progress();
  background_.draw_progress(layout.viewport);
  anim_.draw_record_ui([this] { window_->make_current(); });
  ui::draw_about_window(&show_about_, gl_renderer_);
  ui::draw_keys_window(&show_keys_);
  if (recovery_) {
    const ui::RecoverChoice c = ui::draw_recover_prompt(recovery_->commands, recovery_->log.string());
    if (c == ui::RecoverChoice::Recover) {
      const RecoveryOffer offer = *recovery_;
      tool_ctx_.defer("Recovering the previous session", [this, offer] { session_.recover(offer); });
    } else if (c == ui::RecoverChoice::Discard) {
      session_.discard(*recovery_);
      if (!options_.open_log.empty()) open_later(options_.open_log);
    }
    if (c != ui::RecoverChoice::Pending) recovery_.reset();
  }
  if (prompt_for_ != Pending::None && !file_dialog_.is_open()) {
    const ui::QuitChoice q = ui::draw_quit_prompt(st.document, doing(prompt_for_));
    if (q == ui::QuitChoice::Quit) go_on(prompt_for_);  // "Don't save"
    if (q == ui::QuitChoice::Cancel) prompt_for_ = Pending::None;
    if (q == ui::QuitChoice::SaveAndQuit && save_or_ask()) go_on(prompt_for_);  // else the Save dialog goes on
  }

  viewport_input();
  live_preview_ = tools_.live_preview(tool_ctx_);
  guarantees_.update(session_.scene(), live_preview_ ? live_preview_->object : selected_,
                     live_preview_ ? live_preview_->lattice : nullptr, toggles_.show_error_bounds,
                     toggles_.show_fold_certificate);
  guarantees_.draw_legend(layout.viewport);
  if (toggles_.timing_overlay) timing_.draw(layout.viewport);
  const ui::Rect& free = layout.viewport;  // what the panels leave visible: F / Home frame into it
  const glm::dvec2 s(io.DisplayFramebufferScale.x, io.DisplayFramebufferScale.y), lo(free.pos.x, free.pos.y);
  nav_.set_visible_rect(lo * s, (lo + glm::dvec2(free.size.x, free.size.y)) * s);
  if (transform_.active()) draw_transform_header(transform_.header(), free);  // the modal's state on the viewport
  work_.draw_overlay();
  if (!options_.gui_probe.empty()) write_probe();
  render_view();
  render_ui();
}

void App::write_probe() {
  nlohmann::json p = imgui_probe_fields();
  p["frame"] = ++frames_;
  p["document"] = session_.document().string();
  p["modified"] = session_.modified();
  const ui::HistoryView hv = session_.history_view();
  p["history"] = {{"labels", hv.labels}, {"applied", hv.applied}, {"not_written", hv.not_written}};
  p["history"]["outputs"] = nlohmann::json::array();
  for (const ui::HistoryOutputRow& o : hv.outputs)
    p["history"]["outputs"].push_back({{"after", o.after}, {"label", o.label}, {"not_written", o.not_written}});
  const glm::dvec2 scale(ImGui::GetIO().DisplayFramebufferScale.x, ImGui::GetIO().DisplayFramebufferScale.y);
  nlohmann::json objects = nlohmann::json::array(), object_px = nlohmann::json::object(),
                 centroid_px = nlohmann::json::object();
  for (const core::SceneObject& o : session_.scene().objects()) {
    objects.push_back(o.name);
    if (!o.world_mesh || o.world_mesh->positions.empty()) continue;
    const glm::dvec3 c = view_.project(core::mesh_bounds(*o.world_mesh).center());
    object_px[o.name] = {c.x / scale.x, c.y / scale.y};
    // The mean of the vertices: on the body of an object whose box centre thin parts (ears, handles) pull aside.
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& x : o.world_mesh->positions) mean += x;
    const glm::dvec3 m = view_.project(mean / double(o.world_mesh->positions.size()));
    centroid_px[o.name] = {m.x / scale.x, m.y / scale.y};
  }
  p["objects"] = objects;
  p["object_px"] = object_px;
  p["object_centroid_px"] = centroid_px;
  nlohmann::json animated = nlohmann::json::array();  // objects whose shape changes with the scene time
  for (const core::SceneObject& o : session_.scene().objects())
    if (o.animated()) animated.push_back(o.name);
  p["animated"] = animated;
  nlohmann::json hidden = nlohmann::json::array(), render_hidden = nlohmann::json::array();  // object.visibility
  auto add_hidden = [&](const std::string& name, bool visible, bool rendered) {
    if (!visible) hidden.push_back(name);
    if (!rendered) render_hidden.push_back(name);
  };
  for (const core::SceneObject& o : session_.scene().objects()) add_hidden(o.name, o.visible, o.render_visible);
  for (const core::VolumeObject& v : session_.scene().volumes()) add_hidden(v.name, v.visible, v.render_visible);
  p["hidden"] = hidden;
  p["render_hidden"] = render_hidden;
  p["selected"] = selected_;
  p["tool"] = tools_.tool().entry().name;
  const auto& oc = overlay_counts_;
  p["overlays"] = {{"strokes", oc[0]},  {"curves", oc[1]},  {"meshes", oc[2]},
                   {"lattices", oc[3]}, {"spheres", oc[4]}, {"points", oc[5]}};
  nlohmann::json log = nlohmann::json::array();
  const auto& m = messages_.messages();
  for (std::size_t i = m.size() > 5 ? m.size() - 5 : 0; i < m.size(); ++i) log.push_back(m[i].text);
  p["log"] = log;
  const ui::Rect& v = layout_.viewport;
  p["viewport"] = {v.pos.x, v.pos.y, v.pos.x + v.size.x, v.pos.y + v.size.y};
  if (const core::Aabb box = session_.scene().bounds(); box.valid()) {
    const glm::dvec3 c = view_.project(box.center());
    p["scene_center_px"] = {c.x / scale.x, c.y / scale.y};
  }
  p["camera"] = {{"eye", {view_.eye.x, view_.eye.y, view_.eye.z}},
                 {"target", {view_.target.x, view_.target.y, view_.target.z}}};
  p["current_frame"] = anim_.playback().frame;
  p["transform"] = transform_.active() ? nlohmann::json(transform_.header()) : nlohmann::json(nullptr);
  p["guarantees"] = guarantees_.probe();
  p["command"] = background_.running() ? nlohmann::json{{"what", background_.what()},
                                                        {"progress", background_.progress()},
                                                        {"cancelling", background_.cancelling()}}
                                       : nlohmann::json(nullptr);
  p["volume_refining"] = renderer_ && renderer_->last_stats().volume_refining;  // the last frame drawn's
  if (renderer_) {
    const gpu::RenderStats& rs = renderer_->last_stats();
    p["tiles"] = {
        {"layers", rs.ddm_layers_drawn}, {"following", rs.ddm_layers_following}, {"vertices", rs.ddm_vertices}};
  }
  const nlohmann::json volumes = volumes_.probe(session_.scene());
  for (auto it = volumes.begin(); it != volumes.end(); ++it) p[it.key()] = it.value();
  write_probe_file(options_.gui_probe, p);
}

void App::render_ui() {
  if (!ui_timer_) return host_.render();
  gpu::GpuTimer::Scope timed(*ui_timer_);
  host_.render();
}

void App::record_frame_timings(Clock::time_point start, Clock::time_point end, Clock::time_point last) {
  ui::FrameSample sample;
  sample.time_s = std::chrono::duration<double>(end.time_since_epoch()).count();
  sample.work_ms = ms_between(start, end);
  sample.interval_ms = ms_between(last, end);
  ui::TimingContext ctx;
  bool any_animated = false;
  for (const core::SceneObject& o : session_.scene().objects()) any_animated = any_animated || o.animated();
  if (renderer_) {
    const gpu::RenderStats& rs = renderer_->last_stats();
    sample.passes.ffd_ms = rs.ffd_ms;
    sample.passes.draw_ms = rs.draw_ms;
    sample.passes.ffd_vertices = rs.ffd_vertices;
    sample.passes.volume_ms = rs.volumes_drawn > 0 ? rs.volume_ms : -1.0;
    // The vertex-shader path evaluates while drawing; GLSL compute hands animated objects to it
    // (gpu/render/renderer_ffd.h).
    const core::FfdBackend b = toggles_.ffd_backend;
    sample.passes.ffd_in_draw =
        b == core::FfdBackend::glsl_vertex || (b == core::FfdBackend::glsl_compute && any_animated);
    if (rs.timer_mode && *rs.timer_mode) ctx.timer_mode = rs.timer_mode;
  }
  if (ui_timer_) {
    sample.passes.ui_ms = ui_timer_->last_ms();
    if (ctx.timer_mode.empty()) ctx.timer_mode = ui_timer_->mode_description();
  }
  timing_.add_frame(sample);

  ctx.ffd_backend = ui::ffd_backend_label(toggles_.ffd_backend);
  if (any_animated) ctx.scene_time_s = anim_.time_s();
  ctx.playing = animating();
  const auto& volumes = session_.scene().volumes();
  if (std::any_of(volumes.begin(), volumes.end(), [](const auto& v) { return v.silhouette.enabled; })) {
    ctx.silhouette_ms = volumes_.last_extract_ms();
    ctx.silhouette_points = volumes_.last_points();
    ctx.silhouette_running = volumes_.extracting();
  }
  if (renderer_) {
    const gpu::RenderStats& rs = renderer_->last_stats();
    ctx.ddm_instances = rs.ddm_instances;
    ctx.ddm_drawn = rs.ddm_instances_drawn;
    ctx.ddm_culled = rs.ddm_instances_culled;
    ctx.ddm_keep = rs.ddm_keep;
  }
  ctx.bounds_ms = guarantees_.bounds_ms();
  ctx.certificate_ms = guarantees_.certificate_ms();
  ctx.guarantees = guarantees_.summary();
  const History& h = session_.history();
  if (h.applied() > 0) {
    const core::Command& top = h.at(h.applied() - 1);
    ctx.last_command = top.id();
    ctx.last_stages = ui::stage_timings(top.stats());
    if (session_.last_label() == top.label()) ctx.last_command_ms = session_.last_ms();
  }
  timing_.set_context(std::move(ctx));
}

int App::write_screenshot(const fs::path& path) {
  const glm::ivec2 fb = window_->framebuffer_size();
  try {
    core::write_image_rgba8(path, fb.x, fb.y, ui::capture_back_buffer(fb.x, fb.y));
    messages_.info("screenshot: " + fs::absolute(path).string());
    if (!options_.screenshot.empty()) std::cout << "screenshot: " << path.string() << '\n';
    return 0;
  } catch (const std::exception& e) {
    messages_.error(std::string("cannot write the screenshot: ") + e.what());
    return 1;
  }
}

void App::wait_for_change(bool busy) {
  // A key tapped between two frames is held down for one more frame (ui::ImGuiHost): its release needs that frame.
  const bool input = ui::ImGuiHost::take_input();
  if (input) last_input_ = Clock::now();
  const double since_input = ms_between(last_input_, Clock::now()) * 1e-3;
  if (busy || !options_.screenshot.empty() || input)
    gpu::Window::poll_events();
  else if (since_input < kSettleSeconds)  // hover highlights and tooltips (ImGui's hover delays) appear
    gpu::Window::wait_events(0.1);
  else if (options_.idle_fps > 0.0)
    gpu::Window::wait_events(1.0 / options_.idle_fps);
  else
    gpu::Window::wait_events();  // nothing changes until an event arrives
  if (ui::ImGuiHost::take_input() || window_->take_damage()) last_input_ = Clock::now();
}

int App::run() {
  auto last = Clock::now();
  while (true) {
    if (work_.run_ready(messages_)) idle_frames_ = 0;  // its "Working…" frame was on screen
    // Volumes: a load or a silhouette extraction running, or a volume preview being refined, keeps frames coming; so
    // does a guarantees computation (its result is drawn the frame it is ready).
    const bool busy = !work_.empty() || ImGui::GetIO().MouseDown[0] || ImGui::GetIO().MouseDown[2] || animating() ||
                      anim_.recording() || background_.running() || volumes_.busy() || guarantees_.busy() ||
                      (renderer_ && renderer_->last_stats().ddm_keep < 1.0) ||  // full detail once it stops
                      (renderer_ && renderer_->last_stats().volume_refining) || bench_;
    wait_for_change(busy);
    const auto start = Clock::now();
    if (window_->should_close()) {
      window_->set_should_close(false);
      request(Pending::Quit);
    }
    if (bench_) bench_before_frame();
    frame();
    if (background_.running() || volumes_.busy() || guarantees_.busy() ||
        (renderer_ && renderer_->last_stats().volume_refining))
      idle_frames_ = 0;  // a screenshot waits for loads, silhouettes, guarantees and full-resolution volumes
    if (!options_.screenshot.empty() && work_.empty() && ++idle_frames_ >= kScreenshotFrames)
      return write_screenshot(options_.screenshot);
    if (std::exchange(screenshot_requested_, false))
      write_screenshot("trispline-screenshot-" + std::to_string(std::time(nullptr)) + "-" +
                       std::to_string(++screenshots_) + ".png");
    window_->swap();
    if (bench_)
      if (const int code = bench_after_frame(start); code >= 0) return code;
    if (options_.max_fps > 0.0)  // GUI tests: software-GL frame rates on any machine
      std::this_thread::sleep_until(
          start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / options_.max_fps)));
    const auto end = Clock::now();
    record_frame_timings(start, end, last);
    // Playback: real time × fps, whole frames, looping at frame_end (a stall shows at most 0.1 s of it).
    if (animating()) anim_.advance(std::min(ms_between(last, end) * 1e-3, 0.1));
    last = end;
    if (quit_) {
      session_.finish();
      return 0;
    }
  }
}

int run_editor(const AppOptions& options) {
  std::unique_ptr<App> app;
  try {
    app = std::make_unique<App>(options);
  } catch (const gpu::GlContextError& e) {
    std::cerr << "trispline: no window can be created: " << e.what() << "\n"
              << "  headless, `trispline replay LOG --out DIR` renders a log without a window\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "trispline: cannot start the editor: " << e.what() << '\n';
    return 2;
  }
  try {
    return app->run();
  } catch (const std::exception& e) {
    std::cerr << "trispline: internal error, the session log is kept for recovery: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace trispline::editor
