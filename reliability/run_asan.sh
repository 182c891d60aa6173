#!/usr/bin/env bash
# run_asan.sh — the whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer.
# Configures the `asan` preset (CMakePresets.json: RelWithDebInfo, SHADOWREF_SANITIZE=ON, no
# benchmarks) into BUILD (default build/asan), builds it, and runs every test but the fuzz smoke
# run (which has its own ASan build) with the options below. Prints ctest's summaries; exits
# non-zero when either pass below has a failure.
#
#   reliability/run_asan.sh [BUILD] [extra ctest arguments, e.g. -R BadInput]
#   TARGETS="shadowref scene_test" reliability/run_asan.sh [BUILD] -R ...
#   PART=2/4 reliability/run_asan.sh [BUILD]
# (with extra arguments only the first pass runs, filtered by them; TARGETS builds only those
# targets, for a filter whose tests they are, instead of the whole tree; PART=k/n runs every n-th
# test of BUILD's list from the k-th, the fixtures they need with them, so that the whole list,
# some hours on two cores, runs in n sittings of about equal weight on one unchanged tree; the
# second pass runs with part 1)
#
# Options, and why:
#   ASAN_OPTIONS detect_leaks=1 (the default, stated), abort_on_error=1 (a report is a failure,
#     never a warning), strict_string_checks=1, detect_stack_use_after_return=1,
#     intercept_tls_get_addr=0 (below: LeakSanitizer's tracer and llvmpipe's dynamic TLS);
#   LSAN_OPTIONS suppressions=reliability/lsan.supp: leaks whose allocation stack passes through
#     Mesa, LLVM (llvmpipe's JIT), OpenImageIO or the system libraries listed there, none of ours;
#   UBSAN_OPTIONS print_stacktrace=1 (the build has -fno-sanitize-recover=undefined: UB aborts).
# The child processes the tests start (`shadowref`, determinism_render) inherit all three.
#
# Two passes. The frame-pointer unwinder that ASan uses at every malloc stops at the first frame
# of a library built without frame pointers (libstdc++), so OpenImageIO 2.4's leak on a truncated
# PNG (see lsan.supp) shows only `operator new` and `std::string::_M_assign`, and no suppression
# can name it without also hiding every std::string leak of ours. The tests that read corrupt PNGs
# in-process (DWARF_TESTS) therefore run in a second pass with fast_unwind_on_malloc=0, which
# records whole stacks. Not for the whole suite: at every allocation it costs so much that
# renderer_test (Mesa's shader compiler allocates a lot) passes its 600 s
# limit.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/asan}"
shift || true
part=()
first_part=1
if [ -n "${PART:-}" ]; then
  if ! [[ "$PART" =~ ^([0-9]+)/([0-9]+)$ ]] || [ "${BASH_REMATCH[1]}" -lt 1 ] ||
     [ "${BASH_REMATCH[1]}" -gt "${BASH_REMATCH[2]}" ]; then
    echo "run_asan.sh: PART must be k/n with 1 <= k <= n (PART=2/4), not '$PART'" >&2
    exit 2
  fi
  part=(-I "${BASH_REMATCH[1]},,${BASH_REMATCH[2]}")  # ctest's Start,End,Stride: every n-th from k
  [ "${BASH_REMATCH[1]}" -eq 1 ] || first_part=0
fi
cd "$root"
cmake --preset asan -B "$build" >/dev/null
# shellcheck disable=SC2086 # TARGETS is a list of names
cmake --build "$build" -j "${JOBS:-2}" ${TARGETS:+--target $TARGETS}
# intercept_tls_get_addr=0: LeakSanitizer's tracer thread dies at exit ("Tracer caught signal 11")
# walking the dynamic TLS blocks ASan records through __tls_get_addr in a process that both draws on
# llvmpipe (the dlopened Mesa and LLVM) and builds an Embree scene (random_kernel_test, every run).
# Without those blocks among its roots the leak check can only report more, never hide a leak.
asan="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0"
# The suppressions are read from outside the source tree: install.standalone hides that tree (and the
# build folder inside it) from the installed binary it runs, which would then fail to read them.
supp="$(mktemp --tmpdir shadowref-lsan.XXXXXX.supp)"
trap 'rm -f "$supp"' EXIT
cp "$root/reliability/lsan.supp" "$supp"
export LSAN_OPTIONS="suppressions=$supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1"
DWARF_TESTS='Folders\.RefusesBadFiles'
status=0
ASAN_OPTIONS="$asan" ctest --test-dir "$build" -j "${JOBS:-2}" --output-on-failure --timeout 1800 \
  -E "^(fuzz_smoke|$DWARF_TESTS)\$" ${part[@]+"${part[@]}"} "$@" || status=$?
if [ $# -eq 0 ] && [ "$first_part" -eq 1 ]; then
  echo "-- second pass, whole allocation stacks (fast_unwind_on_malloc=0): $DWARF_TESTS"
  ASAN_OPTIONS="$asan:fast_unwind_on_malloc=0" ctest --test-dir "$build" --output-on-failure --timeout 1800 \
    -R "^($DWARF_TESTS)\$" || status=$?
fi
exit "$status"
