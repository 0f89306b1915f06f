"""LR splines: exact conversion, refinement keeping the geometry, and a file written by SINTEF's LRsplines
evaluated here from its text by local Cox-de Boor."""
import os

import numpy as np
import pytest

import trivar
from conftest import DATA
from reference import local_bsplines, read_lrsplines_volume


def test_lrsplines_file_against_its_own_basis(rng):
    path = os.path.join(DATA, "io", "lr_volume_lrsplines.lr")
    (lr,) = trivar.read(path)
    assert isinstance(lr, trivar.LRVolume)
    degrees, knots, coefs, gammas = read_lrsplines_volume(path)
    assert lr.num_basis == len(coefs) == 2684 and lr.degrees == degrees
    u = rng.uniform(0.01, 0.99, size=(40, 3))
    B = np.ones((len(u), len(coefs)))
    for k in range(3):
        B *= local_bsplines(knots[k], degrees[k], u[:, k])
    assert np.allclose(B @ gammas, 1.0, atol=1e-12)  # partition of unity
    ref = (B * gammas) @ coefs
    assert np.max(np.abs(lr(u) - ref)) < 1e-12


def test_conversion_and_refinement_keep_the_geometry(rng):
    v = trivar.block([2, 2, 2], [3, 3, 3], [1.0, 2.0, 3.0]).transform(np.array([[1.0, 0.3, 0], [0, 1, 0], [0.2, 0, 1]]), np.zeros(3))
    lr = trivar.LRVolume(v)
    u = rng.uniform(0, 1, size=(300, 3))
    assert np.max(np.abs(lr(u) - v(u))) < 1e-13
    assert lr.num_basis == 125 and lr.num_elements == 27
    d = lr.derivatives(u)
    assert d.shape == (300, 4, 3)
    assert np.max(np.abs(d - v.derivatives(u, order=1))) < 1e-12
    changed = lr.refine(elements=[0, 13], strategy="minspan")
    assert changed > 0 and lr.num_elements > 27 and lr.num_basis > 125
    assert np.max(np.abs(lr(u) - v(u))) < 1e-12
    lr.refine(functions=[0], strategy="structured")
    assert np.max(np.abs(lr(u) - v(u))) < 1e-12
    assert lr.check_independence("peeling") in ("independent", "not_tested")
    assert lr.check_independence("exact") == "independent"
    e = lr.elements
    assert e.shape == (lr.num_elements, 3, 2)
    # The elements tile the domain: their volumes sum to 1.
    assert abs(np.sum(np.prod(e[:, :, 1] - e[:, :, 0], axis=1)) - 1.0) < 1e-12
    assert set(lr.element_support(0)) and "LRVolume" in repr(lr)
    # Partition of unity: the scaled B-splines of every element sum to one (gammas of the converted
    # tensor B-splines are 1, split ones below).
    assert np.all(lr.gammas > 0) and np.all(lr.gammas <= 1) and lr.gammas.min() < 1
    assert lr.num_meshrects > 8


def test_lr_surface_fullspan():
    s = trivar.block_surface(2, 4, [1.0, 1.0])
    lr = trivar.LRSurface(s)
    assert lr.refine(elements=[5]) >= 1
    # The refined spline still sums to one with its gammas: constant geometry reproduced.
    uv = np.random.default_rng(3).uniform(0, 1, size=(100, 2))
    assert np.max(np.abs(lr(uv) - s(uv))) < 1e-13
    with pytest.raises(trivar.Error):
        lr.refine(elements=[0], strategy="sideways")
    with pytest.raises(trivar.Error, match="either"):
        lr.refine()


def test_lr_volume_from_raw_arrays(rng):
    """The LRsplines file's B-splines parsed here (local knots, coefficients, gammas) build the same volume."""
    path = os.path.join(DATA, "io", "lr_volume_lrsplines.lr")
    degrees, knots, coefs, gammas = read_lrsplines_volume(path)
    lr = trivar.LRVolume(degrees, knots, coefs, gammas)
    (ref,) = trivar.read(path)
    assert lr.num_basis == ref.num_basis and lr.num_elements == ref.num_elements and not lr.rational
    u = rng.uniform(0, 1, size=(200, 3))
    assert np.max(np.abs(lr(u) - ref(u))) < 1e-12
    # Properties give the arrays back (in the spline's id order): they rebuild it again.
    again = trivar.LRVolume(lr.degrees, lr.knots, lr.coefficients, lr.gammas)
    assert [k.shape for k in lr.knots] == [(2684, p + 2) for p in degrees] and lr.coefficients.shape == (2684, 3)
    assert np.max(np.abs(again(u) - ref(u))) < 1e-12
    # B-splines that do not sum to one are refused with the library's message.
    with pytest.raises(trivar.Error):
        trivar.LRVolume(degrees, knots, coefs, np.ones(len(gammas)))
    with pytest.raises(trivar.Error, match="knots"):
        trivar.LRVolume(degrees, knots[:2], coefs)


def test_rational_lr_surface_from_arrays(rng):
    """A quarter circle as one rational B-spline patch, given as LR B-splines with homogeneous coefficients."""
    s = 1 / np.sqrt(2)
    # Degree 2 x 1: (1, 0), (1, 1) w = s, (0, 1) at radius 1 and 2.
    T = np.array([[0, 0, 0, 1], [0, 0, 1, 1], [0, 1, 1, 1]] * 2, dtype=float)
    V = np.array([[0, 0, 1]] * 3 + [[0, 1, 1]] * 3, dtype=float)
    xyw = []
    for r in (1.0, 2.0):
        xyw += [[r, 0, 1], [r * s, r * s, s], [0, r, 1]]
    lr = trivar.LRSurface([2, 1], [T, V], np.array(xyw), rational=True)
    assert lr.rational and lr.dim == 2
    uv = rng.uniform(0, 1, size=(300, 2))
    x = lr(uv)
    assert np.max(np.abs(np.linalg.norm(x, axis=1) - (1 + uv[:, 1]))) < 1e-14
