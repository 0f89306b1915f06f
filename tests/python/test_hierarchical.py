"""Hierarchical (HB and THB) splines: the identity map of a hand-written G+Smo file, conversion of tensor
splines against NumPy Cox-de Boor, refinement and basis change leaving the spline unchanged to rounding,
derivatives, file round trips."""
import os

import numpy as np
import pytest

import trivar
from conftest import DATA, random_knots
from reference import tensor_eval


def test_thb_identity_from_gismo_file(rng):
    [h] = trivar.read(os.path.join(DATA, "gismo", "thb_identity_corner.xml"))
    assert isinstance(h, trivar.HierarchicalSurface)
    assert h.basis == "thb" and h.num_levels == 2 and h.degrees == [1, 1] and h.dim == 2 and not h.rational
    # 16 cells, the 4 of the corner split into 16: 12 + 16 leaves.
    assert h.num_elements == 28 and sorted(set(h.element_levels)) == [0, 1]
    assert sum(h.num_basis_per_level) == h.num_basis == 37
    assert h.coefficients.shape == (37, 2) and h.parametric_dim == 2
    u = rng.uniform(0, 1, size=(500, 2))
    assert np.max(np.abs(h(u) - u)) < 1e-14
    d = h.derivatives(u)
    assert d.shape == (500, 3, 2)
    assert np.max(np.abs(d[:, 1] - [1, 0])) < 1e-13 and np.max(np.abs(d[:, 2] - [0, 1])) < 1e-13
    e = h.elements
    assert e.shape == (28, 2, 2) and abs(np.prod(e[:, :, 1] - e[:, :, 0], axis=1).sum() - 1) < 1e-14


def random_surface(rng, degrees=(2, 3), elements=(4, 3), dim=3):
    knots = [random_knots(rng, p, n) for p, n in zip(degrees, elements)]
    counts = [len(k) - p - 1 for k, p in zip(knots, degrees)]
    points = rng.normal(size=(int(np.prod(counts)), dim))
    return trivar.Surface(knots, list(degrees), points), knots, points


@pytest.mark.parametrize("basis", ["thb", "hb"])
def test_refinement_keeps_the_surface(rng, basis):
    s, knots, points = random_surface(rng)
    h = trivar.HierarchicalSurface(s, basis=basis)
    u = rng.uniform(0, 1, size=(400, 2))
    ref = tensor_eval(knots, [2, 3], points, u)
    assert np.max(np.abs(h(u) - ref)) < 1e-12 and h.num_levels == 1 and h.basis == basis
    before = h.num_basis
    assert h.refine(elements=[0, 1, 5]) == 3
    assert h.num_levels == 2 and h.num_basis > before
    assert np.max(np.abs(h.evaluate(u, threads=1) - ref)) < 1e-12
    # A second level inside the first, by functions; then the other basis over the same hierarchy.
    fine = h.num_basis - 1
    h.refine(functions=[fine])
    assert h.num_levels == 3 and np.max(np.abs(h(u) - ref)) < 1e-12
    other = h.with_basis("hb" if basis == "thb" else "thb")
    assert other.num_basis == h.num_basis and np.max(np.abs(other(u) - ref)) < 1e-12
    # First derivatives against the tensor spline's (Cox-de Boor).
    d = h.derivatives(u[:50])
    assert np.max(np.abs(d[:, 1] - tensor_eval(knots, [2, 3], points, u[:50], orders=[1, 0]))) < 1e-9
    assert np.max(np.abs(d[:, 2] - tensor_eval(knots, [2, 3], points, u[:50], orders=[0, 1]))) < 1e-9
    with pytest.raises(trivar.Error, match="no element"):
        h.refine(elements=[10 ** 6])
    with pytest.raises(trivar.Error, match="either"):
        h.refine()
    with pytest.raises(trivar.Error, match="hb or thb"):
        trivar.HierarchicalSurface(s, basis="lr")


def test_admissible_volume_refinement_and_files(rng, tmp_path):
    knots = [random_knots(rng, 2, 3) for _ in range(3)]
    counts = [len(k) - 3 for k in knots]
    points = rng.normal(size=(int(np.prod(counts)), 3))
    v = trivar.Volume(knots, 2, points)
    h = trivar.HierarchicalVolume(v)
    u = rng.uniform(0, 1, size=(200, 3))
    ref = tensor_eval(knots, [2, 2, 2], points, u)
    h.refine(elements=[0])
    corner = int(np.argmin(np.sum(h.elements[:, :, 0], axis=1) + 10 * (h.element_levels != 1)))
    h.refine(elements=[corner], admissible=2)
    assert h.num_levels == 3 and np.max(np.abs(h(u) - ref)) < 1e-12
    assert "HierarchicalVolume thb" in repr(h)
    path = str(tmp_path / "h.xml")
    trivar.write(path, [v, h])
    back = trivar.read(path)
    assert isinstance(back[0], trivar.Volume) and isinstance(back[1], trivar.HierarchicalVolume)
    assert back[1].num_basis == h.num_basis and np.max(np.abs(back[1](u) - ref)) < 1e-12
    trivar.write(str(tmp_path / "h.vtu"), h)
    trivar.write(str(tmp_path / "h.stp"), [h])
    assert os.path.getsize(tmp_path / "h.vtu") > 0 and os.path.getsize(tmp_path / "h.stp") > 0
    # STEP holds the HB form as a Part 42 locally refined volume, read back only when it is an LR spline too
    # (HB B-splines of a local refinement do not sum to one): refused with the reader's reason.
    with pytest.raises(trivar.Error, match="sum to one"):
        trivar.read(str(tmp_path / "h.stp"))
    # Refined everywhere, the HB basis is a tensor one: it reads back as an LR volume with the same values.
    full = trivar.HierarchicalVolume(v, basis="hb")
    full.refine(elements=list(range(full.num_elements)))
    trivar.write(str(tmp_path / "full.stp"), full)
    [lr] = trivar.read(str(tmp_path / "full.stp"))
    assert isinstance(lr, trivar.LRVolume) and lr.num_basis == full.num_basis and np.max(np.abs(lr(u) - ref)) < 1e-12
    with pytest.raises(trivar.Error, match="hierarchical"):
        trivar.write(str(tmp_path / "h.lr"), h)
