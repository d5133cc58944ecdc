// Typed access to the fields of a command's JSON line. Every getter throws core::CommandError whose field() is
// the field name and whose message says what was expected ("field 'width': expected a number, got string").
#pragma once

#include <glm/glm.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/commands/command.h"

namespace trispline::core::json_fields {

const nlohmann::json& require(const nlohmann::json& j, const char* field);
bool has(const nlohmann::json& j, const char* field);

std::string get_string(const nlohmann::json& j, const char* field);
std::string get_string(const nlohmann::json& j, const char* field, const std::string& fallback);
double get_number(const nlohmann::json& j, const char* field);  // finite
double get_number(const nlohmann::json& j, const char* field, double fallback);
int get_int(const nlohmann::json& j, const char* field);
int get_int(const nlohmann::json& j, const char* field, int fallback);  // range-checked: no silent wrap-around
// Non-negative 64-bit integer (seeds), range-checked.
std::int64_t get_int64(const nlohmann::json& j, const char* field, std::int64_t fallback);
bool get_bool(const nlohmann::json& j, const char* field, bool fallback);
glm::dvec3 get_vec3(const nlohmann::json& j, const char* field);
glm::dvec3 get_vec3(const nlohmann::json& j, const char* field, const glm::dvec3& fallback);
glm::ivec2 get_ivec2(const nlohmann::json& j, const char* field);
glm::ivec3 get_ivec3(const nlohmann::json& j, const char* field);
// "scale": a number s (uniform) or [sx, sy, sz].
glm::dvec3 get_scale(const nlohmann::json& j, const char* field, const glm::dvec3& fallback);
// [[x, y], ...] list of 2-D points.
std::vector<glm::dvec2> get_points2(const nlohmann::json& j, const char* field);
// One of `allowed`; the error lists them.
std::string get_enum(const nlohmann::json& j, const char* field, const std::vector<std::string>& allowed,
                     const std::string& fallback = {});

nlohmann::json to_json(const glm::dvec3& v);
nlohmann::json to_json(const glm::ivec2& v);
nlohmann::json to_json(const glm::ivec3& v);
nlohmann::json to_json(const std::vector<glm::dvec2>& pts);

// Transform fields shared by scene.load and scene.primitive: translate, rotate_deg, scale.
Transform get_transform(const nlohmann::json& j);
void put_transform(nlohmann::json& j, const Transform& t);

}  // namespace trispline::core::json_fields
