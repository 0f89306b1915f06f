"""Files by extension: round trips of every format trivar writes, files written by other tools (G+Smo, a CAD
system's STEP, LRsplines) checked against closed forms, and STEP B-rep import against OpenCASCADE's volume."""
import math
import os
import struct

import numpy as np
import pytest

import trivar
from conftest import DATA
from step_box import box_step


@pytest.fixture
def volume():
    rng = np.random.default_rng(11)
    v = trivar.block([2, 3, 1], [2, 3, 2], [1.0, 2.0, 3.0])
    return trivar.Volume(v.knots, v.degrees, v.control_points + 0.05 * rng.normal(size=v.control_points.shape),
                         rng.uniform(0.5, 2.0, size=len(v.control_points)))


@pytest.mark.parametrize("ext", [".json", ".g2", ".xml", ".stp"])
def test_tensor_round_trip(tmp_path, volume, ext):
    path = str(tmp_path / ("v" + ext))
    trivar.write(path, volume)
    (back,) = trivar.read(path)
    u = np.random.default_rng(1).uniform(0, 1, size=(100, 3))
    assert isinstance(back, trivar.Volume) and back.rational
    assert np.max(np.abs(back(u) - volume(u))) < 1e-13


def test_several_objects_and_vtu(tmp_path, volume):
    c = trivar.circle_arc()
    trivar.write(str(tmp_path / "both.json"), [c, volume])
    objs = trivar.read(str(tmp_path / "both.json"))
    assert [type(o).__name__ for o in objs] == ["Curve", "Volume"]
    trivar.write(str(tmp_path / "v.vtu"), [volume])
    assert b'<VTKFile type="UnstructuredGrid"' in (tmp_path / "v.vtu").read_bytes()[:300]


@pytest.mark.parametrize("ext", [".lr", ".g2", ".json", ".stp"])
def test_lr_round_trip(tmp_path, volume, ext):
    lr = trivar.LRVolume(volume)
    lr.refine(elements=[1, 4])
    path = str(tmp_path / ("lr" + ext))
    trivar.write(path, [lr])
    (back,) = trivar.read(path)
    assert isinstance(back, trivar.LRVolume)
    assert back.num_basis == lr.num_basis and back.num_elements == lr.num_elements
    u = np.random.default_rng(2).uniform(0, 1, size=(100, 3))
    assert np.max(np.abs(back(u) - lr(u))) < 1e-12


def test_vmodel_files(tmp_path):
    ball = trivar.ball(radius=1.0)
    ball.set_attribute("material", expression=["1 - z", "z"])
    ball.materials = ["a", "b"]
    trivar.write(str(tmp_path / "ball.json"), ball)
    (back,) = trivar.read(str(tmp_path / "ball.json"))
    assert isinstance(back, trivar.VModel) and back.num_cells == 7 and back.materials == ["a", "b"]
    assert abs(back.volume() - ball.volume()) < 1e-14
    trivar.write(str(tmp_path / "ball.stl"), ball, tolerance=0.01)
    with open(tmp_path / "ball.stl", "rb") as f:
        data = f.read()
    (count,) = struct.unpack_from("<I", data, 80)
    assert len(data) == 84 + 50 * count
    assert count == len(ball.tessellate(tolerance=0.01).triangles)
    trivar.write(str(tmp_path / "ball.vtu"), ball)
    assert b'<VTKFile type="UnstructuredGrid"' in (tmp_path / "ball.vtu").read_bytes()[:300]


def test_gismo_quarter_annulus():
    (s,) = trivar.read(os.path.join(DATA, "gismo", "quarter_annulus_nurbs.xml"))
    assert isinstance(s, trivar.Surface) and s.rational
    assert abs(s.measure() - 3 * math.pi / 4) < 1e-12
    t = np.linspace(0, 1, 101)
    for v, r in ((0.0, 1.0), (1.0, 2.0)):
        x = s(np.column_stack([t, np.full_like(t, v)]))
        assert np.max(np.abs(np.linalg.norm(x[:, :2], axis=1) - r)) < 1e-14 * 10


def test_step_circle_from_a_cad_file():
    (c,) = trivar.read(os.path.join(DATA, "step", "geometry", "quarter_circle.stp"))
    x = c(np.linspace(*c.domain[0], 200))
    assert np.max(np.abs(np.linalg.norm(x - [1, 0, 0], axis=1) - 2.0)) < 1e-14 * 10


def test_step_brep_import_of_a_box(tmp_path):
    path = tmp_path / "box.stp"
    path.write_text(box_step(2.0, 3.0, 5.0))
    (solid,) = trivar.import_step(str(path), kernel_volume=True)
    m = solid.model
    assert m.trimmed and m.num_cells == 1
    # The exact volume, and OpenCASCADE's (another kernel's) reading of the same file.
    assert abs(m.volume() - 30.0) < 1e-9 and abs(solid.kernel_volume - 30.0) < 1e-6
    # Six faces that close: the integral of the normal vanishes, the area is the box's 62.
    c = solid.closure
    assert c.closed and c.norm < 1e-12 * c.area and abs(c.area - 62.0) < 1e-9 and len(c.area_vector) == 3
    t = m.tessellate()
    assert t.watertight and abs(t.volume - 30.0) < 1e-9
    s = m.slice(layer_thickness=1.0, dpi=[25.4], z_range=[0.0, 5.0])
    # 1 mm pixels: every layer holds the 2 x 3 section, 6 pixels.
    assert s.cell.shape[0] == 5 and all(int((s.cell[k] >= 0).sum()) == 6 for k in range(5))


def test_file_errors(tmp_path, volume):
    with pytest.raises(trivar.Error, match=r"\.xyz"):
        trivar.write(str(tmp_path / "v.xyz"), volume)
    assert not os.path.exists(tmp_path / "v.xyz")
    with pytest.raises(trivar.Error, match="g2_bad_knots"):
        trivar.read(os.path.join(DATA, "io", "malformed", "g2_bad_knots.g2"))
    with pytest.raises(trivar.Error, match="cannot write"):
        trivar.write(str(tmp_path / "x.json"), [1, 2])
    with pytest.raises(trivar.Error, match="STEP"):
        trivar.write(str(tmp_path / "mixed.json"), [volume, trivar.LRVolume(volume)])


def test_graded_mesh_files(tmp_path):
    import zipfile

    ball = trivar.ball(radius=1.0)
    ball.set_attribute("material", expression=["0.5 - z/2", "0.5 + z/2"])
    t = ball.tessellate(tolerance=0.05)
    f = np.vstack([ball.attribute(c, "material", t.params[t.cell == c]) for c in range(ball.num_cells)])
    order = np.concatenate([np.nonzero(t.cell == c)[0] for c in range(ball.num_cells)])
    fractions = np.empty_like(f)
    fractions[order] = f
    # The fractions at each vertex follow the formula of its z.
    assert np.allclose(fractions[:, 1], 0.5 + t.vertices[:, 2] / 2, atol=1e-12)
    trivar.write_mesh(str(tmp_path / "ball.3mf"), t.vertices, t.triangles, ["a", "b"], fractions)
    with zipfile.ZipFile(tmp_path / "ball.3mf") as z:
        model = z.read("3D/3dmodel.model").decode()
    assert model.count("<vertex ") == len(t.vertices) and model.count("<triangle ") == len(t.triangles)
    trivar.write_mesh(str(tmp_path / "ball.amf"), t.vertices, t.triangles, ["a", "b"], formulas=["0.5 - z/2", "0.5 + z/2"])
    text = (tmp_path / "ball.amf").read_text()
    assert text.count("<triangle>") == len(t.triangles) and "0.5 + z/2" in text
    trivar.write_mesh(str(tmp_path / "ball.stl"), t.vertices, t.triangles)
    assert (tmp_path / "ball.stl").stat().st_size == 84 + 50 * len(t.triangles)
    with pytest.raises(trivar.Error):
        trivar.write_mesh(str(tmp_path / "bad.3mf"), t.vertices, t.triangles, ["a", "b"], fractions[:-1])
    assert not (tmp_path / "bad.3mf").exists()
