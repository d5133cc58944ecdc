#include "editor/tools/ddm_paint_tool.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include "core/commands/ddm_bake.h"
#include "core/commands/ddm_color.h"
#include "core/commands/ddm_fill.h"
#include "core/commands/ddm_remove.h"
#include "core/mesh/mesh_clip.h"
#include "ui/param_widgets.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/ddm/ddm_tile.h"
#include "core/params/codecs.h"
#include "editor/session/session.h"
#include "gpu/gl/gl_context.h"
#include "ui/ddm_anim_panel.h"
#include "ui/gui_probe.h"
#include "ui/number_field.h"
#include "ui/theme.h"

namespace trispline::editor {

namespace {
// The last ImGui item's rectangle (min x, min y, max x, max y), screen pixels.
glm::vec4 last_item_rect() {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  return {lo.x, lo.y, hi.x, hi.y};
}

constexpr double kRadiusStep = 1.15;  // [ and ] scale the brush radius by this
// The generated tiles (core::make_ddm_tile) the Tile list offers, each with its tooltip.
struct GeneratedTile {
  const char *name, *tip;
};
constexpr GeneratedTile kGeneratedTiles[] = {
    {"thorn", "A bent horn on a round foot (626 vertices; seed Fig. 5.6)"},
    {"chain", "Two interlocked chain links (neighbouring cells overlap, as the seed's chains)"},
    {"hex", "A hexagonal slab filling its cell: use the hex layout (seed Fig. 5.11)"},
    {"flower", "A five-petal flower with the thorn's topology: the thorn's metamorphosis partner (seed Eq. 5.3)"},
    {"hair", "A tuft of 32 thin strands leaning one way (1,088 vertices; seed Fig. 5.10)"},
};

bool deformed(const core::SceneObject& o) { return o.ffd || o.dffd || o.clip; }

// The new layer's colour: the panel's swatch when "Own colour" is on.
std::optional<glm::vec3> layer_color(const DdmPaintToolParams& p) {
  return p.own_color ? std::optional<glm::vec3>(p.color) : std::nullopt;
}

}  // namespace

double ddm_default_tile_size(const core::SceneObject* o) {
  if (!o || !o->rest_mesh || o->rest_mesh->empty()) return 1.0;
  const double d = 0.1 * core::mesh_bounds(*o->rest_mesh).diagonal();
  if (!(d > 0.0) || !std::isfinite(d)) return 1.0;
  const double unit = std::pow(10.0, std::floor(std::log10(d)) - 1.0);
  return std::round(d / unit) * unit;
}

double ddm_default_tile_height(const core::SceneObject* o) {
  const double h = ddm_default_tile_size(o) / 3.0;
  const double unit = std::pow(10.0, std::floor(std::log10(h)) - 1.0);
  return std::round(h / unit) * unit;
}

nlohmann::json ddm_paint_line(const std::string& object, const std::vector<glm::dvec2>& stroke_px,
                              const DdmPaintToolParams& params, bool erase, bool new_layer,
                              const std::optional<core::Camera>& view) {
  core::DdmPaintParams p = params.paint;
  p.object = object;
  p.stroke = stroke_px;
  p.erase = erase;
  p.camera = view;
  p.spec_named = new_layer;  // the new layer's fields are logged only for a new layer
  p.spec.color = layer_color(params);
  return core::DdmPaintCommand::schema().to_json(p);
}

nlohmann::json ddm_fill_line(const std::string& object, const DdmPaintToolParams& params) {
  core::DdmFillParams f{object, params.paint.layer, params.paint.spec};
  f.spec.color = layer_color(params);
  return core::DdmFillCommand::schema().to_json(f);
}

ui::ToolEntry DdmPaintTool::entry() const {
  return {"Tile Paint", "T",
          "Paint geometric tiles (thorns, chains, hexagons…) onto a surface with a brush: drag paints, Ctrl-drag "
          "erases, [ and ] resize the brush; Fill covers the whole surface (seed ch. 5, displacement maps)"};
}

void DdmPaintTool::activate(ToolContext& ctx) { follow_selection(ctx); }

void DdmPaintTool::deactivate(ToolContext&) {
  hover_.reset();
  gesture_.cancel();
  erasing_ = false;
}

void DdmPaintTool::mouse_away() {
  if (!gesture_.drawing()) hover_.reset();
}

void DdmPaintTool::follow_selection(const ToolContext& ctx) {
  // The Object combo follows the selection until the user picks another object there.
  if (ctx.selected.empty() || ctx.selected == followed_selection_) return;
  object_ = followed_selection_ = ctx.selected;
  // Like Blender's active layer: a newly selected object that holds layers brings up its last one, unless the
  // panel's layer is one of its layers already.
  const core::SceneObject* o = ctx.session.scene().find(object_);
  if (o && !o->ddm_layers.empty() && new_layer(ctx)) params_.paint.layer = o->ddm_layers.back()->name;
}

const core::SceneObject* DdmPaintTool::target(const ToolContext& ctx) const {
  const core::SceneObject* o = ctx.session.scene().find(object_);
  return o && o->rest_mesh && !o->rest_mesh->empty() ? o : nullptr;
}

bool DdmPaintTool::new_layer(const ToolContext& ctx) const {
  const core::SceneObject* o = ctx.session.scene().find(object_);
  if (!o) return true;
  return std::none_of(o->ddm_layers.begin(), o->ddm_layers.end(),
                      [&](const auto& l) { return l->name == params_.paint.layer; });
}

void DdmPaintTool::scale_radius(double factor) {
  params_.paint.radius_px = std::clamp(params_.paint.radius_px * factor, kMinRadiusPx, kMaxRadiusPx);
}

void DdmPaintTool::handle_input(const ToolInput& in, ToolContext& ctx) {
  hover_ = in.mouse_px;
  if (ImGui::GetCurrentContext() && !ImGui::GetIO().WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_LEFT_BRACKET)) scale_radius(1.0 / kRadiusStep);
    if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT_BRACKET)) scale_radius(kRadiusStep);
  }
  if (in.left_pressed) {
    follow_selection(ctx);
    erasing_ = params_.paint.erase != in.ctrl;  // Ctrl inverts, as in a Blender brush
  }
  const StrokeGesture::Event event = gesture_.update(in, ctx.view);
  if (ImGui::GetCurrentContext()) draw_brush();
  if (event == StrokeGesture::Event::Ended) commit(ctx);
}

const core::SceneObject* DdmPaintTool::target_or_refuse(ToolContext& ctx, bool existing_layer,
                                                        const std::string& refusal) const {
  const core::SceneObject* o = target(ctx);
  if (o && !(existing_layer && new_layer(ctx))) return o;
  ctx.session.messages().error(refusal);
  return nullptr;
}

void DdmPaintTool::commit(ToolContext& ctx) {
  const std::vector<glm::dvec2> stroke = gesture_.take();
  if (stroke.empty()) return;
  const core::SceneObject* o =
      target_or_refuse(ctx, false, "ddm.paint: choose the object to paint on (select it, or the Tool panel's Object)");
  if (!o) return;
  const nlohmann::json line = ddm_paint_line(o->name, stroke, params_, erasing_, new_layer(ctx), gesture_.view());
  ctx.execute_deferred((erasing_ ? "Erasing tiles on " : "Painting tiles on ") + o->name, line);
}

void DdmPaintTool::fill(ToolContext& ctx) {
  const core::SceneObject* o =
      target_or_refuse(ctx, false, "ddm.fill: choose the object to fill (select it, or the Tool panel's Object)");
  if (!o) return;
  const nlohmann::json line = ddm_fill_line(o->name, params_);
  const std::string what = "Filling " + o->name + " with " + params_.paint.spec.tiles.front();
  ctx.execute_long(line, what, "Fill");
}

void DdmPaintTool::bake(ToolContext& ctx) {
  const core::SceneObject* o =
      target_or_refuse(ctx, true, "ddm.bake: paint or fill the layer '" + params_.paint.layer + "' first");
  if (!o) return;
  const std::string name = ctx.session.scene().unique_name(o->name + "." + params_.paint.layer);
  const nlohmann::json line =
      core::DdmBakeCommand::schema().to_json({o->name, params_.paint.layer, name, std::nullopt});
  const std::string what = "Baking " + o->name + "/" + params_.paint.layer;
  ctx.execute_long(line, what, "Bake");
}

void DdmPaintTool::remove_layer(ToolContext& ctx) {
  const core::SceneObject* o =
      target_or_refuse(ctx, true, "ddm.remove: '" + params_.paint.layer + "' is not a layer of the selected object");
  if (!o) return;
  const nlohmann::json line = core::DdmRemoveCommand::schema().to_json({o->name, params_.paint.layer});
  ctx.session.execute(line);  // undoable; errors go to the Log panel
}

std::string DdmPaintTool::hint() const {
  if (gesture_.drawing()) return erasing_ ? "Release to erase the tiles under the stroke" : "Release to paint tiles";
  if (object_.empty()) return "Select the object to paint tiles on";
  return "Drag over " + object_ + " to paint tiles on '" + params_.paint.layer + "'; Ctrl-drag erases; [ ] brush size";
}

void DdmPaintTool::draw_brush() const {
  if (!hover_) return;
  const ImGuiIO& io = ImGui::GetIO();
  // Viewport pixels are framebuffer pixels; ImGui draws in window coordinates.
  const float sx = io.DisplayFramebufferScale.x > 0 ? io.DisplayFramebufferScale.x : 1.0f;
  const float sy = io.DisplayFramebufferScale.y > 0 ? io.DisplayFramebufferScale.y : 1.0f;
  auto screen = [&](glm::dvec2 p) { return ImVec2(float(p.x) / sx, float(p.y) / sy); };
  const bool erase = gesture_.drawing() ? erasing_ : params_.paint.erase != io.KeyCtrl;
  const ImU32 line = erase ? IM_COL32(255, 95, 80, 235) : IM_COL32(255, 205, 90, 235);
  const ImU32 swath = erase ? IM_COL32(255, 95, 80, 45) : IM_COL32(255, 205, 90, 45);
  const float r = float(params_.paint.radius_px) / sx;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  if (gesture_.drawing() &&
      !gesture_.points().empty()) {  // what the stroke covers so far: a disc per sample, a band per segment
    // Not a polyline 2r thick: ImGui mitres its joints, and where a stroke turns sharply the mitre shoots far out of
    // the swath as a big translucent quad.
    dl->AddCircleFilled(screen(gesture_.points().front()), r, swath, 32);
    for (std::size_t i = 1; i < gesture_.points().size(); ++i) {
      const ImVec2 a = screen(gesture_.points()[i - 1]), b = screen(gesture_.points()[i]);
      const float dx = b.x - a.x, dy = b.y - a.y, len = std::sqrt(dx * dx + dy * dy);
      if (len > 0.5f) {
        const ImVec2 n(-dy / len * r, dx / len * r);
        const ImVec2 quad[4] = {
            {a.x + n.x, a.y + n.y}, {b.x + n.x, b.y + n.y}, {b.x - n.x, b.y - n.y}, {a.x - n.x, a.y - n.y}};
        dl->AddConvexPolyFilled(quad, 4, swath);
      }
      dl->AddCircleFilled(b, r, swath, 32);
    }
  }
  dl->AddCircle(screen(*hover_), r, line, 48, 1.5f);
  dl->AddCircle(screen(*hover_), 1.5f, line, 8, 1.5f);
}

void DdmPaintTool::decorate(gpu::ViewOptions& options) const {
  if (!gesture_.drawing()) return;
  gpu::ScreenStroke& stroke = options.add_stroke(gesture_.points());
  stroke.width_px = std::min(stroke.width_px, 2.0f);
  if (erasing_) stroke.color = {1.0f, 0.25f, 0.2f, 1.0f};
}

void DdmPaintTool::draw_layer_combo(ToolContext& ctx, const core::SceneObject* o) {
  const bool fresh = new_layer(ctx);
  const std::string shown = fresh ? params_.paint.layer + "  (new)" : params_.paint.layer;
  if (ImGui::BeginCombo("Layer", shown.c_str())) {
    if (o)
      for (const auto& l : o->ddm_layers) {
        char label[160];
        std::snprintf(label, sizeof label, "%s  (%zu tiles)", l->name.c_str(), l->instances.size());
        if (ImGui::Selectable(label, l->name == params_.paint.layer)) params_.paint.layer = l->name;
      }
    if (ImGui::Selectable("New layer…", false)) {
      std::string name = "tiles";
      for (int i = 1;
           o && std::any_of(o->ddm_layers.begin(), o->ddm_layers.end(), [&](const auto& l) { return l->name == name; });
           ++i) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "tiles.%03d", i);
        name = buf;
      }
      params_.paint.layer = name;
    }
    ImGui::EndCombo();
  }
  ui::tooltip(
      "The tile layer the brush paints on: one of the object's layers, or a new one, made by the first stroke "
      "(or by Fill) with the settings below");
  if (fresh) {
    ImGui::InputText("Name", &params_.paint.layer);
    ui::tooltip("Name of the new layer (unique per object)");
  }
}

void DdmPaintTool::draw_layer_color(ToolContext& ctx, const core::SceneObject& o, const core::DdmLayer& l) {
  if (!color_editing_) layer_color_ = l.color.value_or(o.color);  // follows undo / redo unless being dragged
  ImGui::ColorEdit3("Layer colour", &layer_color_.x, ImGuiColorEditFlags_NoInputs);
  color_editing_ = ImGui::IsItemActive();
  ui::tooltip(l.color ? "The layer's own colour: one ddm.color when you let go"
                      : "The object's colour; edit to give the "
                        "layer its own (one ddm.color)");
  if (ImGui::IsItemDeactivatedAfterEdit()) set_layer_color(ctx, layer_color_);
  if (l.color) {
    ImGui::SameLine();
    if (ImGui::SmallButton("Object's")) set_layer_color(ctx, std::nullopt);
    ui::tooltip("Draw the tiles in the object's colour again");
  }
}

void DdmPaintTool::set_layer_color(ToolContext& ctx, std::optional<glm::vec3> color) {
  const core::SceneObject* o = target(ctx);
  if (!o || new_layer(ctx)) return;
  const nlohmann::json line = core::DdmColorCommand::schema().to_json({o->name, params_.paint.layer, color});
  ctx.session.execute(line);  // undoable; errors go to the Log panel
}

// Tile size or height: ddm.fill's declared size field (ui::size_param_widget); "auto" until typed for the object,
// limited to what the object takes (amber, the reason in its tooltip and the Log). `*value`: the layer spec's.
void DdmPaintTool::draw_size_field(ToolContext& ctx, const core::SceneObject* o, const char* name, double* value,
                                   double diag, std::map<std::string, double>& typed, ui::SizeFieldState& state) {
  const bool own = defaults_for_ == "\x01given" || (o && typed.count(o->name));
  double field = own ? *value : 0.0;  // ≤ 0: follows the object, shown as *value
  const double before = field;
  const std::string limited = ui::size_param_widget(core::ddm_layer_schema(true), name, &field, diag, *value, state,
                                                    std::string("ddm.") + name);
  if (!limited.empty())
    ctx.session.messages().warning(std::string(name == std::string("height") ? "Tile height " : "Tile size ") +
                                   ui::short_number(state.typed) + ": " + limited);
  if (field > 0.0 && field != before) {
    *value = field;
    if (o) typed[o->name] = field;  // the user's value for this object, kept when it is reselected
  }
}

void DdmPaintTool::draw_new_layer_fields(ToolContext& ctx, const core::SceneObject* o) {
  core::DdmLayerSpec& spec = params_.paint.spec;
  const double diag = o && o->rest_mesh && !o->rest_mesh->empty() ? core::mesh_bounds(*o->rest_mesh).diagonal() : 0.0;
  std::string& tile = spec.tiles.front();  // the panel makes one-tile layers
  const bool generated = core::is_generated_ddm_tile(tile);
  const bool open = ImGui::BeginCombo("Tile", generated ? tile.c_str() : "file");
  ui::probe::item("ddm.tile");
  if (open) {
    for (const GeneratedTile& g : kGeneratedTiles) {
      if (ImGui::Selectable(g.name, tile == g.name)) tile = g.name;
      ui::probe::item(std::string("ddm.tile.") + g.name);
      ui::tooltip(g.tip);
    }
    if (ImGui::Selectable("file", !generated)) tile = file_tile_;
    ui::probe::item("ddm.tile.file");
    ui::tooltip(
        "Any mesh (OBJ, PLY, glTF, Collada, FBX) as a tile, fitted into the cell by its bounding box; a "
        "textured file keeps its materials and textures on every tile (seed Fig. 5.12)");
    ImGui::EndCombo();
  }
  if (!core::is_generated_ddm_tile(tile)) {
    if (ImGui::InputText("Tile file", &file_tile_)) tile = file_tile_;
    ui::probe::item("ddm.tile_file");
    ui::tooltip(
        "Path of a mesh file (OBJ / PLY / glTF / Collada / FBX); x, y span the cell, the up axis is the height; "
        "its materials and textures come along");
    ui::param_widget(core::ddm_layer_schema(true), "tile_up", spec);
    bool play = spec.tile_clip.has_value();
    if (ImGui::Checkbox("Play its animation", &play)) {
      if (play)
        spec.tile_clip = core::kAllClips;
      else
        spec.tile_clip.reset();
    }
    ui::probe::item("ddm.tile_clip");
    ui::tooltip(
        "Articulated tiles (seed Fig. 5.13): every tile plays the glTF file's animations (all of them together), "
        "looping from time 0; press Play in the Timeline");
  } else {
    spec.tile_clip.reset();  // a generated tile has no clip
  }
  int layout = static_cast<int>(spec.layout);
  if (ImGui::Combo("Layout", &layout, "rect\0hex\0brick\0")) spec.layout = static_cast<core::DdmLayout>(layout);
  ui::tooltip(
      "Cells per chart: rect n x m; hex rows 0.75 apart, odd rows shifted (seed Fig. 5.11); brick odd rows "
      "shifted by half a cell (Fig. 5.12). hex and brick need n >= 2");
  int by_size = spec.counts ? 0 : 1;
  if (ImGui::Combo("Tiles by", &by_size, "counts\0size\0")) {
    if (by_size) {
      counts_ = spec.counts.value_or(counts_), spec.counts.reset();
      spec.tile_size = tile_size_ > 0.0 ? tile_size_ : ddm_default_tile_size(o);
    } else {
      tile_size_ = spec.tile_size.value_or(tile_size_), spec.tile_size.reset();
      spec.counts = counts_;
    }
  }
  ui::tooltip(
      "size: tiles of one world size over the whole surface (each chart gets as many as fit); counts: the "
      "same n x m cells on every chart (the seed's parametric layouts)");
  if (spec.counts) {
    int counts[2] = {spec.counts->x, spec.counts->y};
    if (ImGui::InputInt2("Counts", counts)) spec.counts = glm::max(glm::ivec2(counts[0], counts[1]), glm::ivec2(1));
    ui::tooltip("Cells along u and v of every chart (a limit base has three charts per triangle)");
  } else {
    if (!spec.tile_size) spec.tile_size = ddm_default_tile_size(o);
    draw_size_field(ctx, o, "tile_size", &*spec.tile_size, diag, typed_tile_size_, tile_size_state_);
  }
  draw_size_field(ctx, o, "height", &spec.height, diag, typed_height_, height_state_);
  const bool teapot = o && o->source == "primitive:teapot";
  const bool uvs = o && o->rest_mesh && !o->rest_mesh->uvs.empty();
  using Base = core::DdmBaseKind;
  if (ImGui::BeginCombo("Base", spec.base ? core::ddm_base_name(*spec.base) : "(the object's)")) {
    if (ImGui::Selectable("limit", spec.base == Base::limit)) spec.base = Base::limit;
    ui::tooltip("The Loop limit surface of the mesh, three charts per triangle: tiles cross faces without cracks");
    if (teapot && ImGui::Selectable("teapot_body", spec.base == Base::teapot_body)) spec.base = Base::teapot_body;
    if (teapot) ui::tooltip("The teapot's 8 Bezier body patches as one chart around the pot");
    if (uvs && ImGui::Selectable("uv", spec.base == Base::uv)) spec.base = Base::uv;
    if (uvs) ui::tooltip("The mesh's texture coordinates (one chart, the UV square; the seed's way)");
    if (ImGui::Selectable("auto_uv", spec.base == Base::auto_uv)) spec.base = Base::auto_uv;
    ui::tooltip(
        "Automatic texture coordinates: charts cut at seams and flattened (CGAL LSCM) at one texel density, "
        "so tiles come out of even size on any mesh");
    ImGui::EndCombo();
  }
  ImGui::Checkbox("Own colour", &params_.own_color);
  ui::tooltip("Draw and export the tiles in a colour of their own instead of the object's");
  if (params_.own_color) {
    ImGui::SameLine();
    ImGui::ColorEdit3("##tile colour", &params_.color.x, ImGuiColorEditFlags_NoInputs);
    ui::tooltip("The layer's colour (linear RGB), used by the viewport, scene.glb and ddm.bake");
  }
}

void DdmPaintTool::apply_object_defaults(const core::SceneObject* o) {
  if (!o || defaults_for_ == "\x01given" || defaults_for_ == o->name) return;
  defaults_for_ = o->name;
  core::DdmLayerSpec& spec = params_.paint.spec;
  spec.base = core::ddm_default_base(*o);
  // Sizes follow the object (a teapot's tiles would be spikes on an apple), unless the user typed them for it.
  const double tile = ddm_default_tile_size(o);
  const auto typed_tile = typed_tile_size_.find(o->name);
  if (!spec.counts) spec.tile_size = typed_tile != typed_tile_size_.end() ? typed_tile->second : tile;
  const auto typed_height = typed_height_.find(o->name);
  spec.height = typed_height != typed_height_.end() ? typed_height->second : ddm_default_tile_height(o);
}

void DdmPaintTool::draw_estimate(const core::SceneObject* o) {
  if (!o || !o->rest_mesh) return;
  core::DdmFillParams f{o->name, params_.paint.layer, params_.paint.spec};
  char mesh[32];
  std::snprintf(mesh, sizeof mesh, "%p", static_cast<const void*>(o->rest_mesh.get()));
  const std::string key = o->name + mesh + core::DdmFillCommand::schema().to_json(f).dump();
  if (key != estimate_key_) {  // only when a field, the object or its mesh changed: a few ms on large meshes
    estimate_key_ = key;
    estimate_error_.clear();
    try {
      estimate_ = core::ddm_fill_estimate(*o, params_.paint.spec);
    } catch (const std::exception& e) {
      estimate_ = {};
      estimate_error_ = e.what();
    }
  }
  ImGui::PushTextWrapPos(0.0f);
  if (!estimate_error_.empty()) {
    ImGui::TextColored(ui::colors::warning, "%s", estimate_error_.c_str());
  } else {
    ImGui::TextColored(ui::colors::dim, "Fill: %s%zu tiles, %zu tile vertices (%zu chart%s)",
                       estimate_.upper_bound ? "up to " : "", estimate_.cells, estimate_.tile_vertices,
                       estimate_.charts, estimate_.charts == 1 ? "" : "s");
    ui::tooltip(estimate_.upper_bound ? "Counted from the layout before the tiles outside the UV islands are pruned"
                                      : "Counted from the layout Fill uses");
  }
  ImGui::PopTextWrapPos();
  ui::probe::value("ddm.estimate_tiles", estimate_error_.empty() ? std::to_string(estimate_.cells) : "");
  ui::probe::value("ddm.estimate_vertices", estimate_error_.empty() ? std::to_string(estimate_.tile_vertices) : "");
  ui::probe::value("ddm.estimate_error", estimate_error_);
}

void DdmPaintTool::draw_fill_prompt(ToolContext& ctx) {
  const char* id = "Large fill";
  if (!ImGui::IsPopupOpen(id)) ImGui::OpenPopup(id);
  ui::probe::value("ddm.fill_prompt", "open");
  if (ImGui::BeginPopupModal(id, nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::Text("Fill makes %s%zu tiles, %zu tile vertices.", estimate_.upper_bound ? "up to " : "", estimate_.cells,
                estimate_.tile_vertices);
    ImGui::TextColored(ui::colors::dim,
                       "More than %zu on this renderer: drawing may be slow. A larger tile size "
                       "makes fewer.",
                       ask_budget_);
    ImGui::Spacing();
    bool done = false;
    if (ImGui::Button("Fill anyway", ImVec2(120, 0))) fill(ctx), done = true;
    ui::probe::item("ddm.fill_anyway");
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(120, 0)) || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false))
      done = true;
    ui::probe::item("ddm.fill_cancel");
    if (done) {
      ask_budget_ = 0;
      ui::probe::value("ddm.fill_prompt", "");
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
}

void DdmPaintTool::draw_panel(ToolContext& ctx) {
  follow_selection(ctx);
  const core::Scene& scene = ctx.session.scene();
  if (ImGui::BeginCombo("Object", object_.empty() ? "(none)" : object_.c_str())) {
    for (const core::SceneObject& o : scene.objects()) {
      const std::string label = deformed(o) ? o.name + "  (deformed)" : o.name;
      if (ImGui::Selectable(label.c_str(), o.name == object_)) object_ = o.name;
    }
    ImGui::EndCombo();
  }
  const core::SceneObject* o = scene.find(object_);
  ImGui::PushTextWrapPos(0.0f);  // long warnings wrap inside the panel instead of running off its edge
  if (o && deformed(*o))
    ImGui::TextColored(ui::colors::warning, "%s is deformed (lattice, split or clip): tiles need an undeformed object.",
                       object_.c_str());
  ImGui::PopTextWrapPos();
  apply_object_defaults(o);
  draw_layer_combo(ctx, o);

  ImGui::Separator();
  ImGui::TextUnformatted("Layer settings");
  if (!new_layer(ctx)) {
    ImGui::PushTextWrapPos(0.0f);  // the panel is narrow: wrap the layer's summary instead of clipping it
    const core::SceneObject& obj = *o;
    for (const auto& l : obj.ddm_layers)
      if (l->name == params_.paint.layer) {
        char cells[64];
        if (l->tile_size)
          std::snprintf(cells, sizeof cells, "tile size %.3g", *l->tile_size);
        else
          std::snprintf(cells, sizeof cells, "%dx%d", l->counts.x, l->counts.y);
        ImGui::TextColored(ui::colors::dim, "%s: %s, %s %s, %zu tiles, height %.3g, %s base", l->name.c_str(),
                           l->tile_sources.empty() ? "?" : l->tile_sources.front().c_str(),
                           core::ddm_layout_name(l->layout), cells, l->instances.size(), l->height,
                           core::ddm_base_name(l->base));
        ui::probe::value("ddm.layer_tiles", std::to_string(l->instances.size()));
        draw_layer_color(ctx, obj, *l);
      }
    ImGui::TextColored(ui::colors::dim, "The brush keeps the layer's own; these apply to Fill (which replaces it).");
    ImGui::PopTextWrapPos();
  }
  draw_new_layer_fields(ctx, o);
  draw_estimate(o);

  ImGui::Separator();
  ImGui::TextUnformatted("Brush");
  const double r_min = kMinRadiusPx, r_max = kMaxRadiusPx;
  ImGui::SliderScalar("Radius (px)", ImGuiDataType_Double, &params_.paint.radius_px, &r_min, &r_max, "%.0f",
                      ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  ui::tooltip(
      "Brush radius in viewport pixels: a cell is painted when its centre on the surface is this close to the "
      "stroke and visible. [ and ] resize it");
  ImGui::Checkbox("Erase", &params_.paint.erase);
  ui::tooltip("Remove the tiles under the stroke instead of adding them (Ctrl held at mouse-down inverts this)");

  ImGui::Spacing();
  ImGui::BeginDisabled(!target(ctx));
  if (ImGui::Button("Fill")) {
    // Above the budget, ask first (the renderer is asked only then: tests without a GL context never get here).
    const std::size_t n = estimate_error_.empty() ? estimate_.tile_vertices : 0;
    const std::size_t budget = n <= kAskFillVerticesSoftware ? 0
                               : gpu::is_software_renderer() ? kAskFillVerticesSoftware
                                                             : kAskFillVertices;
    if (budget > 0 && n > budget)
      ask_budget_ = budget;
    else
      fill(ctx);
  }
  ui::probe::item("ddm.fill");
  fill_rect_ = last_item_rect();
  ui::tooltip("Cover the whole surface with the layer settings above: one ddm.fill (replaces a layer of that name)");
  ImGui::EndDisabled();
  if (ask_budget_ > 0) draw_fill_prompt(ctx);
  ImGui::SameLine();
  ImGui::BeginDisabled(!target(ctx) || new_layer(ctx));
  if (ImGui::Button("Bake")) bake(ctx);
  bake_rect_ = last_item_rect();
  ui::tooltip("Add the layer's tiles as an ordinary mesh object (for export): one ddm.bake");
  ImGui::SameLine();
  if (ImGui::Button("Remove")) remove_layer(ctx);
  remove_rect_ = last_item_rect();
  ui::tooltip("Delete the layer (tiles, maps and animation): one ddm.remove, Ctrl+Z brings it back");
  ImGui::EndDisabled();
  draw_map_export(ctx);

  // Animation of a layer (seed §5.4.2): metamorphosis, turn, scale and w keys and texture-space offset, one
  // ddm.animate per click.
  ImGui::Spacing();
  const bool animation_open = ImGui::CollapsingHeader("Animation");
  ui::probe::item("ddm.animation");
  if (animation_open) {
    const core::SceneObject* o = target(ctx);
    std::vector<ui::DdmLayerInfo> layers;
    if (o)
      for (const auto& l : o->ddm_layers)
        layers.push_back({l->name, l->tile_sources.empty() ? "" : l->tile_sources.front(), l->instances.size(),
                          l->mesh ? l->mesh->vertex_count() : 0, l->animated()});
    const ui::DdmAnimPanelResult r = ui::draw_ddm_anim_panel(anim_params_, anim_layer_, o ? o->name : "", layers);
    if (r.line) ctx.execute_deferred("Animating tiles of " + o->name, *r.line);
  }

  ImGui::Spacing();
  ImGui::Separator();
  ImGui::TextWrapped(
      "Left-drag over the object to paint tiles on the cells under the brush (one undoable step per stroke; a click "
      "paints a dab). Ctrl-drag erases. Cells on the far side or hidden behind other objects are left alone.");
}

}  // namespace trispline::editor
