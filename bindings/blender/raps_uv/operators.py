"""UV > Unwrap with raps and UV > Lightmap with raps.

Run from the menu (invoke), raps works on a worker thread while a modal timer shows its progress
in the status bar and Esc cancels it (the library reports into a raps.ProgressState that the
timer reads and Esc cancels: it stops at its next report, and nothing is written); ModalRun
holds that path apart from Blender's event loop, so that a headless test drives it too. From a
script or the redo panel (execute), the same job runs to its end while Blender waits, showing
progress on the cursor; in `blender -b` without progress (nothing to show, no Esc to press). Either way every selected object's uvs
are written only once all have succeeded: a failure is reported naming the object, and leaves
every object as it was. bl_options UNDO makes the write one Ctrl-Z step.
"""

import time

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from . import mesh_io
from .unwrap import Job, Options

_MAX_UV_MAPS = 8  # Blender's limit per mesh
_NAVIGATION = {"MOUSEMOVE", "INBETWEEN_MOUSEMOVE", "MIDDLEMOUSE", "WHEELUPMOUSE",
               "WHEELDOWNMOUSE", "TRACKPADPAN", "TRACKPADZOOM", "NDOF_MOTION"}

_MONITORS = [
    ("AREA", "Area", "Equidistribute the area distortion (the paper's 6.1)"),
    ("EDGE_LENGTH", "Edge length", "Equidistribute the edge length distortion (6.2)"),
    ("ANGLE", "Angle", "Equidistribute the angle distortion (6.3)"),
    ("NONE", "None", "The quasi-conformal map, without the adaptive step"),
]
_ROTATIONS = [
    ("ANY", "Any", "Turn each chart to its smallest bounding box, then by quarter turns"),
    ("QUARTER", "Quarter turns", "Quarter turns only: texel rows stay texel rows"),
    ("NONE", "None", "Each chart keeps the orientation of its map"),
]
_SIZE_MODES = [
    ("RESOLUTION", "Resolution", "Fill one square texture of the given resolution"),
    ("DENSITY", "Density", "Texels per Blender unit (world scale applied), on pages of at most "
     "the resolution; page p goes to UDIM tile 1001 + p"),
]


def _mesh_objects(context):
    """The selected mesh objects (and the active one in edit mode), each mesh once: linked
    duplicates share one UV map, written once."""
    objects = list(context.selected_objects)
    if context.mode == "EDIT_MESH":
        objects += [o for o in context.objects_in_mode if o not in objects]
    seen = set()
    chosen = []
    for obj in objects:
        if obj.type != "MESH" or obj.data in seen or obj.data.library is not None:
            continue
        seen.add(obj.data)
        chosen.append(obj)
    return chosen


class UnwrapProperties:
    """The options of both operators (the redo panel shows them)."""

    one_atlas: BoolProperty(
        name="One Atlas for All", default=False,
        description="Pack every selected object into one atlas at one texel density (their "
        "world scale applied); off: one atlas per object")
    uv_map: StringProperty(
        name="UV Map", default="",
        description="UV map to write; empty: the active one (UVMap on a mesh without one)")
    new_uv_map: BoolProperty(
        name="New UV Map", default=False,
        description="Add a new UV map (named as above, or raps) instead of writing an existing one")
    monitor: EnumProperty(name="Monitor", items=_MONITORS, default="AREA",
                          description="The distortion the adaptive step evens out")
    alpha: FloatProperty(name="Alpha", default=1.0, min=0.01, max=100.0,
                         description="Strength of the adaptive step (exponent of the monitor)")
    iterations: IntProperty(name="Iterations", default=1, min=1, max=100,
                            description="Adaptive solves per chart")
    size_mode: EnumProperty(name="Size", items=_SIZE_MODES, default="RESOLUTION")
    resolution: IntProperty(name="Resolution", default=1024, min=16, max=16384,
                            description="Texels on each side of the square atlas (with a density: "
                            "the largest page)")
    texels_per_unit: FloatProperty(name="Texels per Unit", default=256.0, min=0.001,
                                   max=1e6, description="Texel density per Blender unit")
    padding: IntProperty(name="Padding", default=1, min=0, max=64,
                         description="Texels kept free between charts")
    rotation: EnumProperty(name="Rotation", items=_ROTATIONS, default="ANY")
    lightmap: BoolProperty(
        name="Lightmap", default=False,
        description="Each object's charts on one page and on whole texels")
    use_seams: BoolProperty(name="Respect Seams", default=True,
                            description="Edges marked as seams are chart boundaries")
    use_materials: BoolProperty(name="Keep Materials Apart", default=False,
                                description="No chart holds faces of two materials")

    def raps_options(self, objects):
        return Options(monitor=self.monitor, alpha=self.alpha, iterations=self.iterations,
                       size_mode=self.size_mode, resolution=self.resolution,
                       texels_per_unit=self.texels_per_unit, padding=self.padding,
                       rotation=self.rotation, lightmap=self.lightmap,
                       use_seams=self.use_seams, use_materials=self.use_materials,
                       one_atlas=self.one_atlas and len(objects) > 1)

    def layer_name(self, mesh):
        """The UV map this run writes on mesh (None: a new one)."""
        if self.new_uv_map:
            return None
        if self.uv_map:
            return self.uv_map
        active = mesh.uv_layers.active
        return active.name if active is not None else "UVMap"

    def draw(self, _context):
        layout = self.layout
        layout.use_property_split = True
        for name in ("one_atlas", "uv_map", "new_uv_map", "monitor", "alpha", "iterations",
                     "size_mode"):
            layout.prop(self, name)
        layout.prop(self, "texels_per_unit" if self.size_mode == "DENSITY" else "resolution")
        if self.size_mode == "DENSITY":
            layout.prop(self, "resolution", text="Largest Page")
        for name in ("padding", "rotation", "lightmap", "use_seams", "use_materials"):
            layout.prop(self, name)


class Run:
    """One operator call: reads the objects, runs the job, writes every object or none."""

    def __init__(self, operator, context):
        self.operator = operator
        self.objects = _mesh_objects(context)
        self.names = [obj.name for obj in self.objects]
        self.edit_mode = context.mode == "EDIT_MESH"
        self.job = None
        self.started = time.perf_counter()

    def prepare(self, progress=True):
        """Builds the job (progress: whether it reports progress and can be cancelled);
        returns a problem to report (nothing is changed then), or None."""
        if not self.objects:
            return "select at least one mesh object"
        for obj in self.objects:
            mesh = obj.data
            name = self.operator.layer_name(mesh)
            if (name is None or name not in mesh.uv_layers) and \
                    len(mesh.uv_layers) >= _MAX_UV_MAPS:
                return "%s: already has %d UV maps, Blender's most" % (obj.name, _MAX_UV_MAPS)
            if self.edit_mode and obj.mode == "EDIT":
                obj.update_from_editmode()
        options = self.operator.raps_options(self.objects)
        inputs = [(obj.name, mesh_io.read_mesh(obj, options.use_seams, options.use_materials))
                  for obj in self.objects]
        for name, data in inputs:
            if len(data.triangles) == 0:
                return "%s: has no faces to unwrap" % name
        self.job = Job(inputs, options, progress)
        return None

    def finish(self, context):
        """Writes the uvs when every object succeeded and reports; returns the operator's
        result set."""
        job = self.job
        operator = self.operator
        if job.failure is not None:
            raise job.failure
        if job.cancelled:
            operator.report({"WARNING"}, "raps: cancelled, no UV map changed")
            return {"CANCELLED"}
        failed = [o for o in job.outcomes if o.error is not None]
        if failed:
            for outcome in failed:
                operator.report({"ERROR"}, "raps: %s: %s (no UV map changed)"
                                % (outcome.name, outcome.error))
            return {"CANCELLED"}
        problem = self._check_unchanged()
        if problem:
            operator.report({"ERROR"}, "raps: %s (no UV map changed)" % problem)
            return {"CANCELLED"}
        self._write(context)
        for outcome in job.outcomes:
            operator.report({"INFO"}, _summary(outcome))
        return {"FINISHED"}

    def _check_unchanged(self):
        """While the job ran, the objects must have stayed as they were read."""
        for obj_name, (name, data) in zip(self.names, self.job.inputs):
            obj = bpy.data.objects.get(obj_name)
            if obj is None or obj.type != "MESH" or len(obj.data.loops) != data.loop_count:
                return "%s: changed or removed while raps ran" % name
        return None

    def _write(self, context):
        if self.edit_mode:
            bpy.ops.object.mode_set(mode="OBJECT")
        try:
            for obj_name, outcome in zip(self.names, self.job.outcomes):
                mesh = bpy.data.objects[obj_name].data
                name = self.operator.layer_name(mesh)
                if name is None or name not in mesh.uv_layers:
                    layer = mesh.uv_layers.new(name=name or self.operator.uv_map or "raps")
                    if self.operator.show_new_map:
                        mesh.uv_layers.active = layer
                    name = layer.name
                mesh_io.write_uvs(mesh, name, outcome.uv)
        finally:
            if self.edit_mode:
                bpy.ops.object.mode_set(mode="EDIT")


def _summary(outcome):
    text = "raps: %s: %d charts, utilization %.2f, L2 stretch %.3f, %.0f ms" % (
        outcome.name, outcome.charts, outcome.utilization, outcome.stretch_l2, outcome.time_ms)
    if outcome.pages > 1:
        text += ", %d pages (UDIM tiles)" % outcome.pages
    if outcome.repaired_polygons:
        text += ", %d faces raps could not keep whole made islands of their own (fewer " \
            "texels)" % outcome.repaired_polygons
    return text


class _UnwrapBase(UnwrapProperties):
    bl_options = {"REGISTER", "UNDO"}
    show_new_map = True  # a UV map the run adds becomes the active one

    @classmethod
    def poll(cls, context):
        return any(o.type == "MESH" for o in context.selected_objects) or \
            context.mode == "EDIT_MESH"

    def execute(self, context):
        """Script, redo panel and background: the job runs while Blender waits."""
        run = Run(self, context)
        # Headless, nobody sees the progress or presses Esc: the library reports nothing.
        problem = run.prepare(progress=not bpy.app.background)
        if problem:
            self.report({"ERROR"}, "raps: " + problem)
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            thread = run.job.start_thread()
            while thread.is_alive():
                thread.join(0.05)
                wm.progress_update(int(100 * run.job.fraction))
        finally:
            wm.progress_end()
        return run.finish(context)

    def invoke(self, context, _event):
        """From the interface: the job runs on a worker thread, Esc cancels it."""
        if context.window is None or bpy.app.background:
            return self.execute(context)
        run = Run(self, context)
        problem = run.prepare()
        if problem:
            self.report({"ERROR"}, "raps: " + problem)
            return {"CANCELLED"}
        self._modal = ModalRun(run, context)
        context.window_manager.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        return self._modal.handle(event.type, context)


class ModalRun:
    """The menu's path, apart from Blender's event loop (so that a test can drive it as the
    loop does): the job on its worker thread, a timer that shows its progress, and handle(),
    which is what the operator's modal does with each event: Esc cancels the job (the library
    stops at its next progress call), a timer tick once the job is done writes every object's
    uvs, or none, and reports."""

    def __init__(self, run, context):
        self.run = run
        self.thread = run.job.start_thread()
        self._timer = None
        if context.window is not None:
            self._timer = context.window_manager.event_timer_add(0.1, window=context.window)
        self._status(context)

    def handle(self, event_type, context):
        """The operator's result for one event: RUNNING_MODAL (or PASS_THROUGH for view
        navigation) while the job runs, then finish()'s FINISHED or CANCELLED."""
        job = self.run.job
        if event_type == "ESC" and not job.done:
            job.cancel()
        if event_type == "TIMER":
            if job.done:
                self.thread.join()
                self._end(context)
                return self.run.finish(context)
            self._status(context)
        # The view may move; every other input waits, so that the objects stay as they were
        # read until the uvs are written.
        return {"PASS_THROUGH"} if event_type in _NAVIGATION else {"RUNNING_MODAL"}

    def _status(self, context):
        if context.workspace is None:
            return
        count = len(self.run.objects)
        context.workspace.status_text_set("raps: unwrapping %d object%s, %d%% (Esc cancels)" % (
            count, "" if count == 1 else "s", int(100 * self.run.job.fraction)))

    def _end(self, context):
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
        if context.workspace is not None:
            context.workspace.status_text_set(None)


class RAPS_OT_unwrap(_UnwrapBase, bpy.types.Operator):
    """Unwrap the selected mesh objects with raps: charts, r-adaptive maps, packed atlas"""
    bl_idname = "raps.unwrap"
    bl_label = "Unwrap with raps"


class RAPS_OT_lightmap(_UnwrapBase, bpy.types.Operator):
    """Lightmap uvs with raps into a second UV map: every object's charts on whole texels of
    one page, 2 texels apart, quarter turns only"""
    bl_idname = "raps.lightmap"
    bl_label = "Lightmap with raps"
    show_new_map = False  # the lightmap is a second map: the textures' map stays active

    uv_map: StringProperty(name="UV Map", default="Lightmap",
                           description="UV map to write (added when missing)")
    padding: IntProperty(name="Padding", default=2, min=0, max=64,
                         description="Texels kept free between charts")
    rotation: EnumProperty(name="Rotation", items=_ROTATIONS, default="QUARTER")
    lightmap: BoolProperty(name="Lightmap", default=True,
                           description="Each object's charts on one page and on whole texels")


CLASSES = (RAPS_OT_unwrap, RAPS_OT_lightmap)
