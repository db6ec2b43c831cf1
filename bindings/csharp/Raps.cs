// The idiomatic C# API of raps over the generated P/Invoke layer (Native.g.cs).
//
// Mesh, Settings and Result own their native object through a SafeHandle: Dispose frees it at
// once, the finalizer frees it if Dispose is forgotten, and never twice; a call on a disposed
// object throws ObjectDisposedException (the marshaller refuses a closed SafeHandle). Failures
// throw RapsException with the status, its name and the library's message. Buffers are arrays:
// Span<T> cannot be pinned by Mono's mcs (no C# 7.3 'fixed' on spans), and this file must build
// unchanged with Mono's mcs and the .NET SDK.
using System;
using System.Runtime.ExceptionServices;
using System.Runtime.InteropServices;
using System.Text;

namespace Raps
{
    public enum Status
    {
        Ok = Native.RAPS_OK,
        InvalidArgument = Native.RAPS_ERROR_INVALID_ARGUMENT,
        OutOfMemory = Native.RAPS_ERROR_OUT_OF_MEMORY,
        EmptyMesh = Native.RAPS_ERROR_EMPTY_MESH,
        IndexCount = Native.RAPS_ERROR_INDEX_COUNT,
        IndexOutOfRange = Native.RAPS_ERROR_INDEX_OUT_OF_RANGE,
        NonFinitePosition = Native.RAPS_ERROR_NON_FINITE_POSITION,
        RepeatedVertex = Native.RAPS_ERROR_REPEATED_VERTEX,
        ZeroAreaTriangle = Native.RAPS_ERROR_ZERO_AREA_TRIANGLE,
        NonManifoldEdge = Native.RAPS_ERROR_NON_MANIFOLD_EDGE,
        NonManifoldVertex = Native.RAPS_ERROR_NON_MANIFOLD_VERTEX,
        InconsistentOrientation = Native.RAPS_ERROR_INCONSISTENT_ORIENTATION,
        IsolatedVertex = Native.RAPS_ERROR_ISOLATED_VERTEX,
        MultipleComponents = Native.RAPS_ERROR_MULTIPLE_COMPONENTS,
        NoBoundary = Native.RAPS_ERROR_NO_BOUNDARY,
        MultipleBoundaries = Native.RAPS_ERROR_MULTIPLE_BOUNDARIES,
        NonzeroGenus = Native.RAPS_ERROR_NONZERO_GENUS,
        TooLarge = Native.RAPS_ERROR_TOO_LARGE,
        Cancelled = Native.RAPS_ERROR_CANCELLED,
        SolverFailed = Native.RAPS_ERROR_SOLVER_FAILED,
        InvalidOperation = Native.RAPS_ERROR_INVALID_OPERATION,
        Internal = Native.RAPS_ERROR_INTERNAL,
        /// <summary>Sphere domain: the mesh is not closed (the message counts its boundary
        /// loops).</summary>
        OpenMesh = Native.RAPS_ERROR_OPEN_MESH,
        /// <summary>Mesh.SetTransform: a coefficient is not finite, or the 3x3 part is
        /// singular.</summary>
        InvalidTransform = Native.RAPS_ERROR_INVALID_TRANSFORM,
        /// <summary>Atlas domain: the triangle groups (Mesh.SetTriangleGroups) are not one per
        /// triangle.</summary>
        GroupCount = Native.RAPS_ERROR_GROUP_COUNT,
        /// <summary>Atlas domain: a seam edge (Mesh.SetSeamEdges) is not an edge of the
        /// mesh.</summary>
        SeamNotAnEdge = Native.RAPS_ERROR_SEAM_NOT_AN_EDGE,
        /// <summary>Repacking (Settings.AtlasRepack): the corner uvs (Mesh.SetCornerUvs) are
        /// not three per triangle.</summary>
        UvCount = Native.RAPS_ERROR_UV_COUNT,
        /// <summary>Mesh.SetCornerUvs: a uv is NaN, infinite or beyond 1e30.</summary>
        NonFiniteUv = Native.RAPS_ERROR_NON_FINITE_UV,
        /// <summary>Repacking: a uv chart has 3D area but no uv area.</summary>
        DegenerateUvChart = Native.RAPS_ERROR_DEGENERATE_UV_CHART
    }

    public enum Param
    {
        Domain = Native.RAPS_PARAM_DOMAIN,
        Weights = Native.RAPS_PARAM_WEIGHTS,
        Monitor = Native.RAPS_PARAM_MONITOR,
        Alpha = Native.RAPS_PARAM_ALPHA,
        Iterations = Native.RAPS_PARAM_ITERATIONS,
        IterationMode = Native.RAPS_PARAM_ITERATION_MODE,
        Boundary = Native.RAPS_PARAM_BOUNDARY,
        MaxTriangles = Native.RAPS_PARAM_MAX_TRIANGLES,
        Threads = Native.RAPS_PARAM_THREADS,
        SphereMethod = Native.RAPS_PARAM_SPHERE_METHOD,
        SphereUv = Native.RAPS_PARAM_SPHERE_UV,
        SphereDamping = Native.RAPS_PARAM_SPHERE_DAMPING,
        SphereTolerance = Native.RAPS_PARAM_SPHERE_TOLERANCE,
        SphereMaxSweeps = Native.RAPS_PARAM_SPHERE_MAX_SWEEPS,
        SphereAlphaSteps = Native.RAPS_PARAM_SPHERE_ALPHA_STEPS,
        MaxMemoryMb = Native.RAPS_PARAM_MAX_MEMORY_MB,
        AtlasResolution = Native.RAPS_PARAM_ATLAS_RESOLUTION,
        AtlasPadding = Native.RAPS_PARAM_ATLAS_PADDING,
        WeldTolerance = Native.RAPS_PARAM_WELD_TOLERANCE,
        HardEdgeAngle = Native.RAPS_PARAM_HARD_EDGE_ANGLE,
        AtlasMaxL2Stretch = Native.RAPS_PARAM_ATLAS_MAX_L2_STRETCH,
        AtlasMaxLinfStretch = Native.RAPS_PARAM_ATLAS_MAX_LINF_STRETCH,
        AtlasTexelsPerUnit = Native.RAPS_PARAM_ATLAS_TEXELS_PER_UNIT,
        AtlasMaxWidth = Native.RAPS_PARAM_ATLAS_MAX_WIDTH,
        AtlasMaxHeight = Native.RAPS_PARAM_ATLAS_MAX_HEIGHT,
        AtlasRotation = Native.RAPS_PARAM_ATLAS_ROTATION,
        AtlasMargin = Native.RAPS_PARAM_ATLAS_MARGIN,
        AtlasBlockAlign = Native.RAPS_PARAM_ATLAS_BLOCK_ALIGN,
        AtlasMeshPerPage = Native.RAPS_PARAM_ATLAS_MESH_PER_PAGE,
        AtlasWholeTexels = Native.RAPS_PARAM_ATLAS_WHOLE_TEXELS,
        AtlasKeepInputSeams = Native.RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS,
        AtlasRepack = Native.RAPS_PARAM_ATLAS_REPACK,
        AtlasStack = Native.RAPS_PARAM_ATLAS_STACK,
        AtlasStackTolerance = Native.RAPS_PARAM_ATLAS_STACK_TOLERANCE
    }

    /// <summary>Which turns the atlas's packing may give a chart (Param.AtlasRotation).</summary>
    public enum Rotation
    {
        /// <summary>Any angle: the chart's smallest bounding box, then a quarter turn (the
        /// default).</summary>
        Any = Native.RAPS_ROTATION_ANY,
        /// <summary>Quarter turns of the chart's map only.</summary>
        Quarter = Native.RAPS_ROTATION_QUARTER,
        /// <summary>None: each chart keeps its map's orientation.</summary>
        None = Native.RAPS_ROTATION_NONE
    }

    /// <summary>Whether congruent charts share one place in the atlas
    /// (Param.AtlasStack).</summary>
    public enum Stacking
    {
        /// <summary>Every chart its own texels (the default).</summary>
        None = Native.RAPS_STACK_NONE,
        /// <summary>Charts congruent up to a rigid motion share one place.</summary>
        Rigid = Native.RAPS_STACK_RIGID,
        /// <summary>Also charts congruent only up to a mirror (their texture appears
        /// mirrored).</summary>
        Mirrored = Native.RAPS_STACK_MIRRORED
    }

    /// <summary>Where one input mesh lies in a result's output (Result.GetMeshRange).</summary>
    public struct MeshRange
    {
        public ulong FirstVertex, VertexCount, FirstIndex, IndexCount;
    }

    public enum Domain
    {
        /// <summary>A topological disk mapped into [0,1]^2 with its boundary on a convex
        /// shape; one output vertex per input vertex.</summary>
        Disk = Native.RAPS_DOMAIN_DISK,
        /// <summary>A closed genus-0 mesh mapped bijectively onto the unit sphere: one output
        /// vertex per input vertex, read with Result.GetSpherePoints; no uvs unless SphereUv is
        /// SphereUv.Octahedral, which adds them and duplicates the cut's vertices.</summary>
        Sphere = Native.RAPS_DOMAIN_SPHERE,
        /// <summary>Any triangle mesh, cut into charts packed into one texture atlas; output
        /// vertices are duplicated along seams (see Result.GetVertexRemap) and each output
        /// triangle, the input one in input order, has a chart (Result.GetChartIds).</summary>
        Atlas = Native.RAPS_DOMAIN_ATLAS
    }

    /// <summary>How the sphere domain computes its map.</summary>
    public enum SphereMethod
    {
        /// <summary>Paper algorithm 7.1 as written: one thread, no safeguards; it may fold
        /// triangles.</summary>
        Literal = Native.RAPS_SPHERE_LITERAL,
        /// <summary>The same relaxation made robust: a bijective initial map, fold-refusing
        /// moves, Moebius centring, continuation in alpha. Never folds (the default).</summary>
        Robust = Native.RAPS_SPHERE_ROBUST
    }

    /// <summary>Texture coordinates for the sphere domain.</summary>
    public enum SphereUv
    {
        /// <summary>Sphere points only: the result has no uvs (the default).</summary>
        None = Native.RAPS_SPHERE_UV_NONE,
        /// <summary>Also unfold the sphere onto [0,1]^2 through the octahedron: one chart, the
        /// cut's vertices duplicated (see Result.GetVertexRemap), no flipped uv
        /// triangle.</summary>
        Octahedral = Native.RAPS_SPHERE_UV_OCTAHEDRAL
    }

    public enum Weights
    {
        MeanValue = Native.RAPS_WEIGHTS_MEAN_VALUE,
        Cotangent = Native.RAPS_WEIGHTS_COTANGENT,
        Uniform = Native.RAPS_WEIGHTS_UNIFORM
    }

    // Not "Monitor": that would clash with System.Threading.Monitor wherever both namespaces
    // are imported.
    public enum ErrorMonitor
    {
        None = Native.RAPS_MONITOR_NONE,
        Area = Native.RAPS_MONITOR_AREA,
        EdgeLength = Native.RAPS_MONITOR_EDGE_LENGTH,
        Angle = Native.RAPS_MONITOR_ANGLE
    }

    public enum IterationMode
    {
        Accumulate = Native.RAPS_ITERATION_ACCUMULATE,
        Reapply = Native.RAPS_ITERATION_REAPPLY
    }

    public enum Boundary
    {
        Circle = Native.RAPS_BOUNDARY_CIRCLE,
        Square = Native.RAPS_BOUNDARY_SQUARE
    }

    public enum Phase
    {
        Validate = Native.RAPS_PHASE_VALIDATE,
        Topology = Native.RAPS_PHASE_TOPOLOGY,
        InitialMap = Native.RAPS_PHASE_INITIAL_MAP,
        Adapt = Native.RAPS_PHASE_ADAPT,
        Metrics = Native.RAPS_PHASE_METRICS,
        /// <summary>Atlas: growing charts.</summary>
        Segment = Native.RAPS_PHASE_SEGMENT,
        /// <summary>Atlas: packing charts.</summary>
        Pack = Native.RAPS_PHASE_PACK
    }

    /// <summary>A failed raps call: the status, the library's name for it and its message
    /// (the offending triangle, vertex, edge or value; empty when the call stores none).</summary>
    public class RapsException : Exception
    {
        private readonly Status status;
        private readonly string statusName;
        private readonly string detail;

        public RapsException(Status status, string detail)
            : base(Describe(status, detail))
        {
            this.status = status;
            this.statusName = Library.StatusString(status);
            this.detail = detail ?? "";
        }

        public Status Status { get { return status; } }
        public string StatusName { get { return statusName; } }
        public string Detail { get { return detail; } }

        private static string Describe(Status status, string detail)
        {
            string text = Library.StatusString(status) + " (status " + (int)status + ")";
            return string.IsNullOrEmpty(detail) ? text : text + ": " + detail;
        }
    }

    internal static class Interop
    {
        // The library's strings are UTF-8 and owned by it: copy, never free.
        internal static string Utf8(IntPtr text)
        {
            if (text == IntPtr.Zero) return "";
            int length = 0;
            while (Marshal.ReadByte(text, length) != 0) length++;
            byte[] bytes = new byte[length];
            Marshal.Copy(text, bytes, 0, length);
            return Encoding.UTF8.GetString(bytes);
        }

        internal static void Check(int status)
        {
            if (status != Native.RAPS_OK) throw new RapsException((Status)status, "");
        }

        internal static void Check(int status, Func<string> message)
        {
            if (status != Native.RAPS_OK) throw new RapsException((Status)status, message());
        }

        internal static UIntPtr Size(long count)
        {
            return new UIntPtr((ulong)count);
        }

        internal static RapsException NoMap()
        {
            return new RapsException(
                Status.InvalidOperation,
                "the result holds no map (Parameterize failed or has not run)");
        }

        internal static RapsException BadInput(string detail)
        {
            return new RapsException(Status.InvalidArgument, detail);
        }
    }

    /// <summary>The input: vertex positions and triangles, copied into the library. Only read
    /// by Parameterize, so one mesh may serve concurrent runs on several threads.</summary>
    public sealed class Mesh : IDisposable
    {
        private readonly MeshHandle handle;

        public Mesh()
        {
            MeshHandle created;
            Interop.Check(Native.raps_mesh_create(out created));
            handle = created;
        }

        /// <summary>A mesh of packed x, y, z per vertex and three indices per triangle
        /// (counter-clockwise seen from the front).</summary>
        public Mesh(float[] xyz, uint[] indices) : this()
        {
            try
            {
                SetPositions(xyz);
                SetIndices(indices);
            }
            catch
            {
                Dispose();
                throw;
            }
        }

        public Mesh(double[] xyz, uint[] indices) : this()
        {
            try
            {
                SetPositions(xyz);
                SetIndices(indices);
            }
            catch
            {
                Dispose();
                throw;
            }
        }

        /// <summary>The owned handle, for calls into Native.</summary>
        public MeshHandle Handle { get { return handle; } }

        private string LastError()
        {
            return Interop.Utf8(Native.raps_mesh_last_error(handle));
        }

        /// <summary>Replaces the positions: packed x, y, z per vertex.</summary>
        public void SetPositions(float[] xyz)
        {
            SetPositions(xyz, 3);
        }

        /// <summary>Places the mesh in world units for Library.ParameterizeScene: m is the 3x4
        /// matrix [A | t], 12 doubles row-major (a point p goes to A p + t); null sets the
        /// identity. A non-finite or singular one throws Status.InvalidTransform.</summary>
        public void SetTransform(double[] m)
        {
            if (m != null && m.Length != 12)
                throw Interop.BadInput("a transform is 12 doubles (3x4, row-major), not " +
                                       m.Length);
            Interop.Check(Native.raps_mesh_set_transform(handle, m), LastError);
        }

        /// <summary>Atlas domain: a group id per triangle (a material, a smoothing group, a
        /// region); no chart holds triangles of two groups. null or an empty array removes
        /// them. A count other than the triangle count throws Status.GroupCount when the mesh
        /// is used.</summary>
        public void SetTriangleGroups(uint[] groups)
        {
            uint[] data = groups != null && groups.Length > 0 ? groups : null;
            Interop.Check(Native.raps_mesh_set_triangle_groups(
                              handle, data, Interop.Size(data == null ? 0 : data.Length)),
                          LastError);
        }

        /// <summary>Atlas domain: a polygon id per triangle, for quads and n-gons
        /// triangulated for raps; triangles that share an edge and an id stay in one chart with
        /// no cut between them, so each polygon corner gets one output vertex. null or an empty
        /// array removes them. A count other than the triangle count throws Status.GroupCount
        /// when the mesh is used.</summary>
        public void SetTrianglePolygons(uint[] polygons)
        {
            uint[] data = polygons != null && polygons.Length > 0 ? polygons : null;
            Interop.Check(Native.raps_mesh_set_triangle_polygons(
                              handle, data, Interop.Size(data == null ? 0 : data.Length)),
                          LastError);
        }

        /// <summary>Atlas domain: seam edges as pairs of vertex indices, packed (a0, b0, a1,
        /// b1, ...); no chart grows or merges across them. null or an empty array removes them.
        /// When the mesh is used, a pair that is not an edge throws Status.SeamNotAnEdge, one
        /// beyond the vertices Status.IndexOutOfRange.</summary>
        public void SetSeamEdges(uint[] vertexPairs)
        {
            if (vertexPairs != null && vertexPairs.Length % 2 != 0)
                throw Interop.BadInput("seam edges are pairs of vertex indices, not " +
                                       vertexPairs.Length + " indices");
            uint[] data = vertexPairs != null && vertexPairs.Length > 0 ? vertexPairs : null;
            Interop.Check(Native.raps_mesh_set_seam_edges(
                              handle, data, Interop.Size(data == null ? 0 : data.Length / 2)),
                          LastError);
        }

        /// <summary>The mesh's own uvs, read when Settings.AtlasRepack repacks them: packed
        /// u, v per triangle corner (corner 3t + k is corner k of triangle t). null or an empty
        /// array removes them. A non-finite uv throws Status.NonFiniteUv; a count other than
        /// three per triangle throws Status.UvCount when the mesh is repacked.</summary>
        public void SetCornerUvs(float[] uv)
        {
            if (uv != null && uv.Length % 2 != 0)
                throw Interop.BadInput("corner uvs are u, v pairs, not " + uv.Length + " values");
            float[] data = uv != null && uv.Length > 0 ? uv : null;
            Interop.Check(Native.raps_mesh_set_corner_uvs_f32(
                              handle, data, Interop.Size(data == null ? 0 : data.Length / 2),
                              UIntPtr.Zero),
                          LastError);
        }

        public void SetCornerUvs(double[] uv)
        {
            if (uv != null && uv.Length % 2 != 0)
                throw Interop.BadInput("corner uvs are u, v pairs, not " + uv.Length + " values");
            double[] data = uv != null && uv.Length > 0 ? uv : null;
            Interop.Check(Native.raps_mesh_set_corner_uvs_f64(
                              handle, data, Interop.Size(data == null ? 0 : data.Length / 2),
                              UIntPtr.Zero),
                          LastError);
        }

        /// <summary>Replaces the positions from an interleaved buffer: vertex i starts at
        /// data[i * stride], stride &gt;= 3 floats apart; as many vertices as data holds
        /// whole.</summary>
        public void SetPositions(float[] data, int stride)
        {
            if (data == null) throw new ArgumentNullException("data");
            long count = PointCount(data.Length, stride);
            Interop.Check(Native.raps_mesh_set_positions_f32(handle, data, Interop.Size(count),
                                                              Interop.Size(stride * 4L)),
                          LastError);
        }

        /// <summary>Replaces the positions: packed x, y, z per vertex, double precision.</summary>
        public void SetPositions(double[] xyz)
        {
            if (xyz == null) throw new ArgumentNullException("xyz");
            long count = PointCount(xyz.Length, 3);
            Interop.Check(Native.raps_mesh_set_positions_f64(handle, xyz, Interop.Size(count),
                                                              UIntPtr.Zero),
                          LastError);
        }

        private static long PointCount(int length, int stride)
        {
            if (stride < 3)
                throw Interop.BadInput("a stride of " + stride + " values is smaller than a point");
            if (stride == 3 && length % 3 != 0)
                throw Interop.BadInput(length + " coordinates are not a multiple of 3");
            return length < 3 ? 0 : (length - 3) / stride + 1;
        }

        /// <summary>Replaces the triangles: three indices each.</summary>
        public void SetIndices(uint[] indices)
        {
            if (indices == null) throw new ArgumentNullException("indices");
            Interop.Check(Native.raps_mesh_set_indices_u32(handle, indices,
                                                            Interop.Size(indices.Length)),
                          LastError);
        }

        /// <summary>Replaces the triangles with 16-bit indices.</summary>
        public void SetIndices(ushort[] indices)
        {
            if (indices == null) throw new ArgumentNullException("indices");
            Interop.Check(Native.raps_mesh_set_indices_u16(handle, indices,
                                                            Interop.Size(indices.Length)),
                          LastError);
        }

        /// <summary>Replaces the triangles from int indices (as Unity and most C# mesh code
        /// keep them); a negative index is refused like one past the vertex count.</summary>
        public void SetIndices(int[] indices)
        {
            if (indices == null) throw new ArgumentNullException("indices");
            var converted = new uint[indices.Length];
            for (int i = 0; i < indices.Length; i++)
            {
                if (indices[i] < 0)
                    throw new RapsException(Status.IndexOutOfRange,
                                            "index " + i + " is negative (" + indices[i] + ")");
                converted[i] = (uint)indices[i];
            }
            SetIndices(converted);
        }

        public long VertexCount
        {
            get { return (long)Native.raps_mesh_vertex_count(handle).ToUInt64(); }
        }

        public long TriangleCount
        {
            get { return (long)Native.raps_mesh_triangle_count(handle).ToUInt64(); }
        }

        public void Dispose()
        {
            handle.Dispose();
        }
    }

    /// <summary>A progress state's latest report: its phase (null before the first), the
    /// fraction of that phase done and the reports since creation or Reset.</summary>
    public struct ProgressReading
    {
        public Phase? Phase;
        public double Fraction;
        public long Reports;
    }

    /// <summary>Progress to poll (raps_progress_state): pass it to Parameterize, then Read it
    /// or Cancel the run from any thread while the run works; the run stops at its next report
    /// with Status.Cancelled, and so does every run started until Reset. No managed code runs
    /// on the library's worker threads. One state may serve several runs, also at once (a
    /// cancel stops them all); dispose it only when no run uses it.</summary>
    public sealed class ProgressState : IDisposable
    {
        private readonly ProgressStateHandle handle;

        public ProgressState()
        {
            ProgressStateHandle created;
            Interop.Check(Native.raps_progress_state_create(out created));
            handle = created;
        }

        /// <summary>The owned handle, for calls into Native.</summary>
        public ProgressStateHandle Handle { get { return handle; } }

        public ProgressReading Read()
        {
            int phase;
            double fraction;
            long reports;
            Interop.Check(Native.raps_progress_state_read(handle, out phase, out fraction,
                                                          out reports));
            return new ProgressReading
            {
                Phase = phase < 0 ? (Phase?)null : (Phase)phase, Fraction = fraction,
                Reports = reports
            };
        }

        public void Cancel()
        {
            Interop.Check(Native.raps_progress_state_cancel(handle));
        }

        public void Reset()
        {
            Interop.Check(Native.raps_progress_state_reset(handle));
        }

        public void Dispose()
        {
            handle.Dispose();
        }
    }

    /// <summary>Facts about a parameter: name, type, inclusive bounds and default.</summary>
    public struct ParamInfo
    {
        public string Name;
        public bool IsFloat;
        public double Min;
        public double Max;
        public double Default;
    }

    /// <summary>Parameters, holding the library's defaults until set:
    /// <c>new Settings { Monitor = ErrorMonitor.Angle, Alpha = 2.0 }</c>. A bad value throws and
    /// leaves the settings unchanged.</summary>
    public sealed class Settings : IDisposable
    {
        private readonly SettingsHandle handle;

        public Settings()
        {
            SettingsHandle created;
            Interop.Check(Native.raps_settings_create(out created));
            handle = created;
        }

        private Settings(SettingsHandle handle)
        {
            this.handle = handle;
        }

        /// <summary>The owned handle, for calls into Native.</summary>
        public SettingsHandle Handle { get { return handle; } }

        /// <summary>An independent copy.</summary>
        public Settings Clone()
        {
            SettingsHandle copy;
            Interop.Check(Native.raps_settings_clone(handle, out copy));
            return new Settings(copy);
        }

        public static ParamInfo GetParamInfo(Param param)
        {
            IntPtr name;
            int isFloat;
            double min, max, fallback;
            Interop.Check(Native.raps_param_info((int)param, out name, out isFloat, out min,
                                                 out max, out fallback),
                          () => "unknown parameter " + (int)param);
            return new ParamInfo
            {
                Name = Interop.Utf8(name), IsFloat = isFloat != 0, Min = min, Max = max,
                Default = fallback
            };
        }

        private string LastError()
        {
            return Interop.Utf8(Native.raps_settings_last_error(handle));
        }

        public void SetInt(Param param, long value)
        {
            Interop.Check(Native.raps_settings_set_int(handle, (int)param, value), LastError);
        }

        public void SetFloat(Param param, double value)
        {
            Interop.Check(Native.raps_settings_set_float(handle, (int)param, value), LastError);
        }

        public long GetInt(Param param)
        {
            long value;
            Interop.Check(Native.raps_settings_get_int(handle, (int)param, out value),
                          () => param + " is not an integer parameter");
            return value;
        }

        public double GetFloat(Param param)
        {
            double value;
            Interop.Check(Native.raps_settings_get_float(handle, (int)param, out value),
                          () => param + " is not a float parameter");
            return value;
        }

        public Domain Domain
        {
            get { return (Domain)GetInt(Param.Domain); }
            set { SetInt(Param.Domain, (long)value); }
        }

        public Weights Weights
        {
            get { return (Weights)GetInt(Param.Weights); }
            set { SetInt(Param.Weights, (long)value); }
        }

        public ErrorMonitor Monitor
        {
            get { return (ErrorMonitor)GetInt(Param.Monitor); }
            set { SetInt(Param.Monitor, (long)value); }
        }

        /// <summary>The exponent of W_ij = w_ij * e_ij^alpha.</summary>
        public double Alpha
        {
            get { return GetFloat(Param.Alpha); }
            set { SetFloat(Param.Alpha, value); }
        }

        /// <summary>The number of adaptive solves.</summary>
        public int Iterations
        {
            get { return (int)GetInt(Param.Iterations); }
            set { SetInt(Param.Iterations, value); }
        }

        public IterationMode IterationMode
        {
            get { return (IterationMode)GetInt(Param.IterationMode); }
            set { SetInt(Param.IterationMode, (long)value); }
        }

        public Boundary Boundary
        {
            get { return (Boundary)GetInt(Param.Boundary); }
            set { SetInt(Param.Boundary, (long)value); }
        }

        /// <summary>The largest triangle count accepted; larger meshes fail before any
        /// work.</summary>
        public long MaxTriangles
        {
            get { return GetInt(Param.MaxTriangles); }
            set { SetInt(Param.MaxTriangles, value); }
        }

        /// <summary>Threads a run may use, 0 = every hardware thread (the default); the output
        /// is the same whatever the value.</summary>
        public int Threads
        {
            get { return (int)GetInt(Param.Threads); }
            set { SetInt(Param.Threads, value); }
        }

        /// <summary>Sphere: how the map is computed (Robust by default).</summary>
        public SphereMethod SphereMethod
        {
            get { return (SphereMethod)GetInt(Param.SphereMethod); }
            set { SetInt(Param.SphereMethod, (long)value); }
        }

        /// <summary>Sphere: whether to unfold the map into uvs (None by default: sphere points
        /// only).</summary>
        public SphereUv SphereUv
        {
            get { return (SphereUv)GetInt(Param.SphereUv); }
            set { SetInt(Param.SphereUv, (long)value); }
        }

        /// <summary>Sphere relaxation: the fraction of the way to the weighted mean of its ring
        /// that a vertex moves per sweep, in (0, 1].</summary>
        public double SphereDamping
        {
            get { return GetFloat(Param.SphereDamping); }
            set { SetFloat(Param.SphereDamping, value); }
        }

        /// <summary>Sphere relaxation: converged when the RMS move of one sweep (in damping
        /// times mean edge length) is below this, in [1e-12, 1].</summary>
        public double SphereTolerance
        {
            get { return GetFloat(Param.SphereTolerance); }
            set { SetFloat(Param.SphereTolerance, value); }
        }

        /// <summary>Sphere relaxation: most sweeps of one relaxation; 0 = the method's
        /// own.</summary>
        public int SphereMaxSweeps
        {
            get { return (int)GetInt(Param.SphereMaxSweeps); }
            set { SetInt(Param.SphereMaxSweeps, value); }
        }

        /// <summary>Robust sphere method: relaxations by which each adaptive iteration reaches
        /// its exponent.</summary>
        public int SphereAlphaSteps
        {
            get { return (int)GetInt(Param.SphereAlphaSteps); }
            set { SetInt(Param.SphereAlphaSteps, value); }
        }

        /// <summary>Memory cap in MiB (0 = none, the default): a run estimated to need more
        /// fails with Status.TooLarge before any work.</summary>
        public int MaxMemoryMb
        {
            get { return (int)GetInt(Param.MaxMemoryMb); }
            set { SetInt(Param.MaxMemoryMb, value); }
        }

        /// <summary>Atlas: texels on each side of the square atlas.</summary>
        public int AtlasResolution
        {
            get { return (int)GetInt(Param.AtlasResolution); }
            set { SetInt(Param.AtlasResolution, value); }
        }

        /// <summary>Atlas: texels kept free between charts.</summary>
        public int AtlasPadding
        {
            get { return (int)GetInt(Param.AtlasPadding); }
            set { SetInt(Param.AtlasPadding, value); }
        }

        /// <summary>Atlas: vertices closer than this (in position units) are welded first; 0
        /// welds identical positions only.</summary>
        public double WeldTolerance
        {
            get { return GetFloat(Param.WeldTolerance); }
            set { SetFloat(Param.WeldTolerance, value); }
        }

        /// <summary>Atlas: edges whose triangles' normals differ by more degrees become
        /// seams; 180 turns this off.</summary>
        public double HardEdgeAngle
        {
            get { return GetFloat(Param.HardEdgeAngle); }
            set { SetFloat(Param.HardEdgeAngle, value); }
        }

        /// <summary>Atlas: charts are split until the L2 stretch is at most this.</summary>
        public double AtlasMaxL2Stretch
        {
            get { return GetFloat(Param.AtlasMaxL2Stretch); }
            set { SetFloat(Param.AtlasMaxL2Stretch, value); }
        }

        /// <summary>Atlas: no chart keeps a triangle stretched more than this (Linf).</summary>
        public double AtlasMaxLinfStretch
        {
            get { return GetFloat(Param.AtlasMaxLinfStretch); }
            set { SetFloat(Param.AtlasMaxLinfStretch, value); }
        }

        /// <summary>Atlas: true repacks the mesh's own uvs (Mesh.SetCornerUvs) instead of
        /// mapping it: the uv islands are the charts, each only moved, turned and uniformly
        /// scaled to the one texel density.</summary>
        public bool AtlasRepack
        {
            get { return GetInt(Param.AtlasRepack) != 0; }
            set { SetInt(Param.AtlasRepack, value ? 1 : 0); }
        }

        /// <summary>Atlas: whether congruent charts share one place (Stacking.None by
        /// default); a stacked chart's Chart.StackedOn names the chart whose texels it
        /// takes.</summary>
        public Stacking AtlasStack
        {
            get { return (Stacking)GetInt(Param.AtlasStack); }
            set { SetInt(Param.AtlasStack, (long)value); }
        }

        public void Dispose()
        {
            handle.Dispose();
        }
    }

    /// <summary>The map: per output vertex a uv in [0,1]^2 (v up) and the input vertex it comes
    /// from, the output triangles and their charts, the statistics and the time of each
    /// phase. A sphere map has a point on the unit sphere per output vertex instead, and uvs
    /// too only with SphereUv.Octahedral. Reading an empty result (after a failure), or what
    /// the result does not hold, throws with Status.InvalidOperation.</summary>
    public sealed class Result : IDisposable
    {
        private readonly ResultHandle handle;

        public Result()
        {
            ResultHandle created;
            Interop.Check(Native.raps_result_create(out created));
            handle = created;
        }

        /// <summary>The owned handle, for calls into Native.</summary>
        public ResultHandle Handle { get { return handle; } }

        internal string LastError()
        {
            return Interop.Utf8(Native.raps_result_last_error(handle));
        }

        public long VertexCount
        {
            get { return (long)Native.raps_result_vertex_count(handle).ToUInt64(); }
        }

        public long IndexCount
        {
            get { return (long)Native.raps_result_index_count(handle).ToUInt64(); }
        }

        public long TriangleCount
        {
            get { return IndexCount / 3; }
        }

        private long RequireMap()
        {
            long count = VertexCount;
            if (count == 0) throw Interop.NoMap();
            return count;
        }

        // The copy functions take a const result and store no message: say which of their
        // failures this is.
        private const string NoUvs =
            "the result holds no uvs: a sphere map has them only with SphereUv.Octahedral (read " +
            "its points with GetSpherePoints)";
        private const string NoSpherePoints =
            "the result holds no sphere points (only Domain.Sphere has them)";

        private static void CheckCopy(int status, string missing, long count, long capacity,
                                      string items)
        {
            if (status == Native.RAPS_OK) return;
            if (status == Native.RAPS_ERROR_INVALID_OPERATION)
                throw new RapsException(Status.InvalidOperation, missing);
            if (status == Native.RAPS_ERROR_INVALID_ARGUMENT && capacity < count)
                throw Interop.BadInput(count + " " + items + " do not fit in a buffer for " +
                                       capacity);
            throw new RapsException((Status)status, "");
        }

        /// <summary>The uvs: u and v of each output vertex, 2 * VertexCount floats.</summary>
        public float[] GetUvs()
        {
            var uvs = new float[2 * RequireMap()];
            CopyUvs(uvs);
            return uvs;
        }

        /// <summary>Copies the uvs into destination (at least 2 * VertexCount long).</summary>
        public void CopyUvs(float[] destination)
        {
            if (destination == null) throw new ArgumentNullException("destination");
            long count = RequireMap(), capacity = destination.Length / 2;
            CheckCopy(Native.raps_result_copy_uvs_f32(handle, destination,
                                                       Interop.Size(capacity), UIntPtr.Zero),
                      NoUvs, count, capacity, "uvs");
        }

        /// <summary>The uvs in double precision.</summary>
        public double[] GetUvsDouble()
        {
            long count = RequireMap();
            var uvs = new double[2 * count];
            CheckCopy(Native.raps_result_copy_uvs_f64(handle, uvs, Interop.Size(count),
                                                       UIntPtr.Zero),
                      NoUvs, count, count, "uvs");
            return uvs;
        }

        /// <summary>Sphere domain: the point on the unit sphere of each output vertex, x, y, z,
        /// 3 * VertexCount floats (with the octahedral unfold, a duplicated vertex has its
        /// input vertex's point).</summary>
        public float[] GetSpherePoints()
        {
            var points = new float[3 * RequireMap()];
            CopySpherePoints(points);
            return points;
        }

        /// <summary>Copies the sphere points into destination (at least 3 * VertexCount
        /// long).</summary>
        public void CopySpherePoints(float[] destination)
        {
            if (destination == null) throw new ArgumentNullException("destination");
            long count = RequireMap(), capacity = destination.Length / 3;
            CheckCopy(Native.raps_result_copy_sphere_points_f32(handle, destination,
                                                                 Interop.Size(capacity),
                                                                 UIntPtr.Zero),
                      NoSpherePoints, count, capacity, "sphere points");
        }

        /// <summary>The sphere points in double precision.</summary>
        public double[] GetSpherePointsDouble()
        {
            long count = RequireMap();
            var points = new double[3 * count];
            CheckCopy(Native.raps_result_copy_sphere_points_f64(handle, points,
                                                                 Interop.Size(count),
                                                                 UIntPtr.Zero),
                      NoSpherePoints, count, count, "sphere points");
            return points;
        }

        /// <summary>The output triangles: three indices into the output vertices each.</summary>
        public uint[] GetIndices()
        {
            RequireMap();
            var indices = new uint[IndexCount];
            Interop.Check(Native.raps_result_copy_indices_u32(handle, indices,
                                                               Interop.Size(indices.Length)));
            return indices;
        }

        /// <summary>Per output vertex, the input vertex it comes from.</summary>
        public uint[] GetVertexRemap()
        {
            long count = RequireMap();
            var remap = new uint[count];
            Interop.Check(Native.raps_result_copy_vertex_remap(handle, remap,
                                                                Interop.Size(count)));
            return remap;
        }

        /// <summary>Per output triangle, its chart (0 .. Stats.ChartCount - 1; all 0 for the
        /// disk domain).</summary>
        public uint[] GetChartIds()
        {
            RequireMap();
            var charts = new uint[TriangleCount];
            Interop.Check(Native.raps_result_copy_chart_ids(handle, charts,
                                                             Interop.Size(charts.Length)));
            return charts;
        }

        /// <summary>The distortion statistics (see raps_stats in raps.h).</summary>
        public Stats GetStats()
        {
            RequireMap();
            var stats = new Stats();
            stats.StructSize = (uint)Marshal.SizeOf(typeof(Stats));
            Interop.Check(Native.raps_result_get_stats(handle, ref stats));
            return stats;
        }

        /// <summary>Input meshes the result holds: 1 after Parameterize, as many as given
        /// after ParameterizeScene.</summary>
        public long MeshCount
        {
            get { return (long)Native.raps_result_mesh_count(handle).ToUInt64(); }
        }

        /// <summary>Where input mesh `mesh` lies in the output: its output vertices and indices
        /// (its indices number its own output vertices from 0, its remap its own input
        /// vertices).</summary>
        public MeshRange GetMeshRange(long mesh)
        {
            ulong[] firstVertex = new ulong[1], vertexCount = new ulong[1];
            ulong[] firstIndex = new ulong[1], indexCount = new ulong[1];
            Interop.Check(Native.raps_result_mesh_range(handle, Interop.Size(mesh), firstVertex,
                                                        vertexCount, firstIndex, indexCount),
                          LastError);
            var range = new MeshRange
            {
                FirstVertex = firstVertex[0],
                VertexCount = vertexCount[0],
                FirstIndex = firstIndex[0],
                IndexCount = indexCount[0]
            };
            return range;
        }

        /// <summary>Atlas domain: every chart's record, by chart id (its mesh, page, texel
        /// rectangle, rotation, triangles, areas, L2 stretch; Flags holds
        /// Native.RAPS_CHART_SCALED_DOWN for a chart shrunk to fit a page).</summary>
        public Chart[] GetCharts()
        {
            var charts = new Chart[GetStats().ChartCount];
            for (int c = 0; c < charts.Length; c++)
            {
                charts[c].StructSize = (uint)Marshal.SizeOf(typeof(Chart));
                Interop.Check(Native.raps_result_get_chart(handle, Interop.Size(c),
                                                           ref charts[c]),
                              LastError);
            }
            return charts;
        }

        /// <summary>Wall-clock milliseconds the run that filled this result spent in a
        /// phase.</summary>
        public double PhaseMilliseconds(Phase phase)
        {
            return Native.raps_result_phase_ms(handle, (int)phase);
        }

        public void Dispose()
        {
            handle.Dispose();
        }
    }

    public static class Library
    {
        /// <summary>The loaded library's "MAJOR.MINOR.PATCH".</summary>
        public static string Version
        {
            get { return Interop.Utf8(Native.raps_version_string()); }
        }

        /// <summary>The loaded library's version number, MAJOR*10000 + MINOR*100 +
        /// PATCH.</summary>
        public static uint VersionNumber
        {
            get { return Native.raps_version(); }
        }

        /// <summary>The library's short description of a status.</summary>
        public static string StatusString(Status status)
        {
            return Interop.Utf8(Native.raps_status_string((int)status));
        }

        /// <summary>Parameterizes mesh with settings (null: the defaults) into a new Result.
        /// progress, if given, is called with the phase and the fraction done, on this thread
        /// or, unless Threads is 1, on the run's worker threads (never two calls at once);
        /// returning false cancels (RapsException with Status.Cancelled), and an exception it
        /// throws cancels the run and is rethrown here.</summary>
        public static Result Parameterize(Mesh mesh, Settings settings = null,
                                          Func<Phase, double, bool> progress = null)
        {
            var result = new Result();
            try
            {
                Parameterize(mesh, settings, result, progress);
            }
            catch
            {
                result.Dispose();
                throw;
            }
            return result;
        }

        /// <summary>Like Parameterize, the run reporting into progress (read and cancelled from
        /// other threads) instead of calling back.</summary>
        public static Result Parameterize(Mesh mesh, Settings settings, ProgressState progress)
        {
            using (Settings run = ReportingInto(settings, progress))
                return Parameterize(mesh, run);
        }

        /// <summary>Packs several meshes into one atlas at one texel density (settings must set
        /// Domain.Atlas); each mesh is placed by its transform (Mesh.SetTransform). The result
        /// holds the meshes' outputs one after another (Result.GetMeshRange).</summary>
        public static Result ParameterizeScene(Mesh[] meshes, Settings settings)
        {
            if (meshes == null) throw new ArgumentNullException("meshes");
            if (settings == null) throw new ArgumentNullException("settings");
            var raw = new IntPtr[meshes.Length];
            for (int m = 0; m < meshes.Length; m++)
            {
                if (meshes[m] == null) throw new ArgumentNullException("meshes[" + m + "]");
                raw[m] = meshes[m].Handle.DangerousGetHandle();
            }
            var result = new Result();
            int status = Native.raps_parameterize_scene(raw, Interop.Size(raw.Length),
                                                        settings.Handle, result.Handle);
            GC.KeepAlive(meshes);  // the raw pointers are theirs: alive until the call returned
            try
            {
                Interop.Check(status, result.LastError);
            }
            catch
            {
                result.Dispose();
                throw;
            }
            return result;
        }

        /// <summary>Like ParameterizeScene, the run reporting into progress (read and cancelled
        /// from other threads).</summary>
        public static Result ParameterizeScene(Mesh[] meshes, Settings settings,
                                               ProgressState progress)
        {
            if (settings == null) throw new ArgumentNullException("settings");
            using (Settings run = ReportingInto(settings, progress))
                return ParameterizeScene(meshes, run);
        }

        // A private copy of settings (null: the defaults) that reports into progress, so that
        // settings shared with other threads never do.
        private static Settings ReportingInto(Settings settings, ProgressState progress)
        {
            if (progress == null) throw new ArgumentNullException("progress");
            Settings run = settings != null ? settings.Clone() : new Settings();
            try
            {
                Interop.Check(Native.raps_settings_set_progress_state(run.Handle,
                                                                      progress.Handle));
            }
            catch
            {
                run.Dispose();
                throw;
            }
            return run;
        }

        /// <summary>Like Parameterize, refilling result (which is empty after a
        /// failure).</summary>
        public static void Parameterize(Mesh mesh, Settings settings, Result result,
                                        Func<Phase, double, bool> progress = null)
        {
            if (mesh == null) throw new ArgumentNullException("mesh");
            if (result == null) throw new ArgumentNullException("result");
            if (progress == null && settings != null)
            {
                Interop.Check(Native.raps_parameterize(mesh.Handle, settings.Handle,
                                                       result.Handle),
                              result.LastError);
                return;
            }
            // The callback goes on a private copy, so settings shared with other threads never
            // see it; the delegate stays reachable until the native call has returned. It may run
            // on the library's worker threads (Threads != 1); the library never overlaps the
            // calls, and the lock also publishes 'raised' to this thread.
            Exception raised = null;
            var serial = new object();
            ProgressFn callback = null;
            if (progress != null)
            {
                callback = (user, phase, fraction) =>
                {
                    lock (serial)
                    {
                        if (raised != null) return 0;
                        try
                        {
                            return progress((Phase)phase, fraction) ? 1 : 0;
                        }
                        catch (Exception error)  // must not unwind through native frames
                        {
                            raised = error;
                            return 0;
                        }
                    }
                };
            }
            using (Settings run = settings != null ? settings.Clone() : new Settings())
            {
                if (callback != null)
                    Interop.Check(Native.raps_settings_set_progress(run.Handle, callback,
                                                                    IntPtr.Zero));
                int status = Native.raps_parameterize(mesh.Handle, run.Handle, result.Handle);
                GC.KeepAlive(callback);
                Exception failure;
                lock (serial) failure = raised;
                if (failure != null) ExceptionDispatchInfo.Capture(failure).Throw();
                Interop.Check(status, result.LastError);
            }
        }
    }
}
