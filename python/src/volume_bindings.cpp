// trispline.silhouettes: the silhouette curves of a scene volume's iso-surface (core/volume/silhouettes.h).
#include <memory>

#include "core/volume/silhouettes.h"
#include "python/src/bindings.h"
#include "python/src/py_scene.h"

namespace trispline::python {
namespace {

glm::dvec3 vec3_of(const py::handle& v, const char* what) {
  const auto a = v.cast<std::array<double, 3>>();
  for (double x : a)
    if (!std::isfinite(x)) throw py::value_error(std::string("camera['") + what + "'] must be finite");
  return {a[0], a[1], a[2]};
}

// The scene camera with the given dict's entries (eye, target, up, fov_deg, viewport) in place of its own.
core::Camera camera_of(core::Camera c, const py::object& camera) {
  if (camera.is_none()) return c;
  const py::dict d = camera.cast<py::dict>();
  for (auto item : d) {
    const std::string k = item.first.cast<std::string>();
    if (k == "eye")
      c.eye = vec3_of(item.second, "eye");
    else if (k == "target")
      c.target = vec3_of(item.second, "target");
    else if (k == "up")
      c.up = vec3_of(item.second, "up");
    else if (k == "fov_deg")
      c.fov_deg = item.second.cast<double>();
    else if (k == "viewport") {
      const auto v = item.second.cast<std::array<int, 2>>();
      c.viewport = {v[0], v[1]};
    } else {
      throw py::value_error("camera: unknown key '" + k + "' (eye, target, up, fov_deg, viewport)");
    }
  }
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("camera: ") + e.what());
  }
  return c;
}

py::list silhouettes(const PyScene& s, const std::string& volume_id, const py::object& camera, bool details) {
  std::shared_ptr<const core::SilhouetteResult> result;
  {
    core::VolumeObject vol;
    core::Camera cam;
    {
      py::gil_scoped_release nogil;
      std::lock_guard<std::mutex> lock(s.mutex());
      const core::VolumeObject* v = s.scene().find_volume(volume_id);
      if (!v) throw py::key_error("no volume named '" + volume_id + "'");
      vol = *v;  // shares the spline and table (shared pointers)
      cam = s.scene().camera;
    }
    cam = camera_of(cam, camera);
    py::gil_scoped_release nogil;
    result = std::make_shared<const core::SilhouetteResult>(
        core::extract_silhouettes(*vol.spline, *vol.table, vol.iso, vol.silhouette_view(cam), vol.silhouette.params));
  }
  py::list out;
  for (const core::SilhouettePolyline& pl : result->polylines) {
    py::array_t<double> pts({py::ssize_t(pl.points.size()), py::ssize_t(3)},
                            reinterpret_cast<const double*>(pl.points.data()));
    if (!details) {
      out.append(pts);
      continue;
    }
    py::dict d;
    d["points"] = pts;
    d["visible"] = py::array_t<bool>(py::ssize_t(pl.visible.size()), reinterpret_cast<const bool*>(pl.visible.data()));
    d["gradient_norm"] = py::array_t<float>(py::ssize_t(pl.gradient_norm.size()), pl.gradient_norm.data());
    d["closed"] = pl.closed;
    out.append(d);
  }
  return out;
}

}  // namespace

void init_volume(py::module_& m) {
  m.def("silhouettes", &silhouettes, py::arg("scene"), py::arg("volume"), py::arg("camera") = py::none(),
        py::arg("details") = false,
        R"doc(Silhouette curves of a volume's iso-surface D = iso for a camera (seed §7.3.3, Eq. 7.2).

scene    trispline.Scene holding the volume (volume.load: a CT/MRI file or an analytic test volume).
volume   its id. The volume's own iso-level, projection (perspective / orthographic) and silhouette settings apply
         (volume.iso, volume.silhouettes).
camera   None for the scene camera, or a dict overriding any of eye, target, up (world units = millimetres),
         fov_deg (degrees), viewport ((width, height) pixels).
details  False: a list of #K×3 float64 polylines (world millimetres; a closed curve does not repeat its first
         point). True: a list of dicts {points #K×3, visible #K bool (not hidden by the iso-surface), gradient_norm #K
         float32 (|∇D| per mm), closed bool}.
Points hidden by the iso-surface are included (details tells them apart). Deterministic. The GIL is released while
the curves are traced (oneTBB threads).
Raises KeyError (unknown volume), ValueError (a bad camera).)doc");
}

}  // namespace trispline::python
