#!/usr/bin/python3
"""Writes the stress corpus that tests/cli/stress.cmake runs through the CLI: one small folding sheet (a 12 × 12 grid,
288 triangles, its right half folding over its left between the two frames) at scales and offsets where the
arithmetic is tested — ×2^-20 and ×2^20 (exact scalings: the contacts must be the unscaled ones), moved 1e9 from
the origin, ×2^±600 (beyond what the pipeline computes reliably: refused) — and degenerate frames: every vertex
collapsing to one point, every vertex at one point in both frames, every vertex on one line, one triangle.

Run from anywhere: /usr/bin/python3 tests/cli/stress/make_stress.py. The files are committed.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
N = 12


def sheet(fold, scale=1.0, offset=0.0):
    """Grid vertices, the half x > 1/2 turned by fold·π about the line x = 1/2 (a fold), then scaled and moved."""
    vs = []
    for j in range(N + 1):
        for i in range(N + 1):
            x, y = i / N, j / N
            z = 0.3 * fold * math.sin(3 * x + 2 * y)
            if x > 0.5:
                a, d = fold * math.pi, x - 0.5
                x, z = 0.5 + d * math.cos(a), z + d * math.sin(a)
            vs.append((x * scale + offset, y * scale, z * scale))
    return vs


def faces():
    fs = []
    for j in range(N):
        for i in range(N):
            a = j * (N + 1) + i
            fs += [(a, a + 1, a + N + 2), (a, a + N + 2, a + N + 1)]
    return fs


def write(name, vs, fs):
    with open(os.path.join(HERE, name), "w") as f:
        f.write("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in vs))
        f.write("".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in fs))


F = faces()
for name, scale, offset in [("unit", 1.0, 0.0), ("small", 2.0**-20, 0.0), ("large", 2.0**20, 0.0),
                            ("far", 1.0, 1e9), ("tiny", 2.0**-600, 0.0), ("huge", 2.0**600, 0.0)]:
    write(f"{name}_t0.obj", sheet(0.9, scale, offset), F)
    write(f"{name}_t1.obj", sheet(1.02, scale, offset), F)
count = (N + 1) ** 2
write("point.obj", [(0.3, 0.3, 0.3)] * count, F)
write("line_t0.obj", [(0.01 * i, 0.0, 0.0) for i in range(count)], F)
write("line_t1.obj", [(0.01 * i, 0.0, 0.001 * (i % 3)) for i in range(count)], F)
write("one_t0.obj", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)])
write("one_t1.obj", [(0, 0, 1), (1, 0, 1), (0, 1, 1)], [(0, 1, 2)])
print(f"wrote the stress corpus under {HERE}")
