"""Blender meshes to raps's input, and raps's output back to a Blender UV map.

raps takes triangles; Blender's faces are polygons whose uvs live on their loops (face
corners). The loop triangles (Mesh.loop_triangles, the triangulation Blender itself renders) go
to raps with their polygon as their polygon id (raps_mesh_set_triangle_polygons), so raps keeps
each polygon's triangles in one chart with no cut between them, and every loop takes the uv of
the output vertex at its corner: one uv per loop whichever triangle it is read from. Where raps
cannot (a polygon whose triangles it sets aside: zero area, or across a non-manifold edge), the
polygon becomes a small island of its own here, and the report counts it.

Only vertices used by a face go to raps (loose vertices and edges have no uvs and would be
isolated vertices to it); seams are the edges marked use_seam that some face uses.
"""

import re

import numpy

# One raps run's input as read from a Blender mesh, in raps's vertex numbering.
class MeshInput:
    __slots__ = ("positions", "triangles", "triangle_loops", "triangle_polygons", "groups",
                 "polygons", "seams", "transform", "loop_count", "polygon_count",
                 "blender_vertex")


def world_transform(obj):
    """The object's world matrix as raps's 3x4 row-major transform (scale, rotation, place)."""
    m = obj.matrix_world
    return [[m[r][c] for c in range(4)] for r in range(3)]


def _read(collection, attribute, count, dtype, width=1):
    """foreach_get into a numpy array. dtype must be the property's own (uint32 for integers,
    float32 for floats, bool): Blender copies those as one block, and converts any other
    element by element (loop triangles' vertices as int64: 5 ms instead of 1 ms on 100K
    triangles; an edge index as int32: 12 ms instead of 0.3 ms)."""
    values = numpy.empty(count * width, dtype=dtype)
    collection.foreach_get(attribute, values)
    return values.reshape(-1, width) if width > 1 else values


def read_mesh(obj, use_seams=True, use_materials=False):
    """A MeshInput of obj's mesh data (not the modifiers' result, which the uvs do not live on)."""
    mesh = obj.data
    mesh.calc_loop_triangles()
    tri_count = len(mesh.loop_triangles)
    triangles = _read(mesh.loop_triangles, "vertices", tri_count, numpy.uint32, 3)
    loops = _read(mesh.loop_triangles, "loops", tri_count, numpy.uint32, 3)
    polygons = _read(mesh.loop_triangles, "polygon_index", tri_count, numpy.uint32)
    positions = _read(mesh.vertices, "co", len(mesh.vertices), numpy.float32, 3)

    # raps numbers only the vertices that faces use, in Blender's order.
    used = numpy.zeros(len(mesh.vertices), dtype=bool)
    used[triangles.reshape(-1)] = True
    new_index = numpy.cumsum(used) - 1

    data = MeshInput()
    data.positions = positions[used]
    data.blender_vertex = numpy.nonzero(used)[0]
    data.triangles = new_index[triangles].astype(numpy.uint32)
    data.triangle_loops = loops
    data.triangle_polygons = polygons
    data.loop_count = len(mesh.loops)
    data.polygon_count = len(mesh.polygons)
    data.transform = world_transform(obj)
    data.groups = None
    # Polygon ids only where a polygon has several triangles (a triangle mesh needs none).
    data.polygons = polygons if tri_count > len(mesh.polygons) else None
    if use_materials and tri_count:
        materials = _read(mesh.polygons, "material_index", len(mesh.polygons), numpy.uint32)
        data.groups = materials[polygons]
    data.seams = _face_seams(mesh, used, new_index) if use_seams else None
    return data


def _face_seams(mesh, used, new_index):
    """use_seam edges that a face uses, as pairs of raps vertex indices (None when there are
    none): a seam on a loose edge is no edge of any triangle, which raps would refuse."""
    edge_count = len(mesh.edges)
    if edge_count == 0:
        return None
    seam = _read(mesh.edges, "use_seam", edge_count, bool)
    if not seam.any():
        return None
    in_face = numpy.zeros(edge_count, dtype=bool)
    in_face[_read(mesh.loops, "edge_index", len(mesh.loops), numpy.uint32)] = True
    ends = _read(mesh.edges, "vertices", edge_count, numpy.uint32, 2)[seam & in_face]
    # A face's edges join vertices that faces use, so every end has a raps index.
    return new_index[ends].astype(numpy.uint32) if len(ends) else None


def corner_uvs(uvs, indices, pages, chart_of_triangle):
    """Per triangle corner (t, 3, 2) uvs of one mesh's share of a raps result; page p is moved
    p to the right in u (Blender's UDIM tiles 1001, 1002, ...)."""
    corners = uvs[indices].copy()
    if pages is not None and len(pages) and pages.max() > 0:
        corners[:, :, 0] += pages[chart_of_triangle][:, None]
    return corners


def split_polygons(data, out_vertices):
    """The polygons whose loops raps gave different output vertices in different triangles
    (a triangle raps set aside took another chart's vertex)."""
    owner = numpy.full(data.loop_count, -1, dtype=numpy.int64)
    owner[data.triangle_loops.reshape(-1)] = out_vertices.reshape(-1)
    split = (owner[data.triangle_loops] != out_vertices).any(axis=1)
    return numpy.unique(data.triangle_polygons[split])


def loop_uvs(data, corners, out_vertices):
    """Per loop uvs (loop_count, 2) from per corner uvs, and the number of polygons made
    islands of their own because raps's output cuts through them."""
    loops = data.triangle_loops.reshape(-1)
    uv = numpy.zeros((data.loop_count, 2), dtype=numpy.float64)
    uv[loops] = corners.reshape(-1, 2)
    split = split_polygons(data, out_vertices)
    if len(split):
        _repair_split_polygons(data, corners, split, uv)
    return uv, len(split)


def _repair_split_polygons(data, corners, split_polygons, uv):
    """A polygon raps's output still cuts becomes an island of its own inside
    the uv triangle of its largest part: its triangles unfolded into the plane across their
    shared diagonals (each keeps its shape and orientation), then shrunk about their centroid
    into that triangle's incircle. Its uvs then overlap no other face's and stay in the atlas;
    the face gets fewer texels than its neighbours (the report counts such faces)."""
    world = _world_positions(data)
    is_split = numpy.zeros(data.polygon_count, dtype=bool)
    is_split[split_polygons] = True
    triangles_of = {}
    for t in numpy.nonzero(is_split[data.triangle_polygons])[0]:
        triangles_of.setdefault(int(data.triangle_polygons[t]), []).append(int(t))
    for triangles in triangles_of.values():
        reference = max(triangles, key=lambda t: abs(_area_2d(corners[t])))
        vertex_of_loop = {int(data.triangle_loops[t][k]): int(data.triangles[t][k])
                          for t in triangles for k in range(3)}
        loops = list(vertex_of_loop)
        flat = _unfold(world, [[int(v) for v in data.triangles[t]] for t in triangles])
        points = numpy.array([flat[vertex_of_loop[loop]] for loop in loops])
        centre, inradius = _incircle(corners[reference])
        middle = points.mean(axis=0)
        reach = numpy.linalg.norm(points - middle, axis=1).max()
        scale = 0.95 * inradius / reach if reach > 0 else 0.0
        uv[loops] = centre + scale * (points - middle)


def _area_2d(triangle):
    (ax, ay), (bx, by), (cx, cy) = triangle
    return 0.5 * ((bx - ax) * (cy - ay) - (cx - ax) * (by - ay))


def _incircle(triangle):
    """Centre and radius of a 2D triangle's inscribed circle."""
    a, b, c = (numpy.asarray(p, dtype=numpy.float64) for p in triangle)
    la, lb, lc = numpy.linalg.norm(b - c), numpy.linalg.norm(c - a), numpy.linalg.norm(a - b)
    perimeter = la + lb + lc
    if perimeter == 0:
        return a, 0.0
    return (la * a + lb * b + lc * c) / perimeter, 2.0 * abs(_area_2d(triangle)) / perimeter


def _world_positions(data):
    m = numpy.asarray(data.transform, dtype=numpy.float64)
    return data.positions @ m[:, :3].T + m[:, 3]


def _unfold(world, triangles):
    """2D positions of a polygon's vertices: its first triangle laid out counter-clockwise,
    each next one across an edge it shares with those placed (a polygon's triangulation is a
    tree of triangles, so each brings one new vertex), keeping its edge lengths."""
    a, b, c = triangles[0]
    place = {a: numpy.zeros(2), b: numpy.array([numpy.linalg.norm(world[b] - world[a]), 0.0])}
    place[c] = _apex(place[a], place[b], world, a, b, c)
    pending = list(triangles[1:])
    while pending:
        progressed = False
        for triangle in list(pending):
            new = [k for k in range(3) if triangle[k] not in place]
            if len(new) == 1:
                k = new[0]
                u, v, w = triangle[(k + 1) % 3], triangle[(k + 2) % 3], triangle[k]
                place[w] = _apex(place[u], place[v], world, u, v, w)
            if len(new) <= 1:
                pending.remove(triangle)
                progressed = True
        if not progressed:  # not a tree of shared edges: place the rest as they lie
            for triangle in pending:
                for vertex in triangle:
                    place.setdefault(vertex, place[a] + world[vertex][:2] - world[a][:2])
            break
    return place


def _apex(p, q, world, u, v, w):
    """Where w goes, left of p -> q (triangle u, v, w counter-clockwise), at its 3D distances
    from u and v."""
    du = numpy.linalg.norm(world[w] - world[u])
    dv = numpy.linalg.norm(world[w] - world[v])
    d = numpy.linalg.norm(q - p)
    if d == 0:
        return p.copy()
    along = (du * du - dv * dv + d * d) / (2 * d)
    height = numpy.sqrt(max(du * du - along * along, 0.0))
    e = (q - p) / d
    return p + along * e + height * numpy.array([-e[1], e[0]])


def write_uvs(mesh, layer_name, uv):
    """Writes per loop uvs into the UV map layer_name of mesh, creating it when missing."""
    layer = mesh.uv_layers.get(layer_name)
    if layer is None:
        layer = mesh.uv_layers.new(name=layer_name)
    layer.data.foreach_set("uv", uv.astype(numpy.float32).reshape(-1))
    mesh.update()
    return layer


def blender_message(data, message):
    """raps's message with its vertex numbers turned into Blender's (raps numbers only the
    vertices that faces use)."""
    def vertex(match):
        index = int(match.group(1))
        if index < len(data.blender_vertex):
            return "vertex %d" % data.blender_vertex[index]
        return match.group(0)
    return re.sub(r"vertex (\d+)", vertex, message)
