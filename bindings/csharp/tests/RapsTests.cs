// Tests of the C# binding against the real libraps. A self-contained runner, so that the same
// file runs under Mono and .NET without a test framework (Debian's NUnit is 2.6, and NuGet is out
// of reach here). Usage: RapsTests.exe SHARED_DATA_DIR. It prints one line per test and
// "N passed, N failed"; the exit code is the number of failures. Missing shared data fails.
using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Runtime.InteropServices;
using System.Threading;
using Raps;

static class RapsTests
{
    static string dataDir;

    class Off
    {
        public double[] Xyz;
        public uint[] Indices;
    }

    // positions and triangles of an OFF file, polygons fanned.
    static Off ReadOff(string relative)
    {
        string path = Path.Combine(dataDir, relative);
        if (!File.Exists(path)) throw new Exception("shared test data missing: " + path);
        var words = File.ReadAllLines(path)
                        .SelectMany(line => line.Split('#')[0].Split((char[])null,
                                                StringSplitOptions.RemoveEmptyEntries))
                        .ToArray();
        Expect(words[0] == "OFF", "an OFF file");
        int nv = int.Parse(words[1]), nf = int.Parse(words[2]);
        int at = 4;
        var xyz = new double[3 * nv];
        for (int i = 0; i < 3 * nv; i++)
            xyz[i] = double.Parse(words[at++], CultureInfo.InvariantCulture);
        var indices = new List<uint>();
        for (int f = 0; f < nf; f++)
        {
            int n = int.Parse(words[at++]);
            var face = new uint[n];
            for (int k = 0; k < n; k++) face[k] = uint.Parse(words[at++]);
            for (int k = 1; k + 1 < n; k++)
                indices.AddRange(new[] { face[0], face[k], face[k + 1] });
        }
        return new Off { Xyz = xyz, Indices = indices.ToArray() };
    }

    // A closed mesh: no boundary loop, which the disk domain refuses.
    static Off Icosahedron()
    {
        double t = (1 + Math.Sqrt(5)) / 2;
        return new Off
        {
            Xyz = new[] { -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t,
                          0, 1, -t, t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1 },
            Indices = new uint[] { 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5,
                                   11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2,
                                   6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7,
                                   9, 8, 1 }
        };
    }

    // An open mesh: a hexagonal cap, one vertex raised above the middle of six on a circle.
    static Off FanDisk()
    {
        var xyz = new List<double> { 0, 0, 0.5 };
        var indices = new List<uint>();
        for (int k = 0; k < 6; k++)
        {
            xyz.AddRange(new[] { Math.Cos(k * Math.PI / 3), Math.Sin(k * Math.PI / 3), 0.0 });
            indices.AddRange(new[] { 0u, (uint)(1 + k), (uint)(1 + (k + 1) % 6) });
        }
        return new Off { Xyz = xyz.ToArray(), Indices = indices.ToArray() };
    }

    static void Expect(bool condition, string what)
    {
        if (!condition) throw new Exception("expected " + what);
    }

    static RapsException ExpectFailure(Status status, Action action)
    {
        try
        {
            action();
        }
        catch (RapsException error)
        {
            Expect(error.Status == status, status + ", got " + error.Status + ": " + error.Message);
            return error;
        }
        throw new Exception("expected RapsException " + status);
    }

    static double SignedArea(float[] uv, uint a, uint b, uint c)
    {
        return (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1]) -
               (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
    }

    // det[a, b, c] of three points on the sphere: positive when the triangle is
    // counter-clockwise seen from outside.
    static double Det(double[] p, uint a, uint b, uint c)
    {
        double ax = p[3 * a], ay = p[3 * a + 1], az = p[3 * a + 2];
        double bx = p[3 * b], by = p[3 * b + 1], bz = p[3 * b + 2];
        double cx = p[3 * c], cy = p[3 * c + 1], cz = p[3 * c + 2];
        return ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
    }

    // What the binding must hand over of a sphere map: one unit point (x, y, z) per vertex, and
    // every triangle of the input counter-clockwise seen from outside on them.
    static void ExpectSphereMap(Result result, Off input)
    {
        int n = input.Xyz.Length / 3;
        double[] points = result.GetSpherePointsDouble();
        Expect(points.Length == 3 * n, "a point per vertex");
        for (int i = 0; i < n; i++)
        {
            double norm = Math.Sqrt(points[3 * i] * points[3 * i] +
                                    points[3 * i + 1] * points[3 * i + 1] +
                                    points[3 * i + 2] * points[3 * i + 2]);
            Expect(Math.Abs(norm - 1) <= 1e-9, "point " + i + " of unit norm, got " + norm);
        }
        for (int t = 0; t < input.Indices.Length; t += 3)
            Expect(Det(points, input.Indices[t], input.Indices[t + 1], input.Indices[t + 2]) > 0,
                   "triangle " + t / 3 + " counter-clockwise on the sphere");
        float[] single = result.GetSpherePoints();
        for (int i = 0; i < points.Length; i++)
            Expect(Math.Abs(single[i] - points[i]) < 1e-6, "float and double points agree");
        Stats stats = result.GetStats();
        Expect(stats.FlippedTriangles == 0, "no flipped triangle");
        Expect(stats.RelaxationSweeps > 0, "relaxation sweeps counted");
        Expect(stats.VertexCount == (ulong)n && stats.ChartCount == 1 && stats.Utilization == 0,
               "one chart, one output vertex per input vertex, no uv area");
        Expect(result.GetIndices().SequenceEqual(input.Indices), "the input triangles");
        Expect(result.GetVertexRemap().SequenceEqual(Enumerable.Range(0, n).Select(i => (uint)i)),
               "the identity remap");
    }

    static Settings SphereSettings()
    {
        var settings = new Settings { Domain = Domain.Sphere };
        Expect(settings.Domain == Domain.Sphere, "the sphere domain set");
        return settings;
    }

    // The phases of a run's progress calls in the order entered, each once: a phase entered
    // twice, or two phases' calls interleaved, show up as a repeat.
    static List<Phase> PhaseSequence(IEnumerable<Phase> calls)
    {
        var sequence = new List<Phase>();
        foreach (Phase phase in calls)
            if (sequence.Count == 0 || sequence[sequence.Count - 1] != phase) sequence.Add(phase);
        return sequence;
    }

    static string Show(IEnumerable<Phase> phases)
    {
        return string.Join(", ", phases.Select(p => p.ToString()).ToArray());
    }

    static void AreaMonitorIsValidAndLessDistorted()
    {
        Off camel = ReadOff("meshes/camelhead.off");
        int n = camel.Xyz.Length / 3;
        using (var mesh = new Mesh(camel.Xyz, camel.Indices))
        using (var plain = new Settings { Monitor = ErrorMonitor.None })
        using (var adaptive = new Settings())
        using (var first = Library.Parameterize(mesh, plain))
        using (var second = Library.Parameterize(mesh, adaptive))
        {
            Expect(mesh.VertexCount == n && mesh.TriangleCount == camel.Indices.Length / 3,
                   "the mesh's counts");
            Expect(adaptive.Monitor == ErrorMonitor.Area, "the area monitor by default");
            foreach (var result in new[] { first, second })
            {
                Stats stats = result.GetStats();
                Expect(stats.FlippedTriangles == 0, "no flipped triangle");
                Expect(stats.VertexCount == (ulong)n, "one output vertex per input vertex");
                float[] uv = result.GetUvs();
                Expect(uv.Length == 2 * n, "2n uv values");
                Expect(uv.All(c => c >= 0 && c <= 1), "uvs in [0,1]^2");
                for (int t = 0; t < camel.Indices.Length; t += 3 * 97)
                    Expect(SignedArea(uv, camel.Indices[t], camel.Indices[t + 1],
                                      camel.Indices[t + 2]) > 0,
                           "counter-clockwise triangles stay counter-clockwise");
                Expect(result.GetIndices().SequenceEqual(camel.Indices), "the input triangles");
                Expect(result.GetVertexRemap().SequenceEqual(
                           Enumerable.Range(0, n).Select(i => (uint)i)),
                       "the identity remap");
            }
            Expect(first.GetStats().AdaptiveSolves == 0 && second.GetStats().AdaptiveSolves == 1,
                   "0 and 1 adaptive solves");
            double before = first.GetStats().AreaLogMean, after = second.GetStats().AreaLogMean;
            // The adaptive step equidistributes area: docs/bench-method.md measures 2.509 -> 0.721.
            Expect(after < 0.5 * before, "area distortion " + before + " -> " + after);
            Expect(second.PhaseMilliseconds(Phase.Adapt) > 0, "a timed adaptive phase");
        }
    }

    static void PrecisionsStridesAndIndexTypesAgree()
    {
        Off camel = ReadOff("meshes/camelhead.off");
        int n = camel.Xyz.Length / 3;
        var interleaved = new float[6 * n];
        var packed = new float[3 * n];
        for (int i = 0; i < n; i++)
            for (int c = 0; c < 3; c++)
                interleaved[6 * i + c] = packed[3 * i + c] = (float)camel.Xyz[3 * i + c];
        using (var strided = new Mesh())
        using (var plain = new Mesh(packed, camel.Indices))
        {
            strided.SetPositions(interleaved, 6);
            strided.SetIndices(camel.Indices.Select(i => (ushort)i).ToArray());
            Expect(strided.VertexCount == n, "n vertices read from the interleaved buffer");
            using (var a = Library.Parameterize(strided))
            using (var b = Library.Parameterize(plain))
            {
                Expect(a.GetUvsDouble().SequenceEqual(b.GetUvsDouble()), "identical maps");
                float[] single = b.GetUvs();
                double[] twice = b.GetUvsDouble();
                for (int i = 0; i < single.Length; i++)
                    Expect(Math.Abs(single[i] - twice[i]) < 1e-6, "float and double uvs agree");
            }
            plain.SetIndices(camel.Indices.Select(i => (int)i).ToArray());
            Expect(plain.TriangleCount == camel.Indices.Length / 3, "int indices");
        }
    }

    static void ConcurrentRunsShareMeshAndSettings()
    {
        Off camel = ReadOff("meshes/camelhead.off");
        using (var mesh = new Mesh(camel.Xyz, camel.Indices))
        using (var settings = new Settings { Iterations = 2 })
        using (var reference = Library.Parameterize(mesh, settings))
        {
            double[] expected = reference.GetUvsDouble();
            var outputs = new double[4][];
            var threads = Enumerable.Range(0, 4).Select(k => new Thread(() =>
            {
                using (var result = Library.Parameterize(mesh, settings))
                    outputs[k] = result.GetUvsDouble();
            })).ToList();
            threads.ForEach(t => t.Start());
            threads.ForEach(t => t.Join());
            Expect(outputs.All(o => o != null && o.SequenceEqual(expected)),
                   "concurrent runs equal the serial one");
        }
    }

    static void ProgressReportsPhasesAndCancels()
    {
        Off camel = ReadOff("meshes/camelhead.off");
        using (var mesh = new Mesh(camel.Xyz, camel.Indices))
        using (var settings = new Settings())
        {
            var phases = new List<Phase>();
            bool fractionsInRange = true;
            using (Library.Parameterize(mesh, settings, (phase, fraction) =>
                   {
                       phases.Add(phase);
                       fractionsInRange &= fraction >= 0 && fraction <= 1;
                       return true;
                   }))
            {
            }
            // The disk domain's five phases, in order; Segment and Pack are the atlas's.
            var disk = new[] { Phase.Validate, Phase.Topology, Phase.InitialMap, Phase.Adapt,
                               Phase.Metrics };
            Expect(PhaseSequence(phases).SequenceEqual(disk),
                   "the disk phases in order, got " + Show(PhaseSequence(phases)));
            Expect(fractionsInRange, "fractions in [0, 1]");

            using (var result = new Result())
            {
                ExpectFailure(Status.Cancelled, () => Library.Parameterize(
                    mesh, settings, result, (phase, fraction) => phase < Phase.Adapt));
                Expect(result.VertexCount == 0, "an empty result after cancelling");
                // The callback was on a private copy: the shared settings run without it.
                Library.Parameterize(mesh, settings, result);
                Expect(result.VertexCount == camel.Xyz.Length / 3, "the handles still usable");
            }

            try
            {
                Library.Parameterize(mesh, settings, (phase, fraction) =>
                {
                    throw new TimeoutException("from the callback");
                });
                throw new Exception("expected the callback's exception");
            }
            catch (TimeoutException error)
            {
                Expect(error.Message == "from the callback", "the callback's own exception");
            }
        }
    }

    static void ClosedMeshHasNoBoundary()
    {
        Off ico = Icosahedron();
        using (var mesh = new Mesh(ico.Xyz, ico.Indices))
        {
            RapsException error =
                ExpectFailure(Status.NoBoundary, () => Library.Parameterize(mesh));
            Expect(error.Detail.Length > 0, "a message from the library");
            Expect(error.StatusName.Length > 0 && error.StatusName != "unknown status",
                   "the status's name");
            Expect(error.Message.Contains(error.StatusName) && error.Message.Contains(error.Detail),
                   "Message carries name and detail");
        }
    }

    static void IndexOutOfRangeNamesTheIndex()
    {
        Off ico = Icosahedron();
        ico.Indices[11] = 12;
        using (var mesh = new Mesh(ico.Xyz, ico.Indices))
        using (var result = new Result())
        {
            RapsException error = ExpectFailure(Status.IndexOutOfRange,
                                                () => Library.Parameterize(mesh, null, result));
            Expect(error.Detail.Contains("12"), "the index in the message: " + error.Detail);
            Expect(result.VertexCount == 0, "an empty result");
            ExpectFailure(Status.InvalidOperation, () => result.GetUvs());
            ExpectFailure(Status.InvalidOperation, () => result.GetStats());
            ExpectFailure(Status.InvalidOperation, () => result.GetIndices());
            ExpectFailure(Status.InvalidOperation, () => result.GetChartIds());
        }
    }

    static void SetterErrorsCarryMessagesAndChangeNothing()
    {
        using (var mesh = new Mesh())
        {
            RapsException error =
                ExpectFailure(Status.IndexCount, () => mesh.SetIndices(new uint[] { 0, 1, 2, 3 }));
            Expect(error.Detail.Length > 0, "a message");
            ExpectFailure(Status.NonFinitePosition,
                          () => mesh.SetPositions(new float[] { 0, float.NaN, 0 }));
            Expect(mesh.VertexCount == 0, "a failed setter changes nothing");
            ExpectFailure(Status.InvalidArgument, () => mesh.SetPositions(new float[] { 0, 1 }));
            ExpectFailure(Status.InvalidArgument, () => mesh.SetPositions(new float[6], 2));
            ExpectFailure(Status.IndexOutOfRange, () => mesh.SetIndices(new[] { 0, -1, 2 }));
            ExpectFailure(Status.EmptyMesh, () => Library.Parameterize(mesh));
        }
        using (var settings = new Settings { Alpha = 2.0 })
        {
            RapsException error = ExpectFailure(Status.InvalidArgument, () => settings.Alpha = -1);
            Expect(error.Detail.Contains("alpha"), "the parameter in the message");
            Expect(settings.Alpha == 2.0, "alpha unchanged");
            ExpectFailure(Status.InvalidArgument, () => settings.Iterations = 0);
            Expect(settings.Iterations == 1, "iterations unchanged");
            ExpectFailure(Status.InvalidArgument, () => settings.SetInt((Param)999, 1));
            ExpectFailure(Status.InvalidArgument, () => settings.GetInt(Param.Alpha));
        }
    }

    static void SettingsRoundTripAndClone()
    {
        using (var settings = new Settings
               {
                   Weights = Weights.Uniform, Monitor = ErrorMonitor.Angle, Iterations = 3,
                   IterationMode = IterationMode.Reapply, Boundary = Boundary.Square,
                   MaxTriangles = 1000, MaxMemoryMb = 64, Domain = Domain.Disk
               })
        using (var copy = settings.Clone())
        {
            settings.Iterations = 7;
            Expect(copy.Iterations == 3 && copy.Weights == Weights.Uniform &&
                       copy.Monitor == ErrorMonitor.Angle &&
                       copy.IterationMode == IterationMode.Reapply &&
                       copy.Boundary == Boundary.Square && copy.MaxTriangles == 1000 &&
                       copy.MaxMemoryMb == 64 && copy.Domain == Domain.Disk,
                   "an independent copy");
        }
        ParamInfo info = Settings.GetParamInfo(Param.Alpha);
        Expect(info.Name == "alpha" && info.IsFloat && info.Default == 1.0, "alpha's facts");
        ExpectFailure(Status.InvalidArgument, () => Settings.GetParamInfo((Param)999));
    }

    static Result RunAtlas(Mesh mesh, int threads, Func<Phase, double, bool> progress = null)
    {
        using (var settings = new Settings { Domain = Domain.Atlas, Threads = threads })
        {
            Expect(settings.Domain == Domain.Atlas && settings.Threads == threads,
                   "the atlas settings");
            return Library.Parameterize(mesh, settings, progress);
        }
    }

    static void AtlasOfAClosedMeshIsValid()
    {
        Off bunny = ReadOff("meshes/bunny.off");
        int n = bunny.Xyz.Length / 3, triangles = bunny.Indices.Length / 3;
        using (var mesh = new Mesh(bunny.Xyz, bunny.Indices))
        {
            ExpectFailure(Status.NoBoundary, () => Library.Parameterize(mesh));
            using (var one = RunAtlas(mesh, 1))
            using (var two = RunAtlas(mesh, 2))
            {
                Stats stats = one.GetStats();
                float[] uv = one.GetUvs();
                uint[] indices = one.GetIndices();
                uint[] remap = one.GetVertexRemap();
                uint[] charts = one.GetChartIds();
                // The input triangles, in input order, over vertices duplicated along seams.
                Expect(indices.Length == bunny.Indices.Length, "the input's index count");
                Expect(stats.TriangleCount == (ulong)triangles, "the input's triangle count");
                Expect(remap.Length == one.VertexCount && uv.Length == 2 * remap.Length &&
                           stats.VertexCount == (ulong)remap.Length && remap.Length >= n,
                       "a remap and a uv per output vertex");
                Expect(remap.All(r => r < n), "every remap a valid input vertex");
                for (int i = 0; i < indices.Length; i++)
                    Expect(indices[i] < remap.Length && remap[indices[i]] == bunny.Indices[i],
                           "corner " + i + " remaps to the input triangle's vertex");
                Expect(charts.Length == triangles, "a chart id per triangle");
                Expect(stats.ChartCount >= 1 && charts.All(c => c < stats.ChartCount),
                       "chart ids below the chart count " + stats.ChartCount);
                Expect(uv.All(c => c >= 0 && c <= 1), "uvs in [0,1]^2");
                Expect(stats.FlippedTriangles == 0, "no flipped triangle");
                Expect(stats.AtlasWidth > 0 && stats.AtlasHeight > 0, "a non-empty atlas");
                Expect(stats.Utilization > 0 && stats.Utilization <= 1, "utilization in (0, 1]");
                // The output is the same whatever the thread count.
                Expect(two.GetUvsDouble().SequenceEqual(one.GetUvsDouble()),
                       "identical uvs with 1 and 2 threads");
                Expect(two.GetChartIds().SequenceEqual(charts),
                       "identical charts with 1 and 2 threads");
            }
        }
    }

    static void AtlasProgressReportsItsPhases()
    {
        Off bunny = ReadOff("meshes/bunny.off");
        using (var mesh = new Mesh(bunny.Xyz, bunny.Indices))
        {
            // Chart progress comes from the worker threads: calls must still never overlap.
            var phases = new List<Phase>();
            int inside = 0, overlaps = 0;
            bool fractionsInRange = true;
            using (var result = RunAtlas(mesh, 2, (phase, fraction) =>
                   {
                       if (Interlocked.Increment(ref inside) > 1)
                           Interlocked.Increment(ref overlaps);
                       phases.Add(phase);
                       fractionsInRange &= fraction >= 0 && fraction <= 1;
                       Thread.Sleep(1);  // lets another thread in, were it allowed
                       Interlocked.Decrement(ref inside);
                       return true;
                   }))
            {
                Expect(result.PhaseMilliseconds(Phase.Segment) > 0 &&
                           result.PhaseMilliseconds(Phase.Pack) > 0,
                       "timed segment and pack phases");
            }
            var atlas = new[] { Phase.Validate, Phase.Topology, Phase.Segment, Phase.InitialMap,
                                Phase.Pack, Phase.Metrics };
            Expect(PhaseSequence(phases).SequenceEqual(atlas),
                   "the atlas phases in order, got " + Show(PhaseSequence(phases)));
            Expect(overlaps == 0, "no overlapping progress calls, got " + overlaps);
            Expect(fractionsInRange, "fractions in [0, 1]");

            // An exception thrown on a worker thread cancels the run and reaches the caller.
            using (var result = new Result())
            using (var settings = new Settings { Domain = Domain.Atlas, Threads = 2 })
            {
                try
                {
                    Library.Parameterize(mesh, settings, result, (phase, fraction) =>
                    {
                        if (phase == Phase.InitialMap && fraction > 0)
                            throw new TimeoutException("from a worker");
                        return true;
                    });
                    throw new Exception("expected the callback's exception");
                }
                catch (TimeoutException error)
                {
                    Expect(error.Message == "from a worker", "the callback's own exception");
                }
                Expect(result.VertexCount == 0, "an empty result after the exception");
            }
        }
    }

    static void AtlasSettingsRoundTrip()
    {
        var expected = new[]
        {
            new { Param = Param.Threads, Name = "threads", IsFloat = false, Min = 0.0,
                  Max = 1024.0, Default = 0.0 },
            new { Param = Param.AtlasResolution, Name = "atlas_resolution", IsFloat = false,
                  Min = 16.0, Max = 16384.0, Default = 1024.0 },
            new { Param = Param.AtlasPadding, Name = "atlas_padding", IsFloat = false, Min = 0.0,
                  Max = 64.0, Default = 1.0 },
            new { Param = Param.WeldTolerance, Name = "weld_tolerance", IsFloat = true,
                  Min = 0.0, Max = double.MaxValue, Default = 0.0 },
            new { Param = Param.HardEdgeAngle, Name = "hard_edge_angle", IsFloat = true,
                  Min = 0.0, Max = 180.0, Default = 180.0 },
            new { Param = Param.AtlasMaxL2Stretch, Name = "atlas_max_l2_stretch", IsFloat = true,
                  Min = 1.0, Max = 10.0, Default = 1.01 },
            new { Param = Param.AtlasMaxLinfStretch, Name = "atlas_max_linf_stretch",
                  IsFloat = true, Min = 1.0, Max = 1000.0, Default = 2.9 },
        };
        using (var defaults = new Settings())
        {
            foreach (var facts in expected)
            {
                ParamInfo info = Settings.GetParamInfo(facts.Param);
                Expect(info.Name == facts.Name && info.IsFloat == facts.IsFloat &&
                           info.Min == facts.Min && info.Max == facts.Max &&
                           info.Default == facts.Default,
                       facts.Name + "'s facts");
                double value = facts.IsFloat ? defaults.GetFloat(facts.Param)
                                             : defaults.GetInt(facts.Param);
                Expect(value == facts.Default, facts.Name + " holds its default");
            }
            Expect(defaults.Threads == 0 && defaults.AtlasResolution == 1024 &&
                       defaults.AtlasPadding == 1 && defaults.WeldTolerance == 0 &&
                       defaults.HardEdgeAngle == 180 && defaults.AtlasMaxL2Stretch == 1.01 &&
                       defaults.AtlasMaxLinfStretch == 2.9,
                   "the properties read the defaults");
        }
        using (var settings = new Settings
               {
                   Domain = Domain.Atlas, Threads = 2, AtlasResolution = 512, AtlasPadding = 4,
                   WeldTolerance = 1e-6, HardEdgeAngle = 60, AtlasMaxL2Stretch = 1.5,
                   AtlasMaxLinfStretch = 4
               })
        using (var copy = settings.Clone())
        {
            Expect(copy.Domain == Domain.Atlas && copy.Threads == 2 &&
                       copy.AtlasResolution == 512 && copy.AtlasPadding == 4 &&
                       copy.WeldTolerance == 1e-6 && copy.HardEdgeAngle == 60 &&
                       copy.AtlasMaxL2Stretch == 1.5 && copy.AtlasMaxLinfStretch == 4,
                   "the atlas parameters set and cloned");
            ExpectFailure(Status.InvalidArgument, () => settings.Threads = -1);
            ExpectFailure(Status.InvalidArgument, () => settings.AtlasResolution = 8);
            ExpectFailure(Status.InvalidArgument, () => settings.AtlasPadding = 65);
            ExpectFailure(Status.InvalidArgument, () => settings.HardEdgeAngle = 181);
            ExpectFailure(Status.InvalidArgument, () => settings.AtlasMaxL2Stretch = 0.5);
            Expect(settings.AtlasResolution == 512 && settings.HardEdgeAngle == 60,
                   "a failed setter changes nothing");
        }
    }

    static void SphereMapOfAnIcosahedronIsBijective()
    {
        Off ico = Icosahedron();
        using (var mesh = new Mesh(ico.Xyz, ico.Indices))
        using (var settings = SphereSettings())
        using (var result = Library.Parameterize(mesh, settings))
        {
            Expect(settings.SphereMethod == SphereMethod.Robust &&
                       settings.SphereUv == SphereUv.None,
                   "the robust method without uvs by default");
            ExpectSphereMap(result, ico);
            // The area monitor's iteration reached through 2 relaxations (SphereAlphaSteps).
            Expect(result.GetStats().AdaptiveSolves == 2, "2 adaptive relaxations");
            // Without the octahedral unfold a sphere map has no uvs, and says so.
            RapsException error = ExpectFailure(Status.InvalidOperation, () => result.GetUvs());
            Expect(error.Detail.Contains("Octahedral") && error.Detail.Contains("GetSpherePoints"),
                   "the message points to the unfold and the points: " + error.Detail);
            ExpectFailure(Status.InvalidOperation, () => result.GetUvsDouble());
            ExpectFailure(Status.InvalidArgument, () => result.CopySpherePoints(new float[35]));
        }
        // The literal method starts from the Gauss map, which the symmetric icosahedron keeps:
        // vertex i's point is its position normalised, x, y, z in that order.
        using (var mesh = new Mesh(ico.Xyz, ico.Indices))
        using (var settings = new Settings
               {
                   Domain = Domain.Sphere, SphereMethod = SphereMethod.Literal,
                   Monitor = ErrorMonitor.None
               })
        using (var result = Library.Parameterize(mesh, settings))
        {
            ExpectSphereMap(result, ico);
            double[] points = result.GetSpherePointsDouble();
            for (int i = 0; i < 12; i++)
            {
                double norm = Math.Sqrt(ico.Xyz[3 * i] * ico.Xyz[3 * i] +
                                        ico.Xyz[3 * i + 1] * ico.Xyz[3 * i + 1] +
                                        ico.Xyz[3 * i + 2] * ico.Xyz[3 * i + 2]);
                for (int c = 0; c < 3; c++)
                    Expect(Math.Abs(points[3 * i + c] - ico.Xyz[3 * i + c] / norm) < 1e-9,
                           "vertex " + i + " at its normalised position");
            }
        }
    }

    static void SphereMapOfASharedMeshEquidistributesArea()
    {
        Off bunny = ReadOff("meshes/bunny.off");
        using (var mesh = new Mesh(bunny.Xyz, bunny.Indices))
        using (var plain = new Settings { Domain = Domain.Sphere, Monitor = ErrorMonitor.None })
        using (var adaptive = SphereSettings())
        using (var first = Library.Parameterize(mesh, plain))
        using (var second = Library.Parameterize(mesh, adaptive))
        {
            ExpectSphereMap(first, bunny);
            ExpectSphereMap(second, bunny);
            Expect(first.GetStats().AdaptiveSolves == 0, "no adaptive step with monitor None");
            // Spherical area distortion, measured in tests/test_sphere.c: 1.638 -> 0.667.
            double before = first.GetStats().AreaLogMean, after = second.GetStats().AreaLogMean;
            Expect(after < 0.5 * before, "spherical area distortion " + before + " -> " + after);
            Expect(second.PhaseMilliseconds(Phase.Adapt) > 0, "a timed adaptive phase");
            // SphereMaxSweeps and SphereAlphaSteps reach the library: 2 adaptive relaxations,
            // and at most 3 sweeps in each of the 3 relaxations.
            using (var capped = new Settings
                   {
                       Domain = Domain.Sphere, SphereMaxSweeps = 3, SphereAlphaSteps = 2
                   })
            using (var result = Library.Parameterize(mesh, capped))
            {
                Stats stats = result.GetStats();
                Expect(stats.AdaptiveSolves == 2, "2 adaptive relaxations, got " +
                                                      stats.AdaptiveSolves);
                Expect(stats.RelaxationSweeps > 0 && stats.RelaxationSweeps <= 9 &&
                           second.GetStats().RelaxationSweeps > 9,
                       "sweeps capped at 3 per relaxation, got " + stats.RelaxationSweeps);
            }
        }
    }

    static void OctahedralUnfoldGivesUvsInTheSquare()
    {
        foreach (Off input in new[] { Icosahedron(), ReadOff("meshes/bunny.off") })
        {
            int n = input.Xyz.Length / 3;
            using (var mesh = new Mesh(input.Xyz, input.Indices))
            using (var plain = SphereSettings())
            using (var unfolded = new Settings
                   {
                       Domain = Domain.Sphere, SphereUv = SphereUv.Octahedral
                   })
            using (var sphere = Library.Parameterize(mesh, plain))
            using (var result = Library.Parameterize(mesh, unfolded))
            {
                Expect(unfolded.SphereUv == SphereUv.Octahedral, "the octahedral unfold set");
                long count = result.VertexCount;
                // The cut's vertices are duplicated: more output vertices than input.
                Expect(count > n, count + " output vertices for " + n);
                float[] uv = result.GetUvs();
                uint[] remap = result.GetVertexRemap();
                uint[] indices = result.GetIndices();
                double[] points = result.GetSpherePointsDouble();
                double[] original = sphere.GetSpherePointsDouble();
                Expect(uv.Length == 2 * count && remap.Length == count &&
                           points.Length == 3 * count,
                       "a uv, a remap and a point per output vertex");
                Expect(uv.All(c => c >= 0 && c <= 1), "uvs in [0,1]^2");
                Expect(indices.Length == input.Indices.Length, "the input's triangle count");
                for (int i = 0; i < indices.Length; i++)
                    Expect(remap[indices[i]] == input.Indices[i],
                           "corner " + i + " remaps to the input triangle's vertex");
                for (int t = 0; t < indices.Length; t += 3)
                    Expect(SignedArea(uv, indices[t], indices[t + 1], indices[t + 2]) > 0,
                           "uv triangle " + t / 3 + " counter-clockwise");
                for (long o = 0; o < count; o++)
                    for (int c = 0; c < 3; c++)
                        Expect(points[3 * o + c] == original[3 * remap[o] + c],
                               "output vertex " + o + " at its input vertex's sphere point");
                Stats stats = result.GetStats();
                Expect(stats.FlippedTriangles == 0 && stats.VertexCount == (ulong)count &&
                           stats.RelaxationSweeps > 0 && stats.ChartCount == 1 &&
                           stats.Utilization > 0 && stats.Utilization <= 1,
                       "the statistics of one flip-free chart");
            }
        }
    }

    static void SphereRefusesAnOpenMesh()
    {
        Off fan = FanDisk();
        using (var mesh = new Mesh(fan.Xyz, fan.Indices))
        using (var settings = SphereSettings())
        using (var result = new Result())
        {
            RapsException error = ExpectFailure(
                Status.OpenMesh, () => Library.Parameterize(mesh, settings, result));
            Expect(error.Detail.Contains("closed mesh") &&
                       error.Detail.Contains("1 boundary loop"),
                   "the message counts the loops: " + error.Detail);
            Expect(error.StatusName == Library.StatusString(Status.OpenMesh) &&
                       error.StatusName != "unknown status",
                   "the status's name: " + error.StatusName);
            Expect(result.VertexCount == 0, "an empty result");
            ExpectFailure(Status.InvalidOperation, () => result.GetSpherePoints());
            // The disk domain maps the same mesh; its result has uvs but no sphere points.
            Library.Parameterize(mesh, null, result);
            error = ExpectFailure(Status.InvalidOperation, () => result.GetSpherePointsDouble());
            Expect(error.Detail.Contains("sphere points"), "a message: " + error.Detail);
        }
    }

    static void SphereProgressReportsItsPhases()
    {
        Off bunny = ReadOff("meshes/bunny.off");
        using (var mesh = new Mesh(bunny.Xyz, bunny.Indices))
        using (var settings = new Settings { Domain = Domain.Sphere, Threads = 2 })
        {
            var phases = new List<Phase>();
            int inside = 0, overlaps = 0;
            bool fractionsInRange = true;
            using (Library.Parameterize(mesh, settings, (phase, fraction) =>
                   {
                       if (Interlocked.Increment(ref inside) > 1)
                           Interlocked.Increment(ref overlaps);
                       phases.Add(phase);
                       fractionsInRange &= fraction >= 0 && fraction <= 1;
                       Thread.Sleep(1);  // lets another thread in, were it allowed
                       Interlocked.Decrement(ref inside);
                       return true;
                   }))
            {
            }
            // The disk domain's five phases: the initial map and its relaxation, then the
            // adaptive relaxations.
            var sphere = new[] { Phase.Validate, Phase.Topology, Phase.InitialMap, Phase.Adapt,
                                 Phase.Metrics };
            Expect(PhaseSequence(phases).SequenceEqual(sphere),
                   "the sphere phases in order, got " + Show(PhaseSequence(phases)));
            Expect(overlaps == 0, "no overlapping progress calls, got " + overlaps);
            Expect(fractionsInRange, "fractions in [0, 1]");

            using (var result = new Result())
            {
                ExpectFailure(Status.Cancelled, () => Library.Parameterize(
                    mesh, settings, result, (phase, fraction) => phase < Phase.Adapt));
                Expect(result.VertexCount == 0, "an empty result after cancelling");
                Library.Parameterize(mesh, settings, result);
                Expect(result.VertexCount == bunny.Xyz.Length / 3, "the handles still usable");
            }
        }
    }

    static void SphereSettingsRoundTrip()
    {
        // As raps_param_info reports them (src/c_api.cpp); (0, 1] has the smallest normal
        // double as its lower bound.
        var expected = new[]
        {
            new { Param = Param.SphereMethod, Name = "sphere_method", IsFloat = false,
                  Min = 0.0, Max = 1.0, Default = 1.0 },
            new { Param = Param.SphereUv, Name = "sphere_uv", IsFloat = false, Min = 0.0,
                  Max = 1.0, Default = 0.0 },
            new { Param = Param.SphereDamping, Name = "sphere_damping", IsFloat = true,
                  Min = 2.2250738585072014e-308, Max = 1.0, Default = 1.0 },
            new { Param = Param.SphereTolerance, Name = "sphere_tolerance", IsFloat = true,
                  Min = 1e-12, Max = 1.0, Default = 1e-4 },
            new { Param = Param.SphereMaxSweeps, Name = "sphere_max_sweeps", IsFloat = false,
                  Min = 0.0, Max = 1e7, Default = 0.0 },
            new { Param = Param.SphereAlphaSteps, Name = "sphere_alpha_steps", IsFloat = false,
                  Min = 1.0, Max = 100.0, Default = 2.0 },
        };
        using (var defaults = new Settings())
        {
            foreach (var facts in expected)
            {
                ParamInfo info = Settings.GetParamInfo(facts.Param);
                Expect(info.Name == facts.Name && info.IsFloat == facts.IsFloat &&
                           info.Min == facts.Min && info.Max == facts.Max &&
                           info.Default == facts.Default,
                       facts.Name + "'s facts");
                double value = facts.IsFloat ? defaults.GetFloat(facts.Param)
                                             : defaults.GetInt(facts.Param);
                Expect(value == facts.Default, facts.Name + " holds its default");
            }
            Expect(defaults.SphereMethod == SphereMethod.Robust &&
                       defaults.SphereUv == SphereUv.None && defaults.SphereDamping == 1 &&
                       defaults.SphereTolerance == 1e-4 && defaults.SphereMaxSweeps == 0 &&
                       defaults.SphereAlphaSteps == 2,
                   "the properties read the defaults");
            ParamInfo domain = Settings.GetParamInfo(Param.Domain);
            Expect(domain.Min == (int)Domain.Disk && domain.Max == (int)Domain.Atlas &&
                       (int)Domain.Disk < (int)Domain.Sphere &&
                       (int)Domain.Sphere < (int)Domain.Atlas,
                   "the sphere inside the domain's bounds");
        }
        using (var settings = new Settings
               {
                   Domain = Domain.Sphere, SphereMethod = SphereMethod.Literal,
                   SphereUv = SphereUv.Octahedral, SphereDamping = 0.5, SphereTolerance = 1e-6,
                   SphereMaxSweeps = 10000000, SphereAlphaSteps = 100
               })
        using (var copy = settings.Clone())
        {
            Expect(copy.Domain == Domain.Sphere && copy.SphereMethod == SphereMethod.Literal &&
                       copy.SphereUv == SphereUv.Octahedral && copy.SphereDamping == 0.5 &&
                       copy.SphereTolerance == 1e-6 && copy.SphereMaxSweeps == 10000000 &&
                       copy.SphereAlphaSteps == 100,
                   "the sphere parameters set and cloned");
            ExpectFailure(Status.InvalidArgument, () => settings.SphereMethod = (SphereMethod)2);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereUv = (SphereUv)2);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereDamping = 0);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereDamping = 1.5);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereTolerance = 1e-13);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereTolerance = 2);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereMaxSweeps = -1);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereMaxSweeps = 10000001);
            ExpectFailure(Status.InvalidArgument, () => settings.SphereAlphaSteps = 0);
            RapsException error =
                ExpectFailure(Status.InvalidArgument, () => settings.SphereAlphaSteps = 101);
            Expect(error.Detail.Contains("sphere_alpha_steps"), "the parameter in the message");
            ExpectFailure(Status.InvalidArgument, () => settings.SetInt(Param.SphereDamping, 1));
            Expect(settings.SphereMethod == SphereMethod.Literal &&
                       settings.SphereUv == SphereUv.Octahedral &&
                       settings.SphereDamping == 0.5 && settings.SphereTolerance == 1e-6 &&
                       settings.SphereMaxSweeps == 10000000 && settings.SphereAlphaSteps == 100,
                   "a failed setter changes nothing");
        }
    }

    static void DisposalIsSafe()
    {
        var mesh = new Mesh();
        var settings = new Settings();
        var result = new Result();
        foreach (IDisposable handle in new IDisposable[] { mesh, settings, result })
        {
            handle.Dispose();
            handle.Dispose();  // no double free
        }
        foreach (Action use in new Action[] { () => { var n = mesh.VertexCount; },
                                              () => settings.Alpha = 2,
                                              () => { var n = result.VertexCount; } })
        {
            try
            {
                use();
                throw new Exception("expected ObjectDisposedException");
            }
            catch (ObjectDisposedException)
            {
            }
        }
        // Forgotten Dispose: the finalizers free each handle once.
        for (int i = 0; i < 2000; i++)
        {
            new Mesh(new float[] { 0, 0, 0, 1, 0, 0, 0, 1, 0 }, new uint[] { 0, 1, 2 });
            new Settings { Alpha = 3 }.Clone();
            new Result();
        }
        GC.Collect();
        GC.WaitForPendingFinalizers();
        GC.Collect();
    }

    static void LayoutAndVersionMatchTheLibrary()
    {
        Off camel = ReadOff("meshes/camelhead.off");
        using (var mesh = new Mesh(camel.Xyz, camel.Indices))
        using (var result = Library.Parameterize(mesh))
        {
            // The library writes back the size it filled: all of ours, if the layouts agree.
            Stats stats = result.GetStats();
            Expect(stats.StructSize == (uint)Marshal.SizeOf(typeof(Stats)), "the struct size");
            Expect(stats.TriangleCount == (ulong)(camel.Indices.Length / 3) &&
                       stats.StretchLinf >= 1.0,
                   "fields read at the library's offsets");
            // The fields appended for the atlas, as the disk domain fills them.
            Expect(stats.ChartCount == 1 && stats.AtlasWidth == 0 && stats.AtlasHeight == 0 &&
                       stats.RelaxationSweeps == 0 && stats.Utilization > 0 &&
                       stats.Utilization <= 1,
                   "the disk domain's chart and atlas fields");
            uint[] charts = result.GetChartIds();
            Expect(charts.Length == camel.Indices.Length / 3 && charts.All(c => c == 0),
                   "every disk triangle in chart 0");
        }
        Expect(Library.VersionNumber / 10000 == Native.RAPS_VERSION_MAJOR, "the major version");
        uint v = Library.VersionNumber;
        Expect(Library.Version == (v / 10000) + "." + (v / 100 % 100) + "." + (v % 100),
               "the version string");
    }

    // Several meshes in one atlas: each mesh's share reads as its own result, a copy scaled by 2
    // gets four times the texels, pages at a density stay within the maximum, bad transforms
    // and scenes are refused.
    static void SceneOfSeveralMeshes()
    {
        Off cap = FanDisk();
        using (var small = new Mesh(cap.Xyz, cap.Indices))
        using (var big = new Mesh(cap.Xyz, cap.Indices))
        using (var settings = new Settings())
        {
            big.SetTransform(new double[] { 2, 0, 0, 4, 0, 2, 0, 0, 0, 0, 2, 0 });
            settings.SetInt(Param.Domain, (long)Domain.Atlas);
            using (Result result = Library.ParameterizeScene(new[] { small, big }, settings))
            {
                Expect(result.MeshCount == 2, "two meshes");
                uint[] remap = result.GetVertexRemap(), indices = result.GetIndices();
                ulong nextVertex = 0;
                for (int m = 0; m < 2; m++)
                {
                    MeshRange range = result.GetMeshRange(m);
                    Expect(range.FirstVertex == nextVertex && range.IndexCount ==
                                                                  (ulong)cap.Indices.Length,
                           "mesh " + m + "'s range");
                    for (int i = 0; i < cap.Indices.Length; i++)
                        Expect(remap[range.FirstVertex + indices[(int)range.FirstIndex + i]] ==
                                   cap.Indices[i],
                               "mesh " + m + "'s own input vertices");
                    nextVertex += range.VertexCount;
                }
                Expect(nextVertex == (ulong)result.VertexCount, "the ranges cover the output");
                Chart[] charts = result.GetCharts();
                double smallTexels = charts.Where(c => c.Mesh == 0).Sum(c => c.AreaTexels);
                double bigTexels = charts.Where(c => c.Mesh == 1).Sum(c => c.AreaTexels);
                Expect(Math.Abs(bigTexels / smallTexels / 4 - 1) < 0.02, "4x the texels");
                ExpectFailure(Status.InvalidArgument, () => result.GetMeshRange(2));
            }
            settings.SetFloat(Param.AtlasTexelsPerUnit, 30);
            settings.SetInt(Param.AtlasMaxWidth, 64);
            settings.SetInt(Param.AtlasMaxHeight, 64);
            settings.SetInt(Param.AtlasRotation, (long)Rotation.None);
            using (Result result = Library.ParameterizeScene(new[] { small, big, small }, settings))
            {
                Stats stats = result.GetStats();
                Expect(stats.PageCount >= 2 && stats.AtlasWidth <= 64 && stats.AtlasHeight <= 64,
                       "pages within 64 x 64");
                Expect(result.GetCharts().All(c => c.Page < stats.PageCount &&
                                                   c.RotationDeg == 0),
                       "charts on their pages, unturned");
            }
            ExpectFailure(Status.InvalidTransform,
                          () => small.SetTransform(new double[] { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,
                                                                  0, 0 }));
            using (var disk = new Settings())
                ExpectFailure(Status.InvalidArgument,
                              () => Library.ParameterizeScene(new[] { small }, disk).Dispose());
            // A progress state follows the scene's phases and cancels it.
            using (var progress = new ProgressState())
            {
                using (Library.ParameterizeScene(new[] { small, big }, settings, progress))
                {
                }
                ProgressReading done = progress.Read();
                Expect(done.Phase == Phase.Metrics && done.Fraction == 1,
                       "the scene run ends at Metrics, fraction 1");
                progress.Reset();
                progress.Cancel();
                ExpectFailure(Status.Cancelled, () => Library.ParameterizeScene(
                    new[] { small, big }, settings, progress));
                Expect(progress.Read().Reports == 1, "cancelled at its first report");
            }
        }
    }

    // The artist's seams: groups and seam edges split the cap's atlas into its two halves, and
    // bad ones are refused with their own statuses.
    static void GroupsAndSeamEdges()
    {
        Off cap = FanDisk();
        using (var mesh = new Mesh(cap.Xyz, cap.Indices))
        using (var settings = new Settings())
        {
            settings.SetInt(Param.Domain, (long)Domain.Atlas);
            Func<uint[]> charts = () =>
            {
                using (Result result = Library.Parameterize(mesh, settings))
                    return result.GetChartIds();
            };
            Expect(charts().All(c => c == 0), "one chart without seams");
            mesh.SetTriangleGroups(new uint[] { 0, 0, 0, 1, 1, 1 });
            uint[] ids = charts();
            Expect(!ids.Take(3).Intersect(ids.Skip(3)).Any(), "no chart holds two groups");
            mesh.SetTriangleGroups(new uint[] { 0, 1 });
            ExpectFailure(Status.GroupCount, () => charts());
            mesh.SetTriangleGroups(null);
            // Polygons reach the library (what they do is the C suite's test_atlas_polygons).
            mesh.SetTrianglePolygons(new uint[] { 0, 0, 1, 1, 2, 2 });
            Expect(charts().Length == 6, "polygons accepted");
            mesh.SetTrianglePolygons(new uint[] { 0, 1 });
            ExpectFailure(Status.GroupCount, () => charts());
            mesh.SetTrianglePolygons(null);
            mesh.SetSeamEdges(new uint[] { 0, 1, 4, 0 });  // rim to rim through the apex
            ids = charts();
            Expect(!ids.Take(3).Intersect(ids.Skip(3)).Any(), "the seams split the cap");
            mesh.SetSeamEdges(new uint[] { 1, 3 });
            ExpectFailure(Status.SeamNotAnEdge, () => charts());
            mesh.SetSeamEdges(new uint[] { 0, 9 });
            ExpectFailure(Status.IndexOutOfRange, () => charts());
            settings.SetInt(Param.AtlasKeepInputSeams, 1);
        }
    }

    // Existing uvs repacked: the cap's two uv islands (one mirrored) come back as two charts,
    // each only moved, turned and uniformly scaled, at one density; bad uvs are refused.
    static void RepackKeepsIslands()
    {
        Off cap = FanDisk();
        var uv = new double[36];
        for (int c = 0; c < 18; c++)
        {
            double x = cap.Xyz[3 * cap.Indices[c]], y = cap.Xyz[3 * cap.Indices[c] + 1];
            uv[2 * c] = c < 9 ? x : 5.0 - 2.0 * x;
            uv[2 * c + 1] = c < 9 ? y : 2.0 * y;
        }
        using (var mesh = new Mesh(cap.Xyz, cap.Indices))
        using (var settings = new Settings())
        {
            settings.SetInt(Param.Domain, (long)Domain.Atlas);
            settings.Threads = 1;
            settings.AtlasRepack = true;
            Expect(settings.AtlasRepack, "repack set");
            ExpectFailure(Status.UvCount, () => Library.Parameterize(mesh, settings).Dispose());
            mesh.SetCornerUvs(uv);
            using (Result result = Library.Parameterize(mesh, settings))
            {
                var stats = result.GetStats();
                Expect(stats.ChartCount == 2 && stats.FlippedTriangles == 3,
                       "two islands, the mirrored one still flipped");
                double[] outUv = result.GetUvsDouble();
                uint[] indices = result.GetIndices();
                uint[] ids = result.GetChartIds();
                for (uint chart = 0; chart < 2; chart++)
                {
                    var corners = Enumerable.Range(0, 18).Where(c => ids[c / 3] == chart).ToList();
                    Func<int, double[]> input = c => new[] { uv[2 * c], uv[2 * c + 1] };
                    Func<int, double[]> output = c => new[] {
                        outUv[2 * indices[c]] * stats.AtlasWidth,
                        outUv[2 * indices[c] + 1] * stats.AtlasHeight };
                    Func<double[], double[], double[]> minus = (p, q) => new[] { p[0] - q[0],
                                                                                 p[1] - q[1] };
                    Func<double[], double> length = p => Math.Sqrt(p[0] * p[0] + p[1] * p[1]);
                    int a = corners[0];
                    int b = corners.OrderByDescending(c => length(minus(input(c), input(a))))
                                .First();
                    // z = (output(b) - output(a)) / (input(b) - input(a)), complex numbers
                    double[] o = minus(output(b), output(a)), d = minus(input(b), input(a));
                    double dd = d[0] * d[0] + d[1] * d[1];
                    double zr = (o[0] * d[0] + o[1] * d[1]) / dd;
                    double zi = (o[1] * d[0] - o[0] * d[1]) / dd;
                    foreach (int c in corners)
                    {
                        double[] e = minus(input(c), input(a));
                        double[] expected = { output(a)[0] + zr * e[0] - zi * e[1],
                                              output(a)[1] + zi * e[0] + zr * e[1] };
                        Expect(length(minus(output(c), expected)) < 1e-6 * length(o),
                               "corner " + c + " only moved, turned and scaled");
                    }
                }
                Chart[] charts = result.GetCharts();
                Expect(Math.Abs(charts[0].AreaTexels / charts[0].Area3d /
                                (charts[1].AreaTexels / charts[1].Area3d) - 1) < 1e-6,
                       "one density");
            }
            uv[9] = double.NaN;
            RapsException error = ExpectFailure(Status.NonFiniteUv, () => mesh.SetCornerUvs(uv));
            Expect(error.Message.Contains("corner 4"), "the message names the corner");
            mesh.SetCornerUvs(Enumerable.Repeat(0.5f, 36).ToArray());  // every island a point
            ExpectFailure(Status.DegenerateUvChart,
                          () => Library.Parameterize(mesh, settings).Dispose());
            mesh.SetCornerUvs((float[])null);
            ExpectFailure(Status.UvCount, () => Library.Parameterize(mesh, settings).Dispose());
        }
    }

    // Stacking: the cap given twice to a scene (the copy moved and turned) costs no texels:
    // every chart of the copy is stacked on the original's and has its uvs, corner for corner.
    static void RepeatedMeshSharesTexels()
    {
        Off cap = FanDisk();
        using (var original = new Mesh(cap.Xyz, cap.Indices))
        using (var copy = new Mesh(cap.Xyz, cap.Indices))
        using (var settings = new Settings { AtlasStack = Stacking.Rigid })
        {
            Expect(settings.AtlasStack == Stacking.Rigid, "stacking set");
            copy.SetTransform(new double[] { 0, -1, 0, 4, 1, 0, 0, 0, 0, 0, 1, 0 });
            settings.SetInt(Param.Domain, (long)Domain.Atlas);
            using (Result result = Library.ParameterizeScene(new[] { original, copy }, settings))
            {
                Chart[] charts = result.GetCharts();
                for (int c = 0; c < charts.Length; c++)
                {
                    bool stacked = (charts[c].Flags & Native.RAPS_CHART_STACKED) != 0;
                    Expect(stacked == (charts[c].Mesh == 1), "the copy's charts are stacked");
                    Expect((charts[c].StackedOn != c) == stacked, "stacked_on names the place");
                }
                double[] uv = result.GetUvsDouble();
                uint[] indices = result.GetIndices();
                MeshRange first = result.GetMeshRange(0), second = result.GetMeshRange(1);
                for (int i = 0; i < 18; i++)
                {
                    ulong a = first.FirstVertex + indices[i];
                    ulong b = second.FirstVertex + indices[18 + i];
                    Expect(uv[2 * a] == uv[2 * b] && uv[2 * a + 1] == uv[2 * b + 1],
                           "corner " + i + " has its original's uv");
                }
            }
        }
    }

    static void ProgressStateIsPolledAndCancelled()
    {
        Off camel = ReadOff("meshes/camelhead.off");
        using (var mesh = new Mesh(camel.Xyz, camel.Indices))
        using (var settings = new Settings())
        using (var progress = new ProgressState())
        {
            ProgressReading before = progress.Read();
            Expect(before.Phase == null && before.Reports == 0, "no phase before any run");

            // A cancel before the run stops it at its first report, and stays until Reset.
            progress.Cancel();
            ExpectFailure(Status.Cancelled, () => Library.Parameterize(mesh, settings, progress));
            Expect(progress.Read().Reports == 1, "the run stopped at its first report");
            ExpectFailure(Status.Cancelled, () => Library.Parameterize(mesh, settings, progress));

            progress.Reset();
            using (Library.Parameterize(mesh, settings, progress))
            {
            }
            ProgressReading done = progress.Read();
            Expect(done.Phase == Phase.Metrics && done.Fraction == 1 && done.Reports > 5,
                   "a finished run ends at Metrics, fraction 1, got " + done.Phase + " " +
                       done.Fraction + " after " + done.Reports + " reports");

            // Another thread polls the state and cancels once the run adapts.
            progress.Reset();
            settings.Iterations = 100;
            bool sawAdapt = false;
            var poller = new Thread(() =>
            {
                var watch = System.Diagnostics.Stopwatch.StartNew();
                while (watch.Elapsed.TotalSeconds < 60)
                {
                    if (progress.Read().Phase == Phase.Adapt)
                    {
                        sawAdapt = true;
                        progress.Cancel();
                        return;
                    }
                    Thread.Sleep(1);
                }
            });
            poller.Start();
            ExpectFailure(Status.Cancelled, () => Library.Parameterize(mesh, settings, progress));
            poller.Join();
            Expect(sawAdapt && progress.Read().Phase == Phase.Adapt,
                   "cancelled from the polling thread during Adapt");
        }
    }

    static int Main(string[] args)
    {
        if (args.Length != 1)
        {
            Console.Error.WriteLine("usage: RapsTests.exe SHARED_DATA_DIR");
            return 2;
        }
        dataDir = args[0];
        var tests = new List<KeyValuePair<string, Action>>
        {
            new KeyValuePair<string, Action>("area monitor is valid and less distorted",
                                             AreaMonitorIsValidAndLessDistorted),
            new KeyValuePair<string, Action>("precisions, strides and index types agree",
                                             PrecisionsStridesAndIndexTypesAgree),
            new KeyValuePair<string, Action>("concurrent runs share mesh and settings",
                                             ConcurrentRunsShareMeshAndSettings),
            new KeyValuePair<string, Action>("progress reports phases and cancels",
                                             ProgressReportsPhasesAndCancels),
            new KeyValuePair<string, Action>("progress state is polled and cancelled",
                                             ProgressStateIsPolledAndCancelled),
            new KeyValuePair<string, Action>("closed mesh has no boundary",
                                             ClosedMeshHasNoBoundary),
            new KeyValuePair<string, Action>("index out of range names the index",
                                             IndexOutOfRangeNamesTheIndex),
            new KeyValuePair<string, Action>("setter errors carry messages, change nothing",
                                             SetterErrorsCarryMessagesAndChangeNothing),
            new KeyValuePair<string, Action>("settings round trip and clone",
                                             SettingsRoundTripAndClone),
            new KeyValuePair<string, Action>("atlas of a closed mesh is valid",
                                             AtlasOfAClosedMeshIsValid),
            new KeyValuePair<string, Action>("atlas progress reports its phases",
                                             AtlasProgressReportsItsPhases),
            new KeyValuePair<string, Action>("atlas settings round trip",
                                             AtlasSettingsRoundTrip),
            new KeyValuePair<string, Action>("sphere map of an icosahedron is bijective",
                                             SphereMapOfAnIcosahedronIsBijective),
            new KeyValuePair<string, Action>("sphere map of a shared mesh equidistributes area",
                                             SphereMapOfASharedMeshEquidistributesArea),
            new KeyValuePair<string, Action>("octahedral unfold gives uvs in the square",
                                             OctahedralUnfoldGivesUvsInTheSquare),
            new KeyValuePair<string, Action>("sphere refuses an open mesh",
                                             SphereRefusesAnOpenMesh),
            new KeyValuePair<string, Action>("sphere progress reports its phases",
                                             SphereProgressReportsItsPhases),
            new KeyValuePair<string, Action>("sphere settings round trip",
                                             SphereSettingsRoundTrip),
            new KeyValuePair<string, Action>("disposal is safe", DisposalIsSafe),
            new KeyValuePair<string, Action>("layout and version match the library",
                                             LayoutAndVersionMatchTheLibrary),
            new KeyValuePair<string, Action>("scene of several meshes", SceneOfSeveralMeshes),
            new KeyValuePair<string, Action>("groups and seam edges", GroupsAndSeamEdges),
            new KeyValuePair<string, Action>("repack keeps the uv islands", RepackKeepsIslands),
            new KeyValuePair<string, Action>("a repeated mesh shares its original's texels",
                                             RepeatedMeshSharesTexels),
        };
        int passed = 0, failed = 0;
        foreach (var test in tests)
        {
            try
            {
                test.Value();
                passed++;
                Console.WriteLine("ok   " + test.Key);
            }
            catch (Exception error)
            {
                failed++;
                Console.WriteLine("FAIL " + test.Key + ": " + error);
            }
        }
        Console.WriteLine("{0} passed, {1} failed", passed, failed);
        return failed;
    }
}
