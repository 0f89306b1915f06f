"""V-models: primitives against closed-form volumes, attributes and mass, the watertight boundary mesh on the
exact sphere, slices against the disk areas of the ball's sections."""
import math

import numpy as np
import pytest

import trivar


def test_primitives_volumes():
    ball = trivar.ball(radius=2.0, center=[1, 0, 0])
    assert ball.num_cells == 7 and len(ball) == 7 and ball.glued
    assert abs(ball.volume() - 4 / 3 * math.pi * 8) < 1e-9 * 34
    assert ball.num_shared_surfaces == 18 and ball.num_boundary_surfaces == 6  # (7 * 6 - 6) / 2
    # The cube's 8 corners and the sphere's 8 cube-sphere corners; 12 + 12 + 8 edges.
    assert ball.num_points == 16 and ball.num_curves == 32
    assert sorted(ball.neighbours(0)) == [1, 2, 3, 4, 5, 6]
    assert np.allclose(ball.bounding_box[:, 0], [-1, -2, -2], atol=1e-12) or np.all(ball.bounding_box[:, 0] <= [-1, -2, -2])
    assert abs(trivar.cylinder(radius=1.5, height=2.0).volume() - math.pi * 2.25 * 2) < 1e-9
    R, r, h = 1.0, 0.5, 2.0
    assert abs(trivar.cone(R, r, h).volume() - math.pi * h / 3 * (R * R + R * r + r * r)) < 1e-9
    assert abs(trivar.torus(2.0, 0.5).volume() - 2 * math.pi ** 2 * 2.0 * 0.25) < 1e-9
    box = trivar.box(size=[1, 2, 3], origin=[1, 1, 1])
    assert abs(box.volume() - 6.0) < 1e-12
    assert "7 cells" in repr(ball)
    # Every cell of the ball is certified valid.
    assert all(c.check_jacobian().valid for c in ball.cells)


def test_sphere_points_are_exact():
    ball = trivar.ball(radius=3.0)
    outer = ball.cells[1]  # w = 1 is the sphere patch
    uv = np.random.default_rng(2).uniform(0, 1, size=(500, 2))
    x = outer(np.column_stack([uv, np.ones(len(uv))]))
    assert np.max(np.abs(np.linalg.norm(x, axis=1) - 3.0)) < 1e-13 * 10


def test_model_from_cells_and_attributes():
    a = trivar.block(1, 1, [1.0, 1.0, 1.0])
    b = a.transform(np.eye(3), [1.0, 0, 0])
    m = trivar.VModel([a, b])
    assert m.num_shared_surfaces == 1 and m.num_cells == 2
    m3 = trivar.VModel([a, b], glue=False)
    assert not m3.glued
    assert m3.add_cell(b.transform(np.eye(3), [1.0, 0, 0])) == 2
    m3.glue()
    assert m3.glued and m3.num_shared_surfaces == 2 and abs(m3.volume() - 3.0) < 1e-12
    m.set_attribute("density", value=[2.5])
    assert abs(m.mass("density") - 5.0) < 1e-12
    m.set_attribute("t", expression=["x + 2*y", "z^2"])
    u = np.random.default_rng(4).uniform(0, 1, size=(50, 3))
    x = m.cells[1](u)
    vals = m.attribute(1, "t", u)
    assert np.allclose(vals[:, 0], x[:, 0] + 2 * x[:, 1], atol=1e-12)
    assert np.allclose(vals[:, 1], x[:, 2] ** 2, atol=1e-12)
    m.set_attribute("p", expression=["u*v"], space="parametric", cells=[0])
    assert np.allclose(m.attribute(0, "p", u)[:, 0], u[:, 0] * u[:, 1])
    field = trivar.block(1, 1, [1.0, 1.0, 1.0])  # a field with values (u, v, w)
    m.set_attribute("f", field=field)
    assert np.allclose(m.attribute(1, "f", u), u, atol=1e-12)
    # Mass of a linear density x over the two cubes [0, 2] x [0, 1]^2: 2.
    m.set_attribute("rho", expression=["x"])
    assert abs(m.mass("rho") - 2.0) < 1e-12
    assert "density" in m.attribute_names(0)
    with pytest.raises(trivar.Error, match="no attribute"):
        m.attribute(0, "missing", u)
    with pytest.raises(trivar.Error):
        m.set_attribute("bad", value=[1.0], expression=["x"])


def test_boundary_tessellation_of_the_ball():
    ball = trivar.ball(radius=1.0)
    t = ball.tessellate(tolerance=1e-3)
    assert t.watertight
    assert t.vertices.shape[1] == 3 and t.triangles.shape[1] == 3 and t.triangles.dtype == np.int32
    assert np.max(np.abs(np.linalg.norm(t.vertices, axis=1) - 1.0)) < 1e-12
    # Inscribed polyhedron: volume and area below the sphere's, within the chordal tolerance.
    assert 4 / 3 * math.pi * (1 - 1e-3) ** 3 - 1e-9 < t.volume < 4 / 3 * math.pi
    assert 4 * math.pi * (1 - 1e-3) ** 2 < t.area < 4 * math.pi
    # Each vertex maps back to its cell parameters.
    cells = ball.cells
    for v in range(0, len(t.vertices), 97):
        assert np.allclose(cells[t.cell[v]](t.params[v]), t.vertices[v], atol=1e-12)


def test_slices_of_a_graded_ball():
    ball = trivar.ball(radius=2.0)
    ball.set_attribute("material", expression=["1 - sqrt(x^2+y^2+z^2)/2", "sqrt(x^2+y^2+z^2)/2"])
    ball.materials = ["core", "shell"]
    assert ball.materials == ["core", "shell"]
    s = ball.slice(layer_thickness=0.5, dpi=[127.0], z_range=[-2.0, 2.0], dither="ordered")
    L, H, W = s.cell.shape
    assert L == 8 and s.fractions.shape == (L, H, W, 2) and s.labels.shape == (L, H, W)
    dx, dy = s.pixel_size
    assert abs(dx - 0.2) < 1e-15
    for k in range(L):
        inside = s.cell[k] >= 0
        area = inside.sum() * dx * dy
        exact = math.pi * (4 - s.z[k] ** 2)
        assert abs(area - exact) < 0.05 * exact
        f = s.fractions[k][inside]
        assert np.allclose(f.sum(axis=1), 1.0, atol=1e-6)
        assert np.all(s.labels[k][~inside] == 0) and np.all(s.labels[k][inside] > 0)
    # The fractions at the pixel centres follow the formula: pixel (i, j) at origin + (i + 0.5, j + 0.5) * size.
    k = L // 2
    J, I = np.nonzero(s.cell[k] >= 0)
    x = s.origin[0] + (I + 0.5) * dx
    y = s.origin[1] + (J + 0.5) * dy
    r = np.sqrt(x * x + y * y + s.z[k] ** 2)
    assert np.max(np.abs(s.fractions[k, J, I, 1] - r / 2)) < 1e-5
    assert s.inside_pixels == int((s.cell >= 0).sum()) and s.max_residual < 1e-6
    with pytest.raises(trivar.Error, match="memory"):
        ball.slice(dpi=[1e6])
    with pytest.raises(trivar.Error, match="memory"):
        ball.tessellate(tolerance=1e-12)
