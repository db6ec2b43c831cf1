"""Positions and polygons of a shared mesh file (OBJ or OFF), as Mesh.from_pydata takes them:
the polygons as they are in the file (Blender's OBJ importer reads OBJ only, and the benchmark
builds every mesh the same way)."""


def read_mesh_file(path):
    """Positions and polygons of an OBJ (v, f) or OFF file."""
    verts, faces = [], []
    if path.endswith(".off"):
        tokens = []
        with open(path) as stream:
            for line in stream:
                tokens += line.split("#")[0].split()
        nv, nf = int(tokens[1]), int(tokens[2])
        at = 4
        for _ in range(nv):
            verts.append(tuple(float(t) for t in tokens[at:at + 3]))
            at += 3
        for _ in range(nf):
            n = int(tokens[at])
            faces.append(tuple(int(t) for t in tokens[at + 1:at + 1 + n]))
            at += 1 + n
        return verts, faces
    with open(path) as stream:
        for line in stream:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                verts.append(tuple(float(t) for t in parts[1:4]))
            elif parts[0] == "f":
                ids = [int(p.split("/")[0]) for p in parts[1:]]
                faces.append(tuple(i - 1 if i > 0 else len(verts) + i for i in ids))
    return verts, faces
