#include "core/base/text.h"
#include "core/commands/object_visibility.h"
#include "core/commands/volume_remove.h"
#include "editor/app_state.h"

namespace trispline::editor {

const char* doing(Pending p) {
  return p == Pending::New ? "starting a new scene" : p == Pending::Open ? "opening another log" : "quitting";
}

void App::open_later(const fs::path& log) {
  // Replayed on a worker (progress bar, Cancel) while the view keeps drawing the current document.
  background_.start_open(log, [this, name = log.filename().string()] {
    selected_.clear();
    // The view is set after a frame of the opened document: a log opened at start-up may be ready before the first
    // frame has laid out the panels that framing avoids.
    tool_ctx_.defer("Showing " + name, [this] {
      // The log's last camera.set is the view it was saved with: shown as it is (even when the same log is opened
      // again after orbiting); a log without one is framed.
      if (session_.scene().camera_set)
        nav_.adopt(session_.scene().camera, window_->framebuffer_size());
      else
        nav_.frame(session_.scene().bounds(), view_.viewport);
      if (!options_.screenshot.empty()) showcase();
    });
  });
}

void App::showcase() {
  const auto& objects = session_.scene().objects();
  for (const core::SceneObject& o : objects)
    if (o.placement) selected_ = o.name;
  if (selected_.empty() && !objects.empty()) selected_ = objects.back().name;
  // Its parameters fill the Tool panel: Tile Paint when the scene is about tile layers, else Sketch.
  const core::SceneObject* tiled = nullptr;
  for (const core::SceneObject& o : objects)
    if (!o.ddm_layers.empty() && !o.placement) tiled = &o;
  if (tiled && std::none_of(objects.begin(), objects.end(), [](const auto& o) { return o.placement != nullptr; })) {
    selected_ = tiled->name;
    tools_.set_active(Toolbox::kDdmPaint);
  } else if (objects.empty() && !session_.scene().volumes().empty()) {
    selected_ = session_.scene().volumes().back().name;  // a volume scene: its Volume panel under the Select tool
    tools_.set_active(Toolbox::kSelect);
  } else {
    tools_.set_active(Toolbox::kSketch);
  }
}

void App::frame_selected() {
  const core::SceneObject* o = session_.scene().find(selected_);
  const core::VolumeObject* v = session_.scene().find_volume(selected_);
  nav_.frame(o && o->world_mesh ? core::mesh_bounds(*o->world_mesh)
             : v                ? v->world_bounds()
                                : session_.scene().bounds(),
             view_.viewport);
}

void App::request(Pending what) {
  if (prompt_for_ != Pending::None && what != Pending::Quit) return;  // a question is open already
  const bool ask =
      what == Pending::Quit ? session_.modified() && session_.history().applied() > 0 : session_.modified();
  if (ask)
    prompt_for_ = what;
  else
    go_on(what);
}

void App::go_on(Pending what) {
  prompt_for_ = Pending::None;
  if (what == Pending::Quit) quit_ = true;
  if (what == Pending::New) {
    session_.new_document();
    selected_.clear();
  }
  if (what == Pending::Open) ask_file(FilePurpose::OpenLog);
}

bool App::save_or_ask() {
  if (!session_.document().empty()) return session_.save(session_.document(), view_);
  ask_file(FilePurpose::SaveLog);
  return false;
}

void App::ask_file(FilePurpose purpose) {
  std::error_code ec;
  const bool writes =
      purpose == FilePurpose::SaveLog || purpose == FilePurpose::ExportVolume || purpose == FilePurpose::ToolSave;
  const fs::path& last = writes ? last_write_folder_ : last_read_folder_;
  const fs::path folder = !last.empty()                                      ? last
                          : document_chosen_ && !session_.document().empty() ? session_.document().parent_path()
                                                                             : fs::current_path(ec);
  file_purpose_ = purpose;
  if (purpose == FilePurpose::LoadMesh) {
    std::vector<std::string> extensions = kMeshExtensions;
    extensions.insert(extensions.end(), kVolumeExtensions.begin(), kVolumeExtensions.end());
    file_dialog_.open("Load a mesh or a CT/MRI volume", ui::FileDialog::Mode::Open, extensions, folder);
    file_dialog_.set_option("Leave out points and lines",
                            "Meshes: a file with point or line elements beside its faces is refused (nothing of a file "
                            "is dropped silently). On: only the faces load; the Log says how many elements were left "
                            "out.",
                            load_ignore_loose_);
    file_dialog_.set_folder_choice("Load this folder",
                                   "A DICOM series is a folder of slices: load the folder listed as one volume");
  } else if (purpose == FilePurpose::ExportVolume && export_request_.kind) {
    const ui::VolumeExportKind& k = *export_request_.kind;
    const bool iso = std::string(k.what) == "iso";
    file_dialog_.open(std::string("Export the ") + (iso ? "iso-surface" : "silhouettes") + " of " +
                          export_request_.volume + " (" + k.extension + ")",
                      ui::FileDialog::Mode::Save, {k.extension}, folder);
    file_dialog_.set_name(export_request_.volume + (iso ? "_iso" : "_silhouettes") + k.extension);
  } else if (purpose == FilePurpose::ToolSave) {
    file_dialog_.open(tool_save_.title + " (" + tool_save_.extension + ")", ui::FileDialog::Mode::Save,
                      {tool_save_.extension}, folder);
    file_dialog_.set_name(tool_save_.name);
  } else if (purpose == FilePurpose::OpenLog)
    file_dialog_.open("Open a command log (.jsonl): it is replayed", ui::FileDialog::Mode::Open, kLogExtensions,
                      folder);
  else {
    file_dialog_.open("Save the scene as a command log (.jsonl)", ui::FileDialog::Mode::Save, kLogExtensions, folder);
    // The document's own name (a command log's extension), or "untitled.jsonl".
    const fs::path doc = session_.document();
    file_dialog_.set_name((doc.empty() ? std::string("untitled") : doc.stem().string()) + ".jsonl");
  }
}

void App::handle_menu(ui::MenuAction action) {
  using A = ui::MenuAction;
  // clang-format off
  switch (action) {
    case A::New: request(Pending::New); break;
    case A::Open: request(Pending::Open); break;
    case A::Save: save_or_ask(); break;
    case A::SaveAs: ask_file(FilePurpose::SaveLog); break;
    case A::Quit: request(Pending::Quit); break;
    case A::Undo: if (session_.history().can_undo()) background_.start_history(session_.history().applied() - 1); break;
    case A::Redo: background_.start_history(session_.history().applied() + 1); break;
    case A::FrameSelected: if (!tools_.owns_mouse()) frame_selected(); break;
    case A::FrameAll: if (!tools_.owns_mouse()) nav_.frame(session_.scene().bounds(), view_.viewport); break;
    case A::About: show_about_ = true; break;
    case A::Keys: show_keys_ = true; break;
    case A::SelectTool: tools_.set_active(Toolbox::kSelect); break;
    case A::SketchTool: tools_.set_active(Toolbox::kSketch); break;
    case A::PressTool: tools_.set_active(Toolbox::kPress); break;
    case A::Screenshot: screenshot_requested_ = true; break;
    case A::Delete: handle_scene({ui::SceneRequest::Kind::Remove, selected_}); break;
    case A::ToggleTimingOverlay:
    case A::TogglePlayback: ui::apply_view_action(toggles_, action); break;
    case A::InsertKeyframe:
    case A::DeleteKeyframe:
    case A::FramePrev:
    case A::FrameNext:
    case A::FrameStart:
    case A::FrameEnd:
    case A::RecordAnimation: anim_.handle_action(action, view_.viewport); break;
    case A::None: break;
  }
  // clang-format on
}

void App::handle_scene(const ui::SceneRequest& r) {
  using K = ui::SceneRequest::Kind;
  if (r.kind == K::Select || r.kind == K::Frame) selected_ = r.name;
  if (r.kind == K::Frame) frame_selected();
  if (r.kind == K::ToggleVisible || r.kind == K::ToggleRender) {  // the eye or camera icon: one step in the log
    const core::SceneObject* o = session_.scene().find(r.name);
    const core::VolumeObject* v = session_.scene().find_volume(r.name);
    core::ObjectVisibilityParams p{r.name, {}, {}};
    if (r.kind == K::ToggleVisible && (o || v)) p.viewport = !(o ? o->visible : v->visible);
    if (r.kind == K::ToggleRender && (o || v)) p.render = !(o ? o->render_visible : v->render_visible);
    if (p.viewport || p.render) session_.execute(core::ObjectVisibilityCommand::schema().to_json(p));
  }
  if (r.kind == K::Load) ask_file(FilePurpose::LoadMesh);
  if (r.kind == K::Transform) {  // one Scene panel field left after an edit: one step
    core::ObjectTransformParams p{r.name, {}, {}, {}};
    (r.field == "translate" ? p.translate : r.field == "rotate_deg" ? p.rotate_deg : p.scale) = r.value;
    session_.execute(core::ObjectTransformCommand::schema().to_json(p));
  }
  if (r.kind == K::AddPrimitive) {
    core::ScenePrimitiveParams p;
    p.kind = r.name;
    p.object.name = session_.scene().unique_name(r.name);
    const nlohmann::json line = core::ScenePrimitiveCommand::schema().to_json(p);
    tool_ctx_.defer("Adding a " + r.name, [this, line] {
      if (session_.execute(line)) selected_ = line["name"];
    });
  }
  if (r.kind == K::AddText) {
    core::SceneTextParams p = text_params_;
    p.object.name = session_.scene().unique_name("text");
    const nlohmann::json line = core::SceneTextCommand::schema().to_json(p);
    tool_ctx_.defer("Adding text", [this, line] {
      if (session_.execute(line)) selected_ = line["name"];
    });
  }
  if (r.kind == K::Remove && session_.scene().find_volume(r.name)) {
    if (session_.execute(core::VolumeRemoveCommand::schema().to_json({r.name}))) selected_.clear();
    return;
  }
  if (r.kind == K::Remove && !r.name.empty() && session_.has_command("scene.remove") &&
      session_.execute(core::SceneRemoveCommand::schema().to_json({r.name})))
    selected_.clear();
}

void App::handle_file(const fs::path& chosen) {
  fs::path path = chosen;
  {
    std::error_code ec;
    const bool writes = file_purpose_ == FilePurpose::SaveLog || file_purpose_ == FilePurpose::ExportVolume ||
                        file_purpose_ == FilePurpose::ToolSave;
    (writes ? last_write_folder_ : last_read_folder_) = fs::is_directory(chosen, ec) ? chosen : chosen.parent_path();
  }
  if (file_purpose_ == FilePurpose::OpenLog || file_purpose_ == FilePurpose::SaveLog) document_chosen_ = true;
  switch (std::exchange(file_purpose_, FilePurpose::None)) {  // reset first: go_on(Open) asks for a file again
    case FilePurpose::LoadMesh: {
      load_ignore_loose_ = file_dialog_.option();
      if (core::is_volume_path(path)) {  // a NIfTI / DICOM / .inv3 file or a folder: prepared on a worker thread
        volumes_.start_load(path);
        break;
      }
      core::SceneLoadParams p;
      p.path = path.string();
      p.loose = load_ignore_loose_ ? "ignore" : "refuse";
      p.object.name = session_.scene().unique_name(path.stem().string());
      const nlohmann::json line = core::SceneLoadCommand::schema().to_json(p);
      tool_ctx_.defer("Loading " + path.filename().string(), [this, line] {
        if (!session_.execute(line)) return;
        const nlohmann::json stats = session_.history().last_executed().stats();
        auto counted = [](long long n, const char* noun) {
          return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
        };
        const long long points = stats.value("ignored_points", 0), lines = stats.value("ignored_lines", 0);
        const std::string name = line["name"];
        if (points || lines)
          messages_.warning(name + ": left out " + counted(points, "point") + " and " + counted(lines, "line") +
                            " of the file");
        if (const long long repeated = stats.value("duplicate_faces", 0))
          messages_.warning(name + ": removed " + counted(repeated, "repeated triangle") + " (a copy of another face)");
        selected_ = line["name"];
        frame_selected();  // a mesh in its own units (mm, km) would otherwise fill or vanish from the view
      });
      break;
    }
    case FilePurpose::OpenLog:
      open_later(path);
      break;
    case FilePurpose::SaveLog:
      if (path.extension() != ".jsonl") path += ".jsonl";
      if (session_.save(path, view_) && prompt_for_ != Pending::None) go_on(prompt_for_);
      break;
    case FilePurpose::ExportVolume:
      if (export_request_.kind)
        tool_ctx_.defer("Exporting " + path.filename().string(), [this, request = export_request_, path] {
          volumes_.export_volume(request.volume, *request.kind, path, view_);
        });
      break;
    case FilePurpose::ToolSave:
      if (!tool_save_.chosen) break;
      if (!core::has_extension(path, tool_save_.extension)) path += tool_save_.extension;
      tool_ctx_.defer("Exporting " + path.filename().string(), [chosen = std::exchange(tool_save_.chosen, nullptr),
                                                                path = fs::absolute(path)] { chosen(path); });
      break;
    case FilePurpose::None:
      break;
  }
}

}  // namespace trispline::editor
