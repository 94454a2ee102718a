#!/usr/bin/env bash
# The main job: install what is missing, build, and run the quick validation suite, writing
# reports/quick/{report.json,summary.md,<case>/series.json,<case>/*.png}.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
bash tools/build.sh
./build/sandcastle validate --tier quick --method all --out reports/quick
