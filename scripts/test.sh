#!/usr/bin/env bash
# Installs what posekit needs, builds everything and runs every test suite:
# the release build (unit, pipeline, conformance, command-line and Python tests) and the malformed-input corpus
# again under AddressSanitizer and UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh

jobs=$(nproc)
export CTEST_PARALLEL_LEVEL=${CTEST_PARALLEL_LEVEL:-$jobs}
# Backends that must be available, not skipped, for the conformance suite to pass.
export POSEKIT_EXPECT_BACKENDS=${POSEKIT_EXPECT_BACKENDS:-cpu,opencl,vulkan}

bash scripts/build.sh release
ctest --preset release

# Everything that parses untrusted files, again under AddressSanitizer and UBSan.
bash scripts/build.sh sanitize --target posekit_cli posekit_cli_tests posekit_mesh_tests
ctest --preset sanitize -L '^(mesh|cli)$'
