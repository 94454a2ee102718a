#!/usr/bin/env python3
"""Calibrates DEM's grain friction and rolling resistance for a bulk friction angle phi.

The procedure of docs/references.md §12: the angle_of_repose pile is run by DEM at its quick spacing
with grain friction mu (from 0.5) and rolling resistance mu_r = 0.05, 0.10, ...; the sweep stops at
the first pile steeper than phi + 3 deg, and mu_r is read off the least-squares line of the repose
angle against mu_r through the sweep, at phi. When no mu_r up to 1 makes the pile that steep (its
slope saturates once grains slide rather than roll), mu is raised by 0.1 and the sweep repeated.
With --dimension 3 the pile is of spheres: the same stepped pyramid extruded across the channel of
column_collapse_3d (its width, between its slip side walls), so that the 3-D cases of that channel
are calibrated on grains packed and walled as theirs.
Prints each run and the values to record in a case's "methods"/"dem".

Usage: tools/calibrate_dem.py --phi 30 [--dimension 2|3] [--sandcastle build/sandcastle] [--mu 0.5]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_case(name):
    with open(os.path.join(ROOT, "cases", name, "case.json")) as f:
        return json.load(f)


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


def channel_pile(pile, channel):
    """The 2-D pile case extruded across the 3-D channel case's width: x stays, the pile's height
    becomes z, y spans the channel between the channel's side walls; only DEM runs it."""
    tank = channel["tank"]
    y0, y1 = tank["min"][1], tank["max"][1]
    margin = pile["tank"]["min"][1] - pile["domain"]["min"][1]
    case = json.loads(json.dumps(pile))
    case["name"] = pile["name"] + "_channel"
    case["description"] = f"The {pile['name']} pile across the channel of {channel['name']} (spheres, DEM only)."
    case["dimension"] = 3
    case["domain"] = {"min": [pile["domain"]["min"][0], y0 - margin, pile["domain"]["min"][1]],
                      "max": [pile["domain"]["max"][0], y1 + margin, pile["domain"]["max"][1]]}
    case["gravity"] = [0.0, 0.0, pile["gravity"][1]]
    for block in case["blocks"]:
        block["min"] = [block["min"][0], y0, block["min"][1]]
        block["max"] = [block["max"][0], y1, block["max"][1]]
    sides = pile["tank"]["sides"]
    case["tank"] = {"min": [pile["tank"]["min"][0], y0, pile["tank"]["min"][1]],
                    "max": [pile["tank"]["max"][0], y1, pile["tank"]["max"][1]],
                    "sides": {"x-": sides["x-"], "x+": sides["x+"], "y-": tank["sides"]["y-"],
                              "y+": tank["sides"]["y+"], "z-": sides["y-"], "z+": sides["y+"]}}
    case["methods"] = {"dem": {}}
    for tier in case["tiers"].values():
        tier["methods"] = ["dem"]
    return case


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
    parser.add_argument("--dimension", type=int, choices=[2, 3], default=2,
                        help="2: discs on the angle_of_repose pile; 3: spheres on it across column_collapse_3d's channel")
    parser.add_argument("--sandcastle", default=os.path.join(ROOT, "build", "sandcastle"))
    args = parser.parse_args()
    case = read_case("angle_of_repose")
    if args.dimension == 3:
        case = channel_pile(case, read_case("column_collapse_3d"))
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
