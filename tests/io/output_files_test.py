#!/usr/bin/env python3
"""Reads trivar's output files with independent readers from Python's standard library (xml.etree, zlib,
struct, zipfile) and checks them against exact geometry and data:
  - .vtu (binary, zlib, appended): Bezier cells evaluated here from VTK's documented point order reproduce a
    sphere of the ball's radius and a Poisson solution close to the exact one;
  - convergence.svg: the polyline points are the CSV's values on the decade axes;
  - .3mf (ZIP with XML) and .amf: archive CRCs, well-formed XML, vertices on the sphere.
Usage: output_files_test.py TRIVAR_EXECUTABLE"""
import csv
import math
import os
import random
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
import zipfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
import read_vtu  # noqa: E402

TRIVAR = sys.argv[1]
failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)


def run(*args):
    r = subprocess.run([TRIVAR, *args], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit("trivar %s failed: %s" % (" ".join(args), r.stderr))
    return r.stdout


def binom(n, k):
    return math.comb(n, k)


def bernstein(p, i, t):
    return binom(p, i) * t ** i * (1 - t) ** (p - i)


def higher_order_nodes(p):
    """Local (i, j[, k]) of every point of a VTK Lagrange/Bezier quadrilateral or hexahedron, in VTK's order:
    corners, edge interiors (bottom edges counter-clockwise, top edges, then the vertical edges), face
    interiors (-u, +u, -v, +v, -w, +w), body; every run with the first free index fastest."""
    if len(p) == 2:
        a, b = p
        order = [(0, 0), (a, 0), (a, b), (0, b)]
        order += [(i, 0) for i in range(1, a)] + [(a, j) for j in range(1, b)]
        order += [(i, b) for i in range(1, a)] + [(0, j) for j in range(1, b)]
        order += [(i, j) for j in range(1, b) for i in range(1, a)]
        return order
    a, b, c = p
    order = [(0, 0, 0), (a, 0, 0), (a, b, 0), (0, b, 0), (0, 0, c), (a, 0, c), (a, b, c), (0, b, c)]
    for z in (0, c):
        order += [(i, 0, z) for i in range(1, a)] + [(a, j, z) for j in range(1, b)]
        order += [(i, b, z) for i in range(1, a)] + [(0, j, z) for j in range(1, b)]
    for x, y in ((0, 0), (a, 0), (a, b), (0, b)):
        order += [(x, y, k) for k in range(1, c)]
    for x in (0, a):
        order += [(x, j, k) for k in range(1, c) for j in range(1, b)]
    for y in (0, b):
        order += [(i, y, k) for k in range(1, c) for i in range(1, a)]
    for z in (0, c):
        order += [(i, j, z) for j in range(1, b) for i in range(1, a)]
    order += [(i, j, k) for k in range(1, c) for j in range(1, b) for i in range(1, a)]
    return order


class Cells:
    """The Bezier cells of one piece, evaluated at local coordinates t in [0, 1]^D."""

    def __init__(self, piece):
        self.a = {name: values for name, _, values in piece["arrays"]}
        self.comps = {name: n for name, n, _ in piece["arrays"]}
        self.n = piece["cells"]

    def cell(self, c):
        offsets = self.a["offsets"]
        begin = offsets[c - 1] if c else 0
        deg = self.a["HigherOrderDegrees"][3 * c:3 * c + 3]
        p = tuple(int(d) for d in deg if d > 0)
        return p, self.a["connectivity"][begin:offsets[c]]

    def eval(self, c, t, field=None):
        p, pts = self.cell(c)
        nodes = higher_order_nodes(p)
        check(len(nodes) == len(pts), "cell %d has %d points for degrees %s" % (c, len(pts), p))
        w = self.a.get("RationalWeights")
        x, f, den = [0.0] * 3, 0.0, 0.0
        for node, q in zip(nodes, pts):
            b = w[q] if w else 1.0
            for k, i in enumerate(node):
                b *= bernstein(p[k], i, t[k])
            den += b
            for d in range(3):
                x[d] += b * self.a["Points"][3 * q + d]
            if field:
                f += b * self.a[field][q]
        return [v / den for v in x], f / den


def check_poisson_solution(work):
    out = run("solve", "poisson", "--problem", "sine-cube", "--degree", "3", "--refine", "6", "--study", "--out",
              os.path.join(work, "s"))
    l2 = min(float(line.split("L2 error ")[1].split(",")[0]) for line in out.splitlines() if "L2 error" in line)
    pieces = read_vtu.read(os.path.join(work, "s", "solution.vtu"))
    check(len(pieces) == 1, "one piece")
    piece = pieces[0]
    check(piece["cells"] == 6 ** 3, "one cell per element: %d" % piece["cells"])
    check(piece["points"] == (3 * 6 + 1) ** 3, "Bezier points shared between elements: %d" % piece["points"])
    cells = Cells(piece)
    check(set(cells.a["types"]) == {79}, "VTK_BEZIER_HEXAHEDRON cells")
    check("RationalWeights" not in cells.a, "a polynomial geometry has no RationalWeights")
    rng = random.Random(7)
    worst = 0.0
    for c in range(0, cells.n, 7):
        t = [rng.random() for _ in range(3)]
        x, u = cells.eval(c, t, "u")
        exact = math.sin(math.pi * x[0]) * math.sin(math.pi * x[1]) * math.sin(math.pi * x[2])
        worst = max(worst, abs(u - exact))
    # On a uniform mesh of a smooth solution the pointwise error is of the order of the L2 error (unit cube);
    # the node values shown as Bezier coefficients instead would be off by O(h^2) = 3e-2.
    check(worst < 20 * l2, "solution between the nodes: error %g, L2 error %g" % (worst, l2))
    check_svg(os.path.join(work, "s"))


def check_svg(folder):
    rows = list(csv.DictReader(open(os.path.join(folder, "convergence.csv"))))
    svg = ET.parse(os.path.join(folder, "convergence.svg")).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    check(svg.tag == "{http://www.w3.org/2000/svg}svg", "SVG root")

    def ticks(cls, coord):
        group = svg.find("s:g[@class='%s']" % cls, ns)
        lines = [float(l.get(coord)) for l in group.findall("s:line", ns)]
        labels = [int(t.find("s:tspan", ns).text) for t in group.findall("s:text", ns)]
        check(all(t.text == "10" for t in group.findall("s:text", ns)), "decade labels read 10^k")
        check(len(lines) >= 2 and len(labels) >= 1, "ticks of " + cls)
        step = lines[1] - lines[0]
        check(all(abs(lines[i + 1] - lines[i] - step) < 0.02 for i in range(len(lines) - 1)), "equal decades")
        return labels[0], lines[0], step

    kx, x0, dx = ticks("x-ticks", "x1")
    ky, y0, dy = ticks("y-ticks", "y1")
    series = {g.find("s:title", ns).text: g for g in svg.findall("s:g[@class='series']", ns)}
    check(sorted(series) == ["H1 error", "L2 error"], "series %s" % sorted(series))
    legend = [t.text for t in svg.find("s:g[@class='legend']", ns).findall("s:text", ns)]
    check(sorted(legend) == sorted(series), "legend entries %s" % legend)
    for name, column in (("L2 error", "l2_error"), ("H1 error", "h1_error")):
        pts = [tuple(map(float, p.split(","))) for p in series[name].find("s:polyline", ns).get("points").split()]
        check(len(pts) == len(rows), "%s: %d points for %d rows" % (name, len(pts), len(rows)))
        for (x, y), row in zip(pts, rows):
            check(abs(x - (x0 + (math.log10(float(row["dofs"])) - kx) * dx)) < 0.01, "%s x of %s" % (name, row))
            check(abs(y - (y0 + (math.log10(float(row[column])) - ky) * dy)) < 0.01, "%s y of %s" % (name, row))


def check_ball(work):
    ball = os.path.join(work, "ball.json")
    run("make", "ball", "--radius", "2", "-o", ball)
    run("convert", ball, os.path.join(work, "ball.vtu"))
    pieces = read_vtu.read(os.path.join(work, "ball.vtu"))
    check(len(pieces) == 7, "one piece per cell of the ball: %d" % len(pieces))
    rng = random.Random(3)
    on_sphere = 0
    for index, piece in enumerate(pieces):
        cells = Cells(piece)
        check(set(cells.a.get("vcell", [index])) == {index}, "vcell of piece %d" % index)
        check("RationalWeights" in cells.a, "the ball's cells are rational")
        for c in range(cells.n):
            for _ in range(3):
                x, _ = cells.eval(c, [rng.random() for _ in range(3)])
                check(math.hypot(*x) <= 2 + 1e-12, "inside the ball: %s" % x)
            # A face whose corners lie on the sphere lies on it everywhere.
            for k in range(3):
                for side in (0.0, 1.0):
                    corners = []
                    for a in (0.0, 1.0):
                        for b in (0.0, 1.0):
                            t = [a, b]
                            t.insert(k, side)
                            corners.append(math.hypot(*cells.eval(c, t)[0]))
                    if all(abs(r - 2) < 1e-12 for r in corners):
                        on_sphere += 1
                        for _ in range(3):
                            t = [rng.random(), rng.random()]
                            t.insert(k, side)
                            r = math.hypot(*cells.eval(c, t)[0])
                            check(abs(r - 2) < 1e-12, "boundary face point at radius %.17g" % r)
    check(on_sphere >= 6, "faces on the sphere: %d" % on_sphere)
    return ball


def check_lr(work):
    lr = os.path.join(work, "box.lr")
    run("make", "box", "--lr", "--degree", "2", "--elements", "3", "3", "3", "--size", "2", "1", "1", "-o", lr)
    run("convert", lr, os.path.join(work, "box.vtu"))
    pieces = read_vtu.read(os.path.join(work, "box.vtu"))
    cells = Cells(pieces[0])
    check(cells.n == 27 and set(cells.a["types"]) == {79}, "one Bezier hexahedron per LR element")
    rng = random.Random(5)
    for c in range(cells.n):
        x, _ = cells.eval(c, [rng.random() for _ in range(3)])
        check(-1e-12 <= x[0] <= 2 + 1e-12 and all(-1e-12 <= v <= 1 + 1e-12 for v in x[1:]), "inside the box %s" % x)


def check_fit(work):
    # A terrain fitted by `trivar fit` and written as Bezier cells: evaluated here from the VTU alone, the surface
    # is the graph of the sampled function (x and y exactly, z within a few tolerances between the points).
    pts = os.path.join(work, "terrain.xyz")
    f = lambda x, y: math.sin(2 * x) * math.cos(3 * y) + 0.2 * x
    with open(pts, "w") as out:
        for j in range(41):
            for i in range(81):
                x, y = 2.0 * i / 80, 1.0 * j / 40
                out.write("%.17g %.17g %.17g\n" % (x, y, f(x, y)))
    vtu = os.path.join(work, "terrain.vtu")
    run("fit", pts, "--tolerance", "1e-3", "-o", vtu)
    cells = Cells(read_vtu.read(vtu)[0])
    check(cells.n > 0 and set(cells.a["types"]) == {77}, "one Bezier quadrilateral per LR element")
    rng = random.Random(6)
    worst = 0.0
    for c in range(cells.n):
        x, _ = cells.eval(c, [rng.random(), rng.random()])
        check(-1e-12 <= x[0] <= 2 + 1e-12 and -1e-12 <= x[1] <= 1 + 1e-12, "fit cell inside the points' box %s" % x)
        worst = max(worst, abs(x[2] - f(x[0], x[1])))
    check(worst < 5e-3, "fitted terrain within 5e-3 of the function between the points, not %g" % worst)


def vertices_on_sphere(xml_text, tag, what):
    root = ET.fromstring(xml_text)
    radii = []
    for v in root.iter():
        if v.tag.split("}")[-1] != tag:
            continue
        if tag == "vertex" and v.get("x") is not None:
            x = [float(v.get(k)) for k in "xyz"]
        else:
            coords = [e for e in v.iter() if e.tag.split("}")[-1] in ("x", "y", "z")]
            if len(coords) != 3:
                continue
            x = [float(e.text) for e in coords]
        radii.append(math.hypot(*x))
    check(len(radii) > 100, "%s: %d vertices" % (what, len(radii)))
    # Tessellation vertices are points of the exact sphere; the files keep them to print precision.
    check(all(abs(r - 2) < 1e-6 for r in radii), "%s: vertex radii in [%g, %g]" % (what, min(radii), max(radii)))


def check_am(work, ball):
    threemf = os.path.join(work, "ball.3mf")
    run("export", ball, threemf, "--tolerance", "0.05")  # a few hundred triangles
    with zipfile.ZipFile(threemf) as z:
        check(z.testzip() is None, "3MF CRCs")
        names = z.namelist()
        for name in ("[Content_Types].xml", "_rels/.rels", "3D/3dmodel.model"):
            check(name in names, "3MF part " + name)
        for name in names:
            ET.fromstring(z.read(name))  # well-formed
        vertices_on_sphere(z.read("3D/3dmodel.model"), "vertex", "3MF")
    amf = os.path.join(work, "ball.amf")
    run("export", ball, amf, "--tolerance", "0.05")
    if zipfile.is_zipfile(amf):
        with zipfile.ZipFile(amf) as z:
            check(z.testzip() is None, "AMF CRCs")
            text = z.read(z.namelist()[0])
    else:
        text = open(amf, "rb").read()
    vertices_on_sphere(text, "vertex", "AMF")


def main():
    with tempfile.TemporaryDirectory() as work:
        check_poisson_solution(work)
        ball = check_ball(work)
        check_lr(work)
        check_fit(work)
        check_am(work, ball)
    for f in failures[:20]:
        print("FAILED:", f)
    if failures:
        sys.exit(1)
    print("all output files read back")


if __name__ == "__main__":
    main()
