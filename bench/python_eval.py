#!/usr/bin/env python3
"""Evaluation of a tricubic volume at 10^6 random points from Python (the trivar module), to set beside the
C++ batch call of bench_spline_eval (BM_VolumeValue, BM_VolumeValueFirstDerivs): the same volume
(bench_volumes.hpp: perturbed_cube(3, 8)), uniformly random parameters, one thread and all threads.

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python_eval.py

Prints per case the best wall and CPU milliseconds over the repetitions and the points per CPU second."""
import os
import time

import numpy as np

import trivar


def perturbed_cube(degree=3, elements=8, a=0.05):
    kv = trivar.KnotVector.open_uniform(degree, elements)
    g = kv.greville
    z, y, x = np.meshgrid(g, g, g, indexing="ij")  # first direction fastest in storage order
    x, y, z = x.ravel(), y.ravel(), z.ravel()
    pts = np.column_stack([x + a * np.sin(3 * y), y + a * np.sin(3 * z), z + a * np.sin(3 * x)])
    return trivar.Volume([kv.knots] * 3, degree, pts)


def best(f, repetitions):
    wall, cpu = [], []
    for _ in range(repetitions):
        w0, c0 = time.perf_counter(), time.process_time()
        f()
        wall.append(time.perf_counter() - w0)
        cpu.append(time.process_time() - c0)
    return 1e3 * min(wall), 1e3 * min(cpu)


def main():
    repetitions = int(os.environ.get("REPETITIONS", "10"))
    v = perturbed_cube()
    n = 1_000_000
    u = np.random.default_rng(42).uniform(0.0, 1.0, size=(n, 3))
    print(f"trivar {trivar.__version__}, kernels {trivar.simd_level()}, {n} points, best of {repetitions}")
    for name, call in (("value", lambda t: v(u, threads=t)), ("value + first derivatives", lambda t: v.derivatives(u, 1, threads=t))):
        for threads in (1, 0):
            wall, cpu = best(lambda: call(threads), repetitions)
            label = "1" if threads == 1 else "all"
            print(f"{name:28s} threads {label:3s}: wall {wall:7.1f} ms, CPU {cpu:7.1f} ms, {n / cpu * 1e3:.3g} points per CPU s")
    # The fixed cost of one call (argument conversion, result allocation, GIL release): one point.
    one = u[:1]
    calls = 20000
    wall, _ = best(lambda: [v(one, threads=1) for _ in range(calls)], 3)
    print(f"one call of one point: {1e3 * wall / calls:.2f} us")


if __name__ == "__main__":
    main()
