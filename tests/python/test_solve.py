"""Analysis: convergence rates from theory (L2 error O(h^(p+1)), H1 O(h^p)), the exact solutions evaluated
through the returned fields, eigenvalues against pi^2 (i^2 + j^2 + k^2)."""
import math
import os

import numpy as np
import pytest

import trivar
from conftest import DATA


def test_poisson_sine_cube_rates_and_field():
    a = trivar.solve_poisson("sine-cube", degree=2, refine=4)
    b = trivar.solve_poisson(problem="sine-cube", degree=2, refine=8)
    assert b.dofs > a.dofs and len(b.coefficients) >= b.dofs
    assert abs(math.log2(a.l2_error / b.l2_error) - 3) < 0.3
    assert abs(math.log2(a.h1_error / b.h1_error) - 2) < 0.3
    u = np.random.default_rng(5).uniform(0, 1, size=(200, 3))
    x = b.geometry(u)
    exact = np.prod(np.sin(math.pi * x), axis=1)
    assert np.max(np.abs(b.field(u)[:, 0] - exact)) < 2e-3


def test_poisson_on_a_user_volume_is_symmetric():
    cube = trivar.block(1, 1, [1.0, 1.0, 1.0])
    r = trivar.solve_poisson_on(cube, degree=2, refine=4)
    assert r.l2_error is None and r.dofs == 4 ** 3  # degree 2, 4 elements: 6^3 functions, 4^3 inside
    # -lap u = 1 on the unit cube, u = 0 on the boundary: symmetric about the centre, max there ~0.0562.
    c = r.field(np.array([0.5, 0.5, 0.5]))[0]
    assert abs(c - 0.05620) < 2e-3
    assert abs(r.field(np.array([0.2, 0.3, 0.5]))[0] - r.field(np.array([0.8, 0.7, 0.5]))[0]) < 1e-8
    square = trivar.block_surface(2, 2, [1.0, 1.0])
    planar = trivar.Surface(square.knots, square.degrees, square.control_points[:, :2])
    r2 = trivar.solve_poisson_on(planar, degree=2, refine=4)
    assert abs(r2.field(np.array([0.5, 0.5]))[0] - 0.07367) < 2e-3


def test_elasticity_lame_ring_displacement():
    r = trivar.solve_elasticity("lame-ring", degree=2, refine=8)
    assert r.l2_error < 1e-4 and r.field.dim == 2
    # Lame: u_r = (1 + nu)/E ((1 - 2 nu) A r + B / r), A = p a^2 / (b^2 - a^2), B = p a^2 b^2 / (b^2 - a^2).
    E, nu, p, a, b = 1000.0, 0.3, 1.0, 1.0, 2.0
    A, B = p * a * a / (b * b - a * a), p * a * a * b * b / (b * b - a * a)
    u = np.random.default_rng(6).uniform(0, 1, size=(100, 2))
    x = r.geometry(u)
    rad = np.linalg.norm(x, axis=1)
    ur = (1 + nu) / E * ((1 - 2 * nu) * A * rad + B / rad)
    disp = r.field(u)
    assert np.max(np.abs(np.sum(disp * x, axis=1) / rad - ur)) < 1e-3 * np.max(ur)
    assert trivar.solve_elasticity("lame-cylinder", degree=2, refine=2).l2_error is not None


def test_laplace_and_elastic_modes():
    r = trivar.solve_modes("cube-modes", degree=3, refine=4, modes=4)
    pi2 = math.pi ** 2
    assert np.allclose(r.values, [3 * pi2, 6 * pi2, 6 * pi2, 6 * pi2], rtol=1e-3)
    assert np.allclose(r.exact, [3 * pi2, 6 * pi2, 6 * pi2, 6 * pi2])
    assert r.vectors.shape[0] == 4
    e = trivar.solve_modes("elastic-cube-modes", degree=2, refine=3, modes=3, youngs=1000.0, poisson_ratio=0.3)
    assert np.allclose(e.values, e.exact, rtol=1e-2)
    cube = trivar.block(1, 1, [1.0, 1.0, 1.0])
    m = trivar.laplace_modes_on(cube, degree=3, refine=4, modes=1)
    assert abs(m.values[0] - 3 * pi2) < 1e-3 * 3 * pi2


def test_poisson_on_a_multipatch_model_matches_one_patch():
    # The unit cube as two glued cells solves the same problem as one patch: equal values at equal points.
    a = trivar.block(1, 1, [0.5, 1.0, 1.0])
    model = trivar.VModel([a, a.transform(np.eye(3), [0.5, 0, 0])])
    r = trivar.solve_poisson_on(model, degree=2, refine=4)
    assert len(r.fields) == 2
    # Cell 1 covers x in [0.5, 1]: its parameter (0, 0.5, 0.5) is the centre, where u ~ 0.0562.
    assert abs(r.fields[1](np.array([0.0, 0.5, 0.5]))[0] - 0.05620) < 2e-3
    # Continuity across the shared face, and the symmetry x -> 1 - x between the cells.
    w = np.random.default_rng(8).uniform(0, 1, size=(50, 2))
    left = r.fields[0](np.column_stack([np.ones(50), w]))
    right = r.fields[1](np.column_stack([np.zeros(50), w]))
    assert np.max(np.abs(left - right)) < 1e-12
    p = np.random.default_rng(9).uniform(0, 1, size=(50, 3))
    mirrored = np.column_stack([1 - p[:, 0], p[:, 1:]])
    assert np.max(np.abs(r.fields[0](p) - r.fields[1](mirrored))) < 1e-8


def test_elasticity_on_a_clamped_beam_against_timoshenko():
    # A 10 x 1 x 1 beam clamped at both ends under its unit weight along -z: Euler-Bernoulli q L^4 / (384 E I)
    # plus Timoshenko's shear term q L^2 / (8 k G A), k = 5/6.
    E, nu, L = 1000.0, 0.3, 10.0
    beam = trivar.block(1, [10, 1, 1], [L, 1.0, 1.0])
    r = trivar.solve_elasticity_on(beam, clamp=[(0, 0), (0, 1)], degree=3, refine=1, youngs=E, poisson_ratio=nu)
    bending = L ** 4 / (384 * E / 12)
    shear = L ** 2 / (8 * 5 / 6 * E / (2 * (1 + nu)))
    w = -r.field(np.array([0.5, 0.5, 0.5]))[2]
    assert abs(w - (bending + shear)) < 0.05 * (bending + shear)
    # Symmetric about the middle.
    p = np.random.default_rng(3).uniform(0, 1, size=(20, 3))
    q = np.column_stack([1 - p[:, 0], p[:, 1:]])
    assert np.max(np.abs(r.field(p)[:, 2] - r.field(q)[:, 2])) < 1e-8
    plate = trivar.block_surface(1, [4, 1], [4.0, 1.0])
    planar = trivar.Surface(plate.knots, plate.degrees, plate.control_points[:, :2])
    assert trivar.solve_elasticity_on(planar, degree=2, refine=2).field.dim == 2


def test_adaptive_lr_beats_the_uniform_rate_on_the_l_shape():
    a = trivar.solve_poisson_adaptive("l-shape", degree=2, refine=4, steps=8)
    assert len(a.dofs) == 8 and np.all(np.diff(a.dofs) > 0)
    # Uniform refinement is limited to H1 error ~ dofs^(-1/3) by the corner singularity; adaptive LR does
    # better (optimal: dofs^(-p/2) = dofs^(-1)).
    slope = np.log(a.h1_error[-1] / a.h1_error[0]) / np.log(a.dofs[-1] / a.dofs[0])
    assert slope < -0.6
    assert isinstance(a.geometry, trivar.LRSurface) and a.field.dim == 1
    # The field is the exact solution up to the error: r^(2/3) sin(2 theta / 3) at a point.
    uv = np.array([[0.3, 0.7]])
    x = a.geometry(uv)[0]
    r, t = np.hypot(*x), np.arctan2(x[1], x[0]) % (2 * np.pi)
    assert abs(a.field(uv)[0, 0] - r ** (2 / 3) * np.sin(2 * t / 3)) < 0.02
    thb = trivar.solve_poisson_adaptive("sine-square", degree=2, refine=4, steps=2, space="thb")
    assert thb.geometry is None and thb.h1_error[1] < thb.h1_error[0]


def two_cell_bar():
    a = trivar.block(1, 1, [1.0, 1.0, 1.0])
    return trivar.VModel([a, a.transform(np.eye(3), [1.0, 0, 0])])


def test_elasticity_on_a_two_material_model_is_exact():
    """An axial body force f along a bar clamped at x = 0, Poisson ratio 0: sigma = f (L - x) whatever the
    materials, u(x) = int_0^x f (L - s) / E(s) ds, piecewise quadratic, which the C0 multipatch space holds."""
    m = two_cell_bar()
    m.set_attribute("youngs_modulus", value=[1000.0], cells=[0])
    m.set_attribute("youngs_modulus", value=[250.0], cells=[1])
    r = trivar.solve_elasticity_on(m, clamp="x-", body_force=[1, 0, 0], degree=2, refine=2, poisson_ratio=0.0)
    assert len(r.fields) == 2 and r.dofs > 0 and r.coefficients.ndim == 1 and len(r.coefficients) >= r.dofs
    u = np.random.default_rng(5).uniform(0, 1, size=(50, 3))
    x = u[:, 0]
    L = 2.0
    d0 = r.fields[0](u)
    d1 = r.fields[1](u)
    assert np.max(np.abs(d0[:, 0] - (L * x - x * x / 2) / 1000)) < 1e-9
    assert np.max(np.abs(d1[:, 0] - (1.5 / 1000 + ((L * (1 + x) - (1 + x) ** 2 / 2) - 1.5) / 250))) < 1e-9
    assert np.max(np.abs(d0[:, 1:])) < 1e-9 and np.max(np.abs(d1[:, 1:])) < 1e-9
    with pytest.raises(trivar.Error, match="a side is x-"):
        trivar.solve_elasticity_on(m, clamp="w-")


def test_modes_on_models_and_patches():
    # Dirichlet Laplace on [0, 2] x [0, 1]^2: pi^2 (i^2 / 4 + j^2 + k^2) = 2.25, 3, 4.25 (x pi^2).
    r = trivar.solve_modes_on(two_cell_bar(), physics="laplace", modes=3, degree=2, refine=4)
    assert np.max(np.abs(r.values / math.pi ** 2 - [2.25, 3.0, 4.25]) / [2.25, 3.0, 4.25]) < 3e-3
    assert r.exact is None and r.vectors.shape == (3, r.vectors.shape[1])
    # A free elastic cube: six rigid-body modes at zero, then a positive pair (the cube's symmetry).
    e = trivar.solve_modes_on(trivar.block(1, 1, [1.0, 1.0, 1.0]), physics="elastic", clamp="none", modes=8, refine=2)
    assert np.max(np.abs(e.values[:6])) < 1e-8 * e.values[6] and abs(e.values[7] - e.values[6]) < 1e-8 * e.values[6]
    # A planar rectangle [0, 2] x [0, 1]: pi^2 (i^2 / 4 + j^2) = 1.25, 2.
    rect = trivar.Surface([[0, 0, 1, 1], [0, 0, 1, 1]], 1, np.array([[0, 0], [2, 0], [0, 1], [2, 1.0]]))
    p = trivar.solve_modes_on(rect, physics="laplace", modes=2, degree=3, refine=8)
    assert np.max(np.abs(p.values / math.pi ** 2 - [1.25, 2.0]) / [1.25, 2.0]) < 1e-4
    with pytest.raises(trivar.Error, match="laplace or elastic"):
        trivar.solve_modes_on(rect, physics="heat")


def square_poisson(x, y, terms=301):
    """-lap u = 1 on the unit square, u = 0 on its sides: the double sine series (odd m, n)."""
    m = np.arange(1, terms + 1, 2, dtype=float)
    sx = np.sin(np.pi * np.multiply.outer(x, m))
    sy = np.sin(np.pi * np.multiply.outer(y, m))
    c = 16 / (np.pi ** 4 * np.multiply.outer(m, m) * np.add.outer(m * m, m * m))
    return np.einsum("pm,mn,pn->p", sx, c, sy)


def unit_square(elements):
    square = trivar.block_surface(2, elements, [1.0, 1.0])
    return trivar.Surface(square.knots, square.degrees, square.control_points[:, :2])


def test_poisson_on_lr_and_hierarchical_surfaces_against_the_series():
    u = np.random.default_rng(9).uniform(0.05, 0.95, size=(60, 2))
    ref = square_poisson(u[:, 0], u[:, 1])
    lr = trivar.LRSurface(unit_square(8))
    lr.refine(elements=[0, 1, 8, 9])
    r = trivar.solve_poisson_on(lr)
    assert r.dofs < lr.num_basis and isinstance(r.field, trivar.LRSurface)
    assert np.max(np.abs(r.field(u)[:, 0] - ref)) < 2e-4
    for basis in ("thb", "hb"):
        h = trivar.HierarchicalSurface(unit_square(8), basis=basis)
        h.refine(elements=[0, 1, 8, 9])
        s = trivar.solve_poisson_on(h)
        assert isinstance(s.field, trivar.HierarchicalSurface) and s.field.num_basis == h.num_basis
        assert np.max(np.abs(s.field(u)[:, 0] - ref)) < 2e-4


def test_poisson_on_a_planar_t_spline(tmp_path):
    """The bicubic Bezier patch of bezier_patch.tsm made planar (z = 0, weights 1) is the square [0, 3]^2 with
    x = 3 s: the same space as a one-element bicubic tensor patch, so the same discrete solution."""
    lines = []
    for line in open(os.path.join(DATA, "tsm", "bezier_patch.tsm")):
        f = line.split()
        lines.append(f"0g {f[1]} {f[2]} 0 1\n" if f and f[0] == "0g" else line)
    path = tmp_path / "planar.tsm"
    path.write_text("".join(lines))
    [t] = trivar.read(str(path))
    r = trivar.solve_poisson_on(t)
    tensor = trivar.solve_poisson_on(trivar.Surface([[0, 0, 1, 1]] * 2, 1, np.array([[0, 0], [3, 0], [0, 3], [3, 3.0]])),
                                     degree=3, refine=1)
    st = np.random.default_rng(2).uniform(0, 1, size=(40, 2))
    xyu = r.field(st)
    assert isinstance(r.field, trivar.TSplineSurface) and r.dofs == tensor.dofs == 4
    assert np.max(np.abs(xyu[:, :2] - 3 * st)) < 1e-12
    assert np.max(np.abs(xyu[:, 2] - tensor.field(st)[:, 0])) < 1e-10
    # The series on [0, 3]^2: u(x, y) = 9 u_1(x / 3, y / 3); four dofs, so only a coarse match (6 % of the max).
    assert np.max(np.abs(xyu[:, 2] - 9 * square_poisson(st[:, 0], st[:, 1]))) < 0.06 * 9 * 0.0737
