#!/usr/bin/env bash
# Times the suite's DEM and LIGGGHTS on the same scene in one run, alternating the two (suite,
# peer, suite, peer, ...) so that both see the same machine, and prints each one's time per grain
# per contact step (medians over the rounds) and their ratio (README.md here; docs/performance.md, "Time per particle").
#
#   reference/peers/liggghts/side_by_side.sh [options]
#     --sandcastle PATH  the suite's binary (default build/sandcastle)
#     --case NAME        the scene (default dem_settle_50k)
#     --steps K          case steps timed (default 50); LIGGGHTS runs K times the contact steps per case step
#     --cores N          OpenMP threads of the suite, MPI processes of LIGGGHTS (default 2)
#     --rounds R         rounds of suite-then-peer (default 3)
#     --out DIR          work folder (default runs/liggghts_side_by_side)
#
# Both start from the suite's first frame of the scene (make_input.py). The suite's figure is its
# bench's mean ms per step over its grains and contact steps per step, LIGGGHTS' its "Loop time"
# over its steps and atoms: wall time per grain-step of the whole timed run, on the same cores. Writes DIR/side_by_side.json. Needs `liggghts` and `mpirun` (Debian packages liggghts
# and openmpi-bin); exit code 2 for bad arguments or a missing program.
set -euo pipefail
usage() { sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
repo="$(cd "$(dirname "$0")/../../.." && pwd)"
sandcastle="$repo/build/sandcastle"; case_name=dem_settle_50k; steps=50; cores=2; rounds=3
out="$repo/runs/liggghts_side_by_side"
while [ $# -gt 0 ]; do
  case "$1" in
    --sandcastle) sandcastle="$(realpath "$2")"; shift 2 ;;
    --case) case_name="$2"; shift 2 ;;
    --steps) steps="$2"; shift 2 ;;
    --cores) cores="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) usage ;;
  esac
done
for program in liggghts mpirun; do
  command -v "$program" >/dev/null || { echo "side_by_side: '$program' not found (apt-get install liggghts openmpi-bin)" >&2; exit 2; }
done
[ -x "$sandcastle" ] || { echo "side_by_side: $sandcastle is not an executable file" >&2; exit 2; }
case_file="$repo/cases/$case_name/case.json"
[ -f "$case_file" ] || { echo "side_by_side: no case $case_file" >&2; exit 2; }
mkdir -p "$out"

# The first frame: the same case cut to one step (only its t = 0 grains are read).
/usr/bin/env python3 - "$case_file" "$out/first/case.json" <<'EOF'
import json, os, sys
case = json.load(open(sys.argv[1]))
case["time"]["end"] = case["time"]["dt"]
os.makedirs(os.path.dirname(sys.argv[2]), exist_ok=True)
json.dump(case, open(sys.argv[2], "w"))
EOF
OMP_NUM_THREADS="$cores" "$sandcastle" run "$out/first/case.json" --tier full --method dem --out "$out/first/run" >/dev/null 2>"$out/first.log"
OMP_NUM_THREADS="$cores" "$sandcastle" bench --scene "$case_name" --method dem --steps 1 --out "$out/probe" >/dev/null 2>"$out/probe.log"
contact_steps=$(/usr/bin/env python3 -c "import json,sys; print(round(json.load(open(sys.argv[1]))['scenes'][0]['own_steps_per_step']))" "$out/probe/bench.json")
/usr/bin/env python3 "$repo/reference/peers/liggghts/make_input.py" "$case_file" "$out/first/run/frame_00000.vtu" \
  $((steps * contact_steps)) "$out/peer" >/dev/null

for r in $(seq 1 "$rounds"); do
  echo "side_by_side: round $r/$rounds suite" >&2
  OMP_NUM_THREADS="$cores" "$sandcastle" bench --scene "$case_name" --method dem --steps "$steps" --out "$out/suite_$r" >/dev/null 2>"$out/suite_$r.log"
  echo "side_by_side: round $r/$rounds LIGGGHTS" >&2
  (cd "$out/peer" && mpirun --allow-run-as-root --oversubscribe -np "$cores" liggghts -in in.settle > "log_$r.txt" 2>&1)
done

/usr/bin/env python3 - "$out" "$rounds" "$cores" <<'EOF'
import json, re, statistics, sys
out, rounds, cores = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
suite, peer = [], []
for r in range(1, rounds + 1):
    scene = json.load(open(f"{out}/suite_{r}/bench.json"))["scenes"][0]
    # the mean over the timed steps, as LIGGGHTS' loop time is the whole run's
    suite.append(1e3 * scene["ms_per_step"]["mean"] / (scene["particles"]["total"] * scene["own_steps_per_step"]))
    m = re.search(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms",
                  open(f"{out}/peer/log_{r}.txt").read())
    peer.append(1e6 * float(m.group(1)) / (int(m.group(2)) * int(m.group(3))))
result = {"cores": cores, "rounds": rounds,
          "suite_us_per_grain_step": suite, "liggghts_us_per_grain_step": peer,
          "suite_median": statistics.median(suite), "liggghts_median": statistics.median(peer)}
result["suite_over_liggghts"] = result["suite_median"] / result["liggghts_median"]
json.dump(result, open(f"{out}/side_by_side.json", "w"), indent=2)
print(f"us per grain per contact step on {cores} cores, medians of {rounds} rounds: "
      f"suite {result['suite_median']:.4f}, LIGGGHTS {result['liggghts_median']:.4f}, "
      f"suite/LIGGGHTS {result['suite_over_liggghts']:.3f}")
EOF
