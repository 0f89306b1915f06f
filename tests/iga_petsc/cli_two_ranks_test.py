#!/usr/bin/env python3
"""`mpiexec -n 2 trivar solve ... --backend petsc` against the serial CLI (the same printed errors and
eigenvalues), its parallel VTK output read back (every element in exactly one rank's piece, the index naming
each piece and declaring its arrays), and its refusals. Arguments: trivar, mpiexec, tests/support folder."""
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

trivar, mpiexec, support = sys.argv[1:4]
sys.path.insert(0, support)
import read_vtu  # noqa: E402

env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def run(args, ranks=None):
    cmd = ([mpiexec, "-n", str(ranks), "--oversubscribe", trivar] if ranks else [trivar]) + args
    return subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)


def numbers(out, pattern):
    return re.findall(pattern, out)


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

r = run(["solve", "poisson", "--problem", "sine-cube", "--adaptive", "--backend", "petsc"], ranks=2)
check(r.returncode != 0 and "--backend petsc" in r.stderr, "--adaptive with petsc: %d %s" % (r.returncode, r.stderr))

for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
