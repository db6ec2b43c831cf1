"""The unwrap job: raps runs on meshes read from Blender, without touching Blender.

A job holds only arrays (mesh_io.MeshInput), so it may run on a worker thread while Blender's
interface keeps drawing: the library runs without the GIL and reports progress into a
raps.ProgressState, which the interface's thread reads and cancels (no Python runs on the
library's threads: a callback there cost 40 to 90 us per call, several times the library's own
time on small meshes). Nothing is written back here; the operator writes every object's uvs
only once all of them have succeeded.
"""

import threading
import time

import numpy

from . import mesh_io
from .native import raps

# How much of one run each phase stands for in the progress bar (measured shares of an atlas
# run: mapping the charts dominates).
_PHASE_SHARE = {"VALIDATE": 0.02, "TOPOLOGY": 0.05, "SEGMENT": 0.15, "INITIAL_MAP": 0.6,
                "ADAPT": 0.0, "PACK": 0.13, "METRICS": 0.05}
# Per phase number (raps.Phase): where its share of the bar starts, and the share.
_PHASE_SPAN = {}
_start = 0.0
for _name in ("VALIDATE", "TOPOLOGY", "SEGMENT", "INITIAL_MAP", "ADAPT", "PACK", "METRICS"):
    _PHASE_SPAN[int(getattr(raps.Phase, _name))] = (_start, _PHASE_SHARE[_name])
    _start += _PHASE_SHARE[_name]



class Options:
    """What the operator's properties ask of raps."""

    def __init__(self, monitor="AREA", alpha=1.0, iterations=1, size_mode="RESOLUTION",
                 resolution=1024, texels_per_unit=256.0, padding=1, rotation="ANY",
                 lightmap=False, use_seams=True, use_materials=False, one_atlas=False):
        self.monitor = monitor
        self.alpha = alpha
        self.iterations = iterations
        self.size_mode = size_mode
        self.resolution = resolution
        self.texels_per_unit = texels_per_unit
        self.padding = padding
        self.rotation = rotation
        self.lightmap = lightmap
        self.use_seams = use_seams
        self.use_materials = use_materials
        self.one_atlas = one_atlas

    def settings(self):
        """raps Settings for these options (raises raps.Error for a value raps refuses)."""
        settings = raps.Settings(domain="atlas", monitor=self.monitor, alpha=self.alpha,
                                 iterations=self.iterations, atlas_padding=self.padding,
                                 atlas_rotation=self.rotation)
        if self.size_mode == "DENSITY":
            settings.atlas_texels_per_unit = self.texels_per_unit
            settings.atlas_max_width = self.resolution
            settings.atlas_max_height = self.resolution
        else:
            settings.atlas_resolution = self.resolution
        if self.lightmap:
            # A lightmap keeps each mesh on one page and its charts on whole texels.
            settings.atlas_mesh_per_page = 1
            if self.size_mode != "DENSITY":
                settings.atlas_whole_texels = 1
        return settings


class Outcome:
    """One object's share of a job: its per loop uvs and figures, or the error that stopped it."""

    def __init__(self, name):
        self.name = name
        self.uv = None
        self.error = None
        self.charts = 0
        self.utilization = 0.0
        self.stretch_l2 = 0.0
        self.flipped = 0
        self.pages = 0
        self.repaired_polygons = 0
        self.time_ms = 0.0


class Cancelled(Exception):
    """The user cancelled the job."""


class Job:
    """Runs raps over named meshes: one atlas each, or one for all (options.one_atlas).

    inputs: [(object name, MeshInput)]. run() fills self.outcomes; progress is read from
    self.fraction (0..1, from any thread) and cancel() stops the run at the library's next
    progress report. With progress=False the library reports nothing (a headless Blender has
    no progress to show and no Esc to press): fraction stays 0 until the job is done, and
    cancel() only keeps the next atlas from starting."""

    def __init__(self, inputs, options, progress=True):
        self.inputs = inputs
        self.options = options
        self.outcomes = [Outcome(name) for name, _ in inputs]
        self.cancelled = False
        self.done = False
        self.failure = None  # an unexpected exception, raised again by the operator
        self._cancel = threading.Event()
        self._state = raps.ProgressState() if progress else None
        self._atlas = (0, 1)  # the atlas running, of how many

    def cancel(self):
        self._cancel.set()
        if self._state is not None:
            self._state.cancel()

    @property
    def fraction(self):
        """How much of the job is done, 0..1: each atlas an equal share, each phase of one the
        share of a run it usually takes (_PHASE_SHARE)."""
        if self.done:
            return 1.0
        number, count = self._atlas
        if self._state is None:
            return number / count
        phase, fraction, _ = self._state.read()
        start, share = _PHASE_SPAN.get(int(phase), (0.0, 0.0)) if phase is not None else \
            (0.0, 0.0)
        return (number + min(start + share * fraction, 1.0)) / count

    def run(self):
        try:
            groups = [list(range(len(self.inputs)))] if self.options.one_atlas else \
                [[i] for i in range(len(self.inputs))]
            for number, members in enumerate(groups):
                if self._cancel.is_set():
                    self.cancelled = True
                    break
                self._atlas = (number, len(groups))
                self._run_atlas(members)
                if self.cancelled:
                    break
        except BaseException as error:  # handed to the main thread, never lost in a thread
            self.failure = error
        finally:
            self.done = True

    def start_thread(self):
        thread = threading.Thread(target=self.run, name="raps-unwrap", daemon=True)
        thread.start()
        return thread

    def _progress(self):
        """What the library reports into for the next atlas: the job's state, its last reading
        cleared but a cancel() made meanwhile kept (set again after the reset), or None."""
        state = self._state
        if state is not None:
            state.reset()
            if self._cancel.is_set():
                state.cancel()
        return state

    def _run_atlas(self, members):
        """One atlas, one run: the library keeps each polygon's triangles in one chart (their
        polygon ids), so every loop of a polygon gets one uv."""
        started = time.perf_counter()
        result = self._solve(members, self._progress())
        if result is None:
            return
        with result:
            self._collect(result, members, 1000.0 * (time.perf_counter() - started))

    def _solve(self, members, progress):
        """The result of one raps run over members, or None after recording why not."""
        meshes = []
        try:
            with self.options.settings() as settings:
                for i in members:
                    try:
                        meshes.append(_raps_mesh(self.inputs[i][1]))
                    except raps.Error as error:  # this object's own data: name it alone
                        self._fail([i], error)
                        self._fail([j for j in members if j != i],
                                   raps.Error(error.status, "not unwrapped: %s failed"
                                              % self.inputs[i][0]))
                        return None
                return raps.parameterize_scene(meshes, settings, progress=progress)
        except raps.Error as error:
            if error.status == raps.Status.CANCELLED:
                self.cancelled = True
            else:
                self._fail(members, error)
            return None
        finally:
            for mesh in meshes:
                mesh.close()

    def _fail(self, members, error):
        message = error.message or error.name
        if len(members) == 1:
            self.outcomes[members[0]].error = mesh_io.blender_message(
                self.inputs[members[0]][1], message)
            return
        # raps names a scene's failing mesh as "mesh N: ..."; name the object instead.
        for position, i in enumerate(members):
            prefix = "mesh %d: " % position
            if message.startswith(prefix):
                self.outcomes[i].error = mesh_io.blender_message(self.inputs[i][1],
                                                                 message[len(prefix):])
                return
        for i in members:
            self.outcomes[i].error = "one atlas for all failed: " + message

    def _collect(self, result, members, elapsed):
        stats = result.stats()
        uvs = result.uvs()
        indices = result.indices()
        chart_ids = numpy.asarray(result.chart_ids(), dtype=numpy.int64)
        charts = result.charts()
        chart_page = numpy.array([c.page for c in charts], dtype=numpy.float64)
        if self.options.size_mode == "DENSITY":
            # Pages at a density are cropped to their charts, their uvs normalised to the page;
            # a UDIM tile is a square texture of the resolution, so the page takes its lower
            # left corner at one scale in u and v.
            uvs = uvs * numpy.array([stats.atlas_width, stats.atlas_height]) / \
                self.options.resolution
        chart_mesh = numpy.array([c.mesh for c in charts], dtype=numpy.int64)
        chart_area = numpy.array([c.area_3d for c in charts], dtype=numpy.float64)
        chart_l2 = numpy.array([c.stretch_l2 for c in charts], dtype=numpy.float64)
        for position, i in enumerate(members):
            data = self.inputs[i][1]
            span = result.mesh_range(position)
            first_t = span.first_index // 3
            count_t = span.index_count // 3
            out_vertices = indices[first_t:first_t + count_t].astype(numpy.int64) + \
                span.first_vertex
            mesh_charts = chart_ids[first_t:first_t + count_t]
            corners = mesh_io.corner_uvs(uvs, out_vertices, chart_page, mesh_charts)
            outcome = self.outcomes[i]
            outcome.uv, outcome.repaired_polygons = mesh_io.loop_uvs(data, corners,
                                                                     out_vertices)
            own = chart_mesh == position
            outcome.charts = int(own.sum())
            weight = chart_area[own].sum()
            outcome.stretch_l2 = float(numpy.sqrt((chart_area[own] * chart_l2[own] ** 2).sum() /
                                                  weight)) if weight > 0 else 0.0
            outcome.utilization = stats.utilization
            outcome.flipped = stats.flipped_triangles
            outcome.pages = max(1, stats.page_count)
            outcome.time_ms = elapsed


def _raps_mesh(data):
    mesh = raps.Mesh(data.positions, data.triangles)
    mesh.set_transform(data.transform)
    if data.groups is not None:
        mesh.set_triangle_groups(data.groups)
    if data.polygons is not None:
        mesh.set_triangle_polygons(data.polygons)
    if data.seams is not None:
        mesh.set_seam_edges(data.seams)
    return mesh
