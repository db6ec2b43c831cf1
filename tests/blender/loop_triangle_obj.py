"""Objects' faces as Blender draws them, written as an OBJ for uvmetrics.py.

Blender's OBJ exporter triangulates polygons its own way (or not at all, leaving uvmetrics to
fan them), which can differ from the loop triangles the viewport draws and raps maps: a sliver
across an n-gon's nearly straight side may then look flipped where Blender shows none. This
writes the loop triangles themselves, with world positions and the active UV map. Shared by the
add-on's test and bench/blender_unwrappers.py.
"""

import numpy


def write(objects, path):
    with open(path, "w") as stream:
        v_base = vt_base = 0
        for obj in objects:
            mesh = obj.data
            mesh.calc_loop_triangles()
            matrix = obj.matrix_world
            for vertex in mesh.vertices:
                stream.write("v %.9g %.9g %.9g\n" % tuple(matrix @ vertex.co))
            layer = mesh.uv_layers.active
            uv = numpy.zeros(2 * len(mesh.loops), dtype=numpy.float32)
            if layer is not None:
                layer.data.foreach_get("uv", uv)
            stream.writelines("vt %.9g %.9g\n" % (uv[2 * i], uv[2 * i + 1])
                              for i in range(len(mesh.loops)))
            for triangle in mesh.loop_triangles:
                stream.write("f" + "".join(
                    " %d/%d" % (v_base + vertex + 1, vt_base + loop + 1)
                    for vertex, loop in zip(triangle.vertices, triangle.loops)) + "\n")
            v_base += len(mesh.vertices)
            vt_base += len(mesh.loops)
