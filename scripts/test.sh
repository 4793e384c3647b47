#!/usr/bin/env bash
# Sets everything up and runs the whole test suite: a warnings-as-errors build with every
# test (unit + integration + CLI), then the unit tests again under ASan + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)
# Tests run side by side (-j nproc): OpenMP threads that spin while they wait would take the
# cores from each other (the 16-seed HardLight test: ~6 s passive, 44 s spinning under load).
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}

cmake --preset ci >/dev/null
cmake --build --preset ci -j "$jobs"
ctest --preset ci -j "$jobs"

cmake --preset asan-ubsan >/dev/null
cmake --build --preset asan-ubsan -j "$jobs" --target radflux_unit_tests
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --preset asan-ubsan -j "$jobs"
