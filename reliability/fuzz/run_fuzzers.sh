#!/usr/bin/env bash
# run_fuzzers.sh — builds the libFuzzer targets with clang (ASan + UBSan + libFuzzer) in a build
# folder of their own and runs each for a bounded time on a copy of its seed corpus.
#
#   reliability/fuzz/run_fuzzers.sh [--smoke | --seconds N | --build-only] [--build-dir DIR] [--jobs J] [TARGET...]
#     --smoke       3 s per target after its seed corpus replays (10 targets: 30 s of fuzzing; what `ctest` runs;
#                   the long runs below are where the fuzzing is)
#     --build-only  configure and build the targets, fuzz nothing (what the main build runs, so
#                   that the test command's fuzz_smoke finds them built)
#     --seconds N   N s per target
#     --runs N      N executions per target, however long it takes (the long run in
#                   reliability/README.md: --runs 1000000)
#     --build-dir   default build/fuzz
#     TARGET        scene_fuzzer obj_fuzzer gltf_fuzzer gltf_scene_fuzzer mask_compare_fuzzer math_args_fuzzer
#                   candidate_fuzzer convention_fuzzer expectations_fuzzer merge_fuzzer (default: all)
# Exit: 0 nothing found, 1 a target crashed, leaked, hung or ran out of memory (the input is kept
# in DIR/artifacts/, and the log in DIR/logs/), 77 clang or libFuzzer is not installed (skipped).
# New inputs found go to DIR/corpus/<target>/, never into the seed corpora of the repository.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
seconds=6
build_only=
runs_limit=
build="$root/build/fuzz"
jobs=2
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --smoke) seconds=3 ;;
    --build-only) build_only=1 ;;
    --seconds) seconds="$2"; shift ;;
    --runs) runs_limit="$2"; shift ;;
    --build-dir) build="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    -h|--help) sed -n 2,17p "$0"; exit 0 ;;
    *) targets+=("$1") ;;
  esac
  shift
done
[ ${#targets[@]} -gt 0 ] || targets=(scene_fuzzer obj_fuzzer gltf_fuzzer gltf_scene_fuzzer mask_compare_fuzzer math_args_fuzzer candidate_fuzzer
                               convention_fuzzer expectations_fuzzer merge_fuzzer)

cxx="$(command -v clang++ || command -v clang++-14 || true)"
cc="$(command -v clang || command -v clang-14 || true)"
if [ -z "$cxx" ] || [ -z "$cc" ] || ! echo 'extern "C" int LLVMFuzzerTestOneInput(const char*, unsigned long) { return 0; }' |
     "$cxx" -x c++ -fsanitize=fuzzer - -o /dev/null 2>/dev/null; then
  echo "run_fuzzers.sh: SKIPPED: clang++ with libFuzzer not found (apt-get install clang libclang-rt-14-dev)"
  exit 77
fi

flags="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -gline-tables-only"
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_C_FLAGS="$flags" -DSHADOWREF_FUZZ=ON -DSHADOWREF_FUZZ_SMOKE=OFF \
    -DSHADOWREF_BUILD_BENCH=OFF >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
fi
start=$(date +%s)
cmake --build "$build" -j "$jobs" --target "${targets[@]}" >"$build.build.log" 2>&1 || { tail -50 "$build.build.log"; exit 1; }
if [ -n "$build_only" ]; then
  echo "run_fuzzers.sh: built ${#targets[@]} target(s) in $(( $(date +%s) - start )) s"
  exit 0
fi
echo "run_fuzzers.sh: built ${#targets[@]} target(s) in $(( $(date +%s) - start )) s; fuzzing ${runs_limit:+$runs_limit executions}${runs_limit:-$seconds s} each"

mkdir -p "$build/artifacts" "$build/logs"
status=0
printf '%-22s %8s %12s %10s %8s  %s\n' target seconds executions exec/s corpus result
for t in "${targets[@]}"; do
  seeds="$here/corpus/${t%_fuzzer}"
  work="$build/corpus/$t"
  mkdir -p "$work"
  log="$build/logs/$t.log"
  if [ -n "$runs_limit" ]; then limit=(-runs="$runs_limit"); else limit=(-max_total_time="$seconds"); fi
  opts=("${limit[@]}" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536
        -print_final_stats=1 -artifact_prefix="$build/artifacts/$t-")
  [ -f "$here/$t.dict" ] && opts+=(-dict="$here/$t.dict")
  # Leaks are findings, except those whose stack passes through a library named in lsan.supp
  # (OpenImageIO 2.4 leaks a 31-byte string on every truncated PNG, fixed upstream in PR #5289);
  # matching a library needs full malloc stacks, which cost speed, so only the target that loads
  # OpenImageIO pays for them.
  asan="detect_leaks=1:allocator_may_return_null=0"
  # The long run (--runs) leaves leak checking to the timed runs for these two: with whole malloc
  # stacks they make about 60 executions a second, without leak checks about 400.
  leaks=()
  case "$t" in mask_compare_fuzzer|candidate_fuzzer)
    if [ -n "$runs_limit" ]; then leaks=(-detect_leaks=0); else asan="$asan:fast_unwind_on_malloc=0"; fi ;;
  esac
  t0=$(date +%s)
  set +e
  ASAN_OPTIONS="$asan" LSAN_OPTIONS="suppressions=$here/../lsan.supp:print_suppressions=0" UBSAN_OPTIONS="print_stacktrace=1" \
    "$build/reliability/fuzz/$t" "${opts[@]}" "${leaks[@]}" "$work" "$seeds" >"$log" 2>&1
  rc=$?
  set -e
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  rate=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
  size=$(find "$work" -type f | wc -l)
  if [ $rc -eq 0 ]; then result=ok; else result="FOUND (exit $rc): see $log"; status=1; fi
  t1=$(date +%s)
  printf '%-22s %8s %12s %10s %8s  %s\n' "$t" "$(( t1 - t0 ))" "${runs:-?}" "${rate:-?}" "$size" "$result"
  if [ $rc -ne 0 ]; then grep -m5 -E 'ERROR|SUMMARY|runtime error|terminate|deadly|Test unit written' "$log" | sed 's/^/    /'; fi
done
exit $status
