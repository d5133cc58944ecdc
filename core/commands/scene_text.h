// `scene.text` — adds a line of text as an extruded mesh object (core/mesh/text_mesh.h), the model the seed places
// over curved surfaces in §2.5 (Fig. 2.15). Fields: declared in scene_text.cpp (ParamSchema; the name, transform
// and colour in codecs.cpp object_fields_schema()), listed in docs/commands.md. The text reads along +x, its glyphs
// stand up +y, its depth is along z, centred on the origin; `place.sketch` with `"up_axis":"z"` lays it flat on a
// surface, with `"up_axis":"y"` upright along the stroke. Errors (CommandError, the scene unchanged): a font that
// cannot be read or has no glyph for a character ("font"), text that is empty, not UTF-8, over 256 characters or
// without a visible character ("text").
#pragma once

#include "core/commands/add_object_command.h"
#include "core/commands/declared_command.h"

namespace trispline::core {

struct SceneTextParams {
  std::string text;
  std::string font;  // file path, absolute once parsed; "" = DejaVu Sans Bold (kDefaultFontPath)
  double size = 1.0, depth = 0.25;
  int curve_segments = 6;
  ObjectFields object;
};

class SceneTextCommand : public DeclaredSnapshotCommand<SceneTextCommand, SceneTextParams, AddObjectCommand> {
 public:
  static Schema declare();

 protected:
  ObjectFields& object_fields() override { return p_.object; }
  TriMesh make_mesh() const override;
  std::string default_name() const override { return "text"; }
  std::string source() const override { return "text:" + p_.text; }
};

}  // namespace trispline::core
