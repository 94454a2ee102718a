#!/usr/bin/env python3
"""Writes the LIGGGHTS input of a DEM speed scene of this suite (cases/dem_settle_50k).

The grains are the suite's own at t = 0 (positions, radii and densities read from the first VTU
frame of `sandcastle run`), so both codes start from the same state. The contact parameters follow
the rules of solver/dem/dem_method.cpp `contact_params` (stiffness from the material's height and the
overlap fraction; normal dashpot from the restitution of a pair of equal grains; tangential spring
2/7 of the normal one with the same damping ratio; rolling resistance by the elastic-plastic
spring-dashpot of Ai et al. 2011, LIGGGHTS' `epsd`), and LIGGGHTS takes the suite's contact step.
LIGGGHTS is a benchmark here, never a build or test dependency: reference/peers/liggghts/README.md.

Usage: make_input.py CASE_JSON FRAME_VTU STEPS OUT_DIR
  STEPS  contact steps to run (the suite's case steps times its contact steps per case step)
"""
import json
import math
import os
import re
import sys


def vtu_arrays(path):
    """The points and the named point arrays of an ASCII VTU file, as lists of floats."""
    text = open(path).read()
    arrays = {}
    for m in re.finditer(r'<DataArray([^>]*)>(.*?)</DataArray>', text, re.S):
        named = re.search(r'Name="([^"]+)"', m.group(1))
        name = named.group(1) if named else "Points"
        if name not in arrays:
            arrays[name] = [float(v) for v in m.group(2).split()]
    return arrays


def contact_parameters(case, dx, mass, gravity):
    own = case["methods"]["dem"]
    friction = own.get("friction", 0.5)
    if own.get("wall_friction", friction) != friction:
        # One atom type: LIGGGHTS' walls take the grains' coefficientFriction.
        sys.exit("make_input.py: the peer input gives the walls the grains' friction; "
                 "this case sets methods/dem/wall_friction to another value")
    overlap = own.get("overlap", 0.01)
    e = own.get("restitution", 0.3)
    heights = [b["max"][2] for b in case["blocks"]], [b["min"][2] for b in case["blocks"]]
    layers = max(1.0, (max(heights[0]) - min(heights[1])) / dx)
    k = layers * mass * gravity / (overlap * 0.5 * dx)
    m_eff = 0.5 * mass
    ln_e = math.log(e)
    gamma_n = -2.0 * ln_e * math.sqrt(k * m_eff / (math.pi ** 2 + ln_e ** 2))
    zeta = gamma_n / (2.0 * math.sqrt(k * m_eff))
    k_t = 2.0 / 7.0 * k
    return {"kn": k, "kt": k_t, "gamman": gamma_n, "gammat": 2.0 * zeta * math.sqrt(k_t * m_eff),
            "friction": friction, "rolling": own.get("rolling_friction", 0.0), "rolling_damping_ratio": zeta,
            "dt_max": 0.1 * math.sqrt(mass / k)}


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    case = json.load(open(sys.argv[1]))
    vtu = vtu_arrays(sys.argv[2])
    steps, out = int(sys.argv[3]), sys.argv[4]
    os.makedirs(out, exist_ok=True)
    x, r, rho, m = vtu["Points"], vtu["support_radius"], vtu["density"], vtu["mass"]
    n = len(r)
    dx = case["tiers"]["full"]["spacings"][-1]
    gravity = math.sqrt(sum(g * g for g in case["gravity"]))
    p = contact_parameters(case, dx, m[0], gravity)
    dt_case = case["time"]["dt"]
    dt = dt_case / math.ceil(dt_case / min(p["dt_max"] * math.sqrt(min(m) / m[0]), dt_case) - 1e-9)
    lo, hi = case["tank"]["min"], case["tank"]["max"]
    with open(os.path.join(out, "grains.data"), "w") as f:
        f.write(f"LIGGGHTS data: {n} grains of {case['name']} at t = 0\n\n{n} atoms\n1 atom types\n\n")
        for d, axis in enumerate("xyz"):
            f.write(f"{lo[d]} {hi[d]} {axis}lo {axis}hi\n")
        f.write("\nAtoms\n\n")
        for i in range(n):
            f.write(f"{i + 1} 1 {2.0 * r[i]:.17g} {rho[i]:.17g} {x[3 * i]:.17g} {x[3 * i + 1]:.17g} {x[3 * i + 2]:.17g}\n")
    model = "model hooke/stiffness tangential history rolling_friction epsd"
    keywords = "absolute_damping on tangential_damping on"
    walls = [("xplane", lo[0]), ("xplane", hi[0]), ("yplane", lo[1]), ("yplane", hi[1]), ("zplane", lo[2])]
    with open(os.path.join(out, "in.settle"), "w") as f:
        f.write(f"""# {case['name']}: the suite's grains and contact parameters (make_input.py)
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
processors * * 1
read_data grains.data
neighbor {0.1 * dx} bin
neigh_modify delay 0
fix m1 all property/global kn peratomtypepair 1 {p['kn']:.17g}
fix m2 all property/global kt peratomtypepair 1 {p['kt']:.17g}
fix m3 all property/global gamman_abs peratomtypepair 1 {p['gamman']:.17g}
fix m4 all property/global gammat_abs peratomtypepair 1 {p['gammat']:.17g}
fix m5 all property/global coefficientFriction peratomtypepair 1 {p['friction']}
fix m6 all property/global coefficientRollingFriction peratomtypepair 1 {p['rolling']}
fix m7 all property/global coefficientRollingViscousDamping peratomtypepair 1 {p['rolling_damping_ratio']:.17g}
pair_style gran {model} {keywords}
pair_coeff * *
timestep {dt:.17g}
fix gravi all gravity {gravity} vector 0.0 0.0 -1.0
""")
        for k, (kind, at) in enumerate(walls):
            f.write(f"fix w{k} all wall/gran {model} primitive type 1 {kind} {at} {keywords}\n")
        f.write(f"""fix integr all nve/sphere
thermo_style custom step atoms ke
thermo {max(1, steps // 10)}
run {steps}
write_dump all custom final.dump id x y z radius
""")
    print(f"{n} grains, contact step {dt:.6g} s, {steps} steps: {out}/in.settle")


if __name__ == "__main__":
    main()
