#!/usr/bin/env bash
# run_tsan.sh — ThreadSanitizer over the code that runs on several threads: the reference's tiles
# (reference_test, every test) and a conformance run (references, renders on llvmpipe's threads,
# comparisons, the cause model) over four scenes and four techniques.
#
#   reliability/run_tsan.sh [BUILD]      BUILD defaults to build/tsan (preset `tsan`)
#
# In the tsan build the reference's tiles run on std::threads (SHADOWREF_PLAIN_THREADS,
# reference/CMakeLists.txt): Debian's libtbb is not instrumented, and TSan would report every TBB
# task hand-off as a race. reliability/tsan.supp hides reports that pass through the uninstrumented
# Embree, oneTBB and Mesa libraries (each with its reason); a race between two of our own accesses
# is still reported. Exit: 0 clean, 1 a report or a failed test.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/tsan}"
if [ ! -f "$build/CMakeCache.txt" ]; then
  if [ "$build" = "$root/build/tsan" ]; then (cd "$root" && cmake --preset tsan >/dev/null)
  else cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADOWREF_SANITIZE_THREAD=ON -DSHADOWREF_BUILD_BENCH=OFF >/dev/null; fi
fi
cmake --build "$build" -j "${JOBS:-2}" --target reference_test shadowref
export TSAN_OPTIONS="halt_on_error=1 exitcode=66 suppressions=$root/reliability/tsan.supp"
status=0
start=$(date +%s)
"$build/reference/tests/reference_test" || status=1
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$build/shadowref" conform --scenes 'ground_sphere,soft_penumbra,two_lights,cornell_box' \
  --techniques shadowmap,pcss,volume-zfail,csm --out "$out" --quiet || status=1
echo "run_tsan.sh: $([ $status -eq 0 ] && echo clean || echo FOUND something) in $(( $(date +%s) - start )) s"
exit $status
