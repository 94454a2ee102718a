#!/usr/bin/env python3
"""Draws the particle snapshots of a 2-D run for `sandcastle render` (docs/render.md).

Usage: particle_snapshots.py WIDTH HEIGHT XMIN XMAX YMIN YMAX (TIME VTU PNG)...
Reads each VTU particle frame (points, and the point arrays phase, saturation, mass, rest_density
where the method writes them) and draws it to PNG, WIDTH x HEIGHT pixels, showing the box
[XMIN, XMAX] x [YMIN, YMAX] with a margin of MARGIN of its size, at equal scale: water blue, sand tan and darker the higher its
saturation, walls grey, each particle a disc of its own size. Uses matplotlib (Debian:
python3-matplotlib), like plot_series.py.
"""
import sys
import xml.etree.ElementTree as ElementTree

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

DPI = 100
WATER = np.array([0.23, 0.49, 0.85])
DRY_SAND = np.array([0.80, 0.66, 0.44])  # the shades of render/pov_scene.cpp
WET_SAND = np.array([0.42, 0.32, 0.19])
WALL = np.array([0.55, 0.55, 0.55])
MARGIN = 0.06  # the tank's walls lie just outside its box


def read_vtu(path):
    """Positions (n x 2) and the point arrays of a VTU frame, by name."""
    piece = ElementTree.parse(path).getroot().find("UnstructuredGrid/Piece")
    points = np.array(piece.find("Points/DataArray").text.split(), dtype=float).reshape(-1, 3)[:, :2]
    arrays = {a.get("Name"): np.array(a.text.split(), dtype=float)
              for a in piece.find("PointData") if a.get("NumberOfComponents") in (None, "1")}
    return points, arrays


def colours(arrays, n):
    phase = arrays.get("phase", np.zeros(n))
    wet = np.clip(arrays.get("saturation", np.zeros(n)), 0.0, 1.0)[:, None]
    sand = (1.0 - wet) * DRY_SAND + wet * WET_SAND
    return np.where((phase == 0)[:, None], WATER, np.where((phase == 1)[:, None], sand, WALL))


def sizes(arrays, n, box_area):
    """Each particle's size in metres: sqrt(mass / rest density), else the box shared evenly."""
    if "mass" in arrays and "rest_density" in arrays:
        return np.sqrt(arrays["mass"] / np.maximum(arrays["rest_density"], 1e-300))
    return np.full(n, np.sqrt(box_area / max(n, 1)))


def draw(width, height, box, time, vtu, png):
    xmin, xmax, ymin, ymax = box
    points, arrays = read_vtu(vtu)
    n = len(points)
    pad = MARGIN * max(xmax - xmin, ymax - ymin)
    scale = min(width / (xmax - xmin + 2 * pad), height / (ymax - ymin + 2 * pad))  # pixels per metre
    cx, cy = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
    fig = plt.figure(figsize=(width / DPI, height / DPI), dpi=DPI)
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_xlim(cx - 0.5 * width / scale, cx + 0.5 * width / scale)
    ax.set_ylim(cy - 0.5 * height / scale, cy + 0.5 * height / scale)
    ax.set_axis_off()
    diameter_points = sizes(arrays, n, (xmax - xmin) * (ymax - ymin)) * scale * 72.0 / DPI
    ax.scatter(points[:, 0], points[:, 1], s=diameter_points ** 2, c=colours(arrays, n), marker="o", linewidths=0)
    ax.plot([xmin, xmax, xmax, xmin, xmin], [ymin, ymin, ymax, ymax, ymin], color="0.3", lw=0.8)
    ax.text(0.01, 0.99, "t = %.3f s" % time, transform=ax.transAxes, va="top", fontsize=9)
    fig.savefig(png, dpi=DPI)
    plt.close(fig)


def main():
    width, height = int(sys.argv[1]), int(sys.argv[2])
    box = [float(v) for v in sys.argv[3:7]]
    rest = sys.argv[7:]
    for k in range(0, len(rest), 3):
        draw(width, height, box, float(rest[k]), rest[k + 1], rest[k + 2])


if __name__ == "__main__":
    main()
