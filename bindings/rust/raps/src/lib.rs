//! r-adaptive surface parameterization: texture coordinates for a triangle mesh, computed by
//! libraps (Zayer, Rössl, Seidel, "r-Adaptive Parameterization of Surfaces").
//!
//! A safe layer over the C ABI in [`sys`] (include/raps.h is the reference for every rule):
//! [`Mesh`], [`Settings`] and [`Parameterization`] own their native handle and free it on
//! drop; every fallible call returns [`Result`], whose [`Error`] carries the status, its name
//! and the library's message; buffers are slices and `Vec`s.
//!
//! ```no_run
//! let xyz = [0.0f32, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0];
//! let mesh = raps::Mesh::from_f32(&xyz, &[0, 1, 2, 0, 2, 3])?;
//! let map = raps::parameterize(&mesh, None)?;
//! println!("{:?}", map.uvs()?);
//! # Ok::<(), raps::Error>(())
//! ```
//!
//! Threads: a [`Mesh`] and a [`Settings`] are only read by [`parameterize`], so both are
//! `Send + Sync` and may be shared by concurrent runs, each with its own [`Parameterization`].
use std::any::Any;
use std::ffi::CStr;
use std::fmt;
use std::os::raw::{c_char, c_void};
use std::panic::{self, AssertUnwindSafe};
use std::ptr::{self, NonNull};
use std::sync::{Mutex, PoisonError};

pub use raps_sys as sys;

/// The distortion statistics of a map (see `raps_stats` in raps.h): the generated struct
/// itself, so fields appended to the header appear here.
pub type Stats = sys::raps_stats;
/// One chart of an atlas ([`Parameterization::charts`]): its mesh, page, texel rectangle,
/// rotation, triangles, areas and L2 stretch (`raps_chart`; `flags` holds
/// `sys::RAPS_CHART_SCALED_DOWN` for a chart shrunk to fit a page).
pub type Chart = sys::raps_chart;

/// A `Result` whose error is a raps [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

// ------------------------------------------------------------------------------------------
// Enum-like values
// ------------------------------------------------------------------------------------------

// The header's enum-like types are int32 with values only ever appended: newtypes with
// associated constants keep every value a newer library may report representable, where a
// Rust enum would have to reject it.
macro_rules! int_values {
    ($(#[$meta:meta])* $name:ident { $($(#[$doc:meta])* $value:ident = $native:path,)* }) => {
        $(#[$meta])*
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub struct $name(pub i32);

        impl $name {
            $($(#[$doc])* pub const $value: $name = $name($native);)*

            /// The constant's name, or `None` for a value this version does not know.
            pub fn name(self) -> Option<&'static str> {
                match self.0 {
                    $(v if v == $native => Some(stringify!($value)),)*
                    _ => None,
                }
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self.name() {
                    Some(name) => write!(f, "{}::{}", stringify!($name), name),
                    None => write!(f, "{}({})", stringify!($name), self.0),
                }
            }
        }
    };
}

int_values! {
    /// A status code (`RAPS_OK`, `RAPS_ERROR_*`).
    Status {
        OK = sys::RAPS_OK,
        INVALID_ARGUMENT = sys::RAPS_ERROR_INVALID_ARGUMENT,
        OUT_OF_MEMORY = sys::RAPS_ERROR_OUT_OF_MEMORY,
        EMPTY_MESH = sys::RAPS_ERROR_EMPTY_MESH,
        INDEX_COUNT = sys::RAPS_ERROR_INDEX_COUNT,
        INDEX_OUT_OF_RANGE = sys::RAPS_ERROR_INDEX_OUT_OF_RANGE,
        NON_FINITE_POSITION = sys::RAPS_ERROR_NON_FINITE_POSITION,
        REPEATED_VERTEX = sys::RAPS_ERROR_REPEATED_VERTEX,
        ZERO_AREA_TRIANGLE = sys::RAPS_ERROR_ZERO_AREA_TRIANGLE,
        NON_MANIFOLD_EDGE = sys::RAPS_ERROR_NON_MANIFOLD_EDGE,
        NON_MANIFOLD_VERTEX = sys::RAPS_ERROR_NON_MANIFOLD_VERTEX,
        INCONSISTENT_ORIENTATION = sys::RAPS_ERROR_INCONSISTENT_ORIENTATION,
        ISOLATED_VERTEX = sys::RAPS_ERROR_ISOLATED_VERTEX,
        MULTIPLE_COMPONENTS = sys::RAPS_ERROR_MULTIPLE_COMPONENTS,
        NO_BOUNDARY = sys::RAPS_ERROR_NO_BOUNDARY,
        MULTIPLE_BOUNDARIES = sys::RAPS_ERROR_MULTIPLE_BOUNDARIES,
        NONZERO_GENUS = sys::RAPS_ERROR_NONZERO_GENUS,
        TOO_LARGE = sys::RAPS_ERROR_TOO_LARGE,
        CANCELLED = sys::RAPS_ERROR_CANCELLED,
        SOLVER_FAILED = sys::RAPS_ERROR_SOLVER_FAILED,
        INVALID_OPERATION = sys::RAPS_ERROR_INVALID_OPERATION,
        INTERNAL = sys::RAPS_ERROR_INTERNAL,
        /// Sphere domain: the mesh is not closed (the message counts its boundary loops).
        OPEN_MESH = sys::RAPS_ERROR_OPEN_MESH,
        /// [`Mesh::set_transform`]: a coefficient is not finite, or the 3x3 part is singular.
        INVALID_TRANSFORM = sys::RAPS_ERROR_INVALID_TRANSFORM,
        /// Atlas domain: the triangle groups ([`Mesh::set_triangle_groups`]) are not one per
        /// triangle.
        GROUP_COUNT = sys::RAPS_ERROR_GROUP_COUNT,
        /// Atlas domain: a seam edge ([`Mesh::set_seam_edges`]) is not an edge of the mesh.
        SEAM_NOT_AN_EDGE = sys::RAPS_ERROR_SEAM_NOT_AN_EDGE,
        /// Repacking ([`Settings::set_atlas_repack`]): the corner uvs
        /// ([`Mesh::set_corner_uvs_f32`]) are not three per triangle.
        UV_COUNT = sys::RAPS_ERROR_UV_COUNT,
        /// [`Mesh::set_corner_uvs_f32`]: a uv is NaN, infinite or beyond 1e30.
        NON_FINITE_UV = sys::RAPS_ERROR_NON_FINITE_UV,
        /// Repacking: a uv chart has 3D area but no uv area.
        DEGENERATE_UV_CHART = sys::RAPS_ERROR_DEGENERATE_UV_CHART,
    }
}

int_values! {
    /// A parameter of [`Settings`] (`RAPS_PARAM_*`).
    Param {
        DOMAIN = sys::RAPS_PARAM_DOMAIN,
        WEIGHTS = sys::RAPS_PARAM_WEIGHTS,
        MONITOR = sys::RAPS_PARAM_MONITOR,
        ALPHA = sys::RAPS_PARAM_ALPHA,
        ITERATIONS = sys::RAPS_PARAM_ITERATIONS,
        ITERATION_MODE = sys::RAPS_PARAM_ITERATION_MODE,
        BOUNDARY = sys::RAPS_PARAM_BOUNDARY,
        MAX_TRIANGLES = sys::RAPS_PARAM_MAX_TRIANGLES,
        THREADS = sys::RAPS_PARAM_THREADS,
        SPHERE_METHOD = sys::RAPS_PARAM_SPHERE_METHOD,
        SPHERE_UV = sys::RAPS_PARAM_SPHERE_UV,
        SPHERE_DAMPING = sys::RAPS_PARAM_SPHERE_DAMPING,
        SPHERE_TOLERANCE = sys::RAPS_PARAM_SPHERE_TOLERANCE,
        SPHERE_MAX_SWEEPS = sys::RAPS_PARAM_SPHERE_MAX_SWEEPS,
        SPHERE_ALPHA_STEPS = sys::RAPS_PARAM_SPHERE_ALPHA_STEPS,
        MAX_MEMORY_MB = sys::RAPS_PARAM_MAX_MEMORY_MB,
        ATLAS_RESOLUTION = sys::RAPS_PARAM_ATLAS_RESOLUTION,
        ATLAS_PADDING = sys::RAPS_PARAM_ATLAS_PADDING,
        WELD_TOLERANCE = sys::RAPS_PARAM_WELD_TOLERANCE,
        HARD_EDGE_ANGLE = sys::RAPS_PARAM_HARD_EDGE_ANGLE,
        ATLAS_MAX_L2_STRETCH = sys::RAPS_PARAM_ATLAS_MAX_L2_STRETCH,
        ATLAS_MAX_LINF_STRETCH = sys::RAPS_PARAM_ATLAS_MAX_LINF_STRETCH,
        ATLAS_TEXELS_PER_UNIT = sys::RAPS_PARAM_ATLAS_TEXELS_PER_UNIT,
        ATLAS_MAX_WIDTH = sys::RAPS_PARAM_ATLAS_MAX_WIDTH,
        ATLAS_MAX_HEIGHT = sys::RAPS_PARAM_ATLAS_MAX_HEIGHT,
        ATLAS_ROTATION = sys::RAPS_PARAM_ATLAS_ROTATION,
        ATLAS_MARGIN = sys::RAPS_PARAM_ATLAS_MARGIN,
        ATLAS_BLOCK_ALIGN = sys::RAPS_PARAM_ATLAS_BLOCK_ALIGN,
        ATLAS_MESH_PER_PAGE = sys::RAPS_PARAM_ATLAS_MESH_PER_PAGE,
        ATLAS_WHOLE_TEXELS = sys::RAPS_PARAM_ATLAS_WHOLE_TEXELS,
        ATLAS_KEEP_INPUT_SEAMS = sys::RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS,
        ATLAS_REPACK = sys::RAPS_PARAM_ATLAS_REPACK,
        ATLAS_STACK = sys::RAPS_PARAM_ATLAS_STACK,
        ATLAS_STACK_TOLERANCE = sys::RAPS_PARAM_ATLAS_STACK_TOLERANCE,
    }
}

int_values! {
    /// Which turns the atlas's packing may give a chart (`RAPS_ROTATION_*`), the value of
    /// [`Param::ATLAS_ROTATION`].
    Rotation {
        /// Any angle: the chart's smallest bounding box, then a quarter turn (the default).
        ANY = sys::RAPS_ROTATION_ANY,
        /// Quarter turns of the chart's map only.
        QUARTER = sys::RAPS_ROTATION_QUARTER,
        /// None: each chart keeps its map's orientation.
        NONE = sys::RAPS_ROTATION_NONE,
    }
}

int_values! {
    /// Whether congruent charts share one place in the atlas (`RAPS_STACK_*`), the value of
    /// [`Param::ATLAS_STACK`].
    Stacking {
        /// Every chart its own texels (the default).
        NONE = sys::RAPS_STACK_NONE,
        /// Charts congruent up to a rigid motion share one place.
        RIGID = sys::RAPS_STACK_RIGID,
        /// Also charts congruent only up to a mirror (their texture appears mirrored).
        MIRRORED = sys::RAPS_STACK_MIRRORED,
    }
}

int_values! {
    /// The parameter domain (`RAPS_DOMAIN_*`).
    Domain {
        /// A topological disk mapped into [0,1]^2 with its boundary on a convex shape.
        DISK = sys::RAPS_DOMAIN_DISK,
        /// A closed genus-0 mesh mapped bijectively onto the unit sphere: one output vertex per
        /// input vertex ([`Parameterization::sphere_points`]), no uvs unless
        /// [`Settings::set_sphere_uv`] asks for the octahedral unfold, which duplicates the
        /// cut's vertices.
        SPHERE = sys::RAPS_DOMAIN_SPHERE,
        /// Any triangle mesh, cut into charts packed into one texture atlas: output vertices
        /// are duplicated along seams ([`Parameterization::vertex_remap`]), and each output
        /// triangle, the input one in input order, has a chart
        /// ([`Parameterization::chart_ids`]).
        ATLAS = sys::RAPS_DOMAIN_ATLAS,
    }
}

int_values! {
    /// How the sphere domain computes its map (`RAPS_SPHERE_*`).
    SphereMethod {
        /// Paper algorithm 7.1 as written: one thread, no safeguards; it may fold triangles.
        LITERAL = sys::RAPS_SPHERE_LITERAL,
        /// The same relaxation made robust (bijective initial map, fold-refusing moves,
        /// Moebius centring, continuation in alpha): never folds (the default).
        ROBUST = sys::RAPS_SPHERE_ROBUST,
    }
}

int_values! {
    /// Texture coordinates for the sphere domain (`RAPS_SPHERE_UV_*`).
    SphereUv {
        /// Sphere points only: the result has no uvs (the default).
        NONE = sys::RAPS_SPHERE_UV_NONE,
        /// Also unfold the sphere onto [0,1]^2 through the octahedron: one chart, the cut's
        /// vertices duplicated ([`Parameterization::vertex_remap`]), no flipped uv triangle.
        OCTAHEDRAL = sys::RAPS_SPHERE_UV_OCTAHEDRAL,
    }
}

int_values! {
    /// Base weights of the Laplace system (`RAPS_WEIGHTS_*`).
    Weights {
        /// Floater's mean value weights: positive, so the map never folds (the default).
        MEAN_VALUE = sys::RAPS_WEIGHTS_MEAN_VALUE,
        /// Cotangent weights: may be negative on obtuse triangles, and the map may fold.
        COTANGENT = sys::RAPS_WEIGHTS_COTANGENT,
        /// Tutte's uniform weights.
        UNIFORM = sys::RAPS_WEIGHTS_UNIFORM,
    }
}

int_values! {
    /// The error monitor of the adaptive step (`RAPS_MONITOR_*`).
    Monitor {
        /// No adaptive step: the quasi-conformal map.
        NONE = sys::RAPS_MONITOR_NONE,
        /// uv area / 3D area (the default).
        AREA = sys::RAPS_MONITOR_AREA,
        /// uv length / 3D length of each edge.
        EDGE_LENGTH = sys::RAPS_MONITOR_EDGE_LENGTH,
        /// uv angle / 3D angle.
        ANGLE = sys::RAPS_MONITOR_ANGLE,
    }
}

int_values! {
    /// How several adaptive solves combine (`RAPS_ITERATION_*`).
    IterationMode {
        /// Each solve multiplies the previous solve's weights (the default).
        ACCUMULATE = sys::RAPS_ITERATION_ACCUMULATE,
        /// Each solve starts again from the base weights.
        REAPPLY = sys::RAPS_ITERATION_REAPPLY,
    }
}

int_values! {
    /// The convex shape the boundary is fixed to (`RAPS_BOUNDARY_*`).
    Boundary {
        /// The circle of radius 0.5 centred at (0.5, 0.5) (the default).
        CIRCLE = sys::RAPS_BOUNDARY_CIRCLE,
        /// The unit square.
        SQUARE = sys::RAPS_BOUNDARY_SQUARE,
    }
}

int_values! {
    /// A phase of a run, reported to progress callbacks and timed (`RAPS_PHASE_*`).
    Phase {
        VALIDATE = sys::RAPS_PHASE_VALIDATE,
        TOPOLOGY = sys::RAPS_PHASE_TOPOLOGY,
        INITIAL_MAP = sys::RAPS_PHASE_INITIAL_MAP,
        ADAPT = sys::RAPS_PHASE_ADAPT,
        METRICS = sys::RAPS_PHASE_METRICS,
        /// Atlas: growing charts.
        SEGMENT = sys::RAPS_PHASE_SEGMENT,
        /// Atlas: packing charts.
        PACK = sys::RAPS_PHASE_PACK,
    }
}

impl Phase {
    /// Every phase of this version, in numeric order. A run enters only its domain's phases:
    /// the disk and sphere domains VALIDATE, TOPOLOGY, INITIAL_MAP, ADAPT, METRICS; the atlas
    /// VALIDATE, TOPOLOGY, SEGMENT, INITIAL_MAP, PACK, METRICS.
    pub fn all() -> impl Iterator<Item = Phase> {
        (0..sys::RAPS_PHASE_COUNT).map(Phase)
    }
}

// ------------------------------------------------------------------------------------------
// Errors
// ------------------------------------------------------------------------------------------

/// A failed raps call: the status, its name from the library and the library's message.
#[derive(Clone, PartialEq, Eq)]
pub struct Error {
    status: Status,
    message: String,
}

impl Error {
    fn new(status: i32, message: String) -> Error {
        Error {
            status: Status(status),
            message,
        }
    }

    /// The status code; compare with the constants of [`Status`].
    pub fn status(&self) -> Status {
        self.status
    }

    /// The library's short description of the status (`raps_status_string`).
    pub fn name(&self) -> &'static str {
        status_string(self.status)
    }

    /// What the library said about this failure (the offending triangle, vertex, edge or
    /// value); empty when the failing call stores no message.
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (status {})", self.name(), self.status.0)?;
        if !self.message.is_empty() {
            write!(f, ": {}", self.message)?;
        }
        Ok(())
    }
}

impl fmt::Debug for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Error")
            .field("status", &self.status)
            .field("name", &self.name())
            .field("message", &self.message)
            .finish()
    }
}

impl std::error::Error for Error {}

/// The library's description of a status ("invalid argument", ...); static, never freed.
pub fn status_string(status: Status) -> &'static str {
    // SAFETY: raps_status_string returns a static NUL-terminated string for any value.
    unsafe { static_str(sys::raps_status_string(status.0)) }
}

unsafe fn static_str(text: *const c_char) -> &'static str {
    if text.is_null() {
        return "";
    }
    CStr::from_ptr(text).to_str().unwrap_or("")
}

unsafe fn owned_string(text: *const c_char) -> String {
    if text.is_null() {
        return String::new();
    }
    CStr::from_ptr(text).to_string_lossy().into_owned()
}

/// Ok for RAPS_OK, else an Error with the message `message()` gives (read only on failure).
fn check(status: i32, message: impl FnOnce() -> String) -> Result<()> {
    if status == sys::RAPS_OK {
        Ok(())
    } else {
        Err(Error::new(status, message()))
    }
}

fn no_message() -> String {
    String::new()
}

fn no_map() -> Error {
    Error::new(
        sys::RAPS_ERROR_INVALID_OPERATION,
        "the result holds no map (parameterize failed or has not run)".to_string(),
    )
}

// The copy functions take a const result and store no message: say which of their failures
// this is.
const NO_UVS: &str = "the result holds no uvs: a sphere map has them only with \
                      SphereUv::OCTAHEDRAL (read its points with sphere_points)";
const NO_SPHERE_POINTS: &str = "the result holds no sphere points (only Domain::SPHERE has them)";

fn copy_check(
    status: i32,
    missing: &str,
    count: usize,
    capacity: usize,
    items: &str,
) -> Result<()> {
    check(status, || {
        if status == sys::RAPS_ERROR_INVALID_OPERATION {
            missing.to_string()
        } else if status == sys::RAPS_ERROR_INVALID_ARGUMENT && capacity < count {
            format!("{} {} do not fit in {}", count, items, capacity)
        } else {
            String::new()
        }
    })
}

/// The library's version as (major, minor, patch).
pub fn version() -> (u32, u32, u32) {
    // SAFETY: no arguments, thread-safe.
    let number = unsafe { sys::raps_version() };
    (number / 10000, number / 100 % 100, number % 100)
}

/// The library's "MAJOR.MINOR.PATCH".
pub fn version_string() -> &'static str {
    // SAFETY: a static string.
    unsafe { static_str(sys::raps_version_string()) }
}

// ------------------------------------------------------------------------------------------
// Mesh
// ------------------------------------------------------------------------------------------

/// The input: vertex positions and triangles, copied into the library.
pub struct Mesh {
    raw: NonNull<sys::raps_mesh>,
}

// SAFETY: the handle has no thread affinity (raps.h: no global state, distinct handles from any
// threads), and `&Mesh` only reaches functions taking `const raps_mesh*`, which only read it
// and may run concurrently; mutation needs `&mut Mesh`, which excludes any other use.
unsafe impl Send for Mesh {}
unsafe impl Sync for Mesh {}

impl Mesh {
    /// An empty mesh.
    pub fn new() -> Result<Mesh> {
        let mut raw = ptr::null_mut();
        // SAFETY: raw is a valid out pointer.
        check(unsafe { sys::raps_mesh_create(&mut raw) }, no_message)?;
        NonNull::new(raw)
            .map(|raw| Mesh { raw })
            .ok_or_else(|| Error::new(sys::RAPS_ERROR_INTERNAL, "NULL mesh".to_string()))
    }

    /// A mesh of `xyz` (x, y, z per vertex) and `indices` (three per triangle, counter-clockwise
    /// seen from the front).
    pub fn from_f32(xyz: &[f32], indices: &[u32]) -> Result<Mesh> {
        let mut mesh = Mesh::new()?;
        mesh.set_positions_f32(xyz)?;
        mesh.set_indices_u32(indices)?;
        Ok(mesh)
    }

    /// Like [`Mesh::from_f32`], with double-precision positions.
    pub fn from_f64(xyz: &[f64], indices: &[u32]) -> Result<Mesh> {
        let mut mesh = Mesh::new()?;
        mesh.set_positions_f64(xyz)?;
        mesh.set_indices_u32(indices)?;
        Ok(mesh)
    }

    fn last_error(&self) -> String {
        // SAFETY: a live handle; the string is copied before any other call on it.
        unsafe { owned_string(sys::raps_mesh_last_error(self.raw.as_ptr())) }
    }

    /// Replaces the positions: packed x, y, z per vertex.
    pub fn set_positions_f32(&mut self, xyz: &[f32]) -> Result<()> {
        self.set_positions_f32_strided(xyz, 3)
    }

    /// Replaces the positions from an interleaved buffer: vertex `i` is
    /// `data[i * stride..i * stride + 3]`, `stride >= 3` values apart; as many vertices as
    /// `data` holds completely.
    pub fn set_positions_f32_strided(&mut self, data: &[f32], stride: usize) -> Result<()> {
        let count = point_count(data.len(), stride)?;
        let bytes = stride * std::mem::size_of::<f32>();
        // SAFETY: `count` points of `stride` values fit in `data`, which the call only reads.
        let status = unsafe {
            sys::raps_mesh_set_positions_f32(self.raw.as_ptr(), data.as_ptr(), count, bytes)
        };
        check(status, || self.last_error())
    }

    /// Replaces the positions: packed x, y, z per vertex, double precision.
    pub fn set_positions_f64(&mut self, xyz: &[f64]) -> Result<()> {
        let count = point_count(xyz.len(), 3)?;
        // SAFETY: `count` packed points fit in `xyz`, which the call only reads.
        let status =
            unsafe { sys::raps_mesh_set_positions_f64(self.raw.as_ptr(), xyz.as_ptr(), count, 0) };
        check(status, || self.last_error())
    }

    /// Replaces the triangles: three indices each, counter-clockwise seen from the front.
    pub fn set_indices_u32(&mut self, indices: &[u32]) -> Result<()> {
        // SAFETY: the call reads `indices.len()` values.
        let status = unsafe {
            sys::raps_mesh_set_indices_u32(self.raw.as_ptr(), indices.as_ptr(), indices.len())
        };
        check(status, || self.last_error())
    }

    /// Replaces the triangles with 16-bit indices (meshes of at most 65536 vertices).
    pub fn set_indices_u16(&mut self, indices: &[u16]) -> Result<()> {
        // SAFETY: the call reads `indices.len()` values.
        let status = unsafe {
            sys::raps_mesh_set_indices_u16(self.raw.as_ptr(), indices.as_ptr(), indices.len())
        };
        check(status, || self.last_error())
    }

    /// Places the mesh in world units for [`parameterize_scene`]: `m` is the 3x4 matrix
    /// [A | t], row-major (a point p goes to A p + t); `None` sets the identity. A non-finite
    /// or singular transform is refused with [`Status::INVALID_TRANSFORM`].
    pub fn set_transform(&mut self, m: Option<&[f64; 12]>) -> Result<()> {
        let matrix = m.map_or(ptr::null(), |m| m.as_ptr());
        // SAFETY: NULL or twelve doubles, only read.
        let status = unsafe { sys::raps_mesh_set_transform(self.raw.as_ptr(), matrix) };
        check(status, || self.last_error())
    }

    /// Atlas domain: a group id per triangle (a material, a smoothing group, a region); no
    /// chart holds triangles of two groups. An empty slice removes them. A count other than
    /// the triangle count is refused with [`Status::GROUP_COUNT`] when the mesh is used.
    pub fn set_triangle_groups(&mut self, groups: &[u32]) -> Result<()> {
        let data = if groups.is_empty() {
            ptr::null()
        } else {
            groups.as_ptr()
        };
        // SAFETY: NULL with 0, or groups.len() integers, only read.
        let status =
            unsafe { sys::raps_mesh_set_triangle_groups(self.raw.as_ptr(), data, groups.len()) };
        check(status, || self.last_error())
    }

    /// Atlas domain: a polygon id per triangle, for quads and n-gons triangulated for raps;
    /// triangles that share an edge and an id stay in one chart with no cut between them, so
    /// each polygon corner gets one output vertex. An empty slice removes them. A count other
    /// than the triangle count is refused with [`Status::GROUP_COUNT`] when the mesh is used.
    pub fn set_triangle_polygons(&mut self, polygons: &[u32]) -> Result<()> {
        let data = if polygons.is_empty() {
            ptr::null()
        } else {
            polygons.as_ptr()
        };
        // SAFETY: NULL with 0, or polygons.len() integers, only read.
        let status = unsafe {
            sys::raps_mesh_set_triangle_polygons(self.raw.as_ptr(), data, polygons.len())
        };
        check(status, || self.last_error())
    }

    /// Atlas domain: seam edges as pairs of vertex indices; no chart grows or merges across
    /// them. An empty slice removes them. When the mesh is used, a pair that is not an edge is
    /// refused with [`Status::SEAM_NOT_AN_EDGE`], one beyond the vertices with
    /// [`Status::INDEX_OUT_OF_RANGE`].
    pub fn set_seam_edges(&mut self, pairs: &[[u32; 2]]) -> Result<()> {
        let data = if pairs.is_empty() {
            ptr::null()
        } else {
            pairs.as_ptr().cast::<u32>()
        };
        // SAFETY: NULL with 0, or 2 * pairs.len() contiguous integers, only read.
        let status = unsafe { sys::raps_mesh_set_seam_edges(self.raw.as_ptr(), data, pairs.len()) };
        check(status, || self.last_error())
    }

    /// The mesh's own uvs, read when [`Settings::set_atlas_repack`] repacks them: packed u, v
    /// per triangle corner (corner `3 t + k` is corner k of triangle t). An empty slice removes
    /// them. A non-finite uv is refused with [`Status::NON_FINITE_UV`]; a count other than
    /// three per triangle with [`Status::UV_COUNT`] when the mesh is repacked.
    pub fn set_corner_uvs_f32(&mut self, uv: &[f32]) -> Result<()> {
        let count = pair_count(uv.len())?;
        let data = if uv.is_empty() {
            ptr::null()
        } else {
            uv.as_ptr()
        };
        // SAFETY: NULL with 0, or `count` packed pairs within `uv`, only read.
        let status =
            unsafe { sys::raps_mesh_set_corner_uvs_f32(self.raw.as_ptr(), data, count, 0) };
        check(status, || self.last_error())
    }

    /// Like [`Mesh::set_corner_uvs_f32`], with double-precision uvs.
    pub fn set_corner_uvs_f64(&mut self, uv: &[f64]) -> Result<()> {
        let count = pair_count(uv.len())?;
        let data = if uv.is_empty() {
            ptr::null()
        } else {
            uv.as_ptr()
        };
        // SAFETY: NULL with 0, or `count` packed pairs within `uv`, only read.
        let status =
            unsafe { sys::raps_mesh_set_corner_uvs_f64(self.raw.as_ptr(), data, count, 0) };
        check(status, || self.last_error())
    }

    /// The number of vertices set (0 before positions are set).
    pub fn vertex_count(&self) -> usize {
        // SAFETY: a live handle, read-only.
        unsafe { sys::raps_mesh_vertex_count(self.raw.as_ptr()) }
    }

    /// The number of triangles set (0 before indices are set).
    pub fn triangle_count(&self) -> usize {
        // SAFETY: a live handle, read-only.
        unsafe { sys::raps_mesh_triangle_count(self.raw.as_ptr()) }
    }

    /// The raw handle, for calls into [`sys`]; it stays owned by this `Mesh`.
    pub fn as_ptr(&self) -> *const sys::raps_mesh {
        self.raw.as_ptr()
    }
}

/// How many u, v pairs `len` packed values hold; an odd count is refused.
fn pair_count(len: usize) -> Result<usize> {
    if len % 2 != 0 {
        return Err(Error::new(
            sys::RAPS_ERROR_INVALID_ARGUMENT,
            format!("{} uv values are not a multiple of 2", len),
        ));
    }
    Ok(len / 2)
}

/// How many whole points of three values `stride` apart a buffer of `len` values holds.
fn point_count(len: usize, stride: usize) -> Result<usize> {
    if stride < 3 {
        return Err(Error::new(
            sys::RAPS_ERROR_INVALID_ARGUMENT,
            format!(
                "a stride of {} values is smaller than one point (3)",
                stride
            ),
        ));
    }
    if stride == 3 && len % 3 != 0 {
        return Err(Error::new(
            sys::RAPS_ERROR_INVALID_ARGUMENT,
            format!("{} coordinates are not a multiple of 3", len),
        ));
    }
    Ok(if len < 3 { 0 } else { (len - 3) / stride + 1 })
}

impl Drop for Mesh {
    fn drop(&mut self) {
        // SAFETY: owned, destroyed exactly once; no borrow can outlive `self`.
        unsafe { sys::raps_mesh_destroy(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Mesh {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Mesh")
            .field("vertex_count", &self.vertex_count())
            .field("triangle_count", &self.triangle_count())
            .finish()
    }
}

// ------------------------------------------------------------------------------------------
// Settings
// ------------------------------------------------------------------------------------------

/// Parameters, holding the library's defaults until set (mean value weights, area monitor,
/// alpha 1, one adaptive solve, circle boundary). Setters return `&mut Self` for chaining:
/// `settings.set_monitor(Monitor::ANGLE)?.set_alpha(2.0)?;`
pub struct Settings {
    raw: NonNull<sys::raps_settings>,
}

// SAFETY: as for Mesh: `&Settings` only reaches functions taking `const raps_settings*`.
unsafe impl Send for Settings {}
unsafe impl Sync for Settings {}

/// Facts about a parameter (`raps_param_info`).
#[derive(Clone, Debug, PartialEq)]
pub struct ParamInfo {
    pub name: &'static str,
    pub is_float: bool,
    pub min: f64,
    pub max: f64,
    pub default: f64,
}

impl Settings {
    /// Settings holding the defaults.
    pub fn new() -> Result<Settings> {
        let mut raw = ptr::null_mut();
        // SAFETY: raw is a valid out pointer.
        check(unsafe { sys::raps_settings_create(&mut raw) }, no_message)?;
        Ok(Settings {
            raw: NonNull::new(raw).expect("raps_settings_create gave NULL"),
        })
    }

    /// An independent copy.
    pub fn try_clone(&self) -> Result<Settings> {
        let mut raw = ptr::null_mut();
        // SAFETY: a live handle, only read; raw is a valid out pointer.
        check(
            unsafe { sys::raps_settings_clone(self.raw.as_ptr(), &mut raw) },
            no_message,
        )?;
        Ok(Settings {
            raw: NonNull::new(raw).expect("raps_settings_clone gave NULL"),
        })
    }

    /// Name, type, bounds and default of a parameter.
    pub fn param_info(param: Param) -> Result<ParamInfo> {
        let mut name = ptr::null();
        let (mut is_float, mut min, mut max, mut default) = (0i32, 0.0, 0.0, 0.0);
        // SAFETY: valid out pointers; the name is a static string.
        let status = unsafe {
            sys::raps_param_info(
                param.0,
                &mut name,
                &mut is_float,
                &mut min,
                &mut max,
                &mut default,
            )
        };
        check(status, || format!("unknown parameter {:?}", param))?;
        // SAFETY: a static string on success.
        let name = unsafe { static_str(name) };
        Ok(ParamInfo {
            name,
            is_float: is_float != 0,
            min,
            max,
            default,
        })
    }

    fn last_error(&self) -> String {
        // SAFETY: a live handle; the string is copied before any other call on it.
        unsafe { owned_string(sys::raps_settings_last_error(self.raw.as_ptr())) }
    }

    /// Sets an integer parameter; a bad value leaves the settings unchanged.
    pub fn set_int(&mut self, param: Param, value: i64) -> Result<&mut Self> {
        // SAFETY: a live handle, exclusively borrowed.
        let status = unsafe { sys::raps_settings_set_int(self.raw.as_ptr(), param.0, value) };
        check(status, || self.last_error())?;
        Ok(self)
    }

    /// Sets a float parameter; a bad value leaves the settings unchanged.
    pub fn set_float(&mut self, param: Param, value: f64) -> Result<&mut Self> {
        // SAFETY: a live handle, exclusively borrowed.
        let status = unsafe { sys::raps_settings_set_float(self.raw.as_ptr(), param.0, value) };
        check(status, || self.last_error())?;
        Ok(self)
    }

    /// Reads an integer parameter.
    pub fn int(&self, param: Param) -> Result<i64> {
        let mut value = 0;
        // SAFETY: a live handle, only read; a valid out pointer.
        let status = unsafe { sys::raps_settings_get_int(self.raw.as_ptr(), param.0, &mut value) };
        check(status, || {
            format!("{:?} is not an integer parameter", param)
        })?;
        Ok(value)
    }

    /// Reads a float parameter.
    pub fn float(&self, param: Param) -> Result<f64> {
        let mut value = 0.0;
        // SAFETY: a live handle, only read; a valid out pointer.
        let status =
            unsafe { sys::raps_settings_get_float(self.raw.as_ptr(), param.0, &mut value) };
        check(status, || format!("{:?} is not a float parameter", param))?;
        Ok(value)
    }

    pub fn set_domain(&mut self, domain: Domain) -> Result<&mut Self> {
        self.set_int(Param::DOMAIN, domain.0.into())
    }
    pub fn set_weights(&mut self, weights: Weights) -> Result<&mut Self> {
        self.set_int(Param::WEIGHTS, weights.0.into())
    }
    pub fn set_monitor(&mut self, monitor: Monitor) -> Result<&mut Self> {
        self.set_int(Param::MONITOR, monitor.0.into())
    }
    /// The exponent of W_ij = w_ij * e_ij^alpha.
    pub fn set_alpha(&mut self, alpha: f64) -> Result<&mut Self> {
        self.set_float(Param::ALPHA, alpha)
    }
    /// The number of adaptive solves.
    pub fn set_iterations(&mut self, iterations: u32) -> Result<&mut Self> {
        self.set_int(Param::ITERATIONS, iterations.into())
    }
    pub fn set_iteration_mode(&mut self, mode: IterationMode) -> Result<&mut Self> {
        self.set_int(Param::ITERATION_MODE, mode.0.into())
    }
    pub fn set_boundary(&mut self, boundary: Boundary) -> Result<&mut Self> {
        self.set_int(Param::BOUNDARY, boundary.0.into())
    }
    /// The largest triangle count accepted; larger meshes fail before any work.
    pub fn set_max_triangles(&mut self, max_triangles: u32) -> Result<&mut Self> {
        self.set_int(Param::MAX_TRIANGLES, max_triangles.into())
    }
    /// Memory cap in MiB (0 = none, the default): a run estimated to need more fails with
    /// [`Status::TOO_LARGE`] before any work.
    pub fn set_max_memory_mb(&mut self, max_memory_mb: u32) -> Result<&mut Self> {
        self.set_int(Param::MAX_MEMORY_MB, max_memory_mb.into())
    }
    /// Threads a run may use, 0 = every hardware thread (the default); the output is the same
    /// whatever the value.
    pub fn set_threads(&mut self, threads: u32) -> Result<&mut Self> {
        self.set_int(Param::THREADS, threads.into())
    }
    /// Sphere: how the map is computed ([`SphereMethod::ROBUST`] by default).
    pub fn set_sphere_method(&mut self, method: SphereMethod) -> Result<&mut Self> {
        self.set_int(Param::SPHERE_METHOD, method.0.into())
    }
    /// Sphere: whether to unfold the map into uvs ([`SphereUv::NONE`] by default: sphere
    /// points only).
    pub fn set_sphere_uv(&mut self, uv: SphereUv) -> Result<&mut Self> {
        self.set_int(Param::SPHERE_UV, uv.0.into())
    }
    /// Sphere relaxation: the fraction of the way to the weighted mean of its ring that a
    /// vertex moves per sweep, in (0, 1].
    pub fn set_sphere_damping(&mut self, damping: f64) -> Result<&mut Self> {
        self.set_float(Param::SPHERE_DAMPING, damping)
    }
    /// Sphere relaxation: converged when the RMS move of one sweep (in damping times mean edge
    /// length) is below this, in [1e-12, 1].
    pub fn set_sphere_tolerance(&mut self, tolerance: f64) -> Result<&mut Self> {
        self.set_float(Param::SPHERE_TOLERANCE, tolerance)
    }
    /// Sphere relaxation: most sweeps of one relaxation; 0 = the method's own.
    pub fn set_sphere_max_sweeps(&mut self, sweeps: u32) -> Result<&mut Self> {
        self.set_int(Param::SPHERE_MAX_SWEEPS, sweeps.into())
    }
    /// Robust sphere method: relaxations by which each adaptive iteration reaches its
    /// exponent.
    pub fn set_sphere_alpha_steps(&mut self, steps: u32) -> Result<&mut Self> {
        self.set_int(Param::SPHERE_ALPHA_STEPS, steps.into())
    }
    /// Atlas: texels on each side of the square atlas.
    pub fn set_atlas_resolution(&mut self, texels: u32) -> Result<&mut Self> {
        self.set_int(Param::ATLAS_RESOLUTION, texels.into())
    }
    /// Atlas: texels kept free between charts.
    pub fn set_atlas_padding(&mut self, texels: u32) -> Result<&mut Self> {
        self.set_int(Param::ATLAS_PADDING, texels.into())
    }
    /// Atlas: vertices closer than this (in position units) are welded first; 0 welds
    /// identical positions only.
    pub fn set_weld_tolerance(&mut self, distance: f64) -> Result<&mut Self> {
        self.set_float(Param::WELD_TOLERANCE, distance)
    }
    /// Atlas: edges whose triangles' normals differ by more degrees become seams; 180 turns
    /// this off.
    pub fn set_hard_edge_angle(&mut self, degrees: f64) -> Result<&mut Self> {
        self.set_float(Param::HARD_EDGE_ANGLE, degrees)
    }
    /// Atlas: charts are split until the L2 stretch is at most this.
    pub fn set_atlas_max_l2_stretch(&mut self, stretch: f64) -> Result<&mut Self> {
        self.set_float(Param::ATLAS_MAX_L2_STRETCH, stretch)
    }
    /// Atlas: no chart keeps a triangle stretched more than this (Linf stretch).
    pub fn set_atlas_max_linf_stretch(&mut self, stretch: f64) -> Result<&mut Self> {
        self.set_float(Param::ATLAS_MAX_LINF_STRETCH, stretch)
    }

    /// Atlas: `true` repacks the mesh's own uvs ([`Mesh::set_corner_uvs_f32`]) instead of
    /// mapping it: the uv islands are the charts, each only moved, turned and uniformly scaled
    /// to the one texel density.
    pub fn set_atlas_repack(&mut self, repack: bool) -> Result<&mut Self> {
        self.set_int(Param::ATLAS_REPACK, repack.into())
    }
    pub fn atlas_repack(&self) -> Result<bool> {
        self.int(Param::ATLAS_REPACK).map(|v| v != 0)
    }
    /// Atlas: whether congruent charts share one place ([`Stacking::NONE`] by default); a
    /// stacked chart's [`Chart`] has `stacked_on`, the chart whose texels it takes.
    pub fn set_atlas_stack(&mut self, stacking: Stacking) -> Result<&mut Self> {
        self.set_int(Param::ATLAS_STACK, stacking.0.into())
    }
    pub fn atlas_stack(&self) -> Result<Stacking> {
        self.int(Param::ATLAS_STACK).map(|v| Stacking(v as i32))
    }

    pub fn domain(&self) -> Result<Domain> {
        self.int(Param::DOMAIN).map(|v| Domain(v as i32))
    }
    pub fn weights(&self) -> Result<Weights> {
        self.int(Param::WEIGHTS).map(|v| Weights(v as i32))
    }
    pub fn monitor(&self) -> Result<Monitor> {
        self.int(Param::MONITOR).map(|v| Monitor(v as i32))
    }
    pub fn alpha(&self) -> Result<f64> {
        self.float(Param::ALPHA)
    }
    pub fn iterations(&self) -> Result<u32> {
        self.int(Param::ITERATIONS).map(|v| v as u32)
    }
    pub fn iteration_mode(&self) -> Result<IterationMode> {
        self.int(Param::ITERATION_MODE)
            .map(|v| IterationMode(v as i32))
    }
    pub fn boundary(&self) -> Result<Boundary> {
        self.int(Param::BOUNDARY).map(|v| Boundary(v as i32))
    }
    pub fn max_triangles(&self) -> Result<u32> {
        self.int(Param::MAX_TRIANGLES).map(|v| v as u32)
    }
    pub fn max_memory_mb(&self) -> Result<u32> {
        self.int(Param::MAX_MEMORY_MB).map(|v| v as u32)
    }
    pub fn threads(&self) -> Result<u32> {
        self.int(Param::THREADS).map(|v| v as u32)
    }
    pub fn sphere_method(&self) -> Result<SphereMethod> {
        self.int(Param::SPHERE_METHOD)
            .map(|v| SphereMethod(v as i32))
    }
    pub fn sphere_uv(&self) -> Result<SphereUv> {
        self.int(Param::SPHERE_UV).map(|v| SphereUv(v as i32))
    }
    pub fn sphere_damping(&self) -> Result<f64> {
        self.float(Param::SPHERE_DAMPING)
    }
    pub fn sphere_tolerance(&self) -> Result<f64> {
        self.float(Param::SPHERE_TOLERANCE)
    }
    pub fn sphere_max_sweeps(&self) -> Result<u32> {
        self.int(Param::SPHERE_MAX_SWEEPS).map(|v| v as u32)
    }
    pub fn sphere_alpha_steps(&self) -> Result<u32> {
        self.int(Param::SPHERE_ALPHA_STEPS).map(|v| v as u32)
    }
    pub fn atlas_resolution(&self) -> Result<u32> {
        self.int(Param::ATLAS_RESOLUTION).map(|v| v as u32)
    }
    pub fn atlas_padding(&self) -> Result<u32> {
        self.int(Param::ATLAS_PADDING).map(|v| v as u32)
    }
    pub fn weld_tolerance(&self) -> Result<f64> {
        self.float(Param::WELD_TOLERANCE)
    }
    pub fn hard_edge_angle(&self) -> Result<f64> {
        self.float(Param::HARD_EDGE_ANGLE)
    }
    pub fn atlas_max_l2_stretch(&self) -> Result<f64> {
        self.float(Param::ATLAS_MAX_L2_STRETCH)
    }
    pub fn atlas_max_linf_stretch(&self) -> Result<f64> {
        self.float(Param::ATLAS_MAX_LINF_STRETCH)
    }

    /// The raw handle, for calls into [`sys`]; it stays owned by these `Settings`.
    pub fn as_ptr(&self) -> *const sys::raps_settings {
        self.raw.as_ptr()
    }
}

impl Drop for Settings {
    fn drop(&mut self) {
        // SAFETY: owned, destroyed exactly once.
        unsafe { sys::raps_settings_destroy(self.raw.as_ptr()) }
    }
}

/// Settings' Debug asks the library about every parameter number below this.
const DEBUG_PARAM_LIMIT: i32 = 256;

impl fmt::Debug for Settings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut s = f.debug_struct("Settings");
        // Every parameter the loaded library knows, also ones newer than this crate. Numbers
        // are only appended, in blocks with gaps between them (1.. general and sphere,
        // 32.. atlas), so each number below DEBUG_PARAM_LIMIT is asked rather than stopping at
        // the first gap.
        for param in (1..DEBUG_PARAM_LIMIT).map(Param) {
            let info = match Settings::param_info(param) {
                Ok(info) => info,
                Err(_) => continue,
            };
            if info.is_float {
                s.field(info.name, &self.float(param).unwrap_or(f64::NAN));
            } else {
                s.field(info.name, &self.int(param).unwrap_or(-1));
            }
        }
        s.finish()
    }
}

// ------------------------------------------------------------------------------------------
// Parameterization (raps_result)
// ------------------------------------------------------------------------------------------

/// The output of [`parameterize`] (a `raps_result`; named so as not to shadow [`Result`]):
/// per output vertex a uv in [0,1]^2 (v up) and the input vertex it comes from, the output
/// triangles and their charts, the statistics and the time of each phase. A sphere map has a
/// point on the unit sphere per output vertex instead, and uvs too only with
/// [`SphereUv::OCTAHEDRAL`]; reading what a result does not hold is an
/// [`Status::INVALID_OPERATION`] error.
pub struct Parameterization {
    raw: NonNull<sys::raps_result>,
}

// SAFETY: no thread affinity; `&Parameterization` only reaches functions taking
// `const raps_result*`, which only read it (they store no message either); refilling it
// needs `&mut`.
unsafe impl Send for Parameterization {}
unsafe impl Sync for Parameterization {}

impl Parameterization {
    /// An empty result, to be filled by [`parameterize_into`].
    pub fn new() -> Result<Parameterization> {
        let mut raw = ptr::null_mut();
        // SAFETY: raw is a valid out pointer.
        check(unsafe { sys::raps_result_create(&mut raw) }, no_message)?;
        Ok(Parameterization {
            raw: NonNull::new(raw).expect("raps_result_create gave NULL"),
        })
    }

    /// Output vertices; 0 when empty (after a failure).
    pub fn vertex_count(&self) -> usize {
        // SAFETY: a live handle, read-only.
        unsafe { sys::raps_result_vertex_count(self.raw.as_ptr()) }
    }

    /// Output indices (three per triangle).
    pub fn index_count(&self) -> usize {
        // SAFETY: a live handle, read-only.
        unsafe { sys::raps_result_index_count(self.raw.as_ptr()) }
    }

    pub fn triangle_count(&self) -> usize {
        self.index_count() / 3
    }

    fn require_map(&self) -> Result<usize> {
        match self.vertex_count() {
            0 => Err(no_map()),
            n => Ok(n),
        }
    }

    /// The uvs, one [u, v] per output vertex.
    pub fn uvs(&self) -> Result<Vec<[f32; 2]>> {
        let n = self.require_map()?;
        let mut uvs = vec![[0.0f32; 2]; n];
        self.copy_uvs_into(&mut uvs)?;
        Ok(uvs)
    }

    /// The uvs in double precision.
    pub fn uvs_f64(&self) -> Result<Vec<[f64; 2]>> {
        let n = self.require_map()?;
        let mut uvs = vec![[0.0f64; 2]; n];
        // SAFETY: [f64; 2] is two packed doubles; the call writes at most `n` of them.
        let status = unsafe {
            sys::raps_result_copy_uvs_f64(self.raw.as_ptr(), uvs.as_mut_ptr() as *mut f64, n, 0)
        };
        copy_check(status, NO_UVS, n, n, "uvs")?;
        Ok(uvs)
    }

    /// Copies the uvs into `dst` (at least [`vertex_count`](Self::vertex_count) long), e.g. a
    /// mapped vertex buffer.
    pub fn copy_uvs_into(&self, dst: &mut [[f32; 2]]) -> Result<()> {
        let n = self.require_map()?;
        // SAFETY: [f32; 2] is two packed floats; the capacity is the slice's length.
        let status = unsafe {
            sys::raps_result_copy_uvs_f32(
                self.raw.as_ptr(),
                dst.as_mut_ptr() as *mut f32,
                dst.len(),
                0,
            )
        };
        copy_check(status, NO_UVS, n, dst.len(), "uvs")
    }

    /// Sphere domain: the point on the unit sphere of each output vertex, [x, y, z] (with the
    /// octahedral unfold, a duplicated vertex has its input vertex's point).
    pub fn sphere_points(&self) -> Result<Vec<[f32; 3]>> {
        let n = self.require_map()?;
        let mut points = vec![[0.0f32; 3]; n];
        self.copy_sphere_points_into(&mut points)?;
        Ok(points)
    }

    /// The sphere points in double precision.
    pub fn sphere_points_f64(&self) -> Result<Vec<[f64; 3]>> {
        let n = self.require_map()?;
        let mut points = vec![[0.0f64; 3]; n];
        // SAFETY: [f64; 3] is three packed doubles; the call writes at most `n` of them.
        let status = unsafe {
            sys::raps_result_copy_sphere_points_f64(
                self.raw.as_ptr(),
                points.as_mut_ptr() as *mut f64,
                n,
                0,
            )
        };
        copy_check(status, NO_SPHERE_POINTS, n, n, "sphere points")?;
        Ok(points)
    }

    /// Copies the sphere points into `dst` (at least [`vertex_count`](Self::vertex_count)
    /// long).
    pub fn copy_sphere_points_into(&self, dst: &mut [[f32; 3]]) -> Result<()> {
        let n = self.require_map()?;
        // SAFETY: [f32; 3] is three packed floats; the capacity is the slice's length.
        let status = unsafe {
            sys::raps_result_copy_sphere_points_f32(
                self.raw.as_ptr(),
                dst.as_mut_ptr() as *mut f32,
                dst.len(),
                0,
            )
        };
        copy_check(status, NO_SPHERE_POINTS, n, dst.len(), "sphere points")
    }

    /// The output triangles, three indices into the output vertices each.
    pub fn indices(&self) -> Result<Vec<u32>> {
        self.require_map()?;
        let mut indices = vec![0u32; self.index_count()];
        // SAFETY: the capacity is the vector's length.
        let status = unsafe {
            sys::raps_result_copy_indices_u32(
                self.raw.as_ptr(),
                indices.as_mut_ptr(),
                indices.len(),
            )
        };
        check(status, no_message)?;
        Ok(indices)
    }

    /// Per output vertex, the input vertex it comes from.
    pub fn vertex_remap(&self) -> Result<Vec<u32>> {
        let n = self.require_map()?;
        let mut remap = vec![0u32; n];
        // SAFETY: the capacity is the vector's length.
        let status =
            unsafe { sys::raps_result_copy_vertex_remap(self.raw.as_ptr(), remap.as_mut_ptr(), n) };
        check(status, no_message)?;
        Ok(remap)
    }

    /// Per output triangle, its chart (`0..stats.chart_count`; all 0 for the disk domain).
    pub fn chart_ids(&self) -> Result<Vec<u32>> {
        self.require_map()?;
        let mut charts = vec![0u32; self.triangle_count()];
        // SAFETY: the capacity is the vector's length.
        let status = unsafe {
            sys::raps_result_copy_chart_ids(self.raw.as_ptr(), charts.as_mut_ptr(), charts.len())
        };
        check(status, no_message)?;
        Ok(charts)
    }

    /// The distortion statistics.
    pub fn stats(&self) -> Result<Stats> {
        self.require_map()?;
        let mut stats = Stats {
            struct_size: std::mem::size_of::<Stats>() as u32,
            ..Stats::default()
        };
        // SAFETY: struct_size tells the library how much of `stats` it may write.
        check(
            unsafe { sys::raps_result_get_stats(self.raw.as_ptr(), &mut stats) },
            no_message,
        )?;
        Ok(stats)
    }

    /// Input meshes the result holds: 1 after [`parameterize`], as many as given after
    /// [`parameterize_scene`].
    pub fn mesh_count(&self) -> usize {
        // SAFETY: a live handle, read-only.
        unsafe { sys::raps_result_mesh_count(self.raw.as_ptr()) }
    }

    /// Where input mesh `mesh` lies in the output: its output vertices and indices (its
    /// indices number its own output vertices from 0; its remap gives its own input vertices).
    pub fn mesh_range(&self, mesh: usize) -> Result<MeshRange> {
        let mut range = MeshRange::default();
        // SAFETY: a live handle; valid out pointers.
        let status = unsafe {
            sys::raps_result_mesh_range(
                self.raw.as_ptr(),
                mesh,
                &mut range.first_vertex,
                &mut range.vertex_count,
                &mut range.first_index,
                &mut range.index_count,
            )
        };
        check(status, || self.last_error())?;
        Ok(range)
    }

    /// Atlas domain: every chart's record, by chart id.
    pub fn charts(&self) -> Result<Vec<Chart>> {
        let count = self.stats()?.chart_count as usize;
        let mut charts = Vec::with_capacity(count);
        for index in 0..count {
            let mut chart = Chart {
                struct_size: std::mem::size_of::<Chart>() as u32,
                ..Chart::default()
            };
            // SAFETY: struct_size tells the library how much of `chart` it may write.
            let status =
                unsafe { sys::raps_result_get_chart(self.raw.as_ptr(), index, &mut chart) };
            check(status, || self.last_error())?;
            charts.push(chart);
        }
        Ok(charts)
    }

    /// Wall-clock milliseconds the run that filled this result spent in a phase.
    pub fn phase_ms(&self, phase: Phase) -> f64 {
        // SAFETY: a live handle, read-only.
        unsafe { sys::raps_result_phase_ms(self.raw.as_ptr(), phase.0) }
    }

    /// The raw handle, for calls into [`sys`]; it stays owned by this value.
    pub fn as_ptr(&self) -> *const sys::raps_result {
        self.raw.as_ptr()
    }

    fn last_error(&self) -> String {
        // SAFETY: a live handle; the string is copied before any other call on it.
        unsafe { owned_string(sys::raps_result_last_error(self.raw.as_ptr())) }
    }
}

impl Drop for Parameterization {
    fn drop(&mut self) {
        // SAFETY: owned, destroyed exactly once.
        unsafe { sys::raps_result_destroy(self.raw.as_ptr()) }
    }
}

impl fmt::Debug for Parameterization {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Parameterization")
            .field("vertex_count", &self.vertex_count())
            .field("index_count", &self.index_count())
            .finish()
    }
}

// ------------------------------------------------------------------------------------------
// Running
// ------------------------------------------------------------------------------------------

/// Parameterizes `mesh` with `settings` (`None`: the defaults) into a new [`Parameterization`].
/// Runs on the calling thread (with the worker threads it starts unless `threads` is 1, all
/// joined before it returns); `mesh` and `settings` are only read.
pub fn parameterize(mesh: &Mesh, settings: Option<&Settings>) -> Result<Parameterization> {
    let mut out = Parameterization::new()?;
    parameterize_into(mesh, settings, &mut out)?;
    Ok(out)
}

/// Like [`parameterize`], refilling `out` (which is empty after a failure).
pub fn parameterize_into(
    mesh: &Mesh,
    settings: Option<&Settings>,
    out: &mut Parameterization,
) -> Result<()> {
    let settings = settings.map_or(ptr::null(), |s| s.raw.as_ptr() as *const _);
    // SAFETY: live handles; mesh and settings are only read, out is exclusively borrowed.
    let status = unsafe { sys::raps_parameterize(mesh.raw.as_ptr(), settings, out.raw.as_ptr()) };
    check(status, || out.last_error())
}

/// Where one input mesh lies in a result's output ([`Parameterization::mesh_range`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MeshRange {
    pub first_vertex: u64,
    pub vertex_count: u64,
    pub first_index: u64,
    pub index_count: u64,
}

/// Packs several meshes into one atlas at one texel density (`settings` must set
/// [`Domain::ATLAS`]); each mesh is placed by its transform ([`Mesh::set_transform`]). The
/// result holds the meshes' outputs one after another ([`Parameterization::mesh_range`]).
pub fn parameterize_scene(meshes: &[&Mesh], settings: &Settings) -> Result<Parameterization> {
    let raw: Vec<*const sys::raps_mesh> = meshes
        .iter()
        .map(|mesh| mesh.raw.as_ptr() as *const _)
        .collect();
    let out = Parameterization::new()?;
    // SAFETY: live handles, only read; `raw` holds meshes.len() of them; out is ours.
    let status = unsafe {
        sys::raps_parameterize_scene(
            raw.as_ptr(),
            raw.len(),
            settings.raw.as_ptr(),
            out.raw.as_ptr(),
        )
    };
    check(status, || out.last_error())?;
    Ok(out)
}

struct Progress<F> {
    callback: F,
    panic: Option<Box<dyn Any + Send + 'static>>,
}

unsafe extern "C" fn progress_trampoline<F: FnMut(Phase, f64) -> bool + Send>(
    user: *mut c_void,
    phase: sys::raps_phase,
    fraction: f64,
) -> i32 {
    // SAFETY: `user` is the Mutex<Progress<F>> of parameterize_with_progress, alive for the
    // whole run (the library joins its worker threads before raps_parameterize returns).
    let shared = &*(user as *const Mutex<Progress<F>>);
    // The library calls back from its worker threads too, one call at a time (raps.h); the lock
    // turns that promise into exclusive access the compiler can check (F: Send, as it runs on
    // whichever thread holds the lock). Panics are caught below, so the
    // lock is never poisoned; were it, the state is still whole.
    let mut guard = shared.lock().unwrap_or_else(PoisonError::into_inner);
    let state = &mut *guard;
    if state.panic.is_some() {
        return 0;
    }
    // A panic must not unwind into C: keep it, cancel the run, and resume it afterwards.
    let callback = &mut state.callback;
    match panic::catch_unwind(AssertUnwindSafe(|| callback(Phase(phase), fraction))) {
        Ok(true) => 1,
        Ok(false) => 0,
        Err(payload) => {
            state.panic = Some(payload);
            0
        }
    }
}

/// Like [`parameterize`], calling `progress(phase, fraction)` at the start and end of every
/// phase and about every 1% of the long ones, on this thread or, unless `threads` is 1, on the
/// run's worker threads (hence `Send`), never two calls at once; returning `false` cancels the
/// run, which then fails with [`Status::CANCELLED`]. A panic in `progress` cancels the run and
/// is resumed here. The callback is set on a private copy of `settings`, so settings shared
/// with other threads never see it.
pub fn parameterize_with_progress<F>(
    mesh: &Mesh,
    settings: Option<&Settings>,
    progress: F,
) -> Result<Parameterization>
where
    F: FnMut(Phase, f64) -> bool + Send,
{
    let private = private_copy(settings)?;
    let state = Mutex::new(Progress {
        callback: progress,
        panic: None,
    });
    // SAFETY: `state` outlives the run below, and `private` (which holds the pointer) is
    // dropped at the end of this function, after the run; the trampoline only takes `&state`.
    let status = unsafe {
        sys::raps_settings_set_progress(
            private.raw.as_ptr(),
            Some(progress_trampoline::<F>),
            &state as *const Mutex<Progress<F>> as *mut c_void,
        )
    };
    check(status, || private.last_error())?;
    let mut out = Parameterization::new()?;
    let result = parameterize_into(mesh, Some(&private), &mut out);
    let panicked = state
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .panic
        .take();
    if let Some(payload) = panicked {
        panic::resume_unwind(payload);
    }
    result.map(|()| out)
}

/// Progress to poll instead of a callback (`raps_progress_state`): pass it to
/// [`parameterize_with_state`], then [`read`](ProgressState::read) it or
/// [`cancel`](ProgressState::cancel) the run from any thread; the run stops at its next report
/// with [`Status::CANCELLED`], and so does every run started until
/// [`reset`](ProgressState::reset). No Rust code runs on the library's worker threads. Several
/// runs may share one state at once (a cancel stops them all); the borrow checker keeps it
/// alive while they run.
pub struct ProgressState {
    raw: NonNull<sys::raps_progress_state>,
}

// SAFETY: every raps_progress_state_* call may run on any thread at any time, also while runs
// report into the state (raps.h); the library locks it.
unsafe impl Send for ProgressState {}
unsafe impl Sync for ProgressState {}

/// A [`ProgressState`]'s latest report.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProgressReading {
    /// The phase of the latest report; `None` before the first.
    pub phase: Option<Phase>,
    /// The fraction of that phase done, in [0, 1].
    pub fraction: f64,
    /// Reports since creation or the last reset.
    pub reports: i64,
}

impl ProgressState {
    /// A state with no report and not cancelled.
    pub fn new() -> Result<ProgressState> {
        let mut raw = ptr::null_mut();
        // SAFETY: raw is a valid out pointer.
        check(
            unsafe { sys::raps_progress_state_create(&mut raw) },
            no_message,
        )?;
        Ok(ProgressState {
            raw: NonNull::new(raw).expect("raps_progress_state_create gave NULL"),
        })
    }

    /// The latest report of any run using this state.
    pub fn read(&self) -> ProgressReading {
        let (mut phase, mut fraction, mut reports) = (-1, 0.0, 0i64);
        // SAFETY: a live handle and valid out pointers; reading is allowed at any time.
        let status = unsafe {
            sys::raps_progress_state_read(
                self.raw.as_ptr(),
                &mut phase,
                &mut fraction,
                &mut reports,
            )
        };
        debug_assert_eq!(status, sys::RAPS_OK);
        ProgressReading {
            phase: if phase < 0 { None } else { Some(Phase(phase)) },
            fraction,
            reports,
        }
    }

    /// Cancels every run using this state at its next report, and every run started until
    /// [`reset`](ProgressState::reset).
    pub fn cancel(&self) {
        // SAFETY: a live handle; cancelling is allowed from any thread at any time.
        let status = unsafe { sys::raps_progress_state_cancel(self.raw.as_ptr()) };
        debug_assert_eq!(status, sys::RAPS_OK);
    }

    /// Clears the reading and the cancel, for the next run.
    pub fn reset(&self) {
        // SAFETY: a live handle; resetting is allowed from any thread at any time.
        let status = unsafe { sys::raps_progress_state_reset(self.raw.as_ptr()) };
        debug_assert_eq!(status, sys::RAPS_OK);
    }
}

impl Drop for ProgressState {
    fn drop(&mut self) {
        // SAFETY: owned, destroyed exactly once; no run borrows it any more.
        unsafe { sys::raps_progress_state_destroy(self.raw.as_ptr()) }
    }
}

/// Like [`parameterize`], the run writing its reports into `progress`, which other threads may
/// read and cancel meanwhile. The state is set on a private copy of `settings`.
pub fn parameterize_with_state(
    mesh: &Mesh,
    settings: Option<&Settings>,
    progress: &ProgressState,
) -> Result<Parameterization> {
    parameterize(mesh, Some(&reporting_into(settings, progress)?))
}

/// Like [`parameterize_scene`], the run writing its reports into `progress`, which other threads
/// may read and cancel meanwhile. The state is set on a private copy of `settings`.
pub fn parameterize_scene_with_state(
    meshes: &[&Mesh],
    settings: &Settings,
    progress: &ProgressState,
) -> Result<Parameterization> {
    parameterize_scene(meshes, &reporting_into(Some(settings), progress)?)
}

/// A private copy of `settings` (`None`: the defaults), so that settings shared with other
/// threads never see what a run adds to it.
fn private_copy(settings: Option<&Settings>) -> Result<Settings> {
    match settings {
        Some(settings) => settings.try_clone(),
        None => Settings::new(),
    }
}

/// A private copy of `settings` that reports into `progress`. The copy holds a pointer to the
/// state, so callers run it and drop it while `progress` is still borrowed.
fn reporting_into(settings: Option<&Settings>, progress: &ProgressState) -> Result<Settings> {
    let private = private_copy(settings)?;
    // SAFETY: live handles; the settings keep the pointer, not the state (raps.h).
    let status = unsafe {
        sys::raps_settings_set_progress_state(private.raw.as_ptr(), progress.raw.as_ptr())
    };
    check(status, || private.last_error())?;
    Ok(private)
}
