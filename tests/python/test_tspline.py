"""T-spline surfaces from .tsm files: values against the rational Bezier patch the file's grips define
(Bernstein polynomials in NumPy), derivatives against finite differences, the partition of unity and the
analysis-suitability of a tensor T-mesh, tessellation points on the surface, round trips through every format,
and a model with star points evaluated per face."""
import math
import os

import numpy as np
import pytest

import trivar
from conftest import DATA

PATCH = os.path.join(DATA, "tsm", "bezier_patch.tsm")
STAR = os.path.join(DATA, "tsm", "star_cube.tsm")


def grips(path):
    """The 4 x 4 control net of the file's grips `0g x y z w`: the net index is (x, y) itself."""
    P = np.zeros((4, 4, 3))
    W = np.zeros((4, 4))
    for line in open(path):
        f = line.split()
        if f and f[0] == "0g":
            x, y, z, w = map(float, f[1:5])
            P[int(x), int(y)] = (x, y, z)
            W[int(x), int(y)] = w
    return P, W


def bernstein3(t):
    t = np.asarray(t)[:, None]
    k = np.arange(4)[None, :]
    return np.array([1, 3, 3, 1])[None, :] * t ** k * (1 - t) ** (3 - k)


def rational_patch(P, W, uv):
    Bs, Bt = bernstein3(uv[:, 0]), bernstein3(uv[:, 1])
    num = np.einsum("ni,nj,ijc,ij->nc", Bs, Bt, P, W)
    den = np.einsum("ni,nj,ij->n", Bs, Bt, W)
    return num / den[:, None]


def test_bezier_patch_against_bernstein(rng):
    [t] = trivar.read(PATCH)
    assert isinstance(t, trivar.TSplineSurface) and t.has_layers and t.star_points == 0
    assert t.degrees == [3, 3] and t.num_basis == 16 and t.num_faces == 1 and t.units == "1 millimeters"
    assert np.allclose(t.domain, [[0, 1], [0, 1]]) and t.elements.shape == (1, 2, 2)
    assert "TSM" in t.format and "16 blending functions" in repr(t)
    P, W = grips(PATCH)
    assert W.max() == 2.0  # one weight off 1: a rational patch
    uv = rng.uniform(0, 1, size=(400, 2))
    assert np.max(np.abs(t(uv) - rational_patch(P, W, uv))) < 1e-12
    assert np.max(np.abs(t.evaluate(uv, threads=1) - rational_patch(P, W, uv))) < 1e-12
    assert t(uv[0]).shape == (3,)
    # Outside the T-faces: NaN.
    assert np.all(np.isnan(t(np.array([[1.5, 0.5]]))))
    assert np.all(np.isnan(t.derivatives(np.array([[0.5, -0.1]]))))


def test_derivatives_against_finite_differences(rng):
    [t] = trivar.read(PATCH)
    P, W = grips(PATCH)
    uv = rng.uniform(0.05, 0.95, size=(50, 2))
    d = t.derivatives(uv)
    assert d.shape == (50, 3, 3) and t.derivatives(uv[0]).shape == (3, 3)
    assert np.max(np.abs(d[:, 0] - rational_patch(P, W, uv))) < 1e-12
    h = 1e-6
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        fd = (rational_patch(P, W, uv + e) - rational_patch(P, W, uv - e)) / (2 * h)
        assert np.max(np.abs(d[:, 1 + k] - fd)) < 1e-7


def test_partition_of_unity_and_classification():
    [t] = trivar.read(PATCH)
    pu = t.partition_of_unity
    assert pu.max_defect < 1e-14 and pu.elements_off == 0
    assert abs(pu.min_sum - 1) < 1e-14 and abs(pu.sampled_max - 1) < 1e-14
    c = t.classify()
    # A single Bezier face: no T-junctions, analysis-suitable, standard; the weight 2 makes sum w B != 1.
    assert c.t_junctions == 0 and c.analysis_suitable and c.dual_compatible and c.standard
    assert not c.semi_standard and c.linear_independence == "independent"
    assert t.analysis_suitable
    i = t.info()
    assert i["t_image"]["faces"] == 1 and i["t_image"]["vertices"] == 4 and i["t_connect_nodes"] == 16
    assert i["units"] == "1 millimeters" and i["tolerance"] == 1e-5 and i["star_points"] == 0
    assert i["repeated_knot_nodes"] == 12 and i["skipped_records"] == {"100001uv": 1}


def test_tessellation_points_lie_on_the_surface():
    [t] = trivar.read(PATCH)
    m = t.tessellate(tolerance=1e-2)
    assert m.vertices.shape[1] == 3 and m.triangles.shape[1] == 3 and len(m.triangles) > 8
    assert m.tolerance == 1e-2 and m.triangles.max() < len(m.vertices)
    assert np.max(np.abs(t(m.params) - m.vertices)) < 1e-12
    # The triangles cover the parameter square once: their (s, t) areas sum to 1.
    a, b, c = (m.params[m.triangles[:, i]] for i in range(3))
    area = 0.5 * ((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    assert np.all(area > 0) and abs(area.sum() - 1) < 1e-12
    # Finer tolerance, more triangles; the default is 1e-3 of the control net's diagonal.
    assert len(t.tessellate(tolerance=1e-3).triangles) > len(m.triangles)
    # At most 8 x 8 quads per element whatever the tolerance.
    assert len(t.tessellate(tolerance=1e-9, max_per_element=8).triangles) == 2 * 8 * 8
    assert abs(t.tessellate().tolerance - 1e-3 * math.dist((0, 0, -0.959), (3, 3, 0.989))) < 1e-12


@pytest.mark.parametrize("name", ["p.tsm", "p.json", "p.stp", "p42.stp", "p.vtu"])
def test_round_trips(tmp_path, rng, name):
    [t] = trivar.read(PATCH)
    path = str(tmp_path / name)
    trivar.write(path, t, step_form="part42" if name.startswith("p42") else "t-spline")
    assert os.path.getsize(path) > 0
    if name.endswith(".vtu"):
        return
    [back] = [o for o in trivar.read(path) if isinstance(o, trivar.TSplineSurface)]
    uv = rng.uniform(0, 1, size=(100, 2))
    assert np.max(np.abs(back(uv) - t(uv))) < 1e-12
    assert back.has_layers == (not name.startswith("p42"))


def test_as_lr_spline(tmp_path, rng):
    [t] = trivar.read(PATCH)
    lr = t.to_lr()
    uv = rng.uniform(0, 1, size=(100, 2))
    assert isinstance(lr, trivar.LRSurface) and lr.rational and lr.num_basis == 16
    assert np.max(np.abs(lr(uv) - t(uv))) < 1e-12
    t.write(str(tmp_path / "p.lr"))
    [back] = trivar.read(str(tmp_path / "p.lr"))
    assert np.max(np.abs(back(uv) - t(uv))) < 1e-12
    with pytest.raises(trivar.Error, match="stl"):
        t.write(str(tmp_path / "p.stl"))


def test_star_points_are_evaluated_per_face(tmp_path):
    [s] = trivar.read(STAR)
    assert s.star_points == 8 and s.num_faces > 0 and "star points" in repr(s)
    with pytest.raises(trivar.Error, match="star points"):
        s(np.array([[0.5, 0.5]]))
    uv = np.array([[0.0, 0.0], [0.5, 0.5], [1.0, 0.25]])
    d = s.evaluate_face(0, uv)
    assert d.shape == (3, 3, 3) and np.all(np.isfinite(d))
    h = 1e-6
    fd = (s.evaluate_face(0, np.array([0.5 + h, 0.5]))[0] - s.evaluate_face(0, np.array([0.5 - h, 0.5]))[0]) / (2 * h)
    assert np.max(np.abs(d[1, 1] - fd)) < 1e-6 * max(1, np.max(np.abs(fd)))
    with pytest.raises(trivar.Error, match="outside"):
        s.evaluate_face(0, np.array([1.5, 0.5]))
    m = s.tessellate(tolerance=0.05)
    assert len(m.triangles) > 100 and m.params.shape == (len(m.vertices), 2)
    assert m.params.min() >= 0 and m.params.max() <= 1
    # A closed surface of genus 0: every edge in two triangles, V - E + F = 2.
    edges = np.sort(np.concatenate([m.triangles[:, [0, 1]], m.triangles[:, [1, 2]], m.triangles[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2) and len(m.vertices) - len(unique) + len(m.triangles) == 2
    s.write(str(tmp_path / "s.tsm"))
    [back] = trivar.read(str(tmp_path / "s.tsm"))
    assert np.allclose(back.evaluate_face(0, uv), d, atol=1e-12)
    # Bezier patches: the cube's 54 faces, 24 of them at star points subdivided towards the corner.
    s.write(str(tmp_path / "s.g2"))
    patches = trivar.read(str(tmp_path / "s.g2"))
    assert len(patches) > 54 and all(list(p.degrees) == [3, 3] for p in patches)


def test_star_points_of_degree_five(tmp_path):
    """The star cube read at degree 5: every face near the star points is averaging subdivision, whose rules are
    convex combinations, so the surface lies in the box of the control points; closed as at degree 3; Bezier patches
    of degree 5."""
    path = tmp_path / "star_cube5.tsm"
    path.write_text(open(STAR).read().replace("degree 3", "degree 5", 1))
    [s] = trivar.read(str(path))
    info = s.info()
    assert info["faces_averaging"] == s.num_faces > 0
    m = s.tessellate(tolerance=0.05)
    grips = np.array([list(map(float, line.split()[1:4])) for line in open(path) if line.startswith("0g ")])
    assert np.all(m.vertices >= grips.min(axis=0) - 1e-12) and np.all(m.vertices <= grips.max(axis=0) + 1e-12)
    edges = np.sort(np.concatenate([m.triangles[:, [0, 1]], m.triangles[:, [1, 2]], m.triangles[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2) and len(m.vertices) - len(unique) + len(m.triangles) == 2
    s.write(str(tmp_path / "s.g2"))
    assert all(list(p.degrees) == [5, 5] for p in trivar.read(str(tmp_path / "s.g2")))


def test_malformed_tsm(tmp_path):
    bad = tmp_path / "bad.tsm"
    bad.write_text("#TS0200\nf 0 0\nv 7 EAST\n")
    with pytest.raises(trivar.Error, match="bad.tsm"):
        trivar.read(str(bad))


def test_fusion_torus(tmp_path):
    """A torus cage as Fusion 360 writes it (its settings, one grip per vertex, no grip map): no star point, but
    a closed strip of faces, so no global (s, t); a closed surface of genus 1; written back in Fusion's form."""
    [s] = trivar.read(os.path.join(DATA, "tsm", "fusion_torus.tsm"))
    assert s.star_points == 0 and s.num_faces == 64
    info = s.info()
    assert info["end_conditions"] == "SUBD_CREASES" and info["star_knot_rule"] == "NURCCS"
    assert info["faces_exact"] == 64 and info["behavior_version"] == "14.2.0"
    m = s.tessellate(tolerance=0.05)
    edges = np.sort(np.concatenate([m.triangles[:, [0, 1]], m.triangles[:, [1, 2]], m.triangles[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2) and len(m.vertices) - len(unique) + len(m.triangles) == 0
    s.write(str(tmp_path / "t.tsm"))
    text = open(tmp_path / "t.tsm").read()
    assert "end-conditions SUBD_CREASES" in text and "\n0m " not in text
    [back] = trivar.read(str(tmp_path / "t.tsm"))
    uv = np.array([[0.0, 0.0], [0.3, 0.7], [1.0, 1.0]])
    for f in (0, 27, 63):
        assert np.array_equal(back.evaluate_face(f, uv), s.evaluate_face(f, uv))


def test_fusion_sharp_creases(tmp_path):
    """A box cage (3 x 3 faces per side, points moved off the cube) as Fusion 360 writes it with its twelve edges
    marked `ec` (sharp creases, 36 edges): six open patches meeting at the creases, evaluated per face; the
    triangles share the creases' points (a closed surface of genus 0); written back with the ec records."""
    [s] = trivar.read(os.path.join(DATA, "tsm", "fusion_creased_box.tsm"))
    info = s.info()
    assert info["crease_edges"] == 36 and info["star_points"] == 8 and s.num_faces == 54
    m = s.tessellate(tolerance=0.01)
    edges = np.sort(np.concatenate([m.triangles[:, [0, 1]], m.triangles[:, [1, 2]], m.triangles[:, [2, 0]]]), axis=1)
    unique, counts = np.unique(edges, axis=0, return_counts=True)
    assert np.all(counts == 2) and len(m.vertices) - len(unique) + len(m.triangles) == 2
    # The cube corner at (-1, -1, -1) is interpolated by the three faces there (sharp corners).
    uv = np.array([[0.0, 0.0]])
    assert np.allclose(s.evaluate_face(0, uv)[0][0], [-1.0141120008059867, -0.92999999999999994, -1.05], atol=1e-14)
    s.write(str(tmp_path / "c.tsm"))
    text = open(tmp_path / "c.tsm").read()
    assert text.count("\nec ") == 36
    [back] = trivar.read(str(tmp_path / "c.tsm"))
    uv = np.array([[0.0, 0.0], [0.3, 0.7], [1.0, 1.0]])
    for f in (0, 20, 53):
        assert np.array_equal(back.evaluate_face(f, uv), s.evaluate_face(f, uv))


def corner_counts(s):
    """The number of faces whose corner each distinct corner point of the faces as given is, sorted."""
    corners = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    points = np.concatenate([s.evaluate_face(f, corners)[:, 0] for f in range(s.num_faces)])
    return sorted(np.unique(np.round(points, 9), axis=0, return_counts=True)[1].tolist())


def test_stepped_box_faces_as_given():
    """Fusion's box with a strip of faces at interval 1.02 (star points 3 edges apart) is refined by two global
    non-uniform Catmull-Clark steps before it is evaluated; evaluate_face still takes the file's 54 faces: their
    corners are the limit points of the file's 56 vertices (3 faces at each of the 8 star points, 4 elsewhere), and
    the derivatives are d/du, d/dv of the face as given (central differences)."""
    [s] = trivar.read(os.path.join(DATA, "tsm", "fusion", "a3_box3_inconsistent_knot3_readback.tsm"))
    info = s.info()
    assert s.num_faces == 54 and info["global_steps"] == 2 and info["star_points"] == 8
    assert corner_counts(s) == [3] * 8 + [4] * 48
    h = 1e-6
    uv = np.array([[0.3, 0.7], [0.61, 0.2]])
    for f in (0, 17, 53):
        d = s.evaluate_face(f, uv)
        du = (s.evaluate_face(f, uv + [h, 0])[:, 0] - s.evaluate_face(f, uv - [h, 0])[:, 0]) / (2 * h)
        dv = (s.evaluate_face(f, uv + [0, h])[:, 0] - s.evaluate_face(f, uv - [0, h])[:, 0]) / (2 * h)
        assert np.allclose(d[:, 1], du, atol=1e-6) and np.allclose(d[:, 2], dv, atol=1e-6)
    with pytest.raises(Exception, match="no face 54"):
        s.evaluate_face(54, uv)


def test_t_junction_lines_near_star_points():
    """Fusion's box with its top centre face split 2 x 2 has T-junctions next to the star points' faces: their two
    lines are completed round the box first (knot insertion along the rows they cross), then two global steps;
    evaluate_face takes the file's 57 faces, whose corners are its 61 vertices (3 faces at each star point, 2 at each
    T-junction, which lies on the side of its third face)."""
    [s] = trivar.read(os.path.join(DATA, "tsm", "fusion", "a3_box3_tjunc_ring2_readback.tsm"))
    info = s.info()
    assert s.num_faces == 57 and info["t_junction_lines"] == 2 and info["global_steps"] == 2
    assert corner_counts(s) == [2] * 4 + [3] * 8 + [4] * 49
