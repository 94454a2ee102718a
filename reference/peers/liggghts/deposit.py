#!/usr/bin/env python3
"""Measures a settled DEM deposit, from the suite's final VTU or LIGGGHTS' final dump, the same way.

Prints the grain count, the deposit's height (the highest grain top) and its spread (the largest
horizontal distance of a grain's edge from the deposit's centre of mass), in metres.

Usage: deposit.py final.vtu | final.dump
"""
import math
import sys

from make_input import vtu_arrays


def grains_of_vtu(path):
    arrays = vtu_arrays(path)
    x, r = arrays["Points"], arrays["support_radius"]
    return [(x[3 * i], x[3 * i + 1], x[3 * i + 2], r[i]) for i in range(len(r))]


def grains_of_dump(path):
    lines = open(path).read().splitlines()
    header = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    columns = lines[header].split()[2:]
    ix, iy, iz, ir = (columns.index(c) for c in ("x", "y", "z", "radius"))
    rows = [line.split() for line in lines[header + 1:] if line.strip()]
    return [(float(v[ix]), float(v[iy]), float(v[iz]), float(v[ir])) for v in rows]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    path = sys.argv[1]
    grains = grains_of_vtu(path) if path.endswith(".vtu") else grains_of_dump(path)
    n = len(grains)
    cx = sum(g[0] for g in grains) / n
    cy = sum(g[1] for g in grains) / n
    height = max(g[2] + g[3] for g in grains)
    spread = max(math.hypot(g[0] - cx, g[1] - cy) + g[3] for g in grains)
    print(f"{path}: {n} grains, height {height:.5f} m, spread {spread:.5f} m")


if __name__ == "__main__":
    main()
