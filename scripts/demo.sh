#!/usr/bin/env bash
# The demo: installs what posekit needs, builds the tool, generates an articulated shape with
# self-intersecting bent poses and runs posekit on them.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh release --target posekit_cli
./build/release/tools/cli/posekit devices
./build/release/tools/cli/posekit demo --output-dir build/demo
