#!/usr/bin/env bash
# Configures and builds sandcastle in build/ (Release). Leaves the command at build/sandcastle.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
