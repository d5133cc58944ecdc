# Blender's viewport redraw time for a scene of ours, to print beside our editor's (`trispline bench editor`,
# editor/app_bench.cpp): Blender 3.4.1 (Debian's /usr/bin/blender) in GUI mode, the same software GL (Mesa llvmpipe
# under Xvfb), the same glb, the same motion (N frames with nothing changed, then N frames orbiting the view about
# the world vertical a few degrees a frame).
#
#   blender --factory-startup --window-geometry 0 0 1280 800 --python scripts/blender_redraw_timer.py -- \
#       --glb SCENE.glb --frames 30 --orbit-deg 3 --out RESULT.json
#   (with DISPLAY set to an X server, e.g. tests/with_xvfb.sh 1280x800x24 blender ...; a glb of a scene:
#    trispline replay assets/scenes/default.jsonl --out DIR writes DIR/scene.glb)
#
# Once the window is up (a bpy.app.timers callback: the --python script runs before the UI exists) it deletes the
# factory startup objects (Cube, Light, Camera), imports the glb (glTF's +Y up becomes Blender's +Z up), makes the
# largest 3D View fill the window (the other areas closed; no header, toolbar, side bar or status bar; the top bar
# stays: the region is 1280 x 773 in a 1280 x 800 window), sets Solid shading and frames all objects
# (view3d.view_all). Overlays (grid floor, axes, 3D cursor, object origins, outlines of the selected objects (the
# importer selects what it imports), text info) and the navigation gizmo stay at Blender's defaults: our editor draws
# a grid and selection outlines of its own, and picking the matching subset is not worth the doubt. --overlays off
# turns them all off (View3DOverlay.show_overlays, SpaceView3D.show_gizmo).
#
# What is timed: one `wm.redraw_timer(type='DRAW', iterations=1)` on the 3D View's WINDOW region, then glFinish, with
# time.perf_counter() around both; 3 untimed redraws first, then --frames idle redraws, then --frames orbit frames
# (rotate region_3d.view_rotation about world +Z by --orbit-deg, then one timed redraw). In Blender 3.4
# (wm_operators.c redraw_timer_step, wm_draw.c wm_draw_region_test) 'DRAW' redraws just the context region: it binds
# the region's offscreen buffer (for the 3D View a GPUViewport), runs ED_region_do_draw (the draw manager: depsgraph-
# evaluated objects drawn by the Workbench engine, then the overlays, gizmos and text info) and unbinds it.
# It does NOT composite the region into the window nor swap buffers, and draws no other region (headers, panels,
# other areas). 'DRAW_WIN' runs the same per-region draw for every visible region of every area (still no window
# composite, no swap); 'DRAW_SWAP' / 'DRAW_WIN_SWAP' go through wm_draw_update (the real frame path: tagged regions
# redrawn, all regions blitted into the window, buffers swapped). With the 3D View filling the window 'DRAW' is the
# bulk of a frame; it leaves out the viewport's colour-managed blit into the window (a full-window pass) and the
# swap. The redraw_timer operator itself issues no glFinish; llvmpipe rasterizes lazily (at a flush, a framebuffer
# change or a finish), so the script calls glFinish (bgl) inside the timed span, as our bench does after each frame
# (the operator's own report, printed as "Warning: 1 x Draw region: ... ms", leaves the finish out).
#
# Caveats, measured on the default scene (38076 vertices, 75986 triangles), 2 shared cores: Workbench's viewport
# anti-aliasing (Preferences > Viewport > Anti-Aliasing, "8" samples with --factory-startup) accumulates one jittered
# sample per redraw while the view stands still and then only re-displays the result, but every moved view starts
# over: idle ~135-160 ms, orbit ~320-390 ms a redraw. --viewport-aa OFF renders every redraw the same way (idle ~170,
# orbit ~185 ms). The overlays are much of the idle cost on llvmpipe: --overlays off gave idle ~60, orbit ~235 ms.
# 'DRAW_WIN_SWAP' instead of 'DRAW' (the whole frame: the 3D View's colour-managed blit into the window, the top bar,
# the swap) gave idle ~185, orbit ~375 ms, i.e. within the run-to-run spread of the orbit, some 30 ms more idle.
#
# Output (--out): {"blender_version", "gl_renderer", "objects" (mesh objects), "vertices", "triangles" (sums over
# mesh objects; triangles from loop_triangles), "viewport": [w, h] (the 3D View's WINDOW region, pixels), "window",
# "idle_median_ms", "idle_p95_ms", "orbit_median_ms", "orbit_p95_ms", "frames", "idle_ms", "orbit_ms" (every frame),
# "viewport_aa", "overlays", "draw_type": "DRAW"}; exit code 0 (wm.quit_blender; it also writes Blender's session
# recovery file /tmp/quit.blend, as any quit does). On any error: {"error": "<message>"} and exit code 1 (os._exit:
# sys.exit does nothing from a timer callback). A watchdog (--timeout-s) writes the error and exits 1 if the run hangs.
import argparse
import math
import os
import sys
import threading
import time
import traceback

import bpy
from mathutils import Quaternion

WARMUP = 3

_args = None
_out_path = None


def _write_json(path, data):
    import json
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def _fail(message, code=1):
    """Writes {"error": message} to --out (when known) and ends the process at once with a non-zero code."""
    print("blender_redraw_timer: error: " + message, file=sys.stderr)
    try:
        if _out_path:
            _write_json(_out_path, {"error": message})
    except Exception as e:  # the exit code still tells
        print("blender_redraw_timer: cannot write %s: %s" % (_out_path, e), file=sys.stderr)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


def _parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_redraw_timer.py", description="Times Blender's 3D View redraw.")
    p.add_argument("--glb", required=True, help="the scene to import (glTF binary)")
    p.add_argument("--out", required=True, help="the JSON result")
    p.add_argument("--frames", type=int, default=30, help="timed redraws idle, then as many orbiting")
    p.add_argument("--orbit-deg", type=float, default=3.0, help="degrees about world +Z per orbit frame")
    p.add_argument("--viewport-aa", default="keep",
                   choices=["keep", "OFF", "FXAA", "5", "8", "11", "16", "32"],
                   help="Preferences > Viewport > Anti-Aliasing for the run (keep: Blender's default)")
    p.add_argument("--overlays", default="on", choices=["on", "off"],
                   help="the 3D View's overlays and gizmos (on: Blender's defaults)")
    p.add_argument("--timeout-s", type=float, default=600.0, help="watchdog: give up after this many seconds")
    # argparse would sys.exit() on bad arguments; report them like any other error instead.
    p.error = lambda message: (_ for _ in ()).throw(ValueError("bad arguments: " + message))
    a = p.parse_args(argv)
    if a.frames < 1:
        raise ValueError("--frames must be >= 1")
    return a


def _percentile(values, q):
    """Linear interpolation between closest ranks (numpy's default), q in [0, 100]."""
    s = sorted(values)
    if len(s) == 1:
        return s[0]
    pos = (len(s) - 1) * q / 100.0
    lo = int(math.floor(pos))
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (s[hi] - s[lo]) * (pos - lo)


def _largest_view3d(window):
    areas = [a for a in window.screen.areas if a.type == 'VIEW_3D']
    if not areas:
        raise RuntimeError("no 3D View area in the window")
    area = max(areas, key=lambda a: a.width * a.height)
    region = next((r for r in area.regions if r.type == 'WINDOW'), None)
    if region is None:
        raise RuntimeError("the 3D View has no WINDOW region")
    return area, region


def _run():
    """The work, as a generator: each yield is a pause (seconds) that lets Blender's event loop run."""
    wm = bpy.context.window_manager
    if not wm.windows:
        raise RuntimeError("no window (run Blender in GUI mode, not --background)")
    window = wm.windows[0]
    prefs = bpy.context.preferences
    prefs.view.use_save_prompt = False   # wm.quit_blender would otherwise ask about the unsaved file
    prefs.view.smooth_view = 0           # view_all jumps instead of animating over timer events
    prefs.use_preferences_save = False   # never write userpref.blend (--factory-startup does not anyway)
    if _args.viewport_aa != "keep":
        prefs.system.viewport_aa = _args.viewport_aa

    # The scene: the glb alone.
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    glb = os.path.abspath(_args.glb)
    if not os.path.isfile(glb):
        raise FileNotFoundError("no such glb: " + glb)
    # Debian's Blender 3.4.1 runs on the system's numpy (1.24 in Debian 12), which dropped the np.bool alias that
    # this Blender's glTF importer still uses (io_scene_gltf2/blender/imp/gltf2_blender_mesh.py, set_poly_smoothing):
    # without it every import fails with "module 'numpy' has no attribute 'bool'". Put the alias back, in this process.
    import numpy
    if "bool" not in numpy.__dict__:
        numpy.bool = bool
    with bpy.context.temp_override(window=window):
        result = bpy.ops.import_scene.gltf(filepath=glb)
    if 'FINISHED' not in result:
        raise RuntimeError("glTF import of %s returned %s" % (glb, sorted(result)))
    meshes = [o for o in bpy.context.scene.objects if o.type == 'MESH']
    if not meshes:
        raise RuntimeError("the glb has no mesh object: " + glb)
    vertices = triangles = 0
    for o in meshes:
        me = o.data
        me.calc_loop_triangles()
        vertices += len(me.vertices)
        triangles += len(me.loop_triangles)

    # The 3D View fills the window: every other area closed, the 3D View's header, tool header, toolbar and side
    # bar hidden, the status bar hidden; the top bar (a global area, no switch for it in 3.4) stays, so the region
    # is the window less the top bar (1280 x 773 in a 1280 x 800 window). screen.screen_full_area would be the one
    # call for this, but in Blender 3.4.1 it crashes the process (SIGSEGV in the next event loop iteration) when
    # run from a timer, with temp_override or a context dict alike; screen.area_close does not.
    # Closing an area can free the neighbour that takes its place and keep the closed one (its struct then holds
    # the neighbour's editor), so every area is looked up again after each close.
    for _ in range(len(window.screen.areas)):
        area, _region = _largest_view3d(window)
        others = [a for a in window.screen.areas if a != area]
        if not others:
            break
        with bpy.context.temp_override(window=window, screen=window.screen, area=others[0]):
            bpy.ops.screen.area_close()
    if len(window.screen.areas) != 1:
        raise RuntimeError("could not close the areas beside the 3D View")
    # Hiding regions before the event loop has laid the screen out anew crashes Blender (SIGSEGV), hence a pause.
    yield 0.5
    area, region = _largest_view3d(window)
    space = area.spaces.active
    space.show_region_header = False
    space.show_region_tool_header = False
    space.show_region_toolbar = False
    space.show_region_ui = False
    window.screen.show_statusbar = False
    yield 0.5  # the event loop lays the screen out again
    area, region = _largest_view3d(window)
    space = area.spaces.active
    space.shading.type = 'SOLID'
    if _args.overlays == "off":
        space.overlay.show_overlays = False
        space.show_gizmo = False
    with bpy.context.temp_override(window=window, area=area, region=region):
        bpy.ops.view3d.view_all(center=False)
    yield 0.5  # one normal frame of the event loop with everything set

    area, region = _largest_view3d(window)
    rv3d = area.spaces.active.region_3d
    import bgl  # deprecated in 3.x but present; glFinish makes llvmpipe finish the redraw inside the timed span

    def redraw():
        with bpy.context.temp_override(window=window, area=area, region=region):
            t0 = time.perf_counter()
            bpy.ops.wm.redraw_timer(type='DRAW', iterations=1)
            bgl.glFinish()
            return (time.perf_counter() - t0) * 1000.0

    for _ in range(WARMUP):
        redraw()
    idle = [redraw() for _ in range(_args.frames)]
    turn = Quaternion((0.0, 0.0, 1.0), math.radians(_args.orbit_deg))
    orbit = []
    for _ in range(_args.frames):
        rv3d.view_rotation = turn @ rv3d.view_rotation
        orbit.append(redraw())

    import gpu
    try:
        renderer = gpu.platform.renderer_get()
    except Exception as e:
        renderer = "unknown (%s)" % e
    r3 = lambda v: round(v, 3)
    _write_json(_out_path, {
        "blender_version": bpy.app.version_string,
        "gl_renderer": renderer,
        "objects": len(meshes),
        "vertices": vertices,
        "triangles": triangles,
        "viewport": [region.width, region.height],
        "window": [window.width, window.height],
        "idle_median_ms": r3(_percentile(idle, 50)),
        "idle_p95_ms": r3(_percentile(idle, 95)),
        "orbit_median_ms": r3(_percentile(orbit, 50)),
        "orbit_p95_ms": r3(_percentile(orbit, 95)),
        "frames": _args.frames,
        "idle_ms": [r3(v) for v in idle],
        "orbit_ms": [r3(v) for v in orbit],
        "viewport_aa": prefs.system.viewport_aa,
        "overlays": _args.overlays,
        "draw_type": "DRAW",
    })
    print("blender_redraw_timer: idle median %.2f ms, orbit median %.2f ms -> %s"
          % (_percentile(idle, 50), _percentile(orbit, 50), _out_path))
    sys.stdout.flush()
    bpy.ops.wm.quit_blender()  # exit code 0


_steps = None


def _tick():
    try:
        return next(_steps)
    except StopIteration:
        return None
    except BaseException as e:  # noqa: B902 -- anything, SystemExit included, ends the run with the error
        traceback.print_exc()
        _fail("%s: %s" % (type(e).__name__, e))


def _main():
    global _args, _out_path, _steps
    if "--out" in sys.argv:  # known before parsing, so that a bad argument still gets its error JSON
        i = sys.argv.index("--out")
        if i + 1 < len(sys.argv):
            _out_path = os.path.abspath(sys.argv[i + 1])
    try:
        _args = _parse_args()
        _out_path = os.path.abspath(_args.out)
        if os.path.exists(_out_path):
            os.remove(_out_path)  # a stale result must not pass for this run's
    except BaseException as e:
        traceback.print_exc()
        _fail("%s: %s" % (type(e).__name__, e))
    watchdog = threading.Timer(_args.timeout_s, lambda: _fail("timed out after %g s" % _args.timeout_s))
    watchdog.daemon = True
    watchdog.start()
    _steps = _run()
    bpy.app.timers.register(_tick, first_interval=1.0)


_main()
