#!/usr/bin/env bash
# Measures a change's speed-up in one run: alternates two sandcastle binaries on the same scenes
# (old, new, old, new, ...), takes each binary's median time per step over the rounds, and prints
# the ratio old/new per scene. On a busy machine both binaries see the same load, so the ratio holds
# where single timings do not (docs/performance.md, "Comparing two binaries").
#
#   tools/bench_compare.sh OLD_BINARY NEW_BINARY [options]
#     --scene NAME     a scene (case name) to time, repeatable (default: bench_water_34k,
#                      bench_water_104k and the four thesis scenes)
#     --threads N      OpenMP threads of both binaries (default 2)
#     --rounds R       rounds of old-then-new per scene (default 3)
#     --steps K        steps per scene (default: bench's own)
#     --out DIR        where the runs and compare.json go (default reports/bench_compare)
#
# Both binaries read the scenes from this repository's cases/, so an old binary built from another
# checkout times the same case files. Each run's bench.json stays in DIR/<scene>/<old|new>_<round>/;
# DIR/compare.json holds, per scene, both medians, the ratio, whether both binaries ended in the
# same state (state checksum) and, for a binary that reports the roofline, the median fraction of
# the machine's limit per pair stage (the limits measured once by the new binary's probe, DIR/probe).
# Exit code 2 for bad arguments.
set -euo pipefail
usage() { sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 2; }
[ $# -ge 2 ] || usage
repo="$(cd "$(dirname "$0")/.." && pwd)"
old="$(realpath "$1")"; new="$(realpath "$2")"; shift 2
for b in "$old" "$new"; do
  [ -x "$b" ] || { echo "bench_compare: $b is not an executable file" >&2; exit 2; }
done
scenes=(); threads=2; rounds=3; steps=(); out="$repo/reports/bench_compare"
while [ $# -gt 0 ]; do
  case "$1" in
    --scene) scenes+=("$2"); shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --rounds) rounds="$2"; shift 2 ;;
    --steps) steps=(--steps "$2"); shift 2 ;;
    --out) out="$2"; shift 2 ;;
    *) echo "bench_compare: unknown argument $1" >&2; usage ;;
  esac
done
[[ "$threads" =~ ^[1-9][0-9]*$ && "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "bench_compare: --threads and --rounds take positive integers" >&2; exit 2; }
[ ${#scenes[@]} -gt 0 ] || scenes=(bench_water_34k bench_water_104k thesis_duck thesis_winnie_box thesis_bunny_winnie thesis_bunny_armadillos)
for s in "${scenes[@]}"; do
  [ -f "$repo/cases/$s/case.json" ] || { echo "bench_compare: no scene $s in $repo/cases" >&2; exit 2; }
done
mkdir -p "$out"

# The roofline's limits (docs/performance.md), measured once for every run of a binary that reads them.
if "$new" bench --help 2>/dev/null | grep -q -- '--limits'; then
  OMP_NUM_THREADS="$threads" "$new" bench --probe --threads "$threads" --out "$out/probe" >"$out/probe.log" 2>&1 \
    || { echo "bench_compare: the probe failed, see $out/probe.log" >&2; exit 1; }
fi
limits_of() {  # the --limits arguments for binary $1, if it takes them
  if [ -f "$out/probe/probe.json" ] && "$1" bench --help 2>/dev/null | grep -q -- '--limits'; then
    echo "--limits" "$out/probe/probe.json"
  fi
}
old_limits=($(limits_of "$old")); new_limits=($(limits_of "$new"))

for s in "${scenes[@]}"; do
  mkdir -p "$out/$s"
  for r in $(seq 1 "$rounds"); do
    for which in old new; do
      bin="$old"; limits=("${old_limits[@]}")
      [ "$which" = new ] && { bin="$new"; limits=("${new_limits[@]}"); }
      dir="$out/$s/${which}_$r"
      echo "bench_compare: $s round $r/$rounds $which" >&2
      OMP_NUM_THREADS="$threads" "$bin" bench --scene "$s" --threads "$threads" "${steps[@]}" "${limits[@]}" \
        --cases-dir "$repo/cases" --out "$dir" >"$dir.log" 2>&1 || { echo "bench_compare: $which failed on $s, see $dir.log" >&2; exit 1; }
    done
  done
done

python3 - "$out" "$old" "$new" "$threads" "${scenes[@]}" <<'EOF'
import json, statistics, sys, pathlib
out, old, new, threads, scenes = pathlib.Path(sys.argv[1]), sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5:]
rows = []
for s in scenes:
    runs = {w: [json.loads(p.read_text())["scenes"][0] for p in sorted((out / s).glob(f"{w}_*/bench.json"))] for w in ("old", "new")}
    med = {w: statistics.median(r["ms_per_step"]["median"] for r in runs[w]) for w in runs}
    same = len({r["checksum"] for r in runs["old"] + runs["new"]}) == 1
    stages = {w: {k: statistics.median(r["stage_ms_per_step"][k] for r in runs[w]) for k in runs[w][0]["stage_ms_per_step"]} for w in runs}
    row = {"scene": s, "particles": runs["new"][0]["particles"]["total"], "rounds": len(runs["new"]),
           "old_ms_per_step": med["old"], "new_ms_per_step": med["new"], "speedup": med["old"] / med["new"],
           "same_state": same, "old_stage_ms_per_step": stages["old"], "new_stage_ms_per_step": stages["new"]}
    for w in runs:  # the median fraction of the limit per pair stage, where the binary reports a roofline
        if all("roofline" in r for r in runs[w]):
            row[f"{w}_fraction_of_limit"] = {k: statistics.median(r["roofline"]["stages"][k].get("fraction_of_limit", 0.0) for r in runs[w])
                                             for k in runs[w][0]["roofline"]["stages"]}
    rows.append(row)
(out / "compare.json").write_text(json.dumps({"old": old, "new": new, "threads": threads, "scenes": rows}, indent=1) + "\n")
print(f"{'scene':26s} {'particles':>9s} {'old ms':>9s} {'new ms':>9s} {'speed-up':>8s}  same state")
for r in rows:
    print(f"{r['scene']:26s} {r['particles']:9d} {r['old_ms_per_step']:9.2f} {r['new_ms_per_step']:9.2f} {r['speedup']:8.3f}  {'yes' if r['same_state'] else 'no'}")
print(f"medians of {rows[0]['rounds'] if rows else 0} rounds at {threads} threads; {out / 'compare.json'}")
EOF
