"""Press's modal drag in Blender's window, driven by input events, and the Object ▸ trispline menu on screen.

    tests/with_xvfb.sh 1280x800x24 blender --factory-startup --enable-event-simulate \
        --python tests/blender/test_press_drag.py -- --source-dir . --module-dir build/python \
        --trispline build/editor/trispline --work /tmp/x

Installs and enables the add-on (test_addon.py's helpers), places the icosphere on the terrain, frames it in the 3D
viewport and invokes Press as the menu does (INVOKE_DEFAULT in the viewport). Then, through Window.event_simulate
(Blender's own event queue, as a mouse would fill it): the wheel once (radius × 1.1), the left button down over the
object, a drag across it, release. Checked: the vertices moved, the log's new lattice.press carries the dragged path
(several centres on the object, radius 0.35 × 1.1) and one ed.undo restores the object. A second drag ended with
Esc changes nothing. Screenshots of the drag and of the open menu go to --work. Any failure exits 1.
"""

import json
import os
import sys
import traceback

import bpy
import numpy as np
from bpy_extras import view3d_utils

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_addon as t  # noqa: E402


def world_vertices(obj):
    W = np.array(obj.matrix_world)
    return np.array([v.co[:] for v in obj.data.vertices]) @ W[:3, :3].T + W[:3, 3]


def steps():
    """A generator run by a timer: each yield gives the event loop that many seconds to handle the events sent."""
    a = t.args()
    a.source_dir, a.module_dir, a.work = (os.path.abspath(p) for p in (a.source_dir, a.module_dir, a.work))
    os.makedirs(a.work, exist_ok=True)
    t.check("--enable-event-simulate" in sys.argv, "Blender runs with --enable-event-simulate")
    bpy.context.preferences.view.smooth_view = 0  # view changes at once, not animated
    t.install(a)
    terrain, ico, tile, gp, _ = t.build_scene()
    t.select([ico, gp, terrain], terrain)
    t.check(bpy.ops.object.trispline_place(view="CAMERA", width=0.3, height=0.35) == {"FINISHED"}, "placed")
    placed = bpy.data.objects["Ico placed"]
    t.select([placed], placed)
    bpy.ops.ed.undo_push(message="placed")  # the state an undo of the press returns to

    win = bpy.context.window_manager.windows[0]
    area = max((ar for ar in win.screen.areas if ar.type == "VIEW_3D"), key=lambda ar: ar.width * ar.height)
    region = next(r for r in area.regions if r.type == "WINDOW")
    rv3d = area.spaces.active.region_3d
    win.event_simulate("ESC", "PRESS", x=win.width // 2, y=win.height // 2)  # the splash screen goes away
    yield 0.2
    with bpy.context.temp_override(window=win, area=area, region=region):
        bpy.ops.view3d.view_axis(type="TOP")
        bpy.ops.view3d.view_selected()
        bpy.ops.view3d.zoom(delta=-1)
    yield 0.3

    def screen_xy(p):
        r = view3d_utils.location_3d_to_region_2d(region, rv3d, p)
        return int(region.x + r.x), int(region.y + r.y)

    # The drag: across the object's middle, seen from the top, between points a fifth in from its ends.
    Pw = world_vertices(placed)
    lo, hi = Pw.min(axis=0), Pw.max(axis=0)
    mid = 0.5 * (lo + hi)
    ends = [np.array([lo[0] + f * (hi[0] - lo[0]), mid[1], hi[2]]) for f in (0.2, 0.8)]
    (x0, y0), (x1, y1) = screen_xy(ends[0]), screen_xy(ends[1])
    t.check(abs(x1 - x0) > 40, f"the object spans {abs(x1 - x0)} pixels of the view")
    drag = [(round(x0 + s * (x1 - x0)), round(y0 + s * (y1 - y0))) for s in np.linspace(0.0, 1.0, 9)]

    def invoke():
        with bpy.context.temp_override(window=win, area=area, region=region):
            return bpy.ops.object.trispline_press("INVOKE_DEFAULT", True, radius=0.35, strength=0.12)

    V0 = np.array([v.co[:] for v in placed.data.vertices])
    log0 = placed["trispline_log"]
    t.check(invoke() == {"RUNNING_MODAL"}, "Press waits for a drag (modal)")
    win.event_simulate("MOUSEMOVE", "NOTHING", x=x0, y=y0)
    yield 0.05
    win.event_simulate("WHEELUPMOUSE", "PRESS", x=x0, y=y0)
    yield 0.05
    win.event_simulate("LEFTMOUSE", "PRESS", x=x0, y=y0)
    yield 0.05
    for x, y in drag[1:]:
        win.event_simulate("MOUSEMOVE", "NOTHING", x=x, y=y)
        yield 0.05
    yield 0.3  # a redraw with the path drawn
    with bpy.context.temp_override(window=win):
        bpy.ops.screen.screenshot(filepath=os.path.join(a.work, "press_drag.png"))
    win.event_simulate("LEFTMOUSE", "RELEASE", x=x1, y=y1)
    yield 0.5
    placed = bpy.data.objects["Ico placed"]
    V1 = np.array([v.co[:] for v in placed.data.vertices])
    moved = float(np.max(np.abs(V1 - V0)))
    t.check(moved > 1e-3, f"the drag pressed the object (vertices moved up to {moved:.3f} m)")
    lines = json.loads(placed["trispline_log"])
    press = lines[-1] if len(lines) == len(json.loads(log0)) + 1 else {}
    t.check(press.get("cmd") == "lattice.press", "one lattice.press recorded for the drag")
    path = np.array(press.get("path", []), dtype=np.float64)
    t.check(len(path) >= 3, f"its path has the drag's sphere centres ({len(path)})")
    t.check(abs(press.get("radius", 0.0) - 0.35 * 1.1) < 1e-6,
            f"the wheel made the radius 0.35 × 1.1 (radius {press.get('radius')})")
    if len(path):
        # trispline is Y-up: (x, y, z) → Blender (x, -z, y)
        P = np.stack([path[:, 0], -path[:, 2], path[:, 1]], axis=1)
        t.check(bool(np.all((P >= lo - 0.05) & (P <= hi + 0.05))), "every centre lies on the object (under the cursor)")
        t.check(P[-1][0] - P[0][0] > 0.3 * (hi[0] - lo[0]), "the centres follow the drag from left to right")

    with bpy.context.temp_override(window=win):
        bpy.ops.ed.undo()
    yield 0.2
    placed = bpy.data.objects["Ico placed"]
    V2 = np.array([v.co[:] for v in placed.data.vertices])
    t.check(np.array_equal(V2, V0) and placed["trispline_log"] == log0, "one ed.undo takes the drag's press back")

    # Esc ends a drag without pressing.
    t.select([placed], placed)
    t.check(invoke() == {"RUNNING_MODAL"}, "Press waits for a second drag")
    win.event_simulate("MOUSEMOVE", "NOTHING", x=x0, y=y0)
    yield 0.05
    win.event_simulate("LEFTMOUSE", "PRESS", x=x0, y=y0)
    yield 0.05
    win.event_simulate("MOUSEMOVE", "NOTHING", x=x1, y=y1)
    yield 0.05
    win.event_simulate("ESC", "PRESS", x=x1, y=y1)
    yield 0.3
    placed = bpy.data.objects["Ico placed"]
    V3 = np.array([v.co[:] for v in placed.data.vertices])
    t.check(np.array_equal(V3, V0) and placed["trispline_log"] == log0, "Esc cancels the drag: nothing pressed")

    # The menu: Object ▸ trispline, opened where the cursor is, pictured, closed.
    win.event_simulate("MOUSEMOVE", "NOTHING", x=region.x + region.width // 3, y=region.y + 2 * region.height // 3)
    yield 0.05
    with bpy.context.temp_override(window=win, area=area, region=region):
        bpy.ops.wm.call_menu(name="VIEW3D_MT_trispline")
    yield 0.3
    shot = os.path.join(a.work, "menu.png")
    with bpy.context.temp_override(window=win):
        bpy.ops.screen.screenshot(filepath=shot)
    t.check(os.path.isfile(shot) and os.path.getsize(shot) > 10000, f"screenshot of the open menu: {shot}")
    win.event_simulate("ESC", "PRESS", x=region.x + 10, y=region.y + 10)
    yield 0.1


def run():
    it = steps()

    def tick():
        try:
            return next(it)
        except StopIteration:
            pass
        except Exception:
            traceback.print_exc()
            t.FAILURES.append("exception")
        print(f"{'FAILED: ' + str(len(t.FAILURES)) + ' check(s)' if t.FAILURES else 'all checks passed'}", flush=True)
        os._exit(1 if t.FAILURES else 0)  # leave without saving quit.blend

    bpy.app.timers.register(tick, first_interval=0.5)


if __name__ == "__main__":
    run()
