// trispline::core::ParamSchema — a command's parameters, each declared once (Blender's RNA_def_property).
//
// A declaration names the JSON field, the member of the command's params struct it fills, and its range, unit,
// one-line help and widget label. The default is the struct's own member initialiser. From that one declaration:
//  * parse(line) fills a params struct, checking type and range, with errors that name the field
//    ("field 'width': must be > 0 (world units)", CommandError::field() == "width"; nested: "springs.mass");
//  * to_json(params) writes the log line back (parse(to_json(p)) == p);
//  * docs() lists the fields for `trispline commands --markdown` and the tables in docs/commands.md;
//  * ui::param_widget() draws a field with its label, range and tooltip.
//
//   return ParamSchema<P>("mesh.refine", "Refine a deformed object's mesh ...")  // a command's declare()
//       .field("object", &P::object, {.required = true, .help = "Object id"})
//       .field("tolerance", &P::tolerance,
//              {.required = true, .range = ParamRange::above(0), .unit = "world units", .help = "..."});
//
// Field types and their JSON: std::string, double (finite), int / std::int64_t (range-checked, no wrap-around),
// bool, glm::dvec2 [x,y], glm::dvec3 / glm::vec3 [x,y,z], glm::ivec2 [a,b], glm::ivec3 [a,b,c], std::vector<glm::dvec2>
// [[x,y],...], std::vector<glm::dvec3>, std::vector<double>, std::vector<std::string>, std::optional<T> of those, and
// nested ParamSchema objects.
#pragma once

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/params/command_context.h"
#include "core/params/param_codecs.h"

namespace trispline::core {

// One field as documented: for docs/commands.md, `trispline commands --markdown` and panel tooltips.
struct ParamDoc {
  std::string name;          // JSON field ("width"; nested fields "springs.stiffness")
  std::string type;          // "number", "integer", "[x,y,z]", "x|y|z", "object", ...
  std::string default_text;  // "required" for required fields
  std::string range;         // "> 0", "[2, 64]", "(0, 1]", or ""
  std::string unit;          // "world units", "pixels", "degrees", "seconds", or ""
  std::string help;          // one line
};

// A closed, open or half-open interval of numbers; each component of a vector field must lie in it.
struct ParamRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  static ParamRange above(double lo) { return {lo, std::numeric_limits<double>::infinity(), true, false}; }
  static ParamRange at_least(double lo) { return {lo, std::numeric_limits<double>::infinity()}; }
  static ParamRange at_most(double hi) { return {-std::numeric_limits<double>::infinity(), hi}; }
  static ParamRange magnitude_at_most(double m) { return {-m, m}; }
  bool bounded() const;
  bool contains(double x) const;
  std::string text() const;  // "> 0", "≥ 0", "[2, 64]", "(0, 1]", "≤ 100"
};

namespace params {

[[noreturn]] void fail(const std::string& field, const std::string& what);
// Re-raises an error from a nested object with its field prefixed: "field 'mass'" → "field 'springs.mass'".
[[noreturn]] void rethrow_nested(const CommandError& e, const std::string& prefix);
std::string choices_text(const std::vector<std::string>& choices);  // "x|y|z"
// "must be in [2, 8] (pixels)", "must be > 0", "|value| must be ≤ 100 (degrees)"; for one of several components
// "component y = -1: must be ...".
std::string range_error(const ParamRange& r, const std::string& unit, double value, int component, int components);
std::string format_number(double x);  // shortest text that reads back the same
// A path field's value made absolute against the log's folder; throws for an empty path.
std::string resolve_path(const std::string& path, const std::string& field, const CommandContext& ctx);

// The default as the docs show it ("[32,8]", "0.15", "extrude").
inline std::string default_text(const nlohmann::json& j);
template <class T>
std::string default_text(const T& v) {
  return default_text(Codec<T>::write(v));
}
inline std::string default_text(const nlohmann::json& j) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_number_float()) return format_number(j.get<double>());
  if (j.is_array() && !j.empty() && j[0].is_number()) {
    std::string out;
    for (const nlohmann::json& x : j) out += (out.empty() ? "[" : ",") + format_number(x.get<double>());
    return out + "]";
  }
  return j.dump();
}

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

}  // namespace params

// How a field is written back by to_json.
enum class ParamWrite {
  Always,         // every line carries it
  UnlessDefault,  // omitted when equal to the struct's default (optional fields: when unset)
  Never,          // read only (a field the line may carry but the command does not keep)
};

// A size that follows the object's (a panel's hint; the command takes the value as given): while the panel's value
// is unset (≤ 0) it shows default_fraction × the object's bounding-box diagonal, and it limits a typed value to
// [min_fraction, max_fraction] × that diagonal, saying why (ui::size_param_widget).
struct ParamObjectSize {
  double default_fraction = 0.0, min_fraction = 0.0, max_fraction = 1.0;
  double relative_step = 0.0;  // drag speed per pixel as a fraction of the value shown; 0 = ParamUi::step
};

// How a panel shows a field: its widget label (empty = not shown by generic widgets), a drag field's speed per pixel
// (0 = from the range) and its printf format ("%.3f"; empty = ImGui's).
struct ParamUi {
  std::string label;
  double step = 0.0;
  std::string format;
};

// What a declared field is, whatever struct holds it: its docs, widget hints, kind, range and how it is written.
struct ParamFieldInfo {
  ParamDoc doc;
  std::string label;      // widget label ("Half-width"); empty = not shown by generic widgets
  double ui_step = 0.0;   // drag speed per pixel; 0 = from the range
  std::string ui_format;  // printf format of the widget ("%.3f"); empty = ImGui's
  ParamKind kind = ParamKind::Other;
  ParamRange range;
  std::vector<std::string> choices;  // ParamKind::Choice: the allowed strings
  enum class ChoiceMember { String, Index, Bool } choice_member = ChoiceMember::String;  // what the member holds
  bool required = false;
  ParamWrite write_mode = ParamWrite::Always;
  bool resolve_path = false;          // a string field holding a file path (see Spec::path)
  std::vector<ParamDoc> nested_docs;  // a nested object's fields
  std::optional<ParamObjectSize> object_size;
  double ui_relative_step = 0.0;  // drag speed per pixel as a fraction of the value shown; 0 = ui_step
};

template <class P>
class ParamSchema {
 public:
  // A field of P: what it is (ParamFieldInfo) and how it reads, writes and checks P.
  struct Field : ParamFieldInfo {
    std::function<void(const Field&, const nlohmann::json&, P&, const CommandContext&)> read;  // value present
    std::function<void(const Field&, const P&, nlohmann::json&)> write;
    std::function<void*(P&)> member;  // for widgets; null for composite fields and enum choices
    // An enum choice's index (choice i = enumerator i), for widgets: read and set through these, not `member`.
    std::function<int(const P&)> choice_index;
    std::function<void(P&, int)> set_choice_index;
    std::function<void(P&)> check;           // a check over several fields (no JSON field of its own); may normalise
    std::function<bool(const P&)> stop;      // parse and to_json end here when it holds (e.g. "remove": true)
    std::function<bool(const P&)> write_if;  // to_json writes the field only when this holds (null: always)
  };

  // A field's settings, given with its declaration in designated-initialiser form:
  //   .field("width", &P::width, {.required = true, .range = ParamRange::above(0), .unit = "world units",
  //                               .help = "Half-width of the lattice"})
  // Members left out keep what the field's type gives (its default, its type text, ParamWrite::Always).
  struct Spec {
    bool required = false;                   // the line must carry it; the docs' default reads "required"
    std::optional<ParamWrite> write;         // how to_json writes it back
    std::function<bool(const P&)> write_if;  // written back only when this holds as well (null: always)
    bool path = false;  // a file path: not empty; resolved against the log's folder, logged absolute and normalised
    std::optional<ParamRange> range;  // every number (every component of a vector) must lie in it
    std::string unit;                 // "world units", "pixels", "degrees", ...
    std::string default_text;         // the default as the docs show it, when the member's own does not say it
    std::string type_text;            // the type as the docs show it (custom fields)
    ParamUi ui;                       // label, drag speed and format in a panel
    std::optional<ParamObjectSize> object_size;  // a size that follows the object's (ParamFieldInfo::object_size)
    std::string help;                            // one line, for the docs and the tooltip
  };

  // The settings of a length in world units that a panel sizes to the object it works on (ParamObjectSize: fractions
  // of the bounding-box diagonal, drag speed relative to the value): range (0, ∞), or [0, ∞) with `zero_allowed`.
  static Spec object_length(std::string label, ParamObjectSize size, std::string help, bool required = false,
                            bool zero_allowed = false) {
    return {.required = required,
            .range = zero_allowed ? ParamRange::at_least(0) : ParamRange::above(0),
            .unit = "world units",
            .ui = {std::move(label), 0.0, "%.4g"},
            .object_size = size,
            .help = std::move(help)};
  }

  ParamSchema(std::string id, std::string summary) : id_(std::move(id)), summary_(std::move(summary)) {}

  const std::string& id() const { return id_; }
  const std::string& summary() const { return summary_; }
  const std::vector<Field>& fields() const { return fields_; }
  const Field* find(const std::string& name) const {
    for (const Field& f : fields_)
      if (f.doc.name == name) return &f;
    return nullptr;
  }

  // A field of one of the supported types (see the header), or std::optional of one.
  template <class T>
  ParamSchema& field(const std::string& name, T P::*m, const Spec& spec = {}) {
    if constexpr (params::is_optional<T>::value)
      return field_as<params::Codec<typename T::value_type>>(name, m, spec);
    else
      return field_as<params::Codec<T>>(name, m, spec);
  }

  // A field read and written by `Codec` (read(json, field) → V, write(V) → json, type(), kind) instead of the
  // default one for its type: e.g. a scale that is a number or [sx,sy,sz].
  template <class Codec, class T>
  ParamSchema& field_as(const std::string& name, T P::*m, const Spec& spec = {}) {
    Field f;
    f.doc.name = name;
    if constexpr (params::is_optional<T>::value) {
      using V = typename T::value_type;
      f.doc.type = Codec::type();
      f.doc.default_text = "unset";
      f.write_mode = ParamWrite::UnlessDefault;
      f.read = [m](const Field& self, const nlohmann::json& v, P& p, const CommandContext&) {
        V x = Codec::read(v, self.doc.name);
        check_range(self, params::components(x));
        p.*m = std::move(x);
      };
      f.write = [m](const Field& self, const P& p, nlohmann::json& line) {
        if (p.*m) line[self.doc.name] = Codec::write(*(p.*m));
      };
    } else {
      f.kind = Codec::kind;
      f.doc.type = Codec::type();
      f.doc.default_text = params::default_text(nlohmann::json(Codec::write(P{}.*m)));
      f.member = [m](P& p) -> void* { return &(p.*m); };
      f.read = [m](const Field& self, const nlohmann::json& v, P& p, const CommandContext& ctx) {
        T x = Codec::read(v, self.doc.name);
        check_range(self, params::components(x));
        if constexpr (std::is_same_v<T, std::string>)
          if (self.resolve_path) x = params::resolve_path(x, self.doc.name, ctx);
        p.*m = std::move(x);
      };
      f.write = [m](const Field& self, const P& p, nlohmann::json& line) {
        if (self.write_mode == ParamWrite::UnlessDefault && p.*m == P{}.*m) return;
        line[self.doc.name] = Codec::write(p.*m);
      };
    }
    return push(std::move(f), spec);
  }

  // A string field holding one of `choices` (the error lists them), or an int member holding the choice's index.
  template <class T>
  ParamSchema& choice(const std::string& name, T P::*m, std::vector<std::string> choices, const Spec& spec = {}) {
    static_assert(
        std::is_same_v<T, std::string> || std::is_same_v<T, int> || std::is_same_v<T, bool> || std::is_enum_v<T>,
        "a choice fills a string, an index, an enum (choice i = enumerator i) or a bool (second = true)");
    Field f;
    f.doc.name = name;
    f.doc.type = params::choices_text(choices);
    f.kind = ParamKind::Choice;
    f.choices = std::move(choices);
    f.choice_member = std::is_same_v<T, std::string> ? Field::ChoiceMember::String
                      : std::is_same_v<T, bool>      ? Field::ChoiceMember::Bool
                                                     : Field::ChoiceMember::Index;
    if constexpr (std::is_enum_v<T>) {
      f.choice_index = [m](const P& p) { return int(p.*m); };
      f.set_choice_index = [m](P& p, int i) { p.*m = T(i); };
    } else {
      f.member = [m](P& p) -> void* { return &(p.*m); };
    }
    auto index_of = [](const Field& self, const T& x) -> int {
      if constexpr (std::is_same_v<T, std::string>) {
        for (std::size_t i = 0; i < self.choices.size(); ++i)
          if (self.choices[i] == x) return int(i);
        return 0;
      } else {
        return int(x);
      }
    };
    f.doc.default_text = f.choices.at(std::size_t(index_of(f, P{}.*m)));
    f.read = [m](const Field& self, const nlohmann::json& v, P& p, const CommandContext&) {
      const std::string s = params::Codec<std::string>::read(v, self.doc.name);
      for (std::size_t i = 0; i < self.choices.size(); ++i) {
        if (self.choices[i] != s) continue;
        if constexpr (std::is_same_v<T, std::string>)
          p.*m = s;
        else
          p.*m = T(i);
        return;
      }
      params::fail(self.doc.name, "'" + s + "' is not one of " + params::choices_text(self.choices));
    };
    f.write = [m, index_of](const Field& self, const P& p, nlohmann::json& line) {
      if (self.write_mode == ParamWrite::UnlessDefault && p.*m == P{}.*m) return;
      line[self.doc.name] = self.choices.at(std::size_t(index_of(self, p.*m)));
    };
    return push(std::move(f), spec);
  }

  // A nested object with its own schema; errors inside it name "<name>.<field>".
  template <class Q>
  ParamSchema& object(const std::string& name, std::optional<Q> P::*m, const ParamSchema<Q>& sub,
                      const Spec& spec = {}) {
    Field f = object_field(name, sub);
    f.doc.default_text = "unset";
    f.write_mode = ParamWrite::UnlessDefault;
    f.read = [m, &sub](const Field& self, const nlohmann::json& v, P& p, const CommandContext& ctx) {
      p.*m = sub.parse_nested(v, self.doc.name, ctx);
    };
    f.write = [m, &sub](const Field& self, const P& p, nlohmann::json& line) {
      if (p.*m) line[self.doc.name] = sub.fields_json(*(p.*m));
    };
    return push(std::move(f), spec);
  }
  template <class Q>
  ParamSchema& object(const std::string& name, Q P::*m, const ParamSchema<Q>& sub, const Spec& spec = {}) {
    Field f = object_field(name, sub);
    f.read = [m, &sub](const Field& self, const nlohmann::json& v, P& p, const CommandContext& ctx) {
      p.*m = sub.parse_nested(v, self.doc.name, ctx);
    };
    f.write = [m, &sub](const Field& self, const P& p, nlohmann::json& line) {
      line[self.doc.name] = sub.fields_json(p.*m);
    };
    return push(std::move(f), spec);
  }

  // The fields of `sub` at this level of the line, filling member `m` (a group of fields several commands share,
  // e.g. an added object's name, transform and colour).
  template <class Q>
  ParamSchema& embed(Q P::*m, const ParamSchema<Q>& sub) {
    for (const auto& sf : sub.fields()) {
      auto shared = std::make_shared<const typename ParamSchema<Q>::Field>(sf);
      Field f;
      static_cast<ParamFieldInfo&>(f) = sf;  // what it is; how it reads and writes P follows
      if (sf.read)
        f.read = [m, shared](const Field&, const nlohmann::json& v, P& p, const CommandContext& ctx) {
          shared->read(*shared, v, p.*m, ctx);
        };
      if (sf.write)
        f.write = [m, shared](const Field&, const P& p, nlohmann::json& line) { shared->write(*shared, p.*m, line); };
      if (sf.member) f.member = [m, shared](P& p) { return shared->member(p.*m); };
      if (sf.choice_index) {
        f.choice_index = [m, shared](const P& p) { return shared->choice_index(p.*m); };
        f.set_choice_index = [m, shared](P& p, int i) { shared->set_choice_index(p.*m, i); };
      }
      if (sf.check) f.check = [m, shared](P& p) { shared->check(p.*m); };
      if (sf.stop) f.stop = [m, shared](const P& p) { return shared->stop(p.*m); };
      if (sf.write_if) f.write_if = [m, shared](const P& p) { return shared->write_if(p.*m); };
      fields_.push_back(std::move(f));
    }
    return *this;
  }

  // As embed(), for a group of optional fields that matter together (the layer ddm.paint makes when there is none):
  // parse sets p.*named when the line has any of them, and to_json writes them back only when p.*named holds.
  template <class Q>
  ParamSchema& embed_named(Q P::*m, const ParamSchema<Q>& sub, bool P::*named) {
    const std::size_t first = fields_.size();
    embed(m, sub);
    for (std::size_t i = first; i < fields_.size(); ++i) {
      Field& f = fields_[i];
      if (f.read)
        f.read = [named, read = std::move(f.read)](const Field& self, const nlohmann::json& v, P& p,
                                                   const CommandContext& ctx) {
          p.*named = true;
          read(self, v, p, ctx);
        };
      if (f.write)
        f.write_if = [named, cond = std::move(f.write_if)](const P& p) { return p.*named && (!cond || cond(p)); };
    }
    return *this;
  }

  // A field with its own reader and writer (a shape no codec covers). Give spec.type_text and spec.default_text for
  // the docs.
  ParamSchema& custom(const std::string& name, decltype(Field::read) read, decltype(Field::write) write,
                      const Spec& spec = {}) {
    Field f;
    f.doc.name = name;
    f.read = std::move(read);
    f.write = std::move(write);
    return push(std::move(f), spec);
  }

  // Every field of `other` (a shared group of fields, e.g. camera_schema()), in its order.
  ParamSchema& include(const ParamSchema& other) {
    for (const Field& f : other.fields_) fields_.push_back(f);
    return *this;
  }

  // A check across fields, run after the fields declared before it; throws CommandError naming a field. It may
  // normalise the params (drop a field another one overrides).
  ParamSchema& check(std::function<void(P&)> fn) {
    Field f;
    f.check = std::move(fn);
    return push(std::move(f), {});
  }

  // What the History panel calls a command with params p (Command::label()): `fn(p)`, e.g.
  //   .label([](const P& p) { return "Refine '" + p.object + "' for its FFD"; })
  // Unset: the command's id.
  ParamSchema& label(std::function<std::string(const P&)> fn) {
    label_ = std::move(fn);
    return *this;
  }
  std::string label(const P& p) const { return label_ ? label_(p) : id_; }
  // The field a command's failure that names no field is reported on (e.g. "path" for a file that cannot be read
  // or written; SnapshotCommand::failure_field()). Unset: none.
  ParamSchema& failure_field(std::string name) {
    failure_field_ = std::move(name);
    return *this;
  }
  const std::string& failure_field() const { return failure_field_; }

  // The fields declared after this are neither read nor written when `fn` holds for those before it (a line that
  // removes something carries only what names it).
  ParamSchema& stop_if(std::function<bool(const P&)> fn) {
    Field f;
    f.stop = std::move(fn);
    return push(std::move(f), {});
  }

  // The params of a log line. Throws CommandError naming the first bad field (missing, mistyped, out of range).
  P parse(const nlohmann::json& line, const CommandContext& ctx = {}) const {
    if (!line.is_object()) throw CommandError("command line is not a JSON object");
    P p{};
    for (const Field& f : fields_) {
      if (f.stop) {
        if (f.stop(p)) break;
        continue;
      }
      if (f.check) {
        f.check(p);
        continue;
      }
      auto it = line.find(f.doc.name);
      if (it == line.end()) {
        if (f.required) params::fail(f.doc.name, "missing");
        continue;
      }
      f.read(f, *it, p, ctx);
    }
    return p;
  }
  // The complete log line: {"cmd": id, fields...}.
  nlohmann::json to_json(const P& p) const {
    nlohmann::json j = fields_json(p);
    j["cmd"] = id_;
    return j;
  }
  nlohmann::json fields_json(const P& p) const {
    nlohmann::json j = nlohmann::json::object();
    for (const Field& f : fields_) {
      if (f.stop && f.stop(p)) break;
      if (f.write && f.write_mode != ParamWrite::Never && (!f.write_if || f.write_if(p))) f.write(f, p, j);
    }
    return j;
  }
  P parse_nested(const nlohmann::json& v, const std::string& name, const CommandContext& ctx) const {
    if (!v.is_object()) params::fail(name, "expected an object, got " + std::string(v.type_name()));
    try {
      return parse(v, ctx);
    } catch (const CommandError& e) {
      params::rethrow_nested(e, name);
    }
  }
  // Every documented field, nested objects' fields as "<name>.<field>" after their object.
  std::vector<ParamDoc> docs() const {
    std::vector<ParamDoc> out;
    for (const Field& f : fields_) {
      if (f.check || f.stop) continue;
      out.push_back(f.doc);
      for (ParamDoc d : f.nested_docs) {
        d.name = f.doc.name + "." + d.name;
        out.push_back(std::move(d));
      }
    }
    return out;
  }

 private:
  template <class>
  friend class ParamSchema;

  static void check_range(const Field& f, const std::vector<double>& values) {
    if (!f.range.bounded()) return;
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!f.range.contains(values[i]))
        params::fail(f.doc.name, params::range_error(f.range, f.doc.unit, values[i], int(i), int(values.size())));
  }
  template <class Q>
  Field object_field(const std::string& name, const ParamSchema<Q>& sub) {
    Field f;
    f.doc.name = name;
    f.doc.type = "object";
    f.doc.default_text = "";
    f.nested_docs = sub.docs();
    return f;
  }
  ParamSchema& push(Field f, const Spec& spec) {
    // The type's default text first: a required field's docs read "required" whatever its member's default.
    if (!spec.default_text.empty()) f.doc.default_text = spec.default_text;
    if (spec.required) f.required = true, f.doc.default_text = "required";
    if (spec.write) f.write_mode = *spec.write;
    if (spec.write_if) f.write_if = spec.write_if;
    f.resolve_path = spec.path;
    if (spec.range) f.range = *spec.range, f.doc.range = f.range.text();
    if (!spec.unit.empty()) f.doc.unit = spec.unit;
    if (!spec.type_text.empty()) f.doc.type = spec.type_text;
    f.label = spec.ui.label;
    f.ui_step = spec.ui.step;
    f.ui_format = spec.ui.format;
    f.object_size = spec.object_size;
    f.ui_relative_step = spec.object_size ? spec.object_size->relative_step : 0.0;
    if (!spec.help.empty()) f.doc.help = spec.help;
    fields_.push_back(std::move(f));
    return *this;
  }

  std::string id_, summary_;
  std::vector<Field> fields_;
  std::function<std::string(const P&)> label_;
  std::string failure_field_;
};

}  // namespace trispline::core
