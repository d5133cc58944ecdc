// The JSON codecs of declared command parameters (params.h): one Codec<T> per supported field type, each reading a
// value with the field named in its errors and writing it back; components() gives the numbers a range checks.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/params/command_context.h"

namespace trispline::core {

// What a panel can draw for a field (ui::param_widget).
enum class ParamKind { Other, String, Number, Integer, Bool, Choice, Vec3, IVec2, IVec3 };

namespace params {

[[noreturn]] void fail(const std::string& field, const std::string& what);

// JSON value ↔ C++ value, with the field named in errors. Specialised for every supported field type.
template <class T, class = void>
struct Codec;

template <>
struct Codec<std::string> {
  static constexpr ParamKind kind = ParamKind::String;
  static std::string read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const std::string& s) { return s; }
  static std::string type() { return "string"; }
};
template <>
struct Codec<double> {
  static constexpr ParamKind kind = ParamKind::Number;
  static double read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(double x) { return x; }
  static std::string type() { return "number"; }
};
template <>
struct Codec<int> {
  static constexpr ParamKind kind = ParamKind::Integer;
  static int read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(int x) { return x; }
  static std::string type() { return "integer"; }
};
template <>
struct Codec<std::int64_t> {
  static constexpr ParamKind kind = ParamKind::Other;
  static std::int64_t read(const nlohmann::json& v, const std::string& field);  // ≥ 0
  static nlohmann::json write(std::int64_t x) { return x; }
  static std::string type() { return "integer ≥ 0"; }
};
template <>
struct Codec<std::size_t> {
  static constexpr ParamKind kind = ParamKind::Other;
  static std::size_t read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(std::size_t x) { return x; }
  static std::string type() { return "integer ≥ 0"; }
};
template <>
struct Codec<bool> {
  static constexpr ParamKind kind = ParamKind::Bool;
  static bool read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(bool b) { return b; }
  static std::string type() { return "true|false"; }
};
template <>
struct Codec<glm::dvec2> {
  static constexpr ParamKind kind = ParamKind::Other;
  static glm::dvec2 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::dvec2& x) { return nlohmann::json::array({x.x, x.y}); }
  static std::string type() { return "[x,y]"; }
};
template <>
struct Codec<glm::vec3> {  // single precision (a colour as the renderer keeps it); read as doubles, then rounded
  static constexpr ParamKind kind = ParamKind::Other;
  static glm::vec3 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::vec3& x) {
    return nlohmann::json::array({double(x.x), double(x.y), double(x.z)});
  }
  static std::string type() { return "[x,y,z]"; }
};
template <>
struct Codec<glm::dvec3> {
  static constexpr ParamKind kind = ParamKind::Vec3;
  static glm::dvec3 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::dvec3& x) { return nlohmann::json::array({x.x, x.y, x.z}); }
  static std::string type() { return "[x,y,z]"; }
};
template <>
struct Codec<glm::ivec2> {
  static constexpr ParamKind kind = ParamKind::IVec2;
  static glm::ivec2 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::ivec2& x) { return nlohmann::json::array({x.x, x.y}); }
  static std::string type() { return "[a,b]"; }
};
template <>
struct Codec<glm::ivec3> {
  static constexpr ParamKind kind = ParamKind::IVec3;
  static glm::ivec3 read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const glm::ivec3& x) { return nlohmann::json::array({x.x, x.y, x.z}); }
  static std::string type() { return "[a,b,c]"; }
};
template <>
struct Codec<std::vector<glm::dvec2>> {
  static constexpr ParamKind kind = ParamKind::Other;
  static std::vector<glm::dvec2> read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const std::vector<glm::dvec2>& pts);
  static std::string type() { return "[[x,y],…]"; }
};
template <>
struct Codec<std::vector<glm::dvec3>> {
  static constexpr ParamKind kind = ParamKind::Other;
  static std::vector<glm::dvec3> read(const nlohmann::json& v, const std::string& field);  // errors name the point
  static nlohmann::json write(const std::vector<glm::dvec3>& pts);
  static std::string type() { return "[[x,y,z],…]"; }
};
template <>
struct Codec<std::vector<double>> {
  static constexpr ParamKind kind = ParamKind::Other;
  static std::vector<double> read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const std::vector<double>& x) { return x; }
  static std::string type() { return "[number,…]"; }
};
template <>
struct Codec<std::vector<std::string>> {
  static constexpr ParamKind kind = ParamKind::Other;
  static std::vector<std::string> read(const nlohmann::json& v, const std::string& field);
  static nlohmann::json write(const std::vector<std::string>& x) { return x; }
  static std::string type() { return "[string,…]"; }
};

// Every number a value holds (for range checks): the value itself, or each component.
inline std::vector<double> components(double x) { return {x}; }
inline std::vector<double> components(int x) { return {double(x)}; }
inline std::vector<double> components(std::int64_t x) { return {double(x)}; }
inline std::vector<double> components(std::size_t x) { return {double(x)}; }
inline std::vector<double> components(const glm::dvec2& v) { return {v.x, v.y}; }
inline std::vector<double> components(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
inline std::vector<double> components(const glm::vec3& v) { return {v.x, v.y, v.z}; }
inline std::vector<double> components(const glm::ivec2& v) { return {double(v.x), double(v.y)}; }
inline std::vector<double> components(const glm::ivec3& v) { return {double(v.x), double(v.y), double(v.z)}; }
inline std::vector<double> components(const std::vector<double>& v) { return v; }
template <class T>
std::vector<double> components(const T&) {
  return {};
}

}  // namespace params
}  // namespace trispline::core
