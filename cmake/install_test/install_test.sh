#!/usr/bin/env bash
# install_test.sh — the installed shadowref, as an engine team outside the source tree gets it.
#
#   install_test.sh prefix       BUILD WORK   `cmake --install BUILD --prefix WORK/prefix` (fresh)
#   install_test.sh cmake        BUILD WORK   a consumer project: find_package(shadowref), shadowref::mathlib
#   install_test.sh pkgconfig    BUILD WORK   the same main.cpp compiled with `pkg-config --cflags shadowref`
#   install_test.sh properties   BUILD WORK   an engine tree calling shadowref_add_math_properties()
#   install_test.sh standalone   BUILD WORK   the installed binary, copied out of the source tree, with
#                                             the source tree hidden: export a pack, render our own
#                                             z-fail masks, judge them from the pack alone
# CTest runs them (cmake/Install.cmake, label `install`); `prefix` is the fixture the others need.
# Each mode exits non-zero with a line saying what went wrong.
set -euo pipefail

mode=$1
build=$(cd "$2" && pwd)
work=$3
here=$(cd "$(dirname "$0")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
prefix=$work/prefix
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$build/CMakeCache.txt")

fail() {
  echo "install test ($mode): $*" >&2
  exit 1
}

case $mode in
prefix)
  rm -rf "$prefix"
  cmake --install "$build" --prefix "$prefix" >/dev/null
  for f in bin/shadowref include/shadowref/shadow_matrix.hpp share/cmake/shadowref/shadowrefConfig.cmake \
    share/pkgconfig/shadowref.pc share/shadowref/conformance/scenes/ground_sphere.json \
    share/shadowref/goldens/images/ground_sphere/mask.png share/shadowref/property_tests/math_properties_test.cpp; do
    [ -e "$prefix/$f" ] || fail "$f is not installed"
  done
  ;;

cmake)
  rm -rf "$work/consumer-cmake"
  cmake -S "$here/consumer" -B "$work/consumer-cmake" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$work/consumer-cmake" -j1 >/dev/null
  "$work/consumer-cmake/consumer"
  ;;

pkgconfig)
  rm -rf "$work/consumer-pkgconfig"
  mkdir -p "$work/consumer-pkgconfig"
  export PKG_CONFIG_PATH=$prefix/share/pkgconfig
  flags=$(pkg-config --cflags shadowref) || fail "pkg-config does not know shadowref"
  case " $flags " in *" -I$prefix/share/pkgconfig/../../include "*) ;; *) fail "Cflags lack the include folder: $flags" ;; esac
  case " $flags " in *eigen3*) ;; *) fail "Cflags lack eigen3's: $flags" ;; esac
  # shellcheck disable=SC2086
  "$cxx" -std=c++20 $flags "$here/consumer/main.cpp" -o "$work/consumer-pkgconfig/consumer"
  "$work/consumer-pkgconfig/consumer"
  ;;

properties)
  rm -rf "$work/consumer-properties"
  cmake -S "$here/properties" -B "$work/consumer-properties" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release \
    -DSHADOWREF_ADAPTER="$prefix/share/shadowref/property_tests/adapters/shadowref_adapter.cpp" >/dev/null
  cmake --build "$work/consumer-properties" -j1 >/dev/null
  RC_PARAMS="max_success=50" ctest --test-dir "$work/consumer-properties" -L property --output-on-failure >"$work/properties.log" ||
    { cat "$work/properties.log"; fail "the properties failed on the installed adapter"; }
  grep -q "tests passed" "$work/properties.log" || fail "no property test ran"
  tail -n 3 "$work/properties.log"
  ;;

standalone)
  # The installed prefix, copied out of the build tree (which lies inside the source tree).
  outside=$(mktemp -d "${TMPDIR:-/tmp}/shadowref-install-test.XXXXXX")
  trap 'rm -rf "$outside"' EXIT
  cp -a "$prefix" "$outside/prefix"
  mkdir "$outside/work"
  exe=$outside/prefix/bin/shadowref

  # The default catalogue is the installed one: an unknown scene's error names the folder searched.
  if err=$(cd "$outside/work" && "$exe" export --scenes no_such_scene --out pack 2>&1); then
    fail "export of an unknown scene succeeded"
  fi
  case $err in
    *"$outside/prefix/share/shadowref/conformance/scenes"*) ;;
    *) fail "the default catalogue is not the installed one: $err" ;;
  esac

  # In a mount namespace of its own, an empty tmpfs over the source tree (the build tree and its
  # prefix included): any source path compiled into the binary now holds nothing. Where no mount
  # namespace can be made (a container without the capability), the run goes on unhidden, and the
  # catalogue check above is what shows that no source path is used.
  judge() {
    set -euo pipefail
    if [ "$4" = hide ]; then
      mount -t tmpfs none "$1"
      [ -z "$(ls -A "$1")" ] || { echo "the source tree is still visible" >&2; return 1; }
    fi
    cd "$2/work"
    "$3" export --out pack --scenes ground_sphere
    [ "$(ls -A)" = pack ] || { echo "export wrote outside --out: $(ls -A)" >&2; return 1; }
    cd pack
    "$3" render --scene scenes/ground_sphere.json --technique volume-zfail --out mine/ground_sphere >/dev/null
    "$3" conform --catalogue scenes --scenes ground_sphere --candidate-dir mine --technique volume-zfail --out verdict
  }
  if [ "$(id -u)" = 0 ]; then hide=(unshare --mount --propagation private); else hide=(unshare --mount --map-root-user); fi
  mkdir "$outside/probe"
  if "${hide[@]}" mount -t tmpfs none "$outside/probe" 2>/dev/null; then
    "${hide[@]}" bash -c "$(declare -f judge); judge '$source_dir' '$outside' '$exe' hide" ||
      fail "export and conform with the installed binary, the source tree hidden, failed"
  else
    echo "install test: no tmpfs in a mount namespace (${hide[*]}): the source tree is not hidden in this run"
    (judge "$source_dir" "$outside" "$exe" show) || fail "export and conform with the installed binary failed"
  fi
  grep -q '"status": "PASS"' "$outside/work/pack/verdict/report.json" || fail "the verdict is not a PASS"
  ;;

*)
  fail "unknown mode"
  ;;
esac
