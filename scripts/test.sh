#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs every ctest test. Non-zero on failure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd "${BUILD_DIR:-build}"
ctest --output-on-failure -j "$(nproc)" --timeout 300
