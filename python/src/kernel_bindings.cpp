// trispline.Lattice, ffd_evaluate, FfdEvaluator, certify: the FFD kernels of core/ffd on NumPy arrays.
#include <mutex>

#include "core/ffd/ffd_evaluator.h"
#include "core/ffd/fold_certificate.h"
#include "python/src/bindings.h"
#include "python/src/lattice.h"

namespace trispline::python {
namespace {

using core::KnotVector;
using Spline = core::TrivariateBSpline<glm::dvec3>;

KnotVector knots_for(int order, int controls, const py::object& knots, int axis) {
  if (knots.is_none()) return KnotVector::clamped_uniform(order, controls);
  const auto k = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(knots);
  if (!k || k.ndim() != 1)
    throw py::value_error("knots[" + std::to_string(axis) + "] must be a 1-D float64 array of #controls + order knots");
  return KnotVector(order, std::vector<double>(k.data(), k.data() + k.size()));
}

// control_points (nu, nv, nw, 3), u slowest in NumPy's C order → the spline's storage, u fastest.
PyLattice make_lattice(const py::object& control_points, std::array<int, 3> orders, const py::object& knots,
                       const py::object& bounds) {
  const auto cp = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(control_points);
  if (!cp || cp.ndim() != 4 || cp.shape(3) != 3)
    throw py::value_error("control_points must be a #nu×nv×nw×3 float64 array");
  const int n[3] = {int(cp.shape(0)), int(cp.shape(1)), int(cp.shape(2))};
  py::list kl;
  if (!knots.is_none()) {
    kl = py::list(knots);
    if (kl.size() != 3) throw py::value_error("knots must be three arrays (u, v, w) or None");
  }
  KnotVector k[3] = {KnotVector::clamped_uniform(2, 2), KnotVector::clamped_uniform(2, 2),
                     KnotVector::clamped_uniform(2, 2)};
  for (int a = 0; a < 3; ++a) {
    if (orders[a] < 2 || orders[a] > n[a])
      throw py::value_error("orders[" + std::to_string(a) + "] = " + std::to_string(orders[a]) +
                            ": an order (degree + 1) must be ≥ 2 and ≤ the control count " + std::to_string(n[a]));
    k[a] = knots_for(orders[a], n[a], knots.is_none() ? py::object(py::none()) : py::object(kl[a]), a);
    if (k[a].control_count() != n[a])
      throw py::value_error("knots[" + std::to_string(a) + "] has " + std::to_string(k[a].knots().size()) +
                            " knots; #controls + order = " + std::to_string(n[a] + orders[a]));
  }
  const double* d = cp.data();
  std::vector<glm::dvec3> pts(std::size_t(n[0]) * n[1] * n[2]);
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int l = 0; l < n[2]; ++l) {
        const double* p = d + 3 * ((std::size_t(i) * n[1] + j) * n[2] + l);
        for (int c = 0; c < 3; ++c)
          if (!std::isfinite(p[c])) throw py::value_error("control_points has a value that is not finite");
        pts[i + std::size_t(n[0]) * (j + std::size_t(n[1]) * l)] = glm::dvec3(p[0], p[1], p[2]);
      }
  PyLattice out{Spline(k[0], k[1], k[2], std::move(pts)), core::Embedding{}};
  if (!bounds.is_none()) {
    const auto b = points_from_array(py::array::ensure(bounds), "bounds");
    if (b.size() != 2) throw py::value_error("bounds must be (lo, hi), two points");
    const glm::dvec3 size = b[1] - b[0];
    if (!(size.x > 0 && size.y > 0 && size.z > 0)) throw py::value_error("bounds: hi must exceed lo on every axis");
    for (int a = 0; a < 3; ++a)
      if (k[a].domain_min() != 0.0 || k[a].domain_max() != 1.0)
        throw py::value_error("bounds map onto [0,1]³: knots[" + std::to_string(a) + "] must have the domain [0, 1]");
    out.embedding.linear = glm::dmat3(1.0 / size.x, 0, 0, 0, 1.0 / size.y, 0, 0, 0, 1.0 / size.z);
    out.embedding.offset = -b[0] / size;
  }
  return out;
}

PyLattice identity_lattice(const py::object& bounds, std::array<int, 3> controls, std::array<int, 3> orders) {
  const auto b = points_from_array(py::array::ensure(bounds), "bounds");
  if (b.size() != 2) throw py::value_error("bounds must be (lo, hi), two points");
  py::array_t<double> cp({controls[0], controls[1], controls[2], 3});
  auto w = cp.mutable_unchecked<4>();
  for (int a = 0; a < 3; ++a)
    if (orders[a] < 2 || orders[a] > controls[a])
      throw py::value_error("orders[" + std::to_string(a) + "] must be in [2, controls[" + std::to_string(a) + "]]");
  std::vector<double> g[3];
  for (int a = 0; a < 3; ++a) g[a] = KnotVector::clamped_uniform(orders[a], controls[a]).greville();
  for (int i = 0; i < controls[0]; ++i)
    for (int j = 0; j < controls[1]; ++j)
      for (int l = 0; l < controls[2]; ++l) {
        const glm::dvec3 t(g[0][i], g[1][j], g[2][l]);
        const glm::dvec3 p = b[0] + t * (b[1] - b[0]);
        for (int c = 0; c < 3; ++c) w(i, j, l, c) = p[c];
      }
  return make_lattice(cp, orders, py::none(), bounds);
}

py::array_t<double> control_points_array(const PyLattice& L) {
  const glm::ivec3 n = L.spline.control_counts();
  py::array_t<double> cp({n.x, n.y, n.z, 3});
  auto w = cp.mutable_unchecked<4>();
  for (int i = 0; i < n.x; ++i)
    for (int j = 0; j < n.y; ++j)
      for (int l = 0; l < n.z; ++l)
        for (int c = 0; c < 3; ++c) w(i, j, l, c) = L.spline.control_point(i, j, l)[c];
  return cp;
}

core::FfdBackend backend_of(const std::string& name) {
  const auto b = core::parse_ffd_backend(name);
  if (!b || core::is_gpu_backend(*b))
    throw py::value_error("backend must be 'cpu_fast' or 'cpu_ref' (got '" + name +
                          "'; the GLSL backends need the editor's GL context)");
  return *b;
}

// The stateful evaluator (bind once, evaluate after every lattice change): core::FfdEvaluator behind a mutex.
struct PyFfdEvaluator {
  std::unique_ptr<core::FfdEvaluator> ev;
  std::mutex mutex;
};

std::unique_ptr<PyFfdEvaluator> make_evaluator(const PyLattice& L, const py::object& points, const py::object& nrm,
                                               const std::string& backend) {
  auto out = std::make_unique<PyFfdEvaluator>();
  out->ev = core::make_cpu_ffd_evaluator(backend_of(backend));
  const core::Embedding E = L.embedding;
  std::vector<glm::dvec3> params =
      points_from_array_mapped(points, "points", [&E](const glm::dvec3& p) { return E.apply(p); });
  std::vector<glm::dvec3> normals;
  if (!nrm.is_none()) {
    normals = points_from_array(nrm, "normals");
    if (normals.size() != params.size())
      throw py::value_error("normals must be #N×3 like points (" + std::to_string(params.size()) + " rows, got " +
                            std::to_string(normals.size()) + ")");
  }
  py::gil_scoped_release nogil;
  out->ev->bind_vertices(params, normals);
  out->ev->set_lattice(L.spline, L.embedding);
  return out;
}

// A C-contiguous, writable float64 #V×3 array for results: `given` when it is one (out=), else a new one (not
// zero-filled). Throws ValueError naming `what` for anything else.
py::array_t<double> result_array(const py::object& given, std::size_t V, const char* what) {
  if (given.is_none()) return py::array_t<double>({py::ssize_t(V), py::ssize_t(3)});
  if (!py::isinstance<py::array_t<double>>(given))
    throw py::value_error(std::string(what) + " must be a float64 NumPy array of shape (#V, 3)");
  auto a = py::reinterpret_borrow<py::array_t<double>>(given);
  if (a.ndim() != 2 || a.shape(0) != py::ssize_t(V) || a.shape(1) != 3 || !a.writeable() ||
      !(a.flags() & py::array::c_style))
    throw py::value_error(std::string(what) + " must be a writable C-contiguous float64 array of shape (" +
                          std::to_string(V) + ", 3)");
  return a;
}

py::tuple evaluate(PyFfdEvaluator& e, const glm::dvec3& offset, const py::object& out) {
  const std::size_t V = e.ev->vertex_count();
  const bool with_normals = e.ev->has_normals();
  py::object out_p = py::none(), out_n = py::none();
  if (!out.is_none()) {
    const auto t = out.cast<py::tuple>();
    if (t.size() != 2) throw py::value_error("out must be a pair (P, N) of arrays (N None without normals)");
    out_p = t[0], out_n = t[1];
  }
  py::array_t<double> P = result_array(out_p, V, "out[0]");
  py::object N = py::none();
  if (with_normals) N = result_array(out_n, V, "out[1]");
  double* p = P.mutable_data();
  double* n = with_normals ? py::reinterpret_borrow<py::array_t<double>>(N).mutable_data() : nullptr;
  {
    py::gil_scoped_release nogil;
    std::lock_guard<std::mutex> lock(e.mutex);
    e.ev->evaluate_into(offset, p, n);
  }
  return py::make_tuple(P, N);
}

glm::dvec3 offset_of(const py::object& o) {
  if (o.is_none()) return glm::dvec3(0.0);
  const auto v = o.cast<std::array<double, 3>>();
  for (double x : v)
    if (!std::isfinite(x)) throw py::value_error("offset must be finite");
  return {v[0], v[1], v[2]};
}

py::dict certify(const PyLattice& L, int max_depth, std::size_t max_boxes) {
  core::FoldCertificateOptions o;
  o.max_depth = max_depth;
  o.max_boxes = max_boxes;
  core::FoldCertificate c;
  {
    py::gil_scoped_release nogil;
    c = core::certify_fold_free(L.spline, o);
  }
  auto cells = [](const std::vector<glm::ivec3>& v) {
    py::array_t<std::int32_t> a({py::ssize_t(v.size()), py::ssize_t(3)});
    auto w = a.mutable_unchecked<2>();
    for (std::size_t i = 0; i < v.size(); ++i)
      for (int c2 = 0; c2 < 3; ++c2) w(i, c2) = v[i][c2];
    return a;
  };
  py::dict d;
  d["verdict"] = core::fold_verdict_name(c.verdict);
  d["fold_free"] = c.verdict == core::FoldVerdict::fold_free;
  d["fold_cells"] = cells(c.fold_cells);
  d["fold_params"] = array_from_points(std::move(c.fold_params));
  d["fold_points"] = array_from_points(std::move(c.fold_points));
  d["fold_det"] = py::array_t<double>(py::ssize_t(c.fold_det.size()), c.fold_det.data());
  d["undecided_cells"] = cells(c.undecided_cells);
  d["budget_cells"] = c.budget_cells;
  d["cells"] = c.cells;
  d["quick_cells"] = c.quick_cells;
  d["boxes"] = c.boxes;
  d["min_det_coefficient"] = c.min_det_coefficient;
  return d;
}

void init_lattice(py::module_& m) {
  py::class_<PyLattice>(m, "Lattice",
                        R"doc(An FFD control lattice: a trivariate tensor-product B-spline F (seed Eq. 2.1) and
the affine embedding E that takes points into its parameter domain, so a point x deforms to F(E(x)).

Lattice(control_points, orders, knots=None, bounds=None)
  control_points  #nu×nv×nw×3 float64, world units; [i, j, k] is the control point P_ijk (u index first).
  orders          (ou, ov, ow), order = degree + 1 (4 = tri-cubic), each in [2, n] (cpu_fast: 2..4).
  knots           three 1-D arrays of #n + order non-decreasing knots (u, v, w), or None for clamped uniform
                  knots on [0, 1] (Piegl & Tiller ch. 2).
  bounds          None: points given to ffd_evaluate are parameters (u, v, w) in the knots' domain (E = identity);
                  (lo, hi): points are world positions and the box lo..hi maps onto [0,1]³ (knots must span [0,1]).
Raises ValueError (shapes, orders, knots, non-finite values). Immutable: with_control_points makes a moved copy.
)doc")
      .def(py::init(&make_lattice), py::arg("control_points"), py::arg("orders"), py::arg("knots") = py::none(),
           py::arg("bounds") = py::none())
      .def_static("identity", &identity_lattice, py::arg("bounds"), py::arg("controls") = std::array<int, 3>{4, 4, 4},
                  py::arg("orders") = std::array<int, 3>{4, 4, 4},
                  R"doc(The identity lattice of the box bounds = (lo, hi), world units: clamped uniform knots, control
points at the Greville abscissae mapped into the box, so F(E(x)) = x for every x in the box (to rounding).
controls: (nu, nv, nw) control points per axis; orders: (ou, ov, ow), order = degree + 1, each ≤ its count.)doc")
      .def(
          "with_control_points",
          [](const PyLattice& L, const py::object& cp) {
            PyLattice out = make_lattice(cp, {L.spline.orders().x, L.spline.orders().y, L.spline.orders().z},
                                         py::make_tuple(py::array_t<double>(py::cast(L.spline.knots(0).knots())),
                                                        py::array_t<double>(py::cast(L.spline.knots(1).knots())),
                                                        py::array_t<double>(py::cast(L.spline.knots(2).knots()))),
                                         py::none());
            out.embedding = L.embedding;
            return out;
          },
          py::arg("control_points"),
          "A copy with other control points (#nu×nv×nw×3, same counts), the same knots and embedding.")
      .def_property_readonly("control_points", &control_points_array,
                             "#nu×nv×nw×3 float64 copy of the control points, world units.")
      .def_property_readonly(
          "orders",
          [](const PyLattice& L) {
            const glm::ivec3 o = L.spline.orders();
            return py::make_tuple(o.x, o.y, o.z);
          },
          "(ou, ov, ow): orders (degree + 1) per axis.")
      .def_property_readonly(
          "knots",
          [](const PyLattice& L) {
            return py::make_tuple(py::array_t<double>(py::cast(L.spline.knots(0).knots())),
                                  py::array_t<double>(py::cast(L.spline.knots(1).knots())),
                                  py::array_t<double>(py::cast(L.spline.knots(2).knots())));
          },
          "(ku, kv, kw): the knot vectors as 1-D float64 arrays.")
      .def_property_readonly(
          "embedding",
          [](const PyLattice& L) {
            py::array_t<double> A({3, 3});
            auto w = A.mutable_unchecked<2>();
            for (int r = 0; r < 3; ++r)
              for (int c = 0; c < 3; ++c) w(r, c) = L.embedding.linear[c][r];  // glm is column-major
            return py::make_tuple(A, py::make_tuple(L.embedding.offset.x, L.embedding.offset.y, L.embedding.offset.z));
          },
          "(A, b): the embedding E(x) = A·x + b into the parameter domain; A a 3×3 float64 array.")
      .def("__repr__", [](const PyLattice& L) {
        const glm::ivec3 n = L.spline.control_counts(), o = L.spline.orders();
        return "<trispline.Lattice " + std::to_string(n.x) + "×" + std::to_string(n.y) + "×" + std::to_string(n.z) +
               ", orders (" + std::to_string(o.x) + ", " + std::to_string(o.y) + ", " + std::to_string(o.z) + ")>";
      });
}

}  // namespace

void init_kernels(py::module_& m) {
  init_lattice(m);
  m.def(
      "ffd_evaluate",
      [](const PyLattice& L, const py::object& points, const std::string& backend, const py::object& normals,
         const py::object& offset) {
        auto e = make_evaluator(L, points, normals, backend);
        return evaluate(*e, offset_of(offset), py::none());
      },
      py::arg("lattice"), py::arg("points"), py::arg("backend") = "cpu_fast", py::arg("normals") = py::none(),
      py::arg("offset") = py::none(), R"doc(Deform points through a lattice: P = F(E(points) + offset).

lattice  trispline.Lattice (F and its embedding E).
points   #N×3 float64, world units (parameters when the lattice has no bounds); outside the box they are clamped to
         it (wrapped on periodic axes).
backend  "cpu_fast" (float, vectorised, oneTBB threads; orders 2..4; within 1e-5 × the lattice's diagonal of cpu_ref)
         or "cpu_ref" (double reference, any order). core/ffd/ffd_evaluator.h.
normals  None, or #N×3 unit normals at the points: mapped exactly through the Jacobian's cofactor matrix,
         n' ∝ cof(J_F · A)·n (seed §4.3), and normalised.
offset   None or (du, dv, dw): a parameter offset added to every point (seed §4.5 animation), parameter units.
Returns (P, N): P #N×3 float64 deformed positions, world units; N #N×3 unit normals, or None without `normals`.
Raises ValueError (shapes, dtypes, non-finite values, an order cpu_fast cannot do, an unknown backend).
For many evaluations of the same points use FfdEvaluator (binding once is about half the cost).)doc");

  py::class_<PyFfdEvaluator>(m, "FfdEvaluator",
                             R"doc(FFD of fixed points through a lattice that changes: binds the points once (their
parameters, sorted by lattice cell for cpu_fast), then evaluate() after each set_lattice() — the editor's live path
and what `trispline bench ffd` times.

FfdEvaluator(lattice, points, normals=None, backend="cpu_fast"): shapes and errors as ffd_evaluate.)doc")
      .def(py::init(&make_evaluator), py::arg("lattice"), py::arg("points"), py::arg("normals") = py::none(),
           py::arg("backend") = "cpu_fast")
      .def(
          "set_lattice",
          [](PyFfdEvaluator& e, const PyLattice& L) {
            py::gil_scoped_release nogil;
            std::lock_guard<std::mutex> lock(e.mutex);
            e.ev->set_lattice(L.spline, L.embedding);
          },
          py::arg("lattice"),
          "Replace the lattice (same embedding expected: the points' parameters were bound with the first one's). "
          "O(#controls); ValueError for an order the backend cannot do.")
      .def(
          "evaluate",
          [](PyFfdEvaluator& e, const py::object& offset, const py::object& out) {
            return evaluate(e, offset_of(offset), out);
          },
          py::arg("offset") = py::none(), py::arg("out") = py::none(),
          "Evaluate every bound point (+ offset, parameter units): returns (P, N) as ffd_evaluate. out=(P, N): "
          "write into these writable C-contiguous float64 #V×3 arrays (N None without normals) instead of new ones "
          "(an animation loop then allocates nothing); ValueError for another shape or dtype.")
      .def_property_readonly("vertex_count", [](const PyFfdEvaluator& e) { return e.ev->vertex_count(); })
      .def_property_readonly("backend", [](const PyFfdEvaluator& e) { return core::to_string(e.ev->backend()); });

  m.def(
      "certify", &certify, py::arg("lattice"), py::arg("max_depth") = 6, py::arg("max_boxes") = std::size_t(1) << 19,
      R"doc(Fold-free certificate of a lattice: is det J of F positive on its whole domain? (core/ffd/fold_certificate.h)

Per Bézier cell, det J = ∂F/∂u · (∂F/∂v × ∂F/∂w) as one Bernstein polynomial: all coefficients > 0 certifies the
cell, a corner value ≤ 0 is a fold, otherwise the cell is halved, down to max_depth (0..12) splits and within
max_boxes Bernstein boxes in all. (Johnen, Remacle & Geuzaine 2013; the seed, §2.6, names injectivity as future
work.) The embedding does not enter (it is affine with det A > 0).
Returns a dict: verdict ("fold_free" | "fold" | "undecided"), fold_free (bool), fold_cells #K×3 int32 (knot-span index
per axis), fold_params #K×3 (parameters with det J ≤ 0), fold_points #K×3 (F there, world units), fold_det #K,
undecided_cells #U×3 int32, budget_cells, cells, quick_cells, boxes, min_det_coefficient.
Raises ValueError: an order below 2, max_depth outside 0..12, max_boxes 0.)doc");
}

}  // namespace trispline::python
