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

// Draws field `name` of `params` as declared in `schema`. False (nothing drawn) for an undeclared or composite field.
template <class P>
bool param_widget(const core::ParamSchema<P>& schema, const std::string& name, P& params) {
  const auto* f = schema.find(name);
  if (!f || !f->member) return false;
  ParamWidget w{schema.id(),           &f->doc,    f->label,    f->kind, f->range, &f->choices,
                int(f->choice_member), f->ui_step, f->ui_format};
  return param_widget(w, f->member(params));
}

}  // namespace trispline::ui
