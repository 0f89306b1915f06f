"""Scattered-data LR fitting (errors against an independent evaluation, exact reproduction of quadratics) and
V-model Booleans (volumes of boxes and a ball, attribute blends integrated in closed form)."""
import math

import numpy as np
import pytest

import trivar


def test_fit_refines_until_the_tolerance(rng):
    p = rng.uniform(0, 1, size=(2000, 2))
    h = np.exp(-40 * ((p[:, 0] - 0.5) ** 2 + (p[:, 1] - 0.4) ** 2))
    r = trivar.fit(p, h, tolerance=1e-3, height_field=True)
    assert r.converged and r.stop_reason == "tolerance reached" and r.tolerance == 1e-3
    it = r.iterations
    assert list(it.level) == list(range(len(it.level))) and len(it.level) >= 2
    assert np.all(np.diff(it.coefficients) > 0) and it.max_error[-1] <= 1e-3 < it.max_error[0]
    assert np.all(it.rms_error <= it.max_error) and np.all(it.mean_error <= it.rms_error + 1e-15)
    assert it.outside[-1] == 0 and it.outside[0] > 0 and all(s == "independent" for s in it.independence)
    assert len(it.elements) == len(it.seconds) == len(it.level)
    # The reported errors are those of the spline returned, evaluated here.
    f = r.spline(p)[:, 0]
    assert np.max(np.abs(np.abs(f - h) - r.errors)) < 1e-13 and r.errors.max() <= 1e-3
    assert r.spline.num_basis == it.coefficients[-1]
    # The same fit as a graph (x, y, h): after local refinement x and y are still the parameters themselves.
    g = trivar.fit(p, h, tolerance=1e-3).spline(p)
    assert np.max(np.abs(g[:, :2] - p)) < 1e-13 and np.max(np.abs(g[:, 2] - f)) < 1e-13
    # MBA: the same tolerance; its carried errors are those of the spline returned.
    m = trivar.fit(p, h, tolerance=1e-3, height_field=True, method="mba")
    assert m.converged and np.max(np.abs(np.abs(m.spline(p)[:, 0] - h) - m.errors)) < 1e-13
    with pytest.raises(trivar.Error, match="unknown method"):
        trivar.fit(p, h, tolerance=1e-3, method="kriging")


def test_fit_reproduces_a_quadratic_and_makes_a_graph(rng):
    p = rng.uniform(-1, 2, size=(500, 2))
    q = 1 + p[:, 0] ** 2 - p[:, 0] * p[:, 1]
    r = trivar.fit(p, q, relative_tolerance=1e-6, levels=0, smoothing=0.0)
    assert r.converged and r.iterations.max_error[0] < 1e-9 and len(r.iterations.level) == 1
    g = r.spline(p)  # the graph (x, y, h): x and y are the parameters themselves
    assert g.shape == (500, 3) and np.max(np.abs(g[:, :2] - p)) < 1e-12 and np.max(np.abs(g[:, 2] - q)) < 1e-9
    # Volume data with two values per point: an LRVolume of dim 2.
    p3 = rng.uniform(0, 1, size=(1500, 3))
    v = np.sin(3 * p3[:, 0]) * p3[:, 1] + p3[:, 2]
    r3 = trivar.fit(p3, np.column_stack([v, 2 * v]), tolerance=1e-2)
    assert isinstance(r3.spline, trivar.LRVolume) and r3.spline.dim == 2 and r3.converged
    f = r3.spline(p3)
    assert np.max(np.abs(f[:, 1] - 2 * f[:, 0])) < 1e-12 and np.max(np.abs(f[:, 0] - v)) <= 1e-2
    with pytest.raises(trivar.Error, match="values"):
        trivar.fit(p, q[:10], tolerance=1e-3)
    with pytest.raises(trivar.Error, match="strategy|fullspan"):
        trivar.fit(p, q, tolerance=1e-3, strategy="nope")


def boxes():
    a = trivar.box(size=[2, 2, 2])
    b = trivar.box(size=[2, 2, 2], origin=[1, 1, 1])
    a.set_attribute("density", value=[1.0])
    b.set_attribute("density", value=[3.0])
    return a, b


def test_boolean_volumes_and_attribute_rules():
    a, b = boxes()
    # 8 + 8 - 1, 8 - 1, 1; the overlap [1, 2]^3 is averaged (density 2).
    u = trivar.boolean(a, b, op="union", rule="average")
    assert abs(u.model.volume() - 15) < 1e-9 and u.cells == u.model.num_cells == 3 and u.pieces == 3
    assert u.pieces_a_only == u.pieces_b_only == u.pieces_both == 1 and u.cells_a == u.cells_b == 1
    assert abs(u.model.mass("density") - (7 * 1 + 7 * 3 + 1 * 2)) < 1e-9
    assert u.interior_faces > 0 and u.boundary_faces > 0 and len(u.neighbours) == 3 and u.exact_attributes > 0
    d = trivar.boolean(a, b, op="difference")
    assert abs(d.model.volume() - 7) < 1e-9 and d.fitted_attributes == 0
    i = trivar.boolean(a, b, op="intersection", rules={"density": "b"})
    assert abs(i.model.volume() - 1) < 1e-9 and abs(i.model.mass("density") - 3) < 1e-9
    # A weight formula: density (1 - w) 1 + w 3 with w = x - 1 on [1, 2]^3 integrates to 2.
    f = trivar.boolean(a, b, op="intersection", rules={"density": ("formula", "x - 1")})
    assert abs(f.model.mass("density") - 2) < 1e-6
    # Operators with the default rules; the result is an operand again.
    assert abs((a | b).volume() - 15) < 1e-9 and abs((a - b).volume() - 7) < 1e-9
    assert abs(((a & b) | a).volume() - 8) < 1e-9
    with pytest.raises(trivar.Error, match="union|op"):
        trivar.boolean(a, b, op="xor")
    with pytest.raises(trivar.Error):
        trivar.boolean(a, trivar.box(origin=[5, 5, 5]), op="intersection")


def test_box_minus_ball_is_exact():
    a = trivar.box(size=[2, 2, 2])
    r = trivar.boolean(a, trivar.ball(radius=1.0), op="difference")
    # The ball's octant at the origin corner is removed: 8 - pi / 6.
    assert abs(r.model.volume() - (8 - math.pi / 6)) < 1e-8
    assert r.model.trimmed
    m = r.model.tessellate()
    assert len(m.triangles) > 0
