#include "core/commands/json_fields.h"

#include "core/commands/params.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace trispline::core::json_fields {
namespace {

std::string type_name(const nlohmann::json& v) { return v.type_name(); }

[[noreturn]] void fail(const char* field, const std::string& what) {
  throw CommandError("field '" + std::string(field) + "': " + what, field);
}

double as_number(const nlohmann::json& v, const char* field) { return params::Codec<double>::read(v, field); }
int as_int(const nlohmann::json& v, const char* field) { return params::Codec<int>::read(v, field); }

}  // namespace

bool has(const nlohmann::json& j, const char* field) { return j.is_object() && j.contains(field); }

const nlohmann::json& require(const nlohmann::json& j, const char* field) {
  if (!j.is_object()) throw CommandError("command line is not a JSON object");
  auto it = j.find(field);
  if (it == j.end()) fail(field, "missing");
  return *it;
}

std::string get_string(const nlohmann::json& j, const char* field) {
  const auto& v = require(j, field);
  if (!v.is_string()) fail(field, "expected a string, got " + type_name(v));
  return v.get<std::string>();
}

std::string get_string(const nlohmann::json& j, const char* field, const std::string& fallback) {
  return has(j, field) ? get_string(j, field) : fallback;
}

double get_number(const nlohmann::json& j, const char* field) { return as_number(require(j, field), field); }

double get_number(const nlohmann::json& j, const char* field, double fallback) {
  return has(j, field) ? get_number(j, field) : fallback;
}

int get_int(const nlohmann::json& j, const char* field) { return as_int(require(j, field), field); }

std::int64_t get_int64(const nlohmann::json& j, const char* field, std::int64_t fallback) {
  if (!has(j, field)) return fallback;
  return params::Codec<std::int64_t>::read(j.at(field), field);
}

int get_int(const nlohmann::json& j, const char* field, int fallback) {
  return has(j, field) ? get_int(j, field) : fallback;
}

bool get_bool(const nlohmann::json& j, const char* field, bool fallback) {
  if (!has(j, field)) return fallback;
  const auto& v = j.at(field);
  if (!v.is_boolean()) fail(field, "expected true or false, got " + type_name(v));
  return v.get<bool>();
}

glm::dvec3 get_vec3(const nlohmann::json& j, const char* field) {
  const auto& v = require(j, field);
  if (!v.is_array() || v.size() != 3) fail(field, "expected an array of 3 numbers");
  return {as_number(v[0], field), as_number(v[1], field), as_number(v[2], field)};
}

glm::dvec3 get_vec3(const nlohmann::json& j, const char* field, const glm::dvec3& fallback) {
  return has(j, field) ? get_vec3(j, field) : fallback;
}

glm::ivec2 get_ivec2(const nlohmann::json& j, const char* field) {
  const auto& v = require(j, field);
  if (!v.is_array() || v.size() != 2) fail(field, "expected an array of 2 integers");
  return {as_int(v[0], field), as_int(v[1], field)};
}

glm::ivec3 get_ivec3(const nlohmann::json& j, const char* field) {
  const auto& v = require(j, field);
  if (!v.is_array() || v.size() != 3) fail(field, "expected an array of 3 integers");
  return {as_int(v[0], field), as_int(v[1], field), as_int(v[2], field)};
}

glm::dvec3 get_scale(const nlohmann::json& j, const char* field, const glm::dvec3& fallback) {
  if (!has(j, field)) return fallback;
  const auto& v = j.at(field);
  glm::dvec3 s;
  if (v.is_number()) {
    s = glm::dvec3(as_number(v, field));
  } else if (v.is_array()) {
    s = get_vec3(j, field);
  } else {
    fail(field, "expected a number or an array of 3 numbers, got " + type_name(v));
  }
  if (s.x == 0.0 || s.y == 0.0 || s.z == 0.0) fail(field, "scale must be non-zero");
  return s;
}

std::vector<glm::dvec2> get_points2(const nlohmann::json& j, const char* field) {
  return params::Codec<std::vector<glm::dvec2>>::read(require(j, field), field);
}

std::string get_enum(const nlohmann::json& j, const char* field, const std::vector<std::string>& allowed,
                     const std::string& fallback) {
  if (!has(j, field) && !fallback.empty()) return fallback;
  const std::string s = get_string(j, field);
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : "|") + a;
    fail(field, "'" + s + "' is not one of " + list);
  }
  return s;
}

nlohmann::json to_json(const glm::dvec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }
nlohmann::json to_json(const glm::ivec2& v) { return nlohmann::json::array({v.x, v.y}); }
nlohmann::json to_json(const glm::ivec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }
nlohmann::json to_json(const std::vector<glm::dvec2>& pts) { return params::Codec<std::vector<glm::dvec2>>::write(pts); }

Transform get_transform(const nlohmann::json& j) {
  Transform t;
  t.translate = get_vec3(j, "translate", glm::dvec3(0.0));
  t.rotate_deg = get_vec3(j, "rotate_deg", glm::dvec3(0.0));
  t.scale = get_scale(j, "scale", glm::dvec3(1.0));
  return t;
}

void put_transform(nlohmann::json& j, const Transform& t) {
  j["translate"] = to_json(t.translate);
  j["rotate_deg"] = to_json(t.rotate_deg);
  if (t.scale.x == t.scale.y && t.scale.y == t.scale.z)
    j["scale"] = t.scale.x;
  else
    j["scale"] = to_json(t.scale);
}

}  // namespace trispline::core::json_fields
