// trispline.Scene and trispline.replay: the command layer (py_scene.h, log_replay.h) and zero-copy mesh views.
#include <climits>
#include <filesystem>

#include "core/commands/mesh_set.h"
#include "python/src/bindings.h"
#include "python/src/lattice.h"
#include "python/src/log_replay.h"
#include "python/src/py_scene.h"

namespace trispline::python {
namespace {

namespace fs = std::filesystem;

// Relative paths of Scene.run resolve against the process's working directory (as a log's against its folder).
core::CommandContext cwd_context() {
  core::CommandContext ctx;
  ctx.base_dir = fs::current_path();
  ctx.output_dir = ctx.base_dir;
  return ctx;
}

// The mesh of object `id` in `space` ("world": evaluated, world units; "rest": as loaded, object space). KeyError for
// an unknown object, ValueError for another space. Called with the scene locked.
std::shared_ptr<const core::TriMesh> object_mesh(const PyScene& s, const std::string& id, const std::string& space) {
  const core::SceneObject* o = s.scene().find(id);
  if (!o) throw py::key_error("no object named '" + id + "'");
  if (space == "world") return o->world_mesh ? o->world_mesh : o->rest_mesh;
  if (space == "rest") return o->rest_mesh;
  throw py::value_error("space must be 'world' or 'rest' (got '" + space + "')");
}

template <class Fn>
auto locked(const PyScene& s, Fn&& fn) {
  py::gil_scoped_release nogil;
  std::lock_guard<std::mutex> lock(s.mutex());
  return fn();
}

py::object vertices(const PyScene& s, const std::string& id, const std::string& space) {
  auto mesh = locked(s, [&] { return object_mesh(s, id, space); });
  return readonly_view(reinterpret_cast<const double*>(mesh->positions.data()), mesh->positions.size(), 3, mesh);
}

py::object normals(const PyScene& s, const std::string& id, const std::string& space) {
  auto mesh = locked(s, [&] { return object_mesh(s, id, space); });
  if (mesh->normals.empty()) return py::none();
  return readonly_view(reinterpret_cast<const double*>(mesh->normals.data()), mesh->normals.size(), 3, mesh);
}

py::object uvs(const PyScene& s, const std::string& id, const std::string& space) {
  auto mesh = locked(s, [&] { return object_mesh(s, id, space); });
  if (mesh->uvs.empty()) return py::none();
  return readonly_view(reinterpret_cast<const double*>(mesh->uvs.data()), mesh->uvs.size(), 2, mesh);
}

// int32 view of the uint32 indices: the same bits for every index below 2^31, which holds when #V ≤ INT32_MAX.
py::object faces(const PyScene& s, const std::string& id, const std::string& space) {
  auto mesh = locked(s, [&] { return object_mesh(s, id, space); });
  if (mesh->vertex_count() > std::size_t(INT32_MAX))
    throw py::value_error("'" + id + "' has more than 2^31 - 1 vertices: its faces do not fit int32");
  return readonly_view(reinterpret_cast<const std::int32_t*>(mesh->triangles.data()), mesh->triangles.size(), 3, mesh);
}

py::object run(PyScene& s, const py::object& command) {
  const nlohmann::json line = json_from_python(command, "command");
  const core::CommandContext ctx = cwd_context();
  const nlohmann::json entry = locked(s, [&] { return s.run(line, ctx); });
  return python_from_json(entry);
}

py::object set_mesh(PyScene& s, const std::string& id, const py::object& V, const py::object& F) {
  core::TriMesh mesh;
  mesh.positions = points_from_array(V, "V", 3);
  mesh.triangles = triangles_from_array(F, mesh.positions.size(), "F");
  const nlohmann::json entry = locked(s, [&] {
    if (!s.scene().find(id)) throw py::key_error("no object named '" + id + "'");
    return s.execute(std::make_unique<core::MeshSetCommand>(id, std::move(mesh)));
  });
  return python_from_json(entry);
}

PyLattice object_lattice(const PyScene& s, const std::string& id) {
  return locked(s, [&] {
    const core::SceneObject* o = s.scene().find(id);
    if (!o) throw py::key_error("no object named '" + id + "'");
    if (!o->ffd) throw py::value_error("'" + id + "' has no FFD lattice (place.sketch or lattice.ring makes one)");
    return PyLattice{o->ffd->lattice, o->ffd->embedding};
  });
}

std::unique_ptr<PyScene> open_scene(const fs::path& path) {
  auto s = std::make_unique<PyScene>();
  LogRun run;
  {
    py::gil_scoped_release nogil;
    run = run_log(*s, path, {}, false);
  }
  if (!run.ok) raise_command_error(run.error, run.field);
  return s;
}

py::dict camera(const PyScene& s) {
  const core::Camera c = locked(s, [&] { return s.scene().camera; });
  py::dict d;
  d["eye"] = py::make_tuple(c.eye.x, c.eye.y, c.eye.z);
  d["target"] = py::make_tuple(c.target.x, c.target.y, c.target.z);
  d["up"] = py::make_tuple(c.up.x, c.up.y, c.up.z);
  d["fov_deg"] = c.fov_deg;
  d["viewport"] = py::make_tuple(c.viewport.x, c.viewport.y);
  return d;
}

}  // namespace

void init_scene(py::module_& m) {
  py::class_<PyScene>(m, "Scene",
                      R"doc(A trispline document: objects, volumes, camera and timeline, with an undo history.

Every change is a command, run exactly as a line of a command log (docs/commands.md): the same registry, the same
validation, the same undo stack as the editor and `trispline replay`. A Scene may be shared between Python threads;
its calls run one at a time, with the GIL released while a command runs.
)doc")
      .def(py::init<>(), "An empty scene (default camera, Blender's default timeline).")
      .def("run", &run, py::arg("command"), R"doc(Run one command and return its report entry.

command: a dict such as {"cmd": "scene.primitive", "kind": "teapot", "name": "pot"} (NumPy arrays and scalars are
  accepted as values), or the same as one JSON line (str). "edit.undo" / "edit.redo" work as in a log.
Relative paths resolve against the current working directory; files a command writes (volume.export) must stay
inside it.
Returns report.json's per-command entry: {"line": n-th entry of this session (1-based), "cmd": id, "ok": True,
  "ms": wall time of the command, "stats": the command's figures (vertex counts, stage timings in ms),
  "command": the line as executed, with every default filled in (what save() writes)}.
Raises trispline.CommandError (.field names the bad JSON field) when the command is refused or fails; the scene is
  then unchanged. ValueError when a dict holds NaN or infinity (JSON has neither).)doc")
      .def(
          "undo", [](PyScene& s) { return locked(s, [&] { return s.undo(); }); },
          "Undo the last applied command. Returns False when there is nothing to undo.")
      .def(
          "redo", [](PyScene& s) { return locked(s, [&] { return s.redo(); }); },
          "Redo the last undone command. Returns False when there is nothing to redo; raises CommandError if it fails.")
      .def_property_readonly(
          "objects",
          [](const PyScene& s) {
            return locked(s, [&] {
              std::vector<std::string> ids;
              for (const auto& o : s.scene().objects()) ids.push_back(o.name);
              return ids;
            });
          },
          "Object ids (names) in scene order: list[str]. Volumes are listed by `volumes`.")
      .def_property_readonly(
          "volumes",
          [](const PyScene& s) {
            return locked(s, [&] {
              std::vector<std::string> ids;
              for (const auto& v : s.scene().volumes()) ids.push_back(v.name);
              return ids;
            });
          },
          "Volume ids (names, shared with objects) in load order: list[str].")
      .def_property_readonly("camera", &camera,
                             "The scene camera (set by camera.set): dict with eye, target, up (world units), fov_deg "
                             "(vertical, degrees), viewport (pixels, width × height).")
      .def("vertices", &vertices, py::arg("id"), py::arg("space") = "world", R"doc(Vertex positions of object `id`.

Returns a read-only #V×3 float64 array viewing the scene's own mesh (no copy); it stays valid, unchanged, after the
scene changes or is deleted (meshes are immutable and shared; the array's base holds this one alive).
space: "world" — the evaluated mesh (transform, FFD / DFFD at scene time 0), world units; "rest" — the mesh as
  loaded or set, object space.
Raises KeyError for an unknown object, ValueError for another space.)doc")
      .def("faces", &faces, py::arg("id"), py::arg("space") = "world",
           "Triangles of object `id`: a read-only #F×3 int32 array of vertex indices (counter-clockwise seen from "
           "outside), a view of the mesh's uint32 indices (no copy). A DFFD split's world mesh has more triangles "
           "than its rest mesh. Raises KeyError for an unknown object.")
      .def("normals", &normals, py::arg("id"), py::arg("space") = "world",
           "Unit vertex normals of object `id`: read-only #V×3 float64 view, or None. Raises KeyError.")
      .def("uvs", &uvs, py::arg("id"), py::arg("space") = "world",
           "Texture coordinates of object `id`: read-only #V×2 float64 view, or None when the mesh has none. "
           "Raises KeyError.")
      .def("set_mesh", &set_mesh, py::arg("id"), py::arg("V"), py::arg("F"), R"doc(Replace the rest mesh of object `id`.

V: #V×3 array of finite positions, object space, world units (any real dtype; float64 read without a copy).
F: #F×3 integer array of vertex indices in [0, #V), counter-clockwise seen from outside.
An undoable command, `mesh.set`, whose log line holds the mesh (every replay rebuilds it: the editor, `trispline
replay`, Scene.open). Normals are recomputed; uvs kept when #V is unchanged.
Returns the report entry (see run). Raises ValueError (wrong shape or dtype, a value not finite, an index out of
range) and KeyError (unknown object) before the scene is touched; CommandError (field "object") for an object with
an FFD lattice, DFFD split, clip, morph or tile layers.)doc")
      .def("lattice", &object_lattice, py::arg("id"),
           "The FFD control lattice of object `id` as a trispline.Lattice, with its embedding (world rest space → "
           "[0,1]³), so ffd_evaluate(scene.lattice(id), scene.vertices(id, 'rest')) deforms as the scene does (for an "
           "untransformed object). Raises KeyError (unknown object), ValueError (no lattice).")
      .def(
          "save", [](const PyScene& s, const fs::path& path) { locked(s, [&] { s.save(path); }); }, py::arg("path"),
          R"doc(Write the applied commands as a command log (JSON Lines), as the editor's Save does: one line per
command, paths relative to the log's folder, written atomically (PATH.tmp, fsync, rename). Raises OSError-like
RuntimeError when the file cannot be written.)doc")
      .def_static("open", &open_scene, py::arg("path"), R"doc(A new Scene made by replaying the command log at `path`.

As the editor's Open: relative paths resolve against the log's folder, edit.undo / edit.redo lines move the
history, and no command writes files (volume.export, anim.record). Raises CommandError ("LOG:LINE: field 'x': ..."
with .field) at the first line that fails.)doc")
      .def("__repr__", [](const PyScene& s) {
        return locked(s, [&] {
          return "<trispline.Scene: " + std::to_string(s.scene().objects().size()) + " objects, " +
                 std::to_string(s.scene().volumes().size()) + " volumes, " + std::to_string(s.history().applied()) +
                 " commands applied>";
        });
      });

  m.def(
      "replay",
      [](const fs::path& log, const fs::path& out) {
        nlohmann::json report;
        {
          py::gil_scoped_release nogil;
          report = replay_log(log, out);
        }
        return python_from_json(report);
      },
      py::arg("log"), py::arg("out"),
      R"doc(Replay a command log headlessly into folder `out`, as `trispline replay LOG --out OUT`.

Writes OUT/report.json (the CLI's schema: log, ok, replay_ms, [error, failed_line], commands [{line, cmd, ok, ms,
[error], [stats]}], objects [{name, vertices, triangles, deformed}], scene_glb) and OUT/scene.glb (the CPU reference
geometry). Without a GPU layer there is no final.png ("final_png_error" says so) and anim.record lines are not
recorded ("record_error"). Files of volume.export lines go under OUT. A failing line does not raise: the report has
ok = False, error and failed_line. Returns the report as a dict.)doc");
}

}  // namespace trispline::python
