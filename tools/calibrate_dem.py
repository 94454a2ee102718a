#!/usr/bin/env python3
"""Calibrates DEM's grain friction and rolling resistance for a bulk friction angle phi.

The procedure of docs/references.md §12: the angle_of_repose pile is run by DEM at its quick spacing
with grain friction mu (from 0.5) and rolling resistance mu_r = 0.05, 0.10, ...; the sweep stops at
the first pile steeper than phi + 3 deg, and mu_r is read off the least-squares line of the repose
angle against mu_r through the sweep, at phi. When no mu_r up to 1 makes the pile that steep (its
slope saturates once grains slide rather than roll), mu is raised by 0.1 and the sweep repeated.
Prints each run and the values to record in a case's "methods"/"dem".

Usage: tools/calibrate_dem.py --phi 30 [--sandcastle build/sandcastle] [--mu 0.5]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def repose_angle(sandcastle, case, mu, mu_r, work):
    """Runs the pile with (mu, mu_r) and returns its repose angle [deg]."""
    case = json.loads(json.dumps(case))
    case["methods"]["dem"] = {"friction": mu, "rolling_friction": mu_r}
    folder = os.path.join(work, f"mu{mu:.2f}_mur{mu_r:.2f}")
    os.makedirs(os.path.join(folder, "case"), exist_ok=True)
    path = os.path.join(folder, "case", "case.json")
    with open(path, "w") as f:
        json.dump(case, f)
    out = subprocess.run([sandcastle, "run", path, "--method", "dem", "--tier", "quick", "--out",
                          os.path.join(folder, "run")], capture_output=True, text=True)
    match = re.search(r"repose_angle_deg = ([0-9.eE+-]+)", out.stdout)
    if not match:
        sys.exit(f"error: the run with mu = {mu}, mu_r = {mu_r} gave no repose angle:\n{out.stderr}")
    return float(match.group(1))


def line(points):
    """Least-squares slope and intercept of y against x."""
    n = len(points)
    sx = sum(x for x, _ in points)
    sy = sum(y for _, y in points)
    sxx = sum(x * x for x, _ in points)
    sxy = sum(x * y for x, y in points)
    slope = (n * sxy - sx * sy) / (n * sxx - sx * sx)
    return slope, (sy - slope * sx) / n


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--phi", type=float, required=True, help="bulk friction angle [deg]")
    parser.add_argument("--mu", type=float, default=0.5, help="first grain friction tried")
    parser.add_argument("--sandcastle", default=os.path.join(ROOT, "build", "sandcastle"))
    args = parser.parse_args()
    with open(os.path.join(ROOT, "cases", "angle_of_repose", "case.json")) as f:
        case = json.load(f)
    mu = args.mu
    with tempfile.TemporaryDirectory(prefix="calibrate_dem_") as work:
        while mu <= 1.0 + 1e-9:
            sweep = []
            for k in range(1, 21):
                mu_r = 0.05 * k
                angle = repose_angle(args.sandcastle, case, mu, mu_r, work)
                print(f"mu = {mu:.2f}  mu_r = {mu_r:.2f}  repose angle = {angle:.2f} deg", flush=True)
                sweep.append((mu_r, angle))
                if angle > args.phi + 3.0:
                    slope, intercept = line(sweep)
                    mu_r = (args.phi - intercept) / slope
                    print(f'phi = {args.phi}: "dem": {{"friction": {mu:.2f}, "rolling_friction": {mu_r:.2f}}}')
                    return 0
            mu += 0.1
    print(f"phi = {args.phi}: no grain friction up to 1 makes the pile steeper than phi + 3 deg")
    return 1


if __name__ == "__main__":
    sys.exit(main())
