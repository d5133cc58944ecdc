#include "core/params/params.h"

#include <charconv>
#include <cmath>
#include <filesystem>

namespace trispline::core {

bool ParamRange::bounded() const { return std::isfinite(lo) || std::isfinite(hi); }

bool ParamRange::contains(double x) const {
  if (lo_open ? !(x > lo) : !(x >= lo)) return false;
  if (hi_open ? !(x < hi) : !(x <= hi)) return false;
  return true;
}

std::string ParamRange::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi) {
    if (lo == -hi && !lo_open && !hi_open) return "|x| ≤ " + params::format_number(hi);
    return std::string(lo_open ? "(" : "[") + params::format_number(lo) + ", " + params::format_number(hi) +
           (hi_open ? ")" : "]");
  }
  if (has_lo) return (lo_open ? "> " : "≥ ") + params::format_number(lo);
  if (has_hi) return (hi_open ? "< " : "≤ ") + params::format_number(hi);
  return "";
}

namespace params {
namespace {

double as_number(const nlohmann::json& v, const std::string& field) {
  if (!v.is_number()) fail(field, "expected a number, got " + std::string(v.type_name()));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(field, "must be finite");
  return d;
}

std::int64_t as_int64(const nlohmann::json& v, const std::string& field, std::int64_t lo, std::int64_t hi) {
  const std::string range = "integer out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!v.is_number_integer()) fail(field, "expected an integer, got " + std::string(v.type_name()));
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) fail(field, range);
  const std::int64_t i = v.get<std::int64_t>();
  if (i < lo || i > hi) fail(field, range);
  return i;
}

int as_int(const nlohmann::json& v, const std::string& field) {
  return static_cast<int>(as_int64(v, field, std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
}

}  // namespace

void fail(const std::string& field, const std::string& what) {
  throw CommandError("field '" + field + "': " + what, field);
}

void rethrow_nested(const CommandError& e, const std::string& prefix) {
  std::string msg = e.what();
  if (msg.rfind("field '", 0) == 0) msg.insert(7, prefix + ".");
  throw CommandError(msg, e.field().empty() ? prefix : prefix + "." + e.field());
}

std::string choices_text(const std::vector<std::string>& choices) {
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : "|") + c;
  return list;
}

std::string range_error(const ParamRange& r, const std::string& unit, double value, int component, int components) {
  const std::string t = r.text(), in_unit = unit.empty() ? "" : " (" + unit + ")";
  std::string what = "";
  if (components > 1)
    what = (components <= 3 ? std::string("component ") + "xyz"[component] : "element " + std::to_string(component)) +
           " = " + format_number(value) + ": ";
  if (t.rfind("|x| ", 0) == 0) return what + "|value| must be " + t.substr(4) + in_unit;
  return what + "must be " + std::string(!t.empty() && (t[0] == '[' || t[0] == '(') ? "in " : "") + t + in_unit;
}

std::string resolve_path(const std::string& path, const std::string& field, const CommandContext& ctx) {
  if (path.empty()) fail(field, "must not be empty");
  return std::filesystem::absolute(ctx.resolve(path)).lexically_normal().string();
}

std::string format_number(double x) {
  if (std::isinf(x)) return x > 0 ? "∞" : "-∞";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string shortest(buf, r.ptr);
  if (const std::size_t e = shortest.find('e'); e != std::string::npos) {  // "1e+06" → "1e6", "1e-06" → "1e-6"
    const bool negative = shortest[e + 1] == '-';
    std::size_t digits = e + 2;
    while (digits + 1 < shortest.size() && shortest[digits] == '0') ++digits;
    shortest = shortest.substr(0, e + 1) + (negative ? "-" : "") + shortest.substr(digits);
  }
  if (x == std::floor(x) && std::abs(x) < 1e15) {
    const std::string whole = std::to_string(static_cast<long long>(x));
    if (whole.size() <= shortest.size() + 3) return whole;  // 16384, 100000; but 1e6, 8e6
  }
  return shortest;
}

std::string Codec<std::string>::read(const nlohmann::json& v, const std::string& field) {
  if (!v.is_string()) fail(field, "expected a string, got " + std::string(v.type_name()));
  return v.get<std::string>();
}

double Codec<double>::read(const nlohmann::json& v, const std::string& field) { return as_number(v, field); }

int Codec<int>::read(const nlohmann::json& v, const std::string& field) { return as_int(v, field); }

std::int64_t Codec<std::int64_t>::read(const nlohmann::json& v, const std::string& field) {
  return as_int64(v, field, 0, std::numeric_limits<std::int64_t>::max());
}

std::size_t Codec<std::size_t>::read(const nlohmann::json& v, const std::string& field) {
  return static_cast<std::size_t>(as_int64(v, field, 0, std::numeric_limits<std::int64_t>::max()));
}

bool Codec<bool>::read(const nlohmann::json& v, const std::string& field) {
  if (!v.is_boolean()) fail(field, "expected true or false, got " + std::string(v.type_name()));
  return v.get<bool>();
}

namespace {

// A JSON array of exactly V::length() components, each read by `component` (as_number or as_int).
template <class V, class Component>
V read_components(const nlohmann::json& v, const std::string& field, const char* what, Component component) {
  constexpr int n = V::length();
  if (!v.is_array() || v.size() != std::size_t(n))
    fail(field, "expected an array of " + std::to_string(n) + " " + what);
  V out;
  for (int i = 0; i < n; ++i) out[i] = component(v[std::size_t(i)], field);
  return out;
}

}  // namespace

glm::dvec2 Codec<glm::dvec2>::read(const nlohmann::json& v, const std::string& field) {
  return read_components<glm::dvec2>(v, field, "numbers", as_number);
}

glm::dvec3 Codec<glm::dvec3>::read(const nlohmann::json& v, const std::string& field) {
  return read_components<glm::dvec3>(v, field, "numbers", as_number);
}

glm::vec3 Codec<glm::vec3>::read(const nlohmann::json& v, const std::string& field) {
  return glm::vec3(Codec<glm::dvec3>::read(v, field));
}

glm::ivec2 Codec<glm::ivec2>::read(const nlohmann::json& v, const std::string& field) {
  return read_components<glm::ivec2>(v, field, "integers", as_int);
}

glm::ivec3 Codec<glm::ivec3>::read(const nlohmann::json& v, const std::string& field) {
  return read_components<glm::ivec3>(v, field, "integers", as_int);
}

std::vector<glm::dvec2> Codec<std::vector<glm::dvec2>>::read(const nlohmann::json& v, const std::string& field) {
  if (!v.is_array()) fail(field, "expected an array of [x, y] points, got " + std::string(v.type_name()));
  std::vector<glm::dvec2> pts;
  pts.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& p = v[i];
    if (!p.is_array() || p.size() != 2) fail(field, "point " + std::to_string(i) + " is not an array of 2 numbers");
    pts.emplace_back(as_number(p[0], field), as_number(p[1], field));
  }
  return pts;
}

nlohmann::json Codec<std::vector<glm::dvec2>>::write(const std::vector<glm::dvec2>& pts) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& p : pts) a.push_back({p.x, p.y});
  return a;
}

std::vector<glm::dvec3> Codec<std::vector<glm::dvec3>>::read(const nlohmann::json& v, const std::string& field) {
  if (!v.is_array()) fail(field, "expected an array of [x, y, z] points, got " + std::string(v.type_name()));
  std::vector<glm::dvec3> pts;
  pts.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    try {
      pts.push_back(Codec<glm::dvec3>::read(v[i], field));
    } catch (const CommandError& e) {
      const std::string what = e.what(), prefix = "field '" + field + "': ";
      fail(field,
           "point " + std::to_string(i) + ": " + (what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what));
    }
  }
  return pts;
}

nlohmann::json Codec<std::vector<glm::dvec3>>::write(const std::vector<glm::dvec3>& pts) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& p : pts) a.push_back({p.x, p.y, p.z});
  return a;
}

std::vector<double> Codec<std::vector<double>>::read(const nlohmann::json& v, const std::string& field) {
  if (!v.is_array()) fail(field, "expected an array of numbers, got " + std::string(v.type_name()));
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      fail(field, "element " + std::to_string(i) + " is not a finite number");
    out.push_back(v[i].get<double>());
  }
  return out;
}

std::vector<std::string> Codec<std::vector<std::string>>::read(const nlohmann::json& v, const std::string& field) {
  if (!v.is_array()) fail(field, "expected an array of strings, got " + std::string(v.type_name()));
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_string())
      fail(field, "element " + std::to_string(i) + ": expected a string, got " + std::string(v[i].type_name()));
    out.push_back(v[i].get<std::string>());
  }
  return out;
}

}  // namespace params
}  // namespace trispline::core
