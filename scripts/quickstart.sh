#!/usr/bin/env bash
# The README's two commands:
#   scripts/quickstart.sh demo   install, build, run the main job on the built-in simulated default
#   scripts/quickstart.sh test   install, build, run the whole test suite with ctest
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-}
case "$what" in
  demo|test) ;;
  *) echo "usage: scripts/quickstart.sh demo|test" >&2; exit 1 ;;
esac

scripts/setup.sh
build=${SCANSTATION_BUILD_DIR:-build}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build "$build" --parallel "$(nproc)"

if [ "$what" = demo ]; then
  "$build/apps/scanstation/scanstation" demo --force
else
  ctest --test-dir "$build" --output-on-failure --parallel "$(nproc)" --timeout 600
fi
