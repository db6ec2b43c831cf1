import math
import raps

# A hexagonal cap: one vertex raised above the middle of six on a circle.
ring = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
mesh = raps.Mesh(positions=[(0.0, 0.0, 0.5)] + ring,
                 indices=[(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)])
settings = raps.Settings(monitor=raps.Monitor.AREA, alpha=1.0)
result = raps.parameterize(mesh, settings)
print("uv of the top:", result.uvs()[0])
print("flipped triangles:", result.stats().flipped_triangles)

# Those uvs repacked into an atlas at 64 texels per unit: one (u, v) per triangle corner; each
# island is only moved, turned and uniformly scaled, never mapped again.
uv = result.uvs()
mesh.set_corner_uvs([uv[v] for triangle in result.indices() for v in triangle])
atlas = raps.parameterize(mesh, raps.Settings(domain="atlas", atlas_repack=1,
                                              atlas_texels_per_unit=64.0))
print("repacked charts:", atlas.stats().chart_count, "texels per unit:",
      atlas.stats().texels_per_unit)

# The cap twice in one scene, the copy moved: with stacking the copy costs no texels.
copy = raps.Mesh(positions=[(0.0, 0.0, 0.5)] + ring,
                 indices=[(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)])
copy.set_transform([[1, 0, 0, 3], [0, 1, 0, 0], [0, 0, 1, 0]])
scene = raps.parameterize_scene([mesh, copy], raps.Settings(domain="atlas", atlas_stack="rigid"))
print("stacked charts:", sum(1 for chart in scene.charts() if chart.stacked))
