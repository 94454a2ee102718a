#!/usr/bin/env bash
# Installs what is missing, builds, and runs the tests: `test.sh` (or `test.sh quick`) runs the unit
# tests and the quick validation tier (CI, under 15 minutes on 2 cores); `test.sh full` adds the
# full validation tier (users; much longer).
set -euo pipefail
cd "$(dirname "$0")/.."
tier="${1:-quick}"
bash tools/install_deps.sh
bash tools/build.sh
cd build
if [ "$tier" = full ]; then
  ctest --output-on-failure --timeout 20000
else
  ctest --output-on-failure -L quick
fi
