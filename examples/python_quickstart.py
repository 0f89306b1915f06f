#!/usr/bin/env python3
"""A first tour of the trivar Python module, after ./scripts/demo.sh has built it:

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python_quickstart.py [OUT_DIR]

Builds an exact NURBS ring and a graded 7-cell ball, evaluates, refines, certifies, inverts, meshes, slices
and solves; cuts a pocket by a Boolean, fits scattered points by an LR surface and refines a THB surface,
printing what it checks, and writes its files to OUT_DIR (default out/python-quickstart, which
must be new or empty)."""
import math
import os
import sys

import numpy as np

import trivar

out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "python-quickstart")
os.makedirs(out, exist_ok=True)
if os.listdir(out):
    sys.exit(f"python_quickstart: {out} is not empty; give a new folder")

# A ring 1 <= r <= 2, 0 <= z <= 1: a rectangle profile in the xz-plane revolved about the z-axis (exact NURBS).
# Control points first direction fastest: S(u, v) = (v, 0, u), so S_u x S_v points along the rotation (+y).
profile = trivar.Surface([[0, 0, 1, 1], [0, 0, 1, 1]], 1, [[0, 0, 0], [0, 0, 1], [1, 0, 0], [1, 0, 1]])
profile = profile.transform(np.eye(3), [1, 0, 0])  # r from 1 to 2
ring = trivar.revolve(profile, angle=360)
print(ring)
print("volume", ring.measure(), "exact", 3 * math.pi)

rng = np.random.default_rng(0)
u = rng.uniform(0, 1, size=(100_000, 3))
x = ring(u)  # (N, 3), one call, no Python loop
r = np.hypot(x[:, 0], x[:, 1])
print(f"radii of 1e5 random points in [{r.min():.15f}, {r.max():.15f}]")
d = ring.derivatives(u[:3], order=1)  # (3, 4, 3): value, d/du, d/dv, d/dw
print("first derivatives at one point:\n", d[0])

fine = ring.refine(2).elevate(1)
print("refined and elevated:", fine, "max change", np.abs(fine(u) - x).max())
print("Jacobian:", ring.check_jacobian())
params, found, residual = ring.invert(x[:5])
print("inverted parameters recover u:", np.abs(params - u[:5]).max() < 1e-9, "found", found.all())

# A graded ball: material fractions blend from the centre to the surface.
ball = trivar.ball(radius=20.0)
ball.set_attribute("material", expression=["1 - sqrt(x^2 + y^2 + z^2) / 20", "sqrt(x^2 + y^2 + z^2) / 20"])
ball.materials = ["core", "shell"]
print(ball, "volume", ball.volume(), "exact", 4 / 3 * math.pi * 20 ** 3)
mesh = ball.tessellate(tolerance=0.01)
print(f"boundary mesh: {len(mesh.vertices)} vertices, {len(mesh.triangles)} triangles, watertight {mesh.watertight}")
layers = ball.slice(layer_thickness=5.0, dpi=[50.0])
print(f"slices: {layers.cell.shape[0]} layers of {layers.cell.shape[2]} x {layers.cell.shape[1]} pixels,",
      f"mid-layer inside area {(layers.cell[len(layers.z) // 2] >= 0).sum() * np.prod(layers.pixel_size):.1f} mm^2")

# Isogeometric analysis with a known solution: errors fall as h^(p+1) in L2.
for n in (4, 8):
    s = trivar.solve_poisson("sine-cube", degree=2, refine=n)
    print(f"Poisson sine-cube, {n}^3 elements: {s.dofs} dofs, L2 error {s.l2_error:.3e}, H1 error {s.h1_error:.3e}")
print("u at the centre:", s.field(np.array([0.5, 0.5, 0.5]))[0], "exact 1")

# A block with a spherical pocket: a V-model Boolean, the density blended where the operands overlap.
block = trivar.box(size=[2, 2, 2])
block.set_attribute("density", value=[1.0])
pocket = trivar.boolean(block, trivar.ball(radius=1.0), op="difference")
print(f"box minus ball octant: volume {pocket.model.volume():.9f}, exact {8 - math.pi / 6:.9f},",
      f"{pocket.cells} trimmed cell(s), {pocket.pieces} pieces")

# Terrain from scattered points: an LR surface refined only where the bump needs it.
xy = rng.uniform(0, 1, size=(3000, 2))
z = np.exp(-40 * ((xy[:, 0] - 0.5) ** 2 + (xy[:, 1] - 0.4) ** 2))
fit = trivar.fit(xy, z, tolerance=1e-3, height_field=True)
for level, n, e in zip(fit.iterations.level, fit.iterations.coefficients, fit.iterations.max_error):
    print(f"fit level {level}: {n} coefficients, max error {e:.2e}")

# A hierarchical (THB) surface: local refinement that keeps the surface exactly.
thb = trivar.HierarchicalSurface(profile.refine(2), basis="thb")
before = thb(u[:, :2])
thb.refine(elements=[0, 1])
print(thb, "max change", np.abs(thb(u[:, :2]) - before).max())

trivar.write(os.path.join(out, "thb.xml"), thb)
trivar.write(os.path.join(out, "terrain.lr"), fit.spline)
trivar.write(os.path.join(out, "ring.json"), ring)
trivar.write(os.path.join(out, "ring.stp"), ring)
trivar.write(os.path.join(out, "ball.json"), ball)
trivar.write(os.path.join(out, "ball.stl"), ball, tolerance=0.01)
print("wrote", ", ".join(sorted(os.listdir(out))), "to", out)
