"""The menu's path, by hand: Unwrap with raps invoked in a Blender with a window, Esc pressed
while raps runs on its worker thread, and the UV map checked unchanged. Not a CTest: it needs
a display (Xvfb), and whether Esc lands before the run ends depends on the machine's speed, so
the mesh is large (126K faces) and the outcome is printed, not asserted blindly:

  xvfb-run -a -s "-screen 0 1280x720x24" blender --factory-startup --enable-event-simulate \
      --python tests/blender/check_modal_cancel.py -- build/bindings/blender/raps_uv.zip

(set BLENDER_USER_SCRIPTS to a scratch folder to keep the add-on out of your own). It prints
when Esc was sent, whether the operator then ended cancelled or finished, and exits 1 when the
UV map changed after a cancel or the operator never ended.
"""

import os
import sys
import threading
import time

import bpy
import numpy

STATE = {"step": 0}


def _uv(name):
    layer = bpy.data.objects[name].data.uv_layers.active
    values = numpy.empty(2 * len(layer.data), dtype=numpy.float32)
    layer.data.foreach_get("uv", values)
    return values


def _view3d():
    window = bpy.context.window_manager.windows[0]
    area = next(a for a in window.screen.areas if a.type == "VIEW_3D")
    return window, area, next(r for r in area.regions if r.type == "WINDOW")


def _finish(code, text):
    print("check_modal_cancel: " + text, flush=True)
    os._exit(code)  # Blender's own quit always exits 0


def _tick():
    step = STATE["step"]
    STATE["step"] += 1
    window, area, region = _view3d()
    if step == 0:
        zip_path = sys.argv[sys.argv.index("--") + 1]
        bpy.ops.preferences.addon_install(filepath=zip_path, overwrite=True)
        bpy.ops.preferences.addon_enable(module="raps_uv")
        for obj in list(bpy.data.objects):
            bpy.data.objects.remove(obj)
        bpy.ops.mesh.primitive_monkey_add()
        modifier = bpy.context.object.modifiers.new("Subdivision", "SUBSURF")
        modifier.levels = 4
        bpy.ops.object.modifier_apply(modifier=modifier.name)
        STATE["name"] = bpy.context.object.name
        STATE["before"] = _uv(STATE["name"]).copy()
        return 0.05
    if step == 1:
        with bpy.context.temp_override(window=window, area=area, region=region):
            result = bpy.ops.raps.unwrap("INVOKE_DEFAULT")
        if result != {"RUNNING_MODAL"}:
            _finish(1, "invoke returned %s, not RUNNING_MODAL" % result)
            return None
        STATE["started"] = time.perf_counter()
        return 0.05
    if step == 2:
        window.event_simulate(type="ESC", value="PRESS")
        window.event_simulate(type="ESC", value="RELEASE")
        print("check_modal_cancel: Esc sent %.2f s after invoke"
              % (time.perf_counter() - STATE["started"]), flush=True)
        return 0.5
    # raps runs on the thread named raps-unwrap; once it has ended, the operator's next timer
    # event ends the operator: registered in the window manager when it finished, not when
    # it was cancelled.
    if any(thread.name == "raps-unwrap" for thread in threading.enumerate()):
        STATE["ended"] = None
        return 0.5
    STATE["ended"] = STATE.get("ended") or time.perf_counter()
    changed = not numpy.array_equal(_uv(STATE["name"]), STATE["before"])
    finished = any(op.bl_idname == "RAPS_OT_unwrap"
                   for op in bpy.context.window_manager.operators)
    if finished:
        _finish(0, "the run ended before Esc was handled (finished; uvs written): rerun on a "
                "faster machine or a larger mesh")
        return None
    if changed:
        _finish(1, "the UV map changed without the operator finishing")
        return None
    if time.perf_counter() - STATE["started"] > 120:
        _finish(1, "the operator neither finished nor stopped within 120 s")
        return None
    if time.perf_counter() - STATE["ended"] > 5:  # its timer fired long since: cancelled
        _finish(0, "cancelled by Esc after %.2f s; the UV map is unchanged"
                % (STATE["ended"] - STATE["started"]))
        return None
    return 0.5


bpy.app.timers.register(_tick, first_interval=1.0)
