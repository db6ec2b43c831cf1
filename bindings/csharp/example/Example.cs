using System;
using Raps;

static class Example
{
    static void Main()
    {
        // A hexagonal cap: one vertex raised above the middle of six on a circle.
        var xyz = new float[] { 0, 0, 0.5f, 1, 0, 0, 0.5f, 0.866f, 0, -0.5f, 0.866f, 0,
                                -1, 0, 0, -0.5f, -0.866f, 0, 0.5f, -0.866f, 0 };
        var indices = new uint[] { 0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 6, 0, 6, 1 };
        using (var mesh = new Mesh(xyz, indices))
        using (var settings = new Settings { Monitor = ErrorMonitor.Area, Alpha = 1.0 })
        using (var result = Library.Parameterize(mesh, settings))
        {
            float[] uvs = result.GetUvs();
            Console.WriteLine("uv of the top: ({0}, {1})", uvs[0], uvs[1]);
            Console.WriteLine("flipped triangles: {0}", result.GetStats().FlippedTriangles);

            // Those uvs repacked into an atlas at 64 texels per unit: one (u, v) per triangle
            // corner; each island is only moved, turned and uniformly scaled, never mapped again.
            uint[] triangles = result.GetIndices();
            var corners = new float[2 * triangles.Length];
            for (int c = 0; c < triangles.Length; c++)
            {
                corners[2 * c] = uvs[2 * triangles[c]];
                corners[2 * c + 1] = uvs[2 * triangles[c] + 1];
            }
            mesh.SetCornerUvs(corners);
            using (var repack = new Settings { AtlasRepack = true })
            {
                repack.SetInt(Param.Domain, (long)Domain.Atlas);
                repack.SetFloat(Param.AtlasTexelsPerUnit, 64.0);
                using (var atlas = Library.Parameterize(mesh, repack))
                    Console.WriteLine("repacked charts: {0}", atlas.GetStats().ChartCount);
            }

            // The cap twice in one scene, the copy moved: with stacking the copy costs no texels.
            using (var copy = new Mesh(xyz, indices))
            using (var stack = new Settings { AtlasStack = Stacking.Rigid })
            {
                copy.SetTransform(new double[] { 1, 0, 0, 3, 0, 1, 0, 0, 0, 0, 1, 0 });
                stack.SetInt(Param.Domain, (long)Domain.Atlas);
                using (var scene = Library.ParameterizeScene(new[] { mesh, copy }, stack))
                {
                    int stacked = 0;
                    foreach (Chart chart in scene.GetCharts())
                        if ((chart.Flags & Native.RAPS_CHART_STACKED) != 0) stacked++;
                    Console.WriteLine("stacked charts: {0}", stacked);
                }
            }
        }
    }
}
