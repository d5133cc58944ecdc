// trispline::ui::param_widget — draws one declared command parameter (core/params/params.h) in a panel: the
// declaration's label in the left column, a widget for its type (drag field, combo, checkbox) limited to its range,
// and a tooltip with its help, unit and range; the widget is named "<command>.<field>" for GUI tests (ui::probe).
// Returns true when an edit is committed (the field was left after an edit, or a combo/checkbox changed): the
// caller re-runs or applies the command then, never per frame.
#pragma once

#include <string>

#include "core/params/params.h"

namespace trispline::ui {

// Label in the left column, widget filling the rest of the row (Blender's property layout).
void row_label(const char* label);
// Shows `text` as the tooltip of the last item while it is hovered.
void tooltip(const char* text);
// The tooltip of a declared field: its help, then its unit and range.
std::string param_tooltip(const core::ParamDoc& doc);

// What param_widget() needs of a field, without its params struct.
struct ParamWidget {
  std::string scope;  // the command id ("place.sketch"), for the probe item "<scope>.<field>"
  const core::ParamDoc* doc = nullptr;
  std::string label;
  core::ParamKind kind = core::ParamKind::Other;
  core::ParamRange range;
  const std::vector<std::string>* choices = nullptr;
  int choice_member = 0;  // 0 string, 1 index, 2 bool
  double step = 0.0;
  std::string format;
};
bool param_widget(const ParamWidget& w, void* value);

// A size field's state in a panel (ParamFieldInfo::object_size): the value as typed or dragged, before the limits, and
// why it was limited ("" = it was not: the field is amber and its tooltip says why while this is set).
struct SizeFieldState {
  double typed = 0.0;
  std::string limit;
  bool committed = false;  // an edit of the field ended this frame (the caller applies or re-runs then)
};

// Draws a size field (a number declared with object_size): `*value` in world units, ≤ 0 = unset and shown as
// `shown_default` (marked "auto"); drag, or one click and type. Each edit is limited as it is typed to the declared
// fractions of `diagonal` (the object's bounding-box diagonal, world units; ≤ 0 without an object: [1e-3 (0 for a
// minimum fraction of 0), 10]). Returns the reason when an edit has just ended limited (for the Log), else "". `probe`
// names the item for GUI tests, with the values "<probe>" (the value shown) and "<probe>.limited" (state.limit).
std::string size_param_widget(const ParamWidget& w, const core::ParamFieldInfo& info, double* value, double diagonal,
                              double shown_default, SizeFieldState& state, const std::string& probe);

// As above for field `name` of `schema`, its value at `value` (the params struct's member, or a value held apart,
// such as an optional field's). "" (nothing drawn) for an undeclared field or one without object_size.
template <class P>
std::string size_param_widget(const core::ParamSchema<P>& schema, const std::string& name, double* value,
                              double diagonal, double shown_default, SizeFieldState& state, const std::string& probe) {
  const auto* f = schema.find(name);
  if (!f || !f->object_size) return {};
  ParamWidget w{schema.id(),           &f->doc,    f->label,    f->kind, f->range, &f->choices,
                int(f->choice_member), f->ui_step, f->ui_format};
  return size_param_widget(w, *f, value, diagonal, shown_default, state, probe);
}

template <class P>
std::string size_param_widget(const core::ParamSchema<P>& schema, const std::string& name, P& params, double diagonal,
                              double shown_default, SizeFieldState& state, const std::string& probe) {
  const auto* f = schema.find(name);
  if (!f || !f->member || f->kind != core::ParamKind::Number) return {};
  return size_param_widget(schema, name, static_cast<double*>(f->member(params)), diagonal, shown_default, state,
                           probe);
}

// Draws field `name` of `params` as declared in `schema` (an enum choice as a combo of its names). False (nothing
// drawn) for an undeclared or composite field.
template <class P>
bool param_widget(const core::ParamSchema<P>& schema, const std::string& name, P& params) {
  const auto* f = schema.find(name);
  if (!f || !(f->member || f->choice_index)) return false;
  ParamWidget w{schema.id(),           &f->doc,    f->label,    f->kind, f->range, &f->choices,
                int(f->choice_member), f->ui_step, f->ui_format};
  if (f->member) return param_widget(w, f->member(params));
  int index = f->choice_index(params);
  const bool committed = param_widget(w, &index);
  if (committed) f->set_choice_index(params, index);
  return committed;
}

}  // namespace trispline::ui
