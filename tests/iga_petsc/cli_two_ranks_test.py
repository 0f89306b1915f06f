#!/usr/bin/env python3
"""`mpiexec -n 2 trivar solve ... --backend petsc` against the serial CLI (the same printed errors and
eigenvalues), its parallel VTK output read back (every element in exactly one rank's piece, the index naming
each piece and declaring its arrays), and its refusals. Arguments: trivar, mpiexec, tests/support folder, and
the part to run: "tensor" (built-in problems, tensor output, refusals), "refined" (LR and hierarchical files,
the adaptive loop) or "multiblock" (multi-block models with T-joints: static problems, modes, the adaptive loop),
three tests that ctest runs side by side."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

trivar, mpiexec, support, part = sys.argv[1:5]
sys.path.insert(0, support)
import read_vtu  # noqa: E402

env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def run(args, ranks=None, timeout=120, quiet=False):
    launcher = [mpiexec, "-n", str(ranks), "--oversubscribe"] + (["--quiet"] if quiet else [])
    cmd = (launcher + [trivar] if ranks else [trivar]) + args
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=timeout)


def numbers(out, pattern):
    return re.findall(pattern, out)


thb_file = os.path.join(support, "..", "data", "gismo", "thb_simple_leaf_boxes.xml")


def points_by_element(path, with_points=False):
    """Every point of a refined solution's .vtu keyed by (element id, parameter), and its coordinates when the
    file holds several blocks (whose element ids and parameters repeat): its coordinates and point data."""
    table = {}
    for piece in read_vtu.read(path):
        arrays = dict((name, (comps, values)) for name, comps, values in piece["arrays"])
        conn, offsets, element = arrays["connectivity"][1], arrays["offsets"][1], arrays["element"][1]
        fields = [n for n in arrays if n not in ("connectivity", "offsets", "types", "element", "support",
                                                 "HigherOrderDegrees", "param")]
        begin = 0
        for c, end in enumerate(offsets):
            for q in conn[begin:end]:
                param = tuple(round(x, 12) for x in arrays["param"][1][3 * q:3 * q + 3])
                key = (int(element[c]), param)
                if with_points:
                    key += tuple(round(x, 9) for x in arrays["Points"][1][3 * q:3 * q + 3])
                check(key not in table, "%s: point %s twice" % (path, key))
                table[key] = {n: arrays[n][1][arrays[n][0] * q:arrays[n][0] * (q + 1)] for n in fields}
            begin = end
    return table


def compare_refined_outputs(what, serial_vtu, petsc_out, stem, fields, blocks=False):
    pieces = [stem + "_0.vtu", stem + "_1.vtu"]
    written = sorted(f for f in os.listdir(petsc_out) if not f.startswith("."))
    check(written == sorted([stem + ".pvtu"] + pieces), "%s: wrote %s" % (what, written))
    index = ET.parse(os.path.join(petsc_out, stem + ".pvtu")).getroot()
    check([p.get("Source") for p in index.iter("Piece")] == pieces, "%s: index pieces" % what)
    declared = {a.get("Name") for a in index.find("PUnstructuredGrid/PPointData")}
    want = points_by_element(serial_vtu, blocks)
    check(set(fields) <= declared and declared - {"param"} == set(next(iter(want.values()))) - {"Points"},
          "%s: index declares %s" % (what, declared))
    got = {}
    for p in pieces:
        part = points_by_element(os.path.join(petsc_out, p), blocks)
        check(part and not set(part) & set(got), "%s: piece %s empty or overlapping" % (what, p))
        got.update(part)
    check(set(got) == set(want), "%s: %d points in the pieces, %d in the serial file" % (what, len(got), len(want)))
    keys = sorted(set(got) & set(want))
    for name in ["Points"] + fields:
        scale = max(max(abs(v) for v in want[k][name]) for k in keys)
        sign = 1.0
        if name.startswith("mode"):
            dot = sum(a * b for k in keys for a, b in zip(got[k][name], want[k][name]))
            sign = -1.0 if dot < 0 else 1.0
        worst = max(abs(sign * a - b) for k in keys for a, b in zip(got[k][name], want[k][name]))
        check(worst <= 1e-10 * scale, "%s: %s differs by %.3e (scale %.3e)" % (what, name, worst, scale))


def tensor_part():
    for args, pattern in [
        (["solve", "poisson", "--problem", "sine-cube", "--degree", "2", "--refine", "6"], r"(L2 error \S+, H1 error \S+)"),
        (["solve", "elasticity", "--problem", "lame-cylinder", "--degree", "2", "--refine", "4"],
         r"(L2 error \S+, H1 error \S+)"),
        (["solve", "modes", "--problem", "cube-modes", "--degree", "2", "--refine", "5", "--modes", "4"],
         r"(lambda \S+)"),
    ]:
        serial = run(args + ["--solver", "cholmod"])
        petsc = run(args + ["--backend", "petsc", "--pc", "mumps" if "modes" in args else "gamg"], ranks=2)
        check(serial.returncode == 0 and petsc.returncode == 0, "%s exits %d / %d: %s" % (
            args[1], serial.returncode, petsc.returncode, petsc.stderr))
        want, got = numbers(serial.stdout, pattern), numbers(petsc.stdout, pattern)
        check(want and want == got, "%s: serial %s, petsc %s" % (args[1], want, got))
        check(re.search(r"ranks 2, CPU per rank .*peak memory per rank \(MB\): \d+ \d+", petsc.stdout), "%s: no per-rank memory line" % args[1])
        check(petsc.stdout.count("dofs") == 1, "%s: rank 1 printed as well" % args[1])

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        n = 6
        r = run(["solve", "poisson", "--problem", "sine-cube", "--degree", "2", "--refine", str(n), "--backend", "petsc",
                 "--out", out], ranks=2)
        check(r.returncode == 0, "pvtu run exits %d: %s" % (r.returncode, r.stderr))
        if r.returncode == 0:
            index = ET.parse(os.path.join(out, "solution.pvtu")).getroot()
            check(index.get("type") == "PUnstructuredGrid", "pvtu type")
            sources = [p.get("Source") for p in index.iter("Piece")]
            check(sources == ["solution_0.vtu", "solution_1.vtu"], "pieces %s" % sources)
            declared = {a.get("Name") for a in index.find("PUnstructuredGrid/PPointData")}
            cells, z_ranges = 0, []
            for s in sources:
                for piece in read_vtu.read(os.path.join(out, s)):
                    cells += piece["cells"]
                    arrays = dict((name, values) for name, _, values in piece["arrays"])
                    check(declared <= set(arrays), "%s lacks arrays %s" % (s, declared - set(arrays)))
                    z = arrays["Points"][2::3]
                    z_ranges.append((min(z), max(z)))
            check(cells == n ** 3, "the pieces hold %d cells, the mesh %d elements" % (cells, n ** 3))
            check(len(z_ranges) == 2 and z_ranges[0][1] <= z_ranges[1][0] + 1e-12, "slabs overlap: %s" % z_ranges)

    # Bad input: every rank refuses together, rank 0 prints the one error line, nothing is written, no rank is left
    # waiting for the others (the timeout). The last two cases' folder holds a file trivar did not write (the last
    # names a folder inside that file, refused before solving: no output line). mpiexec
    # --quiet leaves out Open MPI's own notice of a rank's non-zero exit.
    with tempfile.TemporaryDirectory() as tmp:
        foreign = os.path.join(tmp, "foreign")
        os.makedirs(foreign)
        with open(os.path.join(foreign, "notes.txt"), "w") as f:
            f.write("not trivar's")
        for i, (args, out) in enumerate([
            (["solve", "poisson", os.path.join(tmp, "missing.json")], None),
            (["solve", "poisson", "--problem", "sine-cube", "--degree", "0"], None),
            (["solve", "modes", "--problem", "cube-modes", "--degree", "2", "--refine", "2", "--modes", "50"], None),
            (["solve", "elasticity", thb_file, "--clamp", "none"], None),
            (["solve", "elasticity", thb_file, "--clamp", "z-"], None),
            (["solve", "poisson", "--problem", "sine-cube", "--refine", "2", "--pc", "jacobi"], foreign),
            (["solve", "poisson", thb_file], os.path.join(foreign, "notes.txt", "out")),
        ]):
            out = out or os.path.join(tmp, "out%d" % i)
            try:
                r = run(args + ["--backend", "petsc", "--out", out], ranks=2, timeout=60, quiet=True)
            except subprocess.TimeoutExpired:
                check(False, "%s: the ranks hang" % args)
                continue
            lines = r.stderr.splitlines()
            check(r.returncode != 0, "%s exits 0" % args)
            check(len(lines) == 1 and lines[0].startswith("trivar: error: "), "%s: stderr %r" % (args, r.stderr))
            check(r.stdout == "", "%s: partial output %r" % (args, r.stdout))
            check(sorted(os.listdir(foreign)) == ["notes.txt"] if out.startswith(foreign) else not os.path.exists(out),
                  "%s: wrote into %s" % (args, out))


def refined_part():
    # The adaptive loop on LR and THB spaces, each step's system solved on the ranks: the same meshes and errors.
    for space in ["lr", "thb"]:
        args = ["solve", "poisson", "--problem", "l-shape", "--degree", "2", "--refine", "4", "--adaptive", "--steps", "3",
                "--space", space]
        serial = run(args + ["--solver", "cholmod"])
        petsc = run(args + ["--backend", "petsc", "--pc", "mumps"], ranks=2)
        check(serial.returncode == 0 and petsc.returncode == 0, "adaptive %s exits %d / %d: %s" % (
            space, serial.returncode, petsc.returncode, petsc.stderr))
        pattern = r"(step \d+: dofs \d+, elements \d+, L2 error \S+, H1 error \S+, estimate \S+)"
        want, got = numbers(serial.stdout, pattern), numbers(petsc.stdout, pattern)
        check(len(want) == 3 and want == got, "adaptive %s: serial %s, petsc %s" % (space, want, got))
        check(re.search(r"ranks 2, CPU per rank", petsc.stdout), "adaptive %s: no per-rank line" % space)

    # Locally refined files: the LR volume LRsplines wrote (2,684 B-splines on 2,478 elements), the THB square in
    # G+Smo's layout, and a beam refined here towards its clamped end (T-junctions). Elasticity and modes on the
    # ranks against the serial solve: the same printed digits (petsc_refined_test.cpp checks 1e-10 relative).
    lr_file = os.path.join(support, "..", "data", "io", "lr_volume_lrsplines.lr")
    work = tempfile.mkdtemp()
    beam = os.path.join(work, "beam.lr")
    made = run(["make", "box", "--degree", "2", "--elements", "4", "4", "4", "--size", "2", "1", "1", "-o",
                os.path.join(work, "box.json")])
    refined = run(["refine", os.path.join(work, "box.json"), "--strategy", "minspan", "--box", "0", "0", "0", "0.5", "0.5",
                   "0.5", "-o", beam])
    check(made.returncode == 0 and refined.returncode == 0, "beam.lr: %s %s" % (made.stderr, refined.stderr))
    static = r"(dofs \d+, elements \d+, max \|displacement\| coefficient \S+)"
    # With --out, the serial solution.vtu / modes.vtu against the ranks' solution.pvtu / modes.pvtu: every element
    # in exactly one piece, the index naming the pieces, and at every point the coordinates and the fields of the
    # serial file to 1e-10 (the mode shapes of simple eigenvalues, up to their sign; the beam's lowest two are a
    # pair, its square cross-section bends alike in y and z). The LR volume's 89,208 output points would take the
    # reader here longer than the solves: the beam covers LR volumes.
    for args, pattern, stem, fields in [
        (["solve", "elasticity", beam, "--clamp", "x-"], static, "solution", ["displacement"]),
        (["solve", "modes", beam, "--clamp", "x-", "--modes", "3"], r"omega\^2 (\S+)", "modes", []),
        (["solve", "modes", lr_file, "--physics", "laplace", "--modes", "3"], r"lambda (\S+)", None, []),
        (["solve", "modes", thb_file, "--physics", "laplace", "--modes", "4"], r"lambda (\S+)", "modes", ["mode_1"]),
        (["solve", "elasticity", thb_file, "--clamp", "x-"], static, "solution", ["displacement"]),
        (["solve", "poisson", thb_file], r"(dofs \d+, elements \d+, max \|u\| coefficient \S+)", "solution", ["u"]),
    ]:
        serial_out, petsc_out = os.path.join(work, "serial"), os.path.join(work, "petsc")
        serial = run(args + ["--solver", "cholmod"] + (["--out", serial_out] if stem else []))
        petsc = run(args + ["--backend", "petsc", "--pc", "mumps"] + (["--out", petsc_out] if stem else []), ranks=2)
        check(serial.returncode == 0 and petsc.returncode == 0, "%s exits %d / %d: %s %s" % (
            args[1:3], serial.returncode, petsc.returncode, serial.stderr, petsc.stderr))
        want, got = numbers(serial.stdout, pattern), numbers(petsc.stdout, pattern)
        check(want and want == got, "%s: serial %s, petsc %s" % (args[1:3], want, got))
        if stem and serial.returncode == 0 and petsc.returncode == 0:
            compare_refined_outputs(args[1:3], os.path.join(serial_out, stem + ".vtu"), petsc_out, stem, fields)
        shutil.rmtree(serial_out, ignore_errors=True)
        shutil.rmtree(petsc_out, ignore_errors=True)
    shutil.rmtree(work)

    r = run(["solve", "poisson", "tensor.tsm", "--backend", "petsc"], ranks=2)
    check(r.returncode != 0 and "T-splines" in r.stderr, "T-spline with petsc: %d %s" % (r.returncode, r.stderr))


def write_l_shape_blocks(path):
    """The L-shaped domain [-1, 1]^2 minus [0, 1] x [-1, 0] as three biquadratic blocks in one .g2 file: the left
    column [-1, 0] x [-1, 1] and, on the upper half of its right side, [0, 1] x [0, 1/2] and [0, 1] x [1/2, 1]
    (T-joints at (0, 0) and (0, 1/2)), with 3, 2 and 4 elements per direction (no interface matches)."""
    with open(path, "w") as f:
        for (x0, y0), (w, h), n in [((-1, -1), (1, 2), 3), ((0, 0), (1, 0.5), 2), ((0, 0.5), (1, 0.5), 4)]:
            knots = [0, 0, 0] + [i / n for i in range(1, n)] + [1, 1, 1]
            greville = [(knots[i + 1] + knots[i + 2]) / 2 for i in range(n + 2)]
            f.write("200 1 0 0\n2 0\n")
            for _ in range(2):
                f.write("%d 3\n%s\n" % (n + 2, " ".join(repr(k) for k in knots)))
            for b in greville:
                for a in greville:
                    f.write("%r %r\n" % (x0 + w * a, y0 + h * b))


def agree(want, got, rel):
    """The numbers of two lists of matched strings agree to `rel` relative to the largest of them."""
    def values(matches):
        text = " ".join(" ".join(m) if isinstance(m, tuple) else m for m in matches)
        return [float(x) for x in re.findall(r"-?\d[\d.]*(?:e[-+]?\d+)?", text)]
    a, b = values(want), values(got)
    scale = max([abs(x) for x in a] + [1e-300])
    return bool(a) and len(a) == len(b) and all(abs(x - y) <= rel * max(abs(x), 1e-3 * scale) for x, y in zip(a, b))


def multiblock_part():
    # The three-block L-shape with T-joints solved on the ranks against the serial solve: the same printed digits,
    # and the ranks' .pvtu pieces against the serial .vtu at every point (keys include the coordinates: element ids
    # and parameters repeat from block to block). Then the adaptive loop on the ranks: the same steps.
    work = tempfile.mkdtemp()
    blocks = os.path.join(work, "l_shape.g2")
    write_l_shape_blocks(blocks)
    static = r"dofs (\d+), max \S+ (\S+), mean \S+ (\S+),"
    for args, pattern, stem, fields in [
        (["solve", "poisson", blocks], static, "solution", ["u"]),
        (["solve", "elasticity", blocks, "--clamp", "y-"], static, "solution", ["displacement"]),
        (["solve", "modes", blocks, "--physics", "laplace", "--modes", "3"], r"lambda (\S+)", "modes", ["mode_1"]),
    ]:
        serial_out, petsc_out = os.path.join(work, "serial"), os.path.join(work, "petsc")
        serial = run(args + ["--solver", "cholmod", "--out", serial_out])
        petsc = run(args + ["--backend", "petsc", "--pc", "mumps", "--out", petsc_out], ranks=2)
        check(serial.returncode == 0 and petsc.returncode == 0, "%s exits %d / %d: %s %s" % (
            args[1], serial.returncode, petsc.returncode, serial.stderr, petsc.stderr))
        want, got = numbers(serial.stdout, pattern), numbers(petsc.stdout, pattern)
        check(agree(want, got, 1e-9), "%s: serial %s, petsc %s" % (args[1], want, got))
        check("T-joints" in petsc.stdout and petsc.stdout.count("multi-block") == 1, "%s: %s" % (args[1], petsc.stdout))
        check(re.search(r"ranks 2, CPU per rank", petsc.stdout), "%s: no per-rank line" % args[1])
        if serial.returncode == 0 and petsc.returncode == 0:
            compare_refined_outputs(args[1], os.path.join(serial_out, stem + ".vtu"), petsc_out, stem, fields, True)
        shutil.rmtree(serial_out, ignore_errors=True)
        shutil.rmtree(petsc_out, ignore_errors=True)
    # GAMG (iterative, to 1e-10) against the direct solve: the same numbers to the printed digits.
    gamg = run(["solve", "poisson", blocks, "--backend", "petsc"], ranks=2)
    direct = run(["solve", "poisson", blocks, "--solver", "cholmod"])
    check(agree(numbers(direct.stdout, static), numbers(gamg.stdout, static), 1e-7),
          "gamg: %s, cholmod %s" % (gamg.stdout, direct.stdout))
    args = ["solve", "poisson", blocks, "--adaptive", "--steps", "3"]
    serial = run(args + ["--solver", "cholmod", "--out", os.path.join(work, "adaptive")])
    petsc = run(args + ["--backend", "petsc", "--pc", "mumps", "--out", os.path.join(work, "adaptive_petsc")], ranks=2)
    pattern = r"(step \d+: dofs \d+, elements \d+, estimate \S+)"
    want, got = numbers(serial.stdout, pattern), numbers(petsc.stdout, pattern)
    check(len(want) == 3 and want == got, "adaptive: serial %s, petsc %s (%s)" % (want, got, petsc.stderr))
    written = sorted(os.listdir(os.path.join(work, "adaptive_petsc"))) if petsc.returncode == 0 else []
    check([f for f in written if not f.startswith(".")] == ["convergence.csv", "convergence.svg", "mesh.vtu", "solution.vtu"],
          "adaptive petsc wrote %s" % written)
    shutil.rmtree(work)


{"tensor": tensor_part, "refined": refined_part, "multiblock": multiblock_part}[part]()
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
