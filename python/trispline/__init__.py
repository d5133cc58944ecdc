"""trispline — trivariate tensor-product B-spline functions in solid modelling, from Python.

The editor's document, its command layer and the core kernels of trispline (docs/python.md), on NumPy
arrays. Shapes follow libigl's convention: #V×3 is one row per vertex. Units: world units for positions (the
editor's scenes; millimetres for volumes), parameter domain [0,1]³ for FFD parameters, degrees and pixels for
cameras. "The seed" is S. Schein's 2006 PhD thesis, cited by section (§2.3.1) and equation (Eq. 2.1).

Scenes and commands
  Scene()                       a document with an undo history; every change is a command run as a log line
  Scene.run(command)            {"cmd": "scene.primitive", "kind": "teapot", "name": "pot"} -> report entry dict
  Scene.undo() / redo()
  Scene.objects / volumes       ids (names)
  Scene.vertices(id)            #V×3 float64, read-only, no copy; faces(id) #F×3 int32; normals(id); uvs(id) #V×2
  Scene.set_mesh(id, V, F)      undoable mesh.set
  Scene.lattice(id)             the object's FFD lattice
  Scene.save(path)              the command log (JSON Lines), as the editor's Save
  Scene.open(path)              a new Scene replayed from a log
  replay(log, out)              headless replay writing out/report.json and out/scene.glb
  CommandError                  a refused command: .field (the JSON field to blame) and .message

Kernels
  Lattice(control_points, orders, knots=None, bounds=None), Lattice.identity(bounds, controls, orders)
  ffd_evaluate(lattice, points, backend="cpu_fast", normals=None) -> (P, N)     seed Eq. 2.1, §4.3
  FfdEvaluator(lattice, points, ...)  bind once, evaluate after every lattice change
  certify(lattice) -> dict      fold-free certificate (det J > 0 on the whole domain)
  silhouettes(scene, volume, camera=None) -> list of #K×3 polylines                 seed §7.3.3, Eq. 7.2

Errors: a NumPy argument of the wrong shape or dtype, or holding NaN / infinity, raises ValueError naming the
expected shape; an unknown object id raises KeyError; a refused command raises CommandError. Calls that take more
than a few milliseconds release the GIL (the kernels run on oneTBB threads).
"""

from ._trispline import (  # noqa: F401  (the public API)
    CommandError,
    FfdEvaluator,
    Lattice,
    Scene,
    certify,
    ffd_evaluate,
    replay,
    silhouettes,
)

__all__ = [
    "CommandError",
    "FfdEvaluator",
    "Lattice",
    "Scene",
    "certify",
    "ffd_evaluate",
    "replay",
    "silhouettes",
]
