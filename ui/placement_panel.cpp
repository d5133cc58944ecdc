#include "ui/placement_panel.h"

#include "ui/number_field.h"
#include "ui/theme.h"

#include <imgui.h>

#include <algorithm>

namespace trispline::ui {

const char* axis_name(int axis) {
  static const char* names[] = {"x", "y", "z"};
  return names[std::clamp(axis, 0, 2)];
}

namespace {

constexpr double kExtentMin = 0.01, kExtentMax = 1.0;

void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// Label in the left column, widget filling the rest of the row (Blender's property layout).
void row_label(const char* label) {
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted(label);
  ImGui::SameLine(110.0f);
  ImGui::SetNextItemWidth(-1);
}

}  // namespace

void add_placement_extras(const PlacementParams& p, nlohmann::json& line) {
  if (const std::vector<double> w = profile_samples(p.width_profile); !w.empty()) line["width_profile"] = w;
  if (const std::vector<double> h = profile_samples(p.height_profile); !h.empty()) line["height_profile"] = h;
  if (p.springs_on) {
    const core::SpringParams& sp = p.springs;
    line["springs"] = {{"stiffness", sp.stiffness},         {"damping", sp.damping},
                       {"mass", sp.mass},                   {"threshold_deg", sp.angle_threshold_deg},
                       {"neighbourhood", sp.neighbourhood}, {"max_steps", sp.max_steps},
                       {"rest_length", sp.rest_length_initial ? "initial" : "zero"}};
  }
  if (p.extent != 1.0) line["extent"] = p.extent;
}

void read_placement_extras(const nlohmann::json& j, PlacementParams& p) {
  auto numbers = [](const nlohmann::json& a) {
    std::vector<double> out;
    for (const auto& x : a) out.push_back(x.is_number() ? x.get<double>() : 1.0);
    return out;
  };
  p.width_profile = j.contains("width_profile") ? curve_from_samples(numbers(j["width_profile"])) : flat_curve();
  p.height_profile = flat_curve();
  if (j.contains("height_profile") && j["height_profile"].is_array() && !j["height_profile"].empty()) {
    const nlohmann::json& h = j["height_profile"];
    p.height_profile = curve_from_samples(numbers(h[0].is_array() ? h[0] : h));
  }
  p.springs_on = j.contains("springs") && j["springs"].is_object();
  p.springs = core::SpringParams{};
  if (p.springs_on) {
    const nlohmann::json& s = j["springs"];
    core::SpringParams& sp = p.springs;
    sp.stiffness = s.value("stiffness", sp.stiffness);
    sp.damping = s.value("damping", sp.damping);
    sp.mass = s.value("mass", sp.mass);
    sp.angle_threshold_deg = s.value("threshold_deg", sp.angle_threshold_deg);
    sp.neighbourhood = s.value("neighbourhood", sp.neighbourhood);
    sp.max_steps = s.value("max_steps", sp.max_steps);
    sp.rest_length_initial = s.value("rest_length", std::string("zero")) == "initial";
  }
  p.extent = j.value("extent", 1.0);
}

PlacementPanelResult draw_placement_panel(PlacementParams& p, std::string& object,
                                          const std::vector<std::string>& objects) {
  PlacementPanelResult r;
  auto done = [&] { r.committed |= ImGui::IsItemDeactivatedAfterEdit(); };

  row_label("Object");
  if (ImGui::BeginCombo("##object", object.empty() ? "(choose)" : object.c_str())) {
    for (const std::string& name : objects) {
      if (ImGui::Selectable(name.c_str(), name == object) && name != object) {
        object = name;
        r.object_changed = true;
      }
    }
    ImGui::EndCombo();
  }
  tooltip("The object to place along the stroke (defaults to the selected object)");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Volume");
  ImGui::Separator();
  row_label("Half-width");
  drag_scalar("##width", ImGuiDataType_Double, &p.width, 0.002f, nullptr, nullptr, "%.3f");
  done();
  tooltip("d: half-width of the band around the stroke (C(u) +- d N(u)), world units");
  p.width = std::max(p.width, 1e-4);
  row_label("Height");
  drag_scalar("##height", ImGuiDataType_Double, &p.height, 0.002f, nullptr, nullptr, "%.3f");
  done();
  tooltip("h: height of the deformation volume above the contact surface, world units");
  p.height = std::max(p.height, 1e-4);
  row_label("Type");
  int volume = p.offset_volume ? 1 : 0;
  if (ImGui::Combo("##volume", &volume, "extrude\0offset\0")) {
    p.offset_volume = volume == 1;
    r.committed = true;
  }
  tooltip(
      "extrude: layers along the view direction (Eq. 2.3)\n"
      "offset: layers along the contact surface normals (Eq. 2.4)");

  row_label("Extent");
  ImGui::SliderScalar("##extent", ImGuiDataType_Double, &p.extent, &kExtentMin, &kExtentMax, "%.3f");
  done();
  tooltip(
      "Fraction of the path the object covers along u, in (0, 1] (1 = the whole stroke). Below 1 the object\n"
      "leaves room to walk along the path: key its u offset in the Timeline (seed section 2.4.3)");
  p.extent = std::clamp(p.extent, kExtentMin, kExtentMax);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Width profile d(u)");
  ImGui::Separator();
  r.committed |= curve_editor("width_profile", p.width_profile,
                              "Width factor along the stroke: the band is C(u) +- d*factor(u)*N(u) (seed Eq. 2.5)",
                              70.0f);
  ImGui::TextColored(colors::dim, "Height profile h(u)");
  ImGui::Separator();
  r.committed |= curve_editor("height_profile", p.height_profile,
                              "Height factor along the stroke: the volume is h*factor(u) tall (seed Eq. 2.5)", 70.0f);

  ImGui::Spacing();
  if (ImGui::CollapsingHeader("Contact springs")) {
    if (ImGui::Checkbox("Relax the contact surface", &p.springs_on)) r.committed = true;
    tooltip(
        "Mass-spring contact surface (seed section 2.3.2): control points move along their column until the\n"
        "surface is smooth, never below the scene, so the object bridges gaps instead of sagging into them");
    ImGui::BeginDisabled(!p.springs_on);
    core::SpringParams& sp = p.springs;
    row_label("Stiffness");
    drag_scalar("##k", ImGuiDataType_Double, &sp.stiffness, 1.0f, nullptr, nullptr, "%.1f");
    done();
    tooltip("k > 0: spring stiffness (force per world unit); default 100");
    row_label("Damping");
    drag_scalar("##rho", ImGuiDataType_Double, &sp.damping, 0.5f, nullptr, nullptr, "%.1f");
    done();
    tooltip("rho >= 0: damping (force per unit velocity); >= sqrt(8 k M) is critically damped; default 30");
    row_label("Mass");
    drag_scalar("##mass", ImGuiDataType_Double, &sp.mass, 0.01f, nullptr, nullptr, "%.3f");
    done();
    tooltip("M > 0: mass of each control point (mass units); default 1");
    row_label("Threshold");
    drag_scalar("##thr", ImGuiDataType_Double, &sp.angle_threshold_deg, 0.05f, nullptr, nullptr, "%.2f deg");
    done();
    tooltip("Roughness threshold in (0, 180) degrees: points whose neighbouring normals differ more move; default 2");
    row_label("Neighbourhood");
    drag_int("##nbh", &sp.neighbourhood, 0.1f, -1, 64);
    done();
    tooltip("Grid steps around rough points that may move; -1 = every point moves (default)");
    row_label("Max steps");
    drag_int("##steps", &sp.max_steps, 50.0f, 0, 1000000);
    done();
    tooltip("Integration steps at most, [0, 1000000]; default 20000");
    row_label("Rest length");
    int rest = sp.rest_length_initial ? 1 : 0;
    if (ImGui::Combo("##rest", &rest, "zero\0initial\0")) {
      sp.rest_length_initial = rest == 1;
      r.committed = true;
    }
    tooltip("zero: springs pull neighbours together (the seed); initial: springs keep the starting distances");
    sp.stiffness = std::max(sp.stiffness, 1e-3);
    sp.mass = std::max(sp.mass, 1e-4);
    sp.damping = std::max(sp.damping, 0.0);
    sp.angle_threshold_deg = std::clamp(sp.angle_threshold_deg, 0.01, 179.0);
    sp.max_steps = std::clamp(sp.max_steps, 0, 1000000);
    sp.neighbourhood = std::max(sp.neighbourhood, -1);
    ImGui::EndDisabled();
  }

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Contact sampling");
  ImGui::Separator();
  row_label("Rays u x v");
  drag_int_n("##samples", p.samples, 2, 0.2f, 2, 512);
  done();
  tooltip("nu x nv rays shot along the view direction through the band; more rays follow the surface closer");

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Lattice");
  ImGui::Separator();
  row_label("Order u v w");
  drag_int_n("##order", p.order, 3, 0.05f, 2, 6);
  done();
  tooltip("B-spline order per axis (degree + 1): 2 linear, 3 quadratic, 4 cubic");
  row_label("Controls");
  drag_int_n("##controls", p.controls, 3, 0.1f, 2, 64);
  done();
  tooltip("Control points per axis (u along the stroke, v across, w up); at least the order");
  for (int a = 0; a < 3; ++a) {
    p.order[a] = std::clamp(p.order[a], 2, 6);
    p.controls[a] = std::clamp(p.controls[a], p.order[a], 64);
  }
  // The contact grid must have at least as many samples as control points along u and v.
  for (int a = 0; a < 2; ++a) p.samples[a] = std::clamp(p.samples[a], std::max(2, p.controls[a]), 512);

  ImGui::Spacing();
  ImGui::TextColored(colors::dim, "Object axes");
  ImGui::Separator();
  row_label("Length axis");
  if (ImGui::Combo("##length_axis", &p.length_axis, "x\0y\0z\0")) r.committed = true;
  tooltip("Object axis laid along the stroke (u)");
  row_label("Up axis");
  if (ImGui::Combo("##up_axis", &p.up_axis, "x\0y\0z\0")) r.committed = true;
  tooltip("Object axis pointing away from the surface (w); its minimum sits on the contact surface");
  if (p.up_axis == p.length_axis) ImGui::TextColored(colors::warning, "Length and up axes must differ.");

  ImGui::Spacing();
  if (ImGui::Button("Defaults")) {
    p = PlacementParams{};
    r.reset = r.committed = true;
  }
  tooltip("Reset every parameter to its default");
  return r;
}

}  // namespace trispline::ui
