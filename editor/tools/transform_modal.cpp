#include "editor/tools/transform_modal.h"

#include "core/commands/object_transform.h"
#include "core/mesh/mesh_io.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

namespace trispline::editor {
namespace {

constexpr double kPi = 3.14159265358979323846;

bool same(const core::Transform& a, const core::Transform& b) {
  return a.translate == b.translate && a.rotate_deg == b.rotate_deg && a.scale == b.scale;
}

glm::dvec3 unit_axis(int axis) {
  glm::dvec3 e(0.0);
  e[axis] = 1.0;
  return e;
}

glm::dmat3 rotation_of(const glm::dvec3& rotate_deg) {
  core::Transform r;
  r.rotate_deg = rotate_deg;
  return glm::dmat3(r.matrix());
}

double snapped(double deg) { return std::round(deg * 1e9) / 1e9 + 0.0; }  // + 0.0: no −0

// `t0` rotated by `deg` degrees about `axis_dir` through `pivot`; `axis` (0..2, −1) is the world axis when it is one,
// so a turn about an outer Euler axis adds to that angle exactly instead of going through a matrix.
core::Transform rotated(const core::Transform& t0, glm::dvec3 axis_dir, int axis, double deg, glm::dvec3 pivot) {
  const glm::dmat3 q(glm::rotate(glm::dmat4(1.0), glm::radians(deg), axis_dir));
  core::Transform t = t0;
  const glm::dvec3 r0 = t0.rotate_deg;
  if (axis == 2)
    t.rotate_deg.z = r0.z + deg;  // R = Rz·Ry·Rx: z is outermost
  else if (axis == 1 && r0.z == 0.0)
    t.rotate_deg.y = r0.y + deg;
  else if (axis == 0 && r0.y == 0.0 && r0.z == 0.0)
    t.rotate_deg.x = r0.x + deg;
  else
    t.rotate_deg = euler_xyz_deg(q * rotation_of(r0));
  t.translate = pivot + q * (t0.translate - pivot);
  return t;
}

// `t0` with its scale multiplied by `factor` (per own axis), about `pivot`.
core::Transform scaled(const core::Transform& t0, glm::dvec3 factor, glm::dvec3 pivot) {
  core::Transform t = t0;
  t.scale = t0.scale * factor;
  const glm::dmat3 r = rotation_of(t0.rotate_deg);
  glm::dvec3 local = glm::transpose(r) * (pivot - t0.translate);
  local *= factor;
  t.translate = pivot - r * local;
  return t;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

glm::dvec3 euler_xyz_deg(const glm::dmat3& m) {
  // R = Rz(c)·Ry(b)·Rx(a); glm is column-major: m[col][row].
  const double sb = std::clamp(-m[0][2], -1.0, 1.0);
  double a, b = std::asin(sb), c;
  if (std::abs(sb) < 1.0 - 1e-12) {
    a = std::atan2(m[1][2], m[2][2]);
    c = std::atan2(m[0][1], m[0][0]);
  } else {  // gimbal lock: only a − c (or a + c) is defined; put it all in c
    a = 0.0;
    c = std::atan2(-m[1][0], m[1][1]);
  }
  const double k = 180.0 / kPi;
  return {snapped(a * k), snapped(b * k), snapped(c * k)};
}

std::optional<TransformMode> TransformModal::start_key(const ui::KeyPress& k) {
  if (k.mods & (GLFW_MOD_CONTROL | GLFW_MOD_SHIFT | GLFW_MOD_ALT | GLFW_MOD_SUPER)) return std::nullopt;
  if (k.key == GLFW_KEY_G) return TransformMode::grab;
  if (k.key == GLFW_KEY_R) return TransformMode::rotate;
  if (k.key == GLFW_KEY_S) return TransformMode::scale;
  return std::nullopt;
}

void TransformModal::begin(TransformMode mode, const core::SceneObject& object, const core::Camera& view,
                           glm::dvec2 mouse_px) {
  active_ = true;
  outcome_ = Outcome::running;
  object_ = object.name;
  original_ = object;
  start_ = object.transform;
  view_ = view;
  pivot_ = start_.translate;
  if ((object.ffd || object.dffd) && object.world_mesh && !object.world_mesh->positions.empty())
    pivot_ = core::mesh_bounds(*object.world_mesh).center();
  const glm::dvec3 p = view_.project(pivot_);
  pivot_px_ = glm::dvec2(p);
  const double depth = p.z > 1e-9 ? p.z : glm::length(pivot_ - view_.eye);
  units_per_px_ = 2.0 * depth * std::tan(glm::radians(view_.fov_deg) * 0.5) / std::max(1, view_.viewport.y);
  mouse0_ = mouse_ = mouse_px;
  preview_.reset();
  confirmed_ = nullptr;
  restart(mode);
}

void TransformModal::restart(TransformMode mode) {
  mode_ = mode;
  axis_ = -1;
  text_.clear();
  negative_ = false;
  mouse0_ = mouse_;
}

double TransformModal::typed_value() const {
  double v = 0.0;
  if (!text_.empty() && text_ != ".")
    v = std::strtod(text_.c_str(), nullptr);
  else if (mode_ == TransformMode::scale)
    v = 1.0;  // a bare "-" flips the scale
  return negative_ ? -v : v;
}

bool TransformModal::key(const ui::KeyPress& k) {
  const int key = k.key;
  if (key == GLFW_KEY_ESCAPE) {
    outcome_ = Outcome::cancelled;
    return false;
  }
  if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) {
    outcome_ = Outcome::confirmed;
    return false;
  }
  if (k.mods & (GLFW_MOD_CONTROL | GLFW_MOD_ALT | GLFW_MOD_SUPER)) return true;
  if (key >= GLFW_KEY_X && key <= GLFW_KEY_Z) {
    const int a = key - GLFW_KEY_X;
    axis_ = axis_ == a ? -1 : a;
  } else if (const auto m = start_key(k)) {
    if (*m != mode_) restart(*m);
  } else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) {
    text_ += char('0' + (key - GLFW_KEY_0));
  } else if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) {
    text_ += char('0' + (key - GLFW_KEY_KP_0));
  } else if (key == GLFW_KEY_PERIOD || key == GLFW_KEY_KP_DECIMAL || key == GLFW_KEY_COMMA) {
    if (text_.find('.') == std::string::npos) text_ += '.';
  } else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) {
    negative_ = !negative_;
  } else if (key == GLFW_KEY_BACKSPACE) {
    if (!text_.empty())
      text_.pop_back();
    else
      negative_ = false;
  }
  return true;
}

TransformModal::Outcome TransformModal::update(const TransformModalInput& in, std::size_t first) {
  if (!active_) return Outcome::running;
  mouse_ = in.mouse_px;
  for (std::size_t i = first; i < in.keys.size() && outcome_ == Outcome::running; ++i) key(in.keys[i]);
  if (outcome_ == Outcome::running) {
    if (in.right_clicked)
      outcome_ = Outcome::cancelled;
    else if (in.left_clicked)
      outcome_ = Outcome::confirmed;
  }
  if (outcome_ == Outcome::running) return outcome_;
  if (outcome_ == Outcome::confirmed) confirmed_ = core::ObjectTransformCommand::make(object_, current())->to_json();
  active_ = false;
  preview_.reset();
  original_ = core::SceneObject();  // drop the meshes it held
  return std::exchange(outcome_, Outcome::running);
}

double TransformModal::angle_deg() const {
  if (typing()) return typed_value();
  double deg = 0.0;
  const glm::dvec2 a = mouse0_ - pivot_px_, b = mouse_ - pivot_px_;
  if (glm::length(a) > 0.5 && glm::length(b) > 0.5)  // screen y is down: counter-clockwise on screen is +
    deg = glm::degrees(std::atan2(-b.y, b.x) - std::atan2(-a.y, a.x));
  if (deg > 180.0) deg -= 360.0;
  if (deg <= -180.0) deg += 360.0;
  if (axis_ >= 0 && -view_.forward()[axis_] < 0) deg = -deg;  // the object turns the way the cursor does
  return deg;
}

double TransformModal::factor() const {
  if (typing()) return typed_value();
  return glm::length(mouse_ - pivot_px_) / std::max(glm::length(mouse0_ - pivot_px_), 1.0);
}

core::Transform TransformModal::current() const {
  const glm::dvec2 d = mouse_ - mouse0_;
  switch (mode_) {
    case TransformMode::grab: {
      core::Transform t = start_;
      if (typing()) {
        t.translate += unit_axis(axis_ < 0 ? 0 : axis_) * typed_value();
      } else if (axis_ < 0) {
        t.translate += (d.x * view_.right() - d.y * view_.true_up()) * units_per_px_;
      } else {
        // Pixels per world unit along the axis on screen; an axis seen end-on moves by the screen distance.
        const glm::dvec3 e = unit_axis(axis_);
        const double probe = 100.0 * units_per_px_;
        const glm::dvec2 s = (glm::dvec2(view_.project(pivot_ + e * probe)) - pivot_px_) / probe;
        const double s2 = glm::dot(s, s);
        const double along =
            s2 > 1e-6 / (units_per_px_ * units_per_px_) ? glm::dot(d, s) / s2 : glm::length(d) * units_per_px_;
        t.translate += e * along;
      }
      return t;
    }
    case TransformMode::rotate: {
      const glm::dvec3 towards_viewer = -view_.forward();
      return rotated(start_, axis_ < 0 ? towards_viewer : unit_axis(axis_), axis_, angle_deg(), pivot_);
    }
    case TransformMode::scale: {
      const double f = factor();
      glm::dvec3 factor(f);
      if (axis_ >= 0) factor = glm::dvec3(1.0), factor[axis_] = f;
      return scaled(start_, factor, pivot_);
    }
  }
  return start_;
}

const core::SceneObject& TransformModal::preview_object() {
  const core::Transform t = current();
  if (preview_ && same(t, preview_for_)) return *preview_;
  preview_for_ = t;
  try {
    core::check_transform(t);
    preview_ = core::object_with_transform(original_, t, false);
  } catch (const std::exception&) {  // a typed value the command would refuse: show the object unchanged
    preview_ = original_;
  }
  return *preview_;
}

std::string TransformModal::header() const {
  static const char* kAxis[] = {"X", "Y", "Z"};
  const std::string axis = axis_ < 0 ? "" : std::string(kAxis[axis_]) + ": ";
  const std::string typed = typing() ? std::string("[") + (negative_ ? "-" : "") + text_ + "|]  " : "";
  std::string value;
  if (mode_ == TransformMode::grab) {
    const glm::dvec3 d = current().translate - start_.translate;
    if (axis_ >= 0 || typing())
      value = std::string(kAxis[axis_ < 0 ? 0 : axis_]) + ": " + fmt("%.3f", d[axis_ < 0 ? 0 : axis_]);
    else
      value = "D: " + fmt("%.3f", d.x) + ", " + fmt("%.3f", d.y) + ", " + fmt("%.3f", d.z);
    value = "Grab  " + typed + value;
  } else if (mode_ == TransformMode::rotate) {
    value = "Rotate  " + typed + (axis_ < 0 ? std::string("View: ") : axis) + fmt("%.2f", angle_deg()) + " deg";
  } else {
    value = "Scale  " + typed + axis + fmt("%.3f", factor());
  }
  return value + "  (Esc cancel, Enter confirm)";
}

}  // namespace trispline::editor
