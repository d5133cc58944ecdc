// PYBIND11_MODULE(_trispline): the compiled half of the `trispline` package (python/trispline/__init__.py re-exports
// it). Defines trispline.CommandError and maps the core's exceptions onto Python's.
#include <pybind11/eval.h>

#include "core/params/command_context.h"
#include "editor/commands/command_log.h"
#include "python/src/bindings.h"

namespace trispline::python {
namespace {

py::object& command_error_class() {
  static py::object* cls = nullptr;  // lives as long as the interpreter (the module is never unloaded)
  if (!cls) cls = new py::object();
  return *cls;
}

constexpr const char* kCommandErrorSource = R"py(
class CommandError(Exception):
    """A command was refused; the scene is unchanged.

    Raised by Scene.run, Scene.set_mesh (for a refusal of the command itself, not of the arrays), Scene.redo and
    Scene.open. Attributes:
      field    the JSON field of the command line that is wrong ("width", "springs.mass", "cmd" for an unknown
               command), or "" when no single field is to blame;
      message  the whole message, as the editor and `trispline replay` report it.
    """

    def __init__(self, message, field=""):
        super().__init__(message)
        self.message = message
        self.field = field

    def __repr__(self):
        return f"CommandError({self.message!r}, field={self.field!r})"
)py";

}  // namespace

void raise_command_error(const std::string& message, const std::string& field) {
  py::gil_scoped_acquire gil;
  PyErr_SetObject(command_error_class().ptr(), command_error_class()(message, field).ptr());
  throw py::error_already_set();
}

}  // namespace trispline::python

PYBIND11_MODULE(_trispline, m) {
  namespace py = pybind11;
  using namespace trispline::python;
  m.doc() = "Compiled part of trispline (see help(trispline)).";
  py::dict ns;
  ns["__name__"] = "trispline";
  ns["__builtins__"] = py::module_::import("builtins");
  py::exec(kCommandErrorSource, ns, ns);
  command_error_class() = ns["CommandError"];
  m.attr("CommandError") = command_error_class();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const trispline::core::CommandError& e) {
      PyErr_SetObject(command_error_class().ptr(), command_error_class()(std::string(e.what()), e.field()).ptr());
    } catch (const trispline::editor::LogError& e) {
      PyErr_SetObject(command_error_class().ptr(), command_error_class()(std::string(e.what()), e.field()).ptr());
    }
  });
  init_scene(m);
  init_kernels(m);
  init_volume(m);
}
