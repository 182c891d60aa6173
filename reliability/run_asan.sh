#!/usr/bin/env bash
# run_asan.sh — issue 9, item 3: the whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer.
# Configures the `asan` preset (CMakePresets.json: RelWithDebInfo, SHADOWREF_SANITIZE=ON, no
# benchmarks) into BUILD (default build/asan), builds it, and runs every test but the fuzz smoke
# run (which has its own ASan build) with the options below. Prints ctest's summary; exits with
# ctest's status.
#
#   reliability/run_asan.sh [BUILD] [extra ctest arguments, e.g. -R bad_input]
#
# Options, and why:
#   ASAN_OPTIONS detect_leaks=1 (the default, stated), abort_on_error=1 (a report is a failure,
#     never a warning), strict_string_checks=1, detect_stack_use_after_return=1;
#   LSAN_OPTIONS suppressions=reliability/lsan.supp: leaks whose allocation is wholly inside Mesa,
#     LLVM (llvmpipe's JIT) or the system libraries listed there, none of ours;
#   UBSAN_OPTIONS print_stacktrace=1 (the build has -fno-sanitize-recover=undefined: UB aborts).
# The child processes the tests start (`shadowref`, determinism_render) inherit all three.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/asan}"
shift || true
cd "$root"
cmake --preset asan -B "$build" >/dev/null
cmake --build "$build" -j "${JOBS:-2}"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export LSAN_OPTIONS="suppressions=$root/reliability/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1"
ctest --test-dir "$build" -j "${JOBS:-2}" --output-on-failure -E '^fuzz_smoke$' --timeout 1800 "$@"
