"""Tensor splines: construction from NumPy, evaluation against NumPy Cox-de Boor, refinement and degree
elevation leaving the geometry unchanged, inversion, Jacobian certification, measures."""
import math

import numpy as np
import pytest

import trivar
from conftest import random_knots
from reference import tensor_eval


def random_volume(rng, degrees=(3, 2, 3), elements=(4, 3, 5), dim=3, rational=False):
    knots = [random_knots(rng, p, e) for p, e in zip(degrees, elements)]
    counts = [len(k) - p - 1 for k, p in zip(knots, degrees)]
    points = rng.normal(size=(int(np.prod(counts)), dim))
    weights = rng.uniform(0.5, 2.0, size=len(points)) if rational else None
    return trivar.Volume(knots, list(degrees), points, weights), knots, points, weights


def test_volume_values_match_cox_de_boor(rng):
    v, knots, points, _ = random_volume(rng)
    u = rng.uniform(0, 1, size=(500, 3))
    ref = tensor_eval(knots, [3, 2, 3], points, u)
    assert np.max(np.abs(v(u) - ref)) < 1e-12
    assert np.max(np.abs(v.evaluate(u, threads=1) - ref)) < 1e-12
    # One point (3,) gives (dim,).
    assert v(u[0]).shape == (3,)
    assert np.allclose(v(u[0]), ref[0], atol=1e-12)
    # The domain's right end belongs to the last interval.
    assert np.allclose(v(np.ones(3)), tensor_eval(knots, [3, 2, 3], points, np.ones((1, 3)))[0], atol=1e-12)


def test_rational_volume_values(rng):
    v, knots, points, weights = random_volume(rng, rational=True)
    u = rng.uniform(0, 1, size=(300, 3))
    assert v.rational
    assert np.max(np.abs(v(u) - tensor_eval(knots, [3, 2, 3], points, u, weights=weights))) < 1e-12
    assert np.allclose(v.weights, weights)


def test_derivatives_in_the_documented_order(rng):
    v, knots, points, _ = random_volume(rng)
    u = rng.uniform(0, 1, size=(200, 3))
    d = v.derivatives(u, order=2)
    assert d.shape == (200, 10, 3)
    # f, f_u, f_v, f_w, f_uu, f_uv, f_uw, f_vv, f_vw, f_ww
    order = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (2, 0, 0), (1, 1, 0), (1, 0, 1), (0, 2, 0), (0, 1, 1), (0, 0, 2)]
    for i, o in enumerate(order):
        ref = tensor_eval(knots, [3, 2, 3], points, u, orders=list(o))
        assert np.max(np.abs(d[:, i] - ref)) < 1e-9 * max(1.0, np.max(np.abs(ref))), o


def test_rational_derivatives_against_finite_differences(rng):
    v, _, _, _ = random_volume(rng, rational=True)
    u = rng.uniform(0.1, 0.9, size=(50, 3))
    d = v.derivatives(u, order=1)
    h = 1e-6
    for k in range(3):
        e = np.zeros(3)
        e[k] = h
        fd = (v(u + e) - v(u - e)) / (2 * h)
        assert np.max(np.abs(d[:, 1 + k] - fd)) < 1e-5 * max(1.0, np.max(np.abs(fd)))


def test_curve_and_surface(rng):
    k = random_knots(rng, 3, 6)
    pts = rng.normal(size=(len(k) - 4, 2))
    c = trivar.Curve([k], 3, pts)
    u = rng.uniform(0, 1, 400)
    assert c(u).shape == (400, 2)
    assert np.max(np.abs(c(u) - tensor_eval([k], [3], pts, u[:, None]))) < 1e-12
    ks = [random_knots(rng, 2, 3), random_knots(rng, 4, 2)]
    net = rng.normal(size=(len(ks[0]) - 3, len(ks[1]) - 5, 3))  # indexed [i, j, :]
    s = trivar.Surface(ks, [2, 4], net)
    assert np.array_equal(s.control_net, net)
    flat = net.transpose(1, 0, 2).reshape(-1, 3)  # first direction fastest
    assert np.array_equal(s.control_points, flat)
    uv = rng.uniform(0, 1, size=(100, 2))
    assert np.max(np.abs(s(uv) - tensor_eval(ks, [2, 4], flat, uv))) < 1e-12
    assert s.degrees == [2, 4] and s.counts == [len(ks[0]) - 3, len(ks[1]) - 5]
    w = rng.uniform(0.5, 2.0, size=net.shape[:2])  # indexed [i, j] like the net
    nurbs = trivar.Surface(ks, [2, 4], net, w)
    assert np.allclose(nurbs.weights, w.T.ravel())
    assert np.max(np.abs(nurbs(uv) - tensor_eval(ks, [2, 4], flat, uv, weights=w.T.ravel()))) < 1e-12
    assert s.parametric_dim == 2 and s.dim == 3 and not s.rational
    assert np.allclose(s.domain, [[0, 1], [0, 1]])
    assert "Surface" in repr(s) and "degrees (2, 4)" in repr(s)


def test_kernels_are_named():
    assert trivar.simd_level() in ("generic", "avx2", "avx512")


def test_zero_copy_parameters_and_threads(rng):
    v, _, _, _ = random_volume(rng)
    u = rng.uniform(0, 1, size=(1000, 3))
    # Fortran order and float32 are converted; the values agree.
    assert np.array_equal(v(np.asfortranarray(u)), v(u))
    assert np.allclose(v(u.astype(np.float32)), v(u.astype(np.float32).astype(float)))
    assert np.array_equal(v(u, threads=1), v(u, threads=2))


def test_grid_is_the_tensor_of_parameters(rng):
    v, _, _, _ = random_volume(rng)
    lists = [np.linspace(0, 1, 7), rng.uniform(0, 1, 5), np.linspace(0.2, 0.9, 4)]
    g = v.grid(lists)
    assert g.shape == (7, 5, 4, 3)
    U, V, W = np.meshgrid(*lists, indexing="ij")
    ref = v(np.stack([U.ravel(), V.ravel(), W.ravel()], axis=1)).reshape(7, 5, 4, 3)
    assert np.max(np.abs(g - ref)) < 1e-12


def test_refinement_and_elevation_keep_the_geometry(rng):
    v, _, _, _ = random_volume(rng, rational=True)
    u = rng.uniform(0, 1, size=(300, 3))
    before = v(u)
    r = v.refine(2)
    assert [len(k) for k in r.knots] != [len(k) for k in v.knots]
    assert np.max(np.abs(r(u) - before)) < 1e-12
    e = v.elevate([1, 0, 2])
    assert e.degrees == [4, 2, 5]
    assert np.max(np.abs(e(u) - before)) < 1e-12
    k = v.insert_knots(1, [0.5, 0.5, 0.123])
    assert k.counts[1] == v.counts[1] + 3
    assert np.max(np.abs(k(u) - before)) < 1e-12


def test_exact_circle_and_revolved_ring():
    c = trivar.circle_arc(radius=2.0, center=[1, 2, 3])
    u = np.linspace(0, 1, 1001)
    x = c(u)
    assert np.max(np.abs(np.linalg.norm(x - [1, 2, 3], axis=1) - 2.0)) < 1e-14 * 10
    profile = trivar.block_surface(1, 1, [1.0, 1.0]).transform(np.eye(3), [1.0, 0.0, 0.0])  # x in [1, 2], z = 0
    profile = profile.transform(np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]]), np.zeros(3))  # into the xz-plane
    ring = trivar.revolve(profile)
    vol = ring.measure()
    assert abs(abs(vol) - math.pi * (4 - 1) * 1) < 1e-10
    pts = ring(np.random.default_rng(1).uniform(0, 1, size=(200, 3)))
    r = np.hypot(pts[:, 0], pts[:, 1])
    assert np.all(r > 1 - 1e-12) and np.all(r < 2 + 1e-12)


def test_inversion_recovers_parameters_and_certifies_outside(rng):
    v = trivar.block([3, 3, 3], [4, 4, 4], [2.0, 1.0, 1.0])
    # A smooth near-identity deformation of the control points keeps the map invertible.
    pts = v.control_points
    pts += 0.05 * np.sin(3 * pts[:, [1, 2, 0]])
    v = trivar.Volume(v.knots, 3, pts)
    u = rng.uniform(0, 1, size=(200, 3))
    params, found, residual = v.invert(v(u))
    assert found.all()
    assert np.max(np.abs(params - u)) < 1e-8
    assert np.max(residual) < 1e-9
    p, f, _ = v.invert(np.array([10.0, 10.0, 10.0]))
    assert not f


def test_jacobian_check():
    block = trivar.block([2, 2, 2], [2, 2, 2], [2.0, 1.0, 1.0])
    r = block.check_jacobian()
    assert r.valid and bool(r)
    # x = (2u, v, w): det J = 2 everywhere.
    assert abs(r.min_value - 2.0) < 1e-12 and r.min_lower_bound <= 2.0 + 1e-12
    mirrored = block.transform(np.diag([-1.0, 1.0, 1.0]), np.zeros(3))
    bad = mirrored.check_jacobian()
    assert bad.invalid and not bad.valid and bad.min_value < 0
    assert "invalid" in repr(bad)
    assert isinstance(r, trivar.JacobianReport) and len(r.where) == 3 and r.elements == 8 and r.subdivisions >= 0
    # A planar surface: x = (u, v) on the unit square, det J = 1.
    sq = trivar.block_surface(2, 2, [1.0, 1.0])
    planar = trivar.Surface(sq.knots, sq.degrees, sq.control_points[:, :2])
    s = planar.check_jacobian()
    assert isinstance(s, trivar.SurfaceJacobianReport) and s.valid and abs(s.min_value - 1.0) < 1e-12


def test_measure_and_block():
    b = trivar.block([1, 2, 3], [2, 1, 3], [2.0, 3.0, 0.5])
    assert abs(b.measure() - 3.0) < 1e-12
    assert b.degrees == [1, 2, 3]
    assert abs(trivar.block_curve(2, 3, [4.0]).measure() - 4.0) < 1e-12
    assert abs(trivar.block_surface(2, 3, [2.0, 5.0]).measure() - 10.0) < 1e-12


def test_constructors_volumes():
    square = trivar.block_surface(1, 1, [1.0, 2.0])  # [0, 1] x [0, 2] at z = 0
    assert abs(trivar.extrude(square, [0, 0, 3.0]).measure() - 6.0) < 1e-12
    top = square.transform(np.eye(3), [0, 0, 2.0])
    assert abs(trivar.ruled(square, top).measure() - 4.0) < 1e-12
    sections = [square.transform(np.eye(3), [0, 0, z]) for z in (0.0, 1.0, 2.5)]
    assert abs(trivar.loft(sections, degree=2).measure() - 5.0) < 1e-10
    path = trivar.block_curve(1, 1, [1.0]).transform(np.array([[0, 0, 0], [0, 0, 0], [1.0, 0, 0]]), np.zeros(3))
    assert abs(trivar.extrude_along(square, path).measure() - 2.0) < 1e-12
    # The smoothstep morph between two parallel squares 2 apart: the same volume as the ruled one, and the
    # section at w is at height 2 b(w), b(w) = 3 w^2 - 2 w^3.
    morph = trivar.morph(square, top, smoothness=1)
    assert abs(morph.measure() - 4.0) < 1e-12
    w = np.linspace(0, 1, 11)
    z = morph(np.column_stack([np.full(11, 0.3), np.full(11, 0.6), w]))[:, 2]
    assert np.max(np.abs(z - 2 * (3 * w ** 2 - 2 * w ** 3))) < 1e-14 * 10
    swept, err = trivar.sweep(square, path)
    assert err < 1e-9 and abs(swept.measure() - 2.0) < 1e-9
    b = trivar.block([1, 1, 1], 1, [1.0, 1.0, 1.0])
    faces = []
    for axis in range(3):
        for side in (0.0, 1.0):
            # The face u_axis = side, parametrised by the other two directions in order.
            o = [d for d in range(3) if d != axis]
            A = np.zeros((3, 3))
            A[o[0], 0] = 1
            A[o[1], 1] = 1
            t = np.zeros(3)
            t[axis] = side
            faces.append(trivar.block_surface(1, 1, [1.0, 1.0]).transform(A, t))
    assert abs(trivar.coons(faces).measure() - 1.0) < 1e-12


def test_knot_vector():
    k = trivar.KnotVector(2, [0, 0, 0, 0.5, 1, 1, 1])
    assert k.degree == 2 and k.size == 4 and k.num_elements == 2 and len(k) == 7
    assert np.allclose(k.greville, [0, 0.25, 0.75, 1])
    assert np.allclose(k.breakpoints, [0, 0.5, 1])
    assert k.find_span(0.7) == 3 and k.multiplicity(1.0) == 3
    assert trivar.KnotVector.open_uniform(3, 4).num_elements == 4
    assert "degree 2" in repr(k)


def test_errors_carry_trivar_messages():
    with pytest.raises(trivar.Error, match="knot"):
        trivar.KnotVector(2, [0, 0, 1, 0.5, 1, 1])
    with pytest.raises(ValueError):
        trivar.Volume([[0, 0, 1, 1]] * 3, 1, np.zeros((7, 3)))
    v = trivar.block()
    with pytest.raises(trivar.Error, match="shape"):
        v(np.zeros((5, 2)))
    with pytest.raises(trivar.Error, match="order"):
        v.derivatives(np.zeros((1, 3)), order=-1)
    # Absurd sizes are refused up front with the memory they would need.
    with pytest.raises(trivar.Error, match="memory"):
        v.refine(10**7)


def test_long_evaluations_release_the_gil():
    import threading
    v = trivar.block([3, 3, 3], [8, 8, 8], [1.0, 1.0, 1.0])
    u = np.random.default_rng(9).uniform(0, 1, size=(2_000_000, 3))
    state = {"in_call": False, "done": False}

    def work():
        state["in_call"] = True
        v.derivatives(u, order=1, threads=1)
        state["done"] = True

    t = threading.Thread(target=work)
    ticks = 0
    t.start()
    while not state["done"]:
        if state["in_call"]:
            ticks += 1
    t.join()
    # With the GIL held for the whole C++ call this thread could not run Python code meanwhile.
    assert ticks > 1000
