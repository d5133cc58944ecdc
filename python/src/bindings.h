// trispline::python — what the binding files share: the NumPy conversions (arrays.cpp), trispline.CommandError
// (module.cpp) and each file's registration function. Shapes follow the project's convention (#V × 3: one row per
// vertex); every array check raises ValueError naming the argument and the expected shape.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <glm/glm.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace trispline::python {

namespace py = pybind11;

// A #N × 3 array of real numbers (any float or integer dtype; float64 read without a copy) as points, after checking
// the shape and that every value is finite. Raises ValueError naming `what`: "points must be a #N×3 float64 array
// (got shape (5, 2))", "points[3, 1] is not finite (nan)". `min_rows`: the fewest rows accepted.
std::vector<glm::dvec3> points_from_array(const py::handle& array, const char* what, std::size_t min_rows = 0);
// The same applying `f` to each point while copying (one pass: the FFD's embedding into the parameter domain).
template <class F>
std::vector<glm::dvec3> points_from_array_mapped(const py::handle& array, const char* what, F&& f);
// A #F × 3 array of integer vertex indices in [0, vertex_count) as triangles. Raises ValueError (shape, dtype not an
// integer, an index out of range).
std::vector<glm::uvec3> triangles_from_array(const py::handle& array, std::size_t vertex_count, const char* what);

// A new #N × 3 float64 array owning `points` (moved into the array's base capsule: no copy).
py::array_t<double> array_from_points(std::vector<glm::dvec3>&& points);
// A read-only #N × `cols` view of `data` whose base holds `owner` alive (zero copy); T is double or std::int32_t.
template <class T>
py::array readonly_view(const T* data, std::size_t rows, std::size_t cols, std::shared_ptr<const void> owner);

// JSON ↔ Python: a dict / str command line to nlohmann::json (a str is parsed; a dict is dumped by the json module,
// numpy arrays and scalars through their tolist()), and a json value to Python objects.
nlohmann::json json_from_python(const py::handle& value, const char* what);
py::object python_from_json(const nlohmann::json& value);

// Raises trispline.CommandError(message, field) (defined in module.cpp).
[[noreturn]] void raise_command_error(const std::string& message, const std::string& field);

void init_scene(py::module_& m);    // scene_bindings.cpp: Scene, replay
void init_kernels(py::module_& m);  // kernel_bindings.cpp: Lattice, FfdEvaluator, ffd_evaluate, certify
void init_volume(py::module_& m);   // volume_bindings.cpp: silhouettes

// ---- template definitions ----

py::array checked_rows(const py::handle& array, const char* what, std::size_t cols);  // shape (N, cols), real dtype
[[noreturn]] void raise_not_finite(const char* what, std::size_t row, std::size_t col, double value);

template <class F>
std::vector<glm::dvec3> points_from_array_mapped(const py::handle& array, const char* what, F&& f) {
  const py::array checked = checked_rows(array, what, 3);
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(checked);
  const std::size_t n = std::size_t(a.shape(0));
  const double* d = a.data();
  std::vector<glm::dvec3> out(n);
  std::size_t bad = n;  // the first value that is not finite (row-major index / 3)
  int bad_col = 0;
  {
    py::gil_scoped_release nogil;  // `a` keeps the data alive; 1 M points take a few milliseconds
    for (std::size_t i = 0; i < n && bad == n; ++i) {
      const glm::dvec3 p(d[3 * i], d[3 * i + 1], d[3 * i + 2]);
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(p[c]) && bad == n) bad = i, bad_col = c;
      out[i] = f(p);
    }
  }
  if (bad < n) raise_not_finite(what, bad, std::size_t(bad_col), d[3 * bad + bad_col]);
  return out;
}

template <class T>
py::array readonly_view(const T* data, std::size_t rows, std::size_t cols, std::shared_ptr<const void> owner) {
  auto* keep = new std::shared_ptr<const void>(std::move(owner));
  py::capsule base(keep, [](void* p) { delete static_cast<std::shared_ptr<const void>*>(p); });
  py::array_t<T> view({py::ssize_t(rows), py::ssize_t(cols)}, {py::ssize_t(cols * sizeof(T)), py::ssize_t(sizeof(T))},
                      data, base);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

}  // namespace trispline::python
