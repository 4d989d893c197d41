#!/usr/bin/env bash
# Configures and builds posekit with a CMake preset (default: release). Extra arguments go to the build,
# e.g. `scripts/build.sh release --target posekit_cli`.
set -euo pipefail
cd "$(dirname "$0")/.."
preset=${1:-release}
shift || true
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" "$@"
