#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs every ctest test, then the sanitizer
# build type: the hardening tests (label hardening) under AddressSanitizer and UBSan, any finding
# fatal. Non-zero on failure. ACTUATOR_SKIP_SANITIZE=1 leaves the sanitizer build out (local use).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
(cd "${BUILD_DIR:-build}" && ctest --output-on-failure -j "$(nproc)" --timeout 300)

if [ "${ACTUATOR_SKIP_SANITIZE:-0}" != 1 ]; then
  sanitize_dir=${SANITIZE_BUILD_DIR:-build-sanitize}
  # -O1: the sanitizers' usual level, and half the compile time of Release. Only what the
  # hardening tests run is built.
  cmake -S . -B "$sanitize_dir" -DACTUATOR_SANITIZE=ON -DACTUATOR_NATIVE=OFF -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" >/dev/null
  cmake --build "$sanitize_dir" -j "$(nproc)" --target actuator hardening_tests
  # Leaks inside Mesa's llvmpipe (its JIT keeps allocations to exit) are not ours to fix.
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
  export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan.supp:print_suppressions=0}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
  (cd "$sanitize_dir" && ctest -L hardening --output-on-failure -j "$(nproc)" --timeout 300)
fi
