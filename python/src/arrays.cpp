// NumPy conversions of the bindings (bindings.h).
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>

#include "python/src/bindings.h"

namespace trispline::python {
namespace {

std::string shape_text(const py::array& a) {
  std::ostringstream s;
  s << "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

}  // namespace

py::array checked_rows(const py::handle& array, const char* what, std::size_t cols) {
  py::array a = py::array::ensure(array);
  if (!a) throw py::value_error(std::string(what) + " must be a #N×" + std::to_string(cols) + " array");
  const char kind = a.dtype().kind();
  const std::string expected = std::string(what) + " must be a #N×" + std::to_string(cols) + " float64 array";
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::value_error(expected + " (got dtype " + std::string(py::str(a.dtype())) + ")");
  if (a.ndim() != 2 || a.shape(1) != py::ssize_t(cols))
    throw py::value_error(expected + " (got shape " + shape_text(a) + ")");
  return a;
}

void raise_not_finite(const char* what, std::size_t row, std::size_t col, double value) {
  std::ostringstream s;
  s << what << "[" << row << ", " << col << "] is not finite (" << value << ")";
  throw py::value_error(s.str());
}

std::vector<glm::dvec3> points_from_array(const py::handle& array, const char* what, std::size_t min_rows) {
  std::vector<glm::dvec3> out = points_from_array_mapped(array, what, [](const glm::dvec3& p) { return p; });
  if (out.size() < min_rows)
    throw py::value_error(std::string(what) + " must have at least " + std::to_string(min_rows) + " rows (got " +
                          std::to_string(out.size()) + ")");
  return out;
}

std::vector<glm::uvec3> triangles_from_array(const py::handle& array, std::size_t vertex_count, const char* what) {
  py::array a = checked_rows(array, what, 3);
  if (a.dtype().kind() == 'f')
    throw py::value_error(std::string(what) + " must be a #F×3 int32 array of vertex indices (got dtype " +
                          std::string(py::str(a.dtype())) + ")");
  const auto idx = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  const std::size_t n = std::size_t(idx.shape(0));
  if (n == 0) throw py::value_error(std::string(what) + " must have at least one triangle");
  const std::int64_t* d = idx.data();
  std::vector<glm::uvec3> out(n);
  for (std::size_t f = 0; f < n; ++f)
    for (int c = 0; c < 3; ++c) {
      const std::int64_t v = d[3 * f + c];
      if (v < 0 || std::uint64_t(v) >= vertex_count)
        throw py::value_error(std::string(what) + "[" + std::to_string(f) + ", " + std::to_string(c) +
                              "] = " + std::to_string(v) + " is not a vertex index in [0, " +
                              std::to_string(vertex_count) + ")");
      out[f][c] = std::uint32_t(v);
    }
  return out;
}

py::array_t<double> array_from_points(std::vector<glm::dvec3>&& points) {
  auto* owned = new std::vector<glm::dvec3>(std::move(points));
  py::capsule base(owned, [](void* p) { delete static_cast<std::vector<glm::dvec3>*>(p); });
  static_assert(sizeof(glm::dvec3) == 3 * sizeof(double), "glm::dvec3 must be three packed doubles");
  return py::array_t<double>({py::ssize_t(owned->size()), py::ssize_t(3)},
                             {py::ssize_t(sizeof(glm::dvec3)), py::ssize_t(sizeof(double))},
                             reinterpret_cast<const double*>(owned->data()), base);
}

nlohmann::json json_from_python(const py::handle& value, const char* what) {
  std::string text;
  if (py::isinstance<py::str>(value)) {
    text = value.cast<std::string>();
  } else {
    // numpy arrays and scalars (np.float64, np.int32) become lists and numbers; anything else is a TypeError.
    const py::cpp_function plain([](py::object o) -> py::object {
      if (py::hasattr(o, "tolist")) return o.attr("tolist")();
      throw py::type_error(std::string("not JSON serialisable: ") + std::string(py::str(py::type::of(o))));
    });
    const py::object dumps = py::module_::import("json").attr("dumps");
    try {
      text = dumps(value, py::arg("allow_nan") = false, py::arg("default") = plain).cast<std::string>();
    } catch (py::error_already_set& e) {
      if (e.matches(PyExc_ValueError)) throw py::value_error(std::string(what) + ": " + e.what());
      throw;
    }
  }
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) raise_command_error(std::string(what) + ": malformed JSON", "");
  if (!j.is_object()) raise_command_error(std::string(what) + ": a command must be a JSON object", "");
  return j;
}

py::object python_from_json(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(
      value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace));
}

}  // namespace trispline::python
