#!/bin/sh
# run_seeds.sh BUILD_DIR [FIRST LAST] — runs every property test (ctest -L property) once per seed
# FIRST..LAST (default 1..10), keeping the rest of RC_PARAMS from the environment. Exits non-zero
# on the first seed that fails; its output names the reproduce= string.
set -eu
build=${1:?usage: run_seeds.sh BUILD_DIR [FIRST LAST]}
first=${2:-1}
last=${3:-10}
seed=$first
while [ "$seed" -le "$last" ]; do
  echo "== seed $seed"
  RC_PARAMS="${RC_PARAMS:-} seed=$seed" ctest --test-dir "$build" -L '^property$' -j2 --output-on-failure
  seed=$((seed + 1))
done
