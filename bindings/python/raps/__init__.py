"""raps: r-adaptive surface parameterization (texture coordinates) from Python.

A thin, safe layer over libraps's C ABI (include/raps.h is the reference):

    import raps
    mesh = raps.Mesh(positions, indices)             # numpy arrays or plain sequences
    settings = raps.Settings(monitor=raps.Monitor.AREA, alpha=1.0)
    result = raps.parameterize(mesh, settings)       # raises raps.Error on failure
    uv = result.uvs()                                # (n, 2) numpy array, or [(u, v), ...]

    # A closed genus-0 mesh onto the unit sphere (uvs too with sphere_uv=SphereUv.OCTAHEDRAL):
    points = raps.parameterize(closed, raps.Settings(domain=raps.Domain.SPHERE)).sphere_points()

    # Several meshes in one atlas at one texel density (each placed by its 3x4 transform):
    mesh.set_transform([[2, 0, 0, 5], [0, 2, 0, 0], [0, 0, 2, 0]])
    scene = raps.parameterize_scene([mesh, other], raps.Settings(domain="atlas"))
    first = scene.mesh_range(0)                      # its output vertices and indices
    charts = scene.charts()                          # mesh, page, texel rectangle, ... per chart

    # Existing uvs repacked: one (u, v) per triangle corner, the islands kept as they are.
    mesh.set_corner_uvs(corner_uvs)
    repacked = raps.parameterize(mesh, raps.Settings(domain="atlas", atlas_repack=1))

Handles (Mesh, Settings, Result) own their native object: close() or a `with` block frees it at
once, and garbage collection frees it otherwise; either way exactly once. Errors raise
raps.Error with the status, its name and the library's message.

The library is found through the environment variable RAPS_LIBRARY (a path to libraps.so),
else inside the package (raps/libraps.so, which an installed package carries: setup.py), else by
name through the dynamic loader (LD_LIBRARY_PATH, the system's library folders).
numpy is optional: without it, inputs are sequences and outputs are lists.
"""

import collections
import ctypes
import ctypes.util
import enum
import numbers
import os
import threading
import weakref

from . import _native

try:
    import numpy
except ImportError:  # plain sequences in, lists out
    numpy = None

__all__ = [
    "Boundary", "Chart", "Domain", "Error", "IterationMode", "Mesh", "MeshRange", "Monitor",
    "Param", "ParamInfo", "Phase", "ProgressReading", "ProgressState", "Result", "Rotation",
    "Settings", "SphereMethod", "SphereUv", "Stacking",
    "Stats", "Status", "Weights", "parameterize", "parameterize_scene", "version",
    "version_string", "library_path",
]


# ------------------------------------------------------------------------------------------------
# Loading the library
# ------------------------------------------------------------------------------------------------


def _load():
    """Loads libraps and binds every declaration of the header the bindings were generated from.

    An explicit RAPS_LIBRARY that fails is an error (no silent fallback to another copy)."""
    explicit = os.environ.get("RAPS_LIBRARY")
    bundled = os.path.join(os.path.dirname(os.path.abspath(__file__)), "libraps.so")
    if explicit:
        candidates = [explicit]
    elif os.path.exists(bundled):
        candidates = [bundled]  # the package's own copy, made for these declarations
    else:
        major = _native.RAPS_VERSION_MAJOR
        candidates = ["libraps.so.%d" % major, "libraps.so", "libraps.%d.dylib" % major,
                      "libraps.dylib", "raps.dll"]
        found = ctypes.util.find_library("raps")
        if found:
            candidates.append(found)
    failures = []
    for candidate in candidates:
        try:
            lib = ctypes.CDLL(candidate)
        except OSError as error:
            failures.append("%s: %s" % (candidate, error))
            continue
        try:
            _native.bind(lib)
        except AttributeError as error:
            raise OSError("raps: %s is older than these bindings (made for raps.h %d.%d.%d): %s"
                          % (candidate, _native.RAPS_VERSION_MAJOR, _native.RAPS_VERSION_MINOR,
                             _native.RAPS_VERSION_PATCH, error))
        loaded_major = lib.raps_version() // 10000
        if loaded_major != _native.RAPS_VERSION_MAJOR:
            raise OSError("raps: %s is version %s, these bindings need major version %d"
                          % (candidate, lib.raps_version_string().decode(),
                             _native.RAPS_VERSION_MAJOR))
        return lib, candidate
    raise OSError("raps: cannot load libraps (set RAPS_LIBRARY to its path, or add its folder "
                  "to LD_LIBRARY_PATH); tried:\n  " + "\n  ".join(failures))


_lib, library_path = _load()


# ------------------------------------------------------------------------------------------------
# Constants as enums, built from the generated declarations so that values appended to the
# header appear here without an edit.
# ------------------------------------------------------------------------------------------------


def _enum(name, prefix, skip=(), extra=None):
    members = dict(extra or {})
    for constant, value in vars(_native).items():
        if constant.startswith(prefix) and constant not in skip:
            members[constant[len(prefix):]] = value
    return enum.IntEnum(name, members, module=__name__)


Status = _enum("Status", "RAPS_ERROR_", extra={"OK": _native.RAPS_OK})
Param = _enum("Param", "RAPS_PARAM_")
Domain = _enum("Domain", "RAPS_DOMAIN_")
Weights = _enum("Weights", "RAPS_WEIGHTS_")
Monitor = _enum("Monitor", "RAPS_MONITOR_")
IterationMode = _enum("IterationMode", "RAPS_ITERATION_")
Boundary = _enum("Boundary", "RAPS_BOUNDARY_")
# RAPS_SPHERE_* names the methods, RAPS_SPHERE_UV_* the uv options: one prefix inside the other.
SphereUv = _enum("SphereUv", "RAPS_SPHERE_UV_")
SphereMethod = _enum("SphereMethod", "RAPS_SPHERE_",
                     skip=[name for name in vars(_native) if name.startswith("RAPS_SPHERE_UV_")])
Rotation = _enum("Rotation", "RAPS_ROTATION_")
Stacking = _enum("Stacking", "RAPS_STACK_")
# RAPS_PHASE_COUNT is the number of phases, not a phase.
Phase = _enum("Phase", "RAPS_PHASE_", skip=("RAPS_PHASE_COUNT",))

# The enum each enumerated parameter takes; other parameters take plain numbers.
_PARAM_VALUES = {
    Param.DOMAIN: Domain,
    Param.WEIGHTS: Weights,
    Param.MONITOR: Monitor,
    Param.ITERATION_MODE: IterationMode,
    Param.BOUNDARY: Boundary,
    Param.SPHERE_METHOD: SphereMethod,
    Param.SPHERE_UV: SphereUv,
    Param.ATLAS_ROTATION: Rotation,
    Param.ATLAS_STACK: Stacking,
}


def _known(enum_type, value):
    """value as a member of enum_type, or the plain int for a value a newer library added."""
    try:
        return enum_type(value)
    except ValueError:
        return int(value)


def version():
    """The loaded library's version as (major, minor, patch)."""
    number = _lib.raps_version()
    return (number // 10000, number // 100 % 100, number % 100)


def version_string():
    """The loaded library's "MAJOR.MINOR.PATCH"."""
    return _lib.raps_version_string().decode("utf-8")


# ------------------------------------------------------------------------------------------------
# Errors
# ------------------------------------------------------------------------------------------------


class Error(Exception):
    """A raps call failed.

    status: a Status (or the int of a status this version does not know), name: the library's
    short description of it (raps_status_string), message: what the library said about this
    failure (names the offending triangle, vertex, edge or value; may be empty)."""

    def __init__(self, status, message=""):
        self.status = _known(Status, status)
        self.name = _lib.raps_status_string(int(status)).decode("utf-8")
        self.message = message
        text = "%s (status %d)" % (self.name, int(status))
        super().__init__(text + (": " + message if message else ""))


def _check(status, last_error=None, handle=None):
    """Raises Error for a failed status, with the handle's message when the call stores one."""
    if status != _native.RAPS_OK:
        message = last_error(handle).decode("utf-8", "replace") if last_error else ""
        raise Error(status, message)


# ------------------------------------------------------------------------------------------------
# Handles
# ------------------------------------------------------------------------------------------------


class _Handle:
    """Owns one native handle: destroyed exactly once, by close(), `with` or the collector."""

    def __init__(self, create, native_type, destroy):
        pointer = ctypes.POINTER(native_type)()
        _check(create(ctypes.byref(pointer)))
        self._pointer = pointer
        # finalize runs at most once, whether called by close() or at collection/exit.
        self._finalizer = weakref.finalize(self, destroy, pointer)

    def close(self):
        """Frees the native object now; further use raises ValueError. Safe to call twice."""
        self._pointer = None
        self._finalizer()

    @property
    def closed(self):
        return self._pointer is None

    def _ptr(self):
        if self._pointer is None:
            raise ValueError("raps: %s used after close()" % type(self).__name__)
        return self._pointer

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _is_ndarray(value):
    return numpy is not None and isinstance(value, numpy.ndarray)


def _real(value, what):
    """value, refused when complex: ctypes and float() took a numpy complex number's real part
    with only a warning."""
    if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
        raise TypeError("raps: %s must be real, not %r" % (what, value))
    return value


def _real_array(array, what):
    """array, refused when complex: astype(float64) drops the imaginary part with only a
    warning."""
    if array.dtype.kind == "c":
        raise TypeError("raps: %s must be real, not %s" % (what, array.dtype))
    return array


def _integer(value, what, low=-(1 << 63), high=(1 << 63) - 1):
    """value as a Python int in [low, high]: ctypes would wrap a larger one silently (2**64 + 5
    became 5) and truncate a fraction (or take a complex number's real part)."""
    if isinstance(value, float) and not value.is_integer():
        raise TypeError("raps: %s takes an integer, not %r" % (what, value))
    _real(value, what)
    number = int(value)
    if not low <= number <= high:
        raise ValueError("raps: %s is outside [%d, %d]: %d" % (what, low, high, number))
    return number


def _uint32_array(values, what):
    """values (None, a sequence or a numpy array of integers) as a flat uint32 buffer: a numpy
    array without a copy per element where numpy is there, else a ctypes array."""
    if values is None:
        values = []
    if _is_ndarray(values):
        flat = values.reshape(-1)
        if flat.dtype.kind not in "iu":  # 1.5 and 1.7 would both become 1
            raise TypeError("raps: %s must be an integer, not %s" % (what, flat.dtype))
        if flat.size and (flat.min() < 0 or flat.max() > 0xFFFFFFFF):
            raise ValueError("raps: %s is outside [0, 2^32)" % what)
        return numpy.ascontiguousarray(flat, dtype=numpy.uint32)
    flat = [_integer(v, what) for v in values]
    if any(v < 0 or v > 0xFFFFFFFF for v in flat):
        raise ValueError("raps: %s is outside [0, 2^32)" % what)
    return (ctypes.c_uint32 * len(flat))(*flat)


def _uint32_pointer(array):
    if len(array) == 0:
        return None
    if _is_ndarray(array):
        return array.ctypes.data_as(ctypes.POINTER(ctypes.c_uint32))
    return array


def _flatten(values, width, what, check_count=True):
    """[a, b, c, ...] or [(a, b, c), ...] -> a flat list; checks the count is a multiple."""
    values = list(values)
    if values and not isinstance(values[0], numbers.Number):
        flat = []
        for row in values:
            row = list(row)
            if len(row) != width:
                raise ValueError("raps: each of the %s must have %d values, got %r"
                                 % (what, width, row))
            flat.extend(row)
        return flat
    if check_count and len(values) % width:
        raise ValueError("raps: %d %s values are not a multiple of %d"
                         % (len(values), what, width))
    return values


class Mesh(_Handle):
    """The input: vertex positions and triangles, copied into the library.

    Mesh(positions, indices) sets both; either may also be set later. A mesh is only read by
    parameterize, so one mesh may serve concurrent runs from several threads."""

    def __init__(self, positions=None, indices=None):
        super().__init__(_lib.raps_mesh_create, _native.raps_mesh, _lib.raps_mesh_destroy)
        if positions is not None:
            self.set_positions(positions)
        if indices is not None:
            self.set_indices(indices)

    def set_positions(self, positions):
        """Replaces the positions: an (n, 3) float32 or float64 numpy array (rows may be
        strided, e.g. a view into an interleaved vertex buffer; other dtypes are converted to
        float64), or n (x, y, z) sequences, or 3n numbers."""
        if _is_ndarray(positions):
            array = _real_array(positions, "positions")
            if array.dtype not in (numpy.float32, numpy.float64):
                array = array.astype(numpy.float64)
            if array.ndim == 1:
                if array.size % 3:
                    raise ValueError("raps: %d coordinates are not a multiple of 3" % array.size)
                array = array.reshape(-1, 3)
            if array.ndim != 2 or array.shape[1] != 3:
                raise ValueError("raps: positions must have shape (n, 3), not %s"
                                 % (array.shape,))
            # The library reads rows stride_bytes apart, each row three packed values; 0 means
            # packed, so a broadcast (stride 0) or reversed view must be copied first.
            if array.strides[1] != array.itemsize or array.strides[0] < 3 * array.itemsize:
                array = numpy.ascontiguousarray(array)
            if array.dtype == numpy.float32:
                setter, ctype = _lib.raps_mesh_set_positions_f32, ctypes.c_float
            else:
                setter, ctype = _lib.raps_mesh_set_positions_f64, ctypes.c_double
            status = setter(self._ptr(), array.ctypes.data_as(ctypes.POINTER(ctype)),
                            array.shape[0], array.strides[0])
        else:
            flat = [_real(value, "positions") for value in _flatten(positions, 3, "positions")]
            buffer = (ctypes.c_double * len(flat))(*flat)
            status = _lib.raps_mesh_set_positions_f64(self._ptr(), buffer, len(flat) // 3, 0)
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    def set_indices(self, indices):
        """Replaces the triangles (counter-clockwise seen from the front): a numpy array of
        shape (t, 3) or (3t,) (uint16 and uint32 are passed as they are, other integer types
        are converted), or t (a, b, c) sequences, or 3t integers."""
        if _is_ndarray(indices):
            # reshape(-1) alone read a (t, 4) array as 4t/3 triangles.
            if indices.ndim not in (1, 2) or indices.ndim == 2 and indices.shape[1] != 3:
                raise ValueError("raps: indices must have shape (t, 3) or (3t,), not %s"
                                 % (indices.shape,))
            array = indices.reshape(-1)
            if array.dtype.kind not in "iu":
                raise TypeError("raps: indices must be integers, not %s" % array.dtype)
            if array.dtype not in (numpy.uint16, numpy.uint32):
                if array.size and (array.min() < 0 or array.max() > 0xFFFFFFFF):
                    raise ValueError("raps: an index is outside [0, 2^32)")
                array = array.astype(numpy.uint32)
            array = numpy.ascontiguousarray(array)
            if array.dtype == numpy.uint16:
                setter, ctype = _lib.raps_mesh_set_indices_u16, ctypes.c_uint16
            else:
                setter, ctype = _lib.raps_mesh_set_indices_u32, ctypes.c_uint32
            status = setter(self._ptr(), array.ctypes.data_as(ctypes.POINTER(ctype)), array.size)
        else:
            # A count that is not a multiple of 3 is the library's to report (INDEX_COUNT).
            flat = [_integer(i, "an index")
                    for i in _flatten(indices, 3, "triangles", check_count=False)]
            if any(i < 0 or i > 0xFFFFFFFF for i in flat):
                raise ValueError("raps: an index is outside [0, 2^32)")
            buffer = (ctypes.c_uint32 * len(flat))(*flat)
            status = _lib.raps_mesh_set_indices_u32(self._ptr(), buffer, len(flat))
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    def set_transform(self, matrix):
        """Places the mesh in world units for parameterize_scene: a 3x4 matrix [A | t] (a
        4x4 one's last row is ignored) as rows or 12 numbers, row-major; None sets the
        identity. A non-finite or singular one raises Error(Status.INVALID_TRANSFORM)."""
        if matrix is None:
            status = _lib.raps_mesh_set_transform(self._ptr(), None)
        else:
            rows = [list(row) for row in matrix] if not isinstance(matrix[0], numbers.Number) \
                else [list(matrix[4 * r:4 * r + 4]) for r in range(3)]
            if len(rows) not in (3, 4) or any(len(row) != 4 for row in rows[:3]):
                raise ValueError("raps: a transform is 3x4 (or 4x4), row-major")
            flat = [float(_real(value, "a transform")) for row in rows[:3] for value in row]
            status = _lib.raps_mesh_set_transform(self._ptr(), (ctypes.c_double * 12)(*flat))
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    def set_triangle_groups(self, groups):
        """Atlas domain: a group id per triangle (a material, a smoothing group, a region); no
        chart holds triangles of two groups. None removes them. A count that is not the
        triangle count raises Error(Status.GROUP_COUNT) when the mesh is used."""
        array = _uint32_array(groups, "a group id")
        status = _lib.raps_mesh_set_triangle_groups(self._ptr(), _uint32_pointer(array),
                                                    len(array))
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    def set_triangle_polygons(self, polygons):
        """Atlas domain: a polygon id per triangle, for quads and n-gons triangulated for raps;
        triangles that share an edge and an id stay in one chart with no cut between them, so
        each polygon corner gets one output vertex. None removes them. A count that is not the
        triangle count raises Error(Status.GROUP_COUNT) when the mesh is used."""
        array = _uint32_array(polygons, "a polygon id")
        status = _lib.raps_mesh_set_triangle_polygons(self._ptr(), _uint32_pointer(array),
                                                      len(array))
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    def set_seam_edges(self, pairs):
        """Atlas domain: seam edges as (a, b) pairs of vertex indices (or 2n integers); no
        chart grows or merges across them. None removes them. A pair that is not an edge raises
        Error(Status.SEAM_NOT_AN_EDGE), one beyond the vertices Error(Status.INDEX_OUT_OF_RANGE),
        when the mesh is used."""
        if _is_ndarray(pairs):
            if pairs.ndim > 2 or pairs.ndim == 2 and pairs.shape[1] != 2:
                raise ValueError("raps: seam edges must have shape (n, 2) or (2n,), not %s"
                                 % (pairs.shape,))
            if pairs.size % 2:
                raise ValueError("raps: %d seam edges values are not a multiple of 2"
                                 % pairs.size)
            array = _uint32_array(pairs, "a vertex index")
        else:
            flat = [] if pairs is None else _flatten(pairs, 2, "seam edges")
            array = _uint32_array(flat, "a vertex index")
        status = _lib.raps_mesh_set_seam_edges(self._ptr(), _uint32_pointer(array),
                                               len(array) // 2)
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    def set_corner_uvs(self, uvs):
        """Atlas domain with atlas_repack=1: the mesh's own uvs, one per triangle corner (corner
        3t + k is corner k of triangle t): an (3t, 2) float32 or float64 numpy array (rows may
        be strided; other dtypes are converted to float64), or 3t (u, v) sequences, or 6t
        numbers. None removes them. A non-finite uv raises Error(Status.NON_FINITE_UV); a count
        that is not three per triangle raises Error(Status.UV_COUNT) when the mesh is repacked."""
        if uvs is None:
            status = _lib.raps_mesh_set_corner_uvs_f64(self._ptr(), None, 0, 0)
        elif _is_ndarray(uvs):
            array = _real_array(uvs, "corner uvs")
            if array.dtype not in (numpy.float32, numpy.float64):
                array = array.astype(numpy.float64)
            if array.ndim == 1:
                if array.size % 2:
                    raise ValueError("raps: %d uv values are not a multiple of 2" % array.size)
                array = array.reshape(-1, 2)
            if array.ndim != 2 or array.shape[1] != 2:
                raise ValueError("raps: corner uvs must have shape (n, 2), not %s"
                                 % (array.shape,))
            # As for positions: rows stride_bytes apart, each two packed values.
            if array.strides[1] != array.itemsize or array.strides[0] < 2 * array.itemsize:
                array = numpy.ascontiguousarray(array)
            if array.dtype == numpy.float32:
                setter, ctype = _lib.raps_mesh_set_corner_uvs_f32, ctypes.c_float
            else:
                setter, ctype = _lib.raps_mesh_set_corner_uvs_f64, ctypes.c_double
            status = setter(self._ptr(), array.ctypes.data_as(ctypes.POINTER(ctype)),
                            array.shape[0], array.strides[0])
        else:
            flat = [float(_real(value, "corner uvs")) for value in _flatten(uvs, 2, "corner uvs")]
            buffer = (ctypes.c_double * len(flat))(*flat) if flat else None
            status = _lib.raps_mesh_set_corner_uvs_f64(self._ptr(), buffer, len(flat) // 2, 0)
        _check(status, _lib.raps_mesh_last_error, self._pointer)

    @property
    def vertex_count(self):
        return _lib.raps_mesh_vertex_count(self._ptr())

    @property
    def triangle_count(self):
        return _lib.raps_mesh_triangle_count(self._ptr())


ParamInfo = collections.namedtuple("ParamInfo", "name is_float min max default")


def _param_id(param):
    """param as an int: raps_param is 32 bits, which ctypes would wrap (2**32 + 2 was 2)."""
    return _integer(param, "a parameter id", -(1 << 31), (1 << 31) - 1)


def _param_property(param):
    value_enum = _PARAM_VALUES.get(param)

    def getter(self):
        value = self.get(param)
        return _known(value_enum, value) if value_enum else value

    def setter(self, value):
        self.set(param, value)

    return property(getter, setter, doc="The parameter RAPS_PARAM_%s." % param.name)


class Settings(_Handle):
    """Parameters with the library's defaults (mean value weights, area monitor, alpha 1).

    Settings(monitor=Monitor.ANGLE, alpha=2.0) sets parameters by name; each is also a property
    (settings.iterations = 5), and set(Param.X, value) / get(Param.X) reach any parameter.
    Enumerated parameters also take their member name ("angle"). A bad value raises Error and
    leaves the settings unchanged."""

    def __init__(self, **params):
        super().__init__(_lib.raps_settings_create, _native.raps_settings,
                         _lib.raps_settings_destroy)
        for name, value in params.items():
            if name.upper() not in Param.__members__:
                self.close()
                raise TypeError("raps: unknown parameter %r" % name)
            setattr(self, name.lower(), value)

    @staticmethod
    def param_info(param):
        """ParamInfo(name, is_float, min, max, default) of a parameter."""
        name = ctypes.c_char_p()
        is_float = ctypes.c_int32()
        low, high, default = ctypes.c_double(), ctypes.c_double(), ctypes.c_double()
        param = _param_id(param)
        status = _lib.raps_param_info(param, ctypes.byref(name), ctypes.byref(is_float),
                                      ctypes.byref(low), ctypes.byref(high),
                                      ctypes.byref(default))
        if status != _native.RAPS_OK:
            # raps_param_info stores no message, and the id is all it can refuse here.
            raise Error(status, "unknown parameter id %d (raps.Param names the known ones)"
                        % param)
        return ParamInfo(name.value.decode("utf-8"), bool(is_float.value), low.value,
                         high.value, default.value)

    def set(self, param, value):
        """Sets a parameter; float parameters take numbers, the others integers, enumerated
        ones also their member's name ("atlas")."""
        param = _param_id(param)
        info = self.param_info(param)
        what = "parameter %s" % info.name
        value_enum = _PARAM_VALUES.get(param)
        if value_enum and isinstance(value, str):
            if value.upper() not in value_enum.__members__:
                raise ValueError("raps: %s takes one of %s (or a raps.%s), not %r"
                                 % (what, ", ".join(repr(name.lower())
                                                    for name in value_enum.__members__),
                                    value_enum.__name__, value))
            value = value_enum[value.upper()]
        if info.is_float:
            status = _lib.raps_settings_set_float(self._ptr(), param, float(_real(value, what)))
        else:
            status = _lib.raps_settings_set_int(self._ptr(), param, _integer(value, what))
        _check(status, _lib.raps_settings_last_error, self._pointer)

    def get(self, param):
        """Reads a parameter: a float for float parameters, an int otherwise."""
        param = _param_id(param)
        if self.param_info(param).is_float:
            value = ctypes.c_double()
            _check(_lib.raps_settings_get_float(self._ptr(), param, ctypes.byref(value)))
        else:
            value = ctypes.c_int64()
            _check(_lib.raps_settings_get_int(self._ptr(), param, ctypes.byref(value)))
        return value.value

    def clone(self):
        """An independent copy."""
        copy = Settings.__new__(Settings)
        _Handle.__init__(copy, lambda out: _lib.raps_settings_clone(self._ptr(), out),
                         _native.raps_settings, _lib.raps_settings_destroy)
        return copy

    def as_dict(self):
        """{parameter name: value} of every parameter."""
        return {param.name.lower(): getattr(self, param.name.lower()) for param in Param}


for _param in Param:
    setattr(Settings, _param.name.lower(), _param_property(_param))


# The statistics fields of this version of raps.h, after the size and reserved header.
Stats = collections.namedtuple(
    "Stats", [name for name, _ in _native.raps_stats._fields_
              if name not in ("struct_size", "reserved")])


# One chart of an atlas (raps_chart in raps.h), scaled_down for its RAPS_CHART_SCALED_DOWN flag.
Chart = collections.namedtuple(
    "Chart", [name for name, _ in _native.raps_chart._fields_
              if name not in ("struct_size", "flags", "reserved")] + ["scaled_down", "stacked"])

# Where one input mesh lies in a result's output.
MeshRange = collections.namedtuple("MeshRange",
                                   "first_vertex vertex_count first_index index_count")


# The copy functions take a const result and store no message: say what the result lacks.
_NO_MAP = "the result holds no map (parameterize failed or has not run)"
_NO_UVS = ("the result holds no uvs: a sphere map has them only with "
           "sphere_uv=SphereUv.OCTAHEDRAL (read its points with sphere_points())")
_NO_SPHERE_POINTS = "the result holds no sphere points (only Domain.SPHERE has them)"


def _float_ctype(dtype, what):
    """The ctypes type of a float32 or float64 dtype; another raises, where "int32" once
    returned float64 values."""
    if str(dtype) in ("float32", "f4", "<f4") or dtype is ctypes.c_float or \
            (numpy is not None and dtype is numpy.float32):
        return ctypes.c_float
    if str(dtype) in ("float64", "f8", "<f8") or dtype is float or dtype is ctypes.c_double or \
            (numpy is not None and dtype is numpy.float64):
        return ctypes.c_double
    raise ValueError("raps: %s takes dtype float32 or float64, not %r" % (what, dtype))


class Result(_Handle):
    """The map: per output vertex a uv in [0,1]^2 (v up) and the input vertex it comes from,
    the output triangles with their chart ids, the statistics and the time of each phase.
    A sphere map has a point on the unit sphere per output vertex instead, and uvs too only
    with sphere_uv=SphereUv.OCTAHEDRAL. Filled by parameterize; reading an empty result (after
    a failure), or what the result does not hold, raises Error(Status.INVALID_OPERATION)."""

    def __init__(self):
        super().__init__(_lib.raps_result_create, _native.raps_result, _lib.raps_result_destroy)

    @property
    def vertex_count(self):
        return _lib.raps_result_vertex_count(self._ptr())

    @property
    def index_count(self):
        return _lib.raps_result_index_count(self._ptr())

    @property
    def triangle_count(self):
        return self.index_count // 3

    def _copy(self, copy, ctype, count, *extra, missing=_NO_MAP):
        """Calls a raps_result_copy_* function into a fresh buffer of count values; missing is
        the message when the result does not hold what it copies."""
        if self.vertex_count == 0:
            raise Error(_native.RAPS_ERROR_INVALID_OPERATION, _NO_MAP)
        if numpy is not None:
            values = numpy.empty(count, dtype=ctype)
            status = copy(self._ptr(), values.ctypes.data_as(ctypes.POINTER(ctype)), *extra)
        else:
            values = (ctype * count)()
            status = copy(self._ptr(), values, *extra)
        if status == _native.RAPS_ERROR_INVALID_OPERATION:
            raise Error(status, missing)
        _check(status)
        return values

    def _points(self, copy_f32, copy_f64, width, dtype, missing, what):
        """Per output vertex `width` coordinates: an (n, width) numpy array or a list of
        tuples."""
        ctype = _float_ctype(dtype, what)
        single = ctype is ctypes.c_float
        n = self.vertex_count
        values = self._copy(copy_f32 if single else copy_f64, ctype, width * n, n, 0,
                            missing=missing)
        if numpy is not None:
            return values.reshape(n, width)
        return [tuple(values[width * i:width * i + width]) for i in range(n)]

    def uvs(self, dtype="float64"):
        """The uvs: an (n, 2) numpy array of dtype float64 or float32 (another dtype raises
        ValueError), or a list of (u, v). A sphere map has them only with
        sphere_uv=SphereUv.OCTAHEDRAL."""
        return self._points(_lib.raps_result_copy_uvs_f32, _lib.raps_result_copy_uvs_f64, 2,
                            dtype, _NO_UVS, "uvs()")

    def sphere_points(self, dtype="float64"):
        """Sphere domain: the point on the unit sphere of each output vertex, an (n, 3) numpy
        array of dtype float64 or float32 (as uvs()), or a list of (x, y, z). With the
        octahedral unfold a duplicated vertex has its input vertex's point."""
        return self._points(_lib.raps_result_copy_sphere_points_f32,
                            _lib.raps_result_copy_sphere_points_f64, 3, dtype,
                            _NO_SPHERE_POINTS, "sphere_points()")

    def indices(self):
        """The output triangles: a (t, 3) uint32 numpy array, or a list of (a, b, c)."""
        count = self.index_count
        values = self._copy(_lib.raps_result_copy_indices_u32, ctypes.c_uint32, count, count)
        if numpy is not None:
            return values.reshape(-1, 3)
        return [tuple(values[i:i + 3]) for i in range(0, count, 3)]

    def vertex_remap(self):
        """Per output vertex, the input vertex it comes from: a uint32 numpy array or a list."""
        n = self.vertex_count
        values = self._copy(_lib.raps_result_copy_vertex_remap, ctypes.c_uint32, n, n)
        return values if numpy is not None else list(values)

    def chart_ids(self):
        """Per output triangle, its chart (0 .. stats().chart_count - 1; all 0 for the disk
        domain): a uint32 numpy array or a list."""
        count = self.triangle_count
        values = self._copy(_lib.raps_result_copy_chart_ids, ctypes.c_uint32, count, count)
        return values if numpy is not None else list(values)

    def stats(self):
        """The distortion statistics (see raps_stats in raps.h) as a Stats named tuple."""
        native = _native.raps_stats()
        native.struct_size = ctypes.sizeof(native)
        status = _lib.raps_result_get_stats(self._ptr(), ctypes.byref(native))
        if status == _native.RAPS_ERROR_INVALID_OPERATION:
            raise Error(status, _NO_MAP)
        _check(status)
        return Stats(*(getattr(native, name) for name in Stats._fields))

    def phase_ms(self, phase):
        """Wall-clock milliseconds spent in a Phase by the run that filled this result."""
        return _lib.raps_result_phase_ms(self._ptr(), _integer(phase, "a phase", 0, 0x7FFFFFFF))

    @property
    def mesh_count(self):
        """Input meshes the result holds: 1 after parameterize, len(meshes) after
        parameterize_scene."""
        return _lib.raps_result_mesh_count(self._ptr())

    def mesh_range(self, mesh):
        """MeshRange of input mesh `mesh`: its output vertices and indices (its indices number
        its own output vertices from 0, its remap its own input vertices)."""
        values = [ctypes.c_uint64() for _ in range(4)]
        mesh = _integer(mesh, "a mesh index", 0, (1 << 64) - 1)
        _check(_lib.raps_result_mesh_range(self._ptr(), mesh, *map(ctypes.byref, values)),
               _lib.raps_result_last_error, self._pointer)
        return MeshRange(*(value.value for value in values))

    def charts(self):
        """Atlas domain: a Chart per chart id (its mesh, page, texel rectangle, rotation,
        triangles, areas, L2 stretch, the chart whose texels it shares (stacked_on, itself when
        none), whether it was shrunk to fit a page, whether it is stacked)."""
        charts = []
        for index in range(self.stats().chart_count):
            native = _native.raps_chart()
            native.struct_size = ctypes.sizeof(native)
            _check(_lib.raps_result_get_chart(self._ptr(), index, ctypes.byref(native)),
                   _lib.raps_result_last_error, self._pointer)
            fields = [getattr(native, name) for name in Chart._fields[:-2]]
            charts.append(Chart(*fields, bool(native.flags & _native.RAPS_CHART_SCALED_DOWN),
                                bool(native.flags & _native.RAPS_CHART_STACKED)))
        return charts


ProgressReading = collections.namedtuple("ProgressReading", "phase fraction reports")


class ProgressState(_Handle):
    """Progress to poll: pass it as parameterize's progress and read it from any thread while
    the run works (read()), or cancel the run there (cancel(): the run stops at its next report
    and parameterize raises Error(Status.CANCELLED)). Unlike a progress callback, no Python
    code runs on the library's worker threads, where each call into Python costs tens of
    microseconds. Cancelled stays cancelled until reset(); one state may serve several runs,
    also at once (a cancel stops them all). Close it only when no run uses it."""

    def __init__(self):
        super().__init__(_lib.raps_progress_state_create, _native.raps_progress_state,
                         _lib.raps_progress_state_destroy)

    def read(self):
        """The latest report as ProgressReading(phase, fraction, reports): phase is a Phase, or
        None before the first report; reports counts them since creation or reset()."""
        phase, fraction, reports = _native.raps_phase(), ctypes.c_double(), ctypes.c_int64()
        _check(_lib.raps_progress_state_read(self._ptr(), ctypes.byref(phase),
                                             ctypes.byref(fraction), ctypes.byref(reports)))
        return ProgressReading(None if phase.value < 0 else _known(Phase, phase.value),
                               fraction.value, reports.value)

    def cancel(self):
        """Stops every run reporting into this state at its next report (any thread may call
        it); runs started later stop at once, until reset()."""
        _check(_lib.raps_progress_state_cancel(self._ptr()))

    def reset(self):
        """No report and not cancelled again, for the next run."""
        _check(_lib.raps_progress_state_reset(self._ptr()))


def parameterize(mesh, settings=None, progress=None, result=None):
    """Computes the map of mesh with settings (None: the defaults) and returns a Result.

    progress, if given, is a ProgressState the run reports into (read and cancelled from other
    threads), or a callable called as progress(phase, fraction) at the start and end of every
    phase and about every 1% of the long ones, from this thread or, unless threads is 1, from
    the run's worker threads (never two calls at once); returning False (or 0) cancels, which
    raises Error(Status.CANCELLED). An exception raised by progress (also
    KeyboardInterrupt) cancels the run and is raised here. A callable called from the worker
    threads costs tens of microseconds per call (thousands of calls on a small mesh): where
    that matters, poll a ProgressState instead. result, if given, is refilled
    instead of creating one. mesh and settings are only read: threads may share them (the
    library runs without the GIL), each with its own result."""
    return _run(lambda settings_ptr, result_ptr:
                _lib.raps_parameterize(mesh._ptr(), settings_ptr, result_ptr),
                settings, progress, result)


def parameterize_scene(meshes, settings, progress=None, result=None):
    """Packs several meshes into one atlas at one texel density (settings must have
    domain=Domain.ATLAS); each mesh is placed by its transform (Mesh.set_transform). The
    Result holds the meshes' outputs one after another: mesh_range(i) says where mesh i's
    lies, charts() describes every chart. progress and result as for parameterize."""
    meshes = list(meshes)
    handles = (ctypes.POINTER(_native.raps_mesh) * max(1, len(meshes)))(
        *[mesh._ptr() for mesh in meshes])
    return _run(lambda settings_ptr, result_ptr:
                _lib.raps_parameterize_scene(handles, len(meshes), settings_ptr, result_ptr),
                settings, progress, result)


def _run(call_native, settings, progress, result):
    """Runs call_native(settings pointer, result pointer) with the progress callback, if any,
    on a private copy of the settings."""
    if result is None:
        result = Result()
    if progress is None:
        status = call_native(settings._ptr() if settings else None, result._ptr())
        _check(status, _lib.raps_result_last_error, result._pointer)
        return result
    if isinstance(progress, ProgressState):
        # On a private copy, as the callback below: settings shared with other threads never
        # report into it.
        with (settings.clone() if settings else Settings()) as private:
            _check(_lib.raps_settings_set_progress_state(private._ptr(), progress._ptr()),
                   _lib.raps_settings_last_error, private._pointer)
            status = call_native(private._ptr(), result._ptr())
        _check(status, _lib.raps_result_last_error, result._pointer)
        return result

    # The callback goes on a private copy of the settings, so that settings shared with other
    # threads never see it, and the ctypes function object lives until the run is over.
    # The library's worker threads may report too (threads != 1); the lock keeps progress
    # from ever running twice at once, whatever the library does, as the header promises.
    raised = []
    serial = threading.Lock()

    def call(_user, phase, fraction):
        try:
            with serial:
                if raised:  # already stopping: do not call progress again
                    return 0
                keep_going = progress(_known(Phase, phase), fraction)
        except BaseException as error:  # also KeyboardInterrupt: stop the run, raise below
            raised.append(error)
            return 0
        return 0 if keep_going is not None and not keep_going else 1

    callback = _native.raps_progress_fn(call)
    with (settings.clone() if settings else Settings()) as private:
        _check(_lib.raps_settings_set_progress(private._ptr(), callback, None),
               _lib.raps_settings_last_error, private._pointer)
        status = call_native(private._ptr(), result._ptr())
    if raised:
        raise raised[0]
    _check(status, _lib.raps_result_last_error, result._pointer)
    return result
