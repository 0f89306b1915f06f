#!/usr/bin/env python3
"""A PETSc error raised inside a collective call on one of two ranks (collective_failure.hpp): the job ends
within the timeout (no rank left waiting), with a non-zero exit status and the failing rank's one error line.
Arguments: mpiexec, test_iga_petsc."""
import os
import subprocess
import sys

mpiexec, program = sys.argv[1:3]
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1")
try:
    r = subprocess.run([mpiexec, "-n", "2", "--oversubscribe", "--quiet", program, "--fail-inside-a-collective-call"],
                       env=env, capture_output=True, text=True, timeout=60)
except subprocess.TimeoutExpired:
    print("FAIL: the ranks hang")
    sys.exit(1)
lines = [l for l in r.stderr.splitlines() if l.startswith("trivar:")]
failures = []
if r.returncode == 0:
    failures.append("exit status 0")
if len(lines) != 1 or not lines[0].startswith("trivar: error: petsc: MatAssemblyEnd failed on rank 0 (PETSc error "):
    failures.append("stderr %r" % r.stderr)
elif "nonzero" not in lines[0].lower():
    failures.append("PETSc's message is missing: %r" % lines[0])
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
