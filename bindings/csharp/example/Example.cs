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
        }
    }
}
