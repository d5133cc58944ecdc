#include "core/commands/scene_text.h"

#include <stdexcept>

#include "core/mesh/text_mesh.h"

namespace trispline::core {

auto SceneTextCommand::declare() -> Schema {
  return Schema("scene.text", "Add a line of text as an extruded mesh (TrueType / OpenType font)")
      .field("text", &P::text,
             {.required = true,
              .help = "One line, UTF-8, 1–256 characters; reads along +x, glyphs up +y, centred on the origin"})
      .field("font", &P::font,
             {.write = ParamWrite::UnlessDefault,
              .path = true,
              .default_text = "DejaVu Sans Bold (fonts-dejavu-core)",
              .help = "A TrueType, OpenType or Type 1 font file, relative to the log's folder"})
      .field("size", &P::size,
             {.range = ParamRange{0, 1e6, true, false},
              .unit = "world units",
              .ui = {"Size", 0.01, "%.3g"},
              .help = "The font's em (capitals stand about 0.73 em in DejaVu Sans)"})
      .field("depth", &P::depth,
             {.range = ParamRange{0, 1e6, true, false},
              .unit = "world units",
              .ui = {"Depth", 0.005, "%.3g"},
              .help = "Extrusion along z, centred on z = 0"})
      .field("curve_segments", &P::curve_segments,
             {.write = ParamWrite::UnlessDefault,
              .range = ParamRange{1, kMaxCurveSegments},
              .ui = {"Curve segments", 0.1},
              .help = "Line segments per curved piece of a glyph's outline"})
      .embed(&P::object, object_fields_schema())
      .label([](const P& p) { return "Add text '" + p.text + "'"; })
      .failure_field("font");
}

TriMesh SceneTextCommand::make_mesh() const {
  TextMeshOptions o;
  o.font_path = p_.font;
  o.size = p_.size;
  o.depth = p_.depth;
  o.curve_segments = p_.curve_segments;
  try {
    return make_text_mesh(p_.text, o);
  } catch (const std::invalid_argument& e) {
    throw CommandError(e.what(), "text");
  }
}

}  // namespace trispline::core
