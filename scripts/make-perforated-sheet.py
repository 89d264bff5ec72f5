#!/usr/bin/env python3
"""Writes assets/meshes/perforated_sheet.obj, an open surface for the Policarpo & Oliveira 2006
Section 7 reproduction (configs/papers/policarpo2006-open-surfaces.toml): one square tile of a
thin sheet, z = 0.5 + 0.25 sin(2 pi x) sin(2 pi y) over [0, 1]^2, on a 64 x 64 grid of quads,
with a square hole of 8 x 8 quads in the middle of each of its 4 x 4 blocks. It has no
thickness, so it bounds no solid: every edge of its outline and of its holes is a boundary.
Standard library only.

  scripts/make-perforated-sheet.py [out.obj]
"""
import math
import sys

N, BLOCK, HOLE = 64, 16, 8


def height(x, y):
    return 0.5 + 0.25 * math.sin(2 * math.pi * x) * math.sin(2 * math.pi * y)


def in_hole(i, j):
    lo = (BLOCK - HOLE) // 2
    return lo <= i % BLOCK < lo + HOLE and lo <= j % BLOCK < lo + HOLE


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "assets/meshes/perforated_sheet.obj"
    lines = ["# A perforated wavy sheet, one tile (scripts/make-perforated-sheet.py)"]
    for j in range(N + 1):
        for i in range(N + 1):
            x, y = i / N, j / N
            lines.append("v %.6f %.6f %.6f" % (x, y, height(x, y)))
    def vid(i, j):
        return j * (N + 1) + i + 1
    for j in range(N):
        for i in range(N):
            if in_hole(i, j):
                continue
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            lines.append("f %d %d %d" % (a, b, c))
            lines.append("f %d %d %d" % (a, c, d))
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
