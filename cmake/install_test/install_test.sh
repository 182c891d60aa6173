#!/usr/bin/env bash
# install_test.sh — the installed shadowref, as an engine team outside the source tree gets it.
#
#   install_test.sh prefix       BUILD WORK   `cmake --install BUILD --prefix WORK/prefix` (fresh)
#   install_test.sh cmake        BUILD WORK   a consumer project: find_package(shadowref), shadowref::mathlib
#   install_test.sh pkgconfig    BUILD WORK   the same main.cpp compiled with `pkg-config --cflags shadowref`
#   install_test.sh properties   BUILD WORK   an engine tree calling shadowref_add_math_properties()
#   install_test.sh standalone   BUILD WORK   the installed binary, copied out of the source tree, with
#                                             the source tree hidden: export a pack, render our own
#                                             z-fail masks, judge them from the pack alone; then walk
#                                             the pack README as an engine team would (readme_walk),
#                                             declared light matrices included
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
    share/shadowref/goldens/images/ground_sphere/mask.png share/shadowref/pack/README.template.md \
    share/shadowref/property_tests/math_properties_test.cpp; do
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
  # The pack README followed alone, as an engine team does with the installed binary on its PATH:
  # export two scenes (one light, two lights), write masks where and as "What to write" says (our
  # renderer standing in for the engine: its mask*.png and candidate.json, nothing else), run the
  # README's "How to get the verdict" commands as written, and find what the README says follows:
  # exit 0, my-verdict/report.json with every case PASS, my-verdict/report/index.html. Every pack
  # path the README names (`<scene>/...`, `manifest.json`) must exist in the pack.
  readme_walk() {
    set -euo pipefail
    export PATH="$2/prefix/bin:$PATH"
    mkdir "$2/team" && cd "$2/team"
    shadowref export --out pack --scenes ground_sphere,two_lights >/dev/null
    cd pack
    [ -f README.md ] || { echo "the pack has no README.md" >&2; return 1; }
    # "What to write": one folder per scene, mask.png or mask_<i>.png, candidate.json beside them.
    for scene in ground_sphere two_lights; do
      shadowref render --scene "scenes/$scene.json" --technique shadowmap --out "$2/engine/$scene" >/dev/null
      mkdir -p "my-renders/$scene"
      cp "$2/engine/$scene"/mask*.png "$2/engine/$scene/candidate.json" "my-renders/$scene/"
    done
    [ -f my-renders/two_lights/mask_1.png ] || { echo "two lights did not give mask_<i>.png as the README says" >&2; return 1; }
    # The README's own commands, line by line, in this folder.
    awk '/^## How to get the verdict/{f=1} f&&/^```sh/{c=1;next} c&&/^```/{exit} c{print}' README.md >"$2/commands.sh"
    [ "$(grep -c '^shadowref conform' "$2/commands.sh")" -ge 2 ] || { echo "no conform commands under 'How to get the verdict'" >&2; return 1; }
    while IFS= read -r line; do
      [ -n "$line" ] || continue
      echo "README: $line"
      rm -rf my-verdict
      eval "$line" >"$2/readme-run.log" 2>&1 || { cat "$2/readme-run.log" >&2; echo "README command failed: $line" >&2; return 1; }
      [ -f my-verdict/report.json ] && [ -f my-verdict/report/index.html ] ||
        { echo "README command did not write my-verdict/report.json and report/index.html: $line" >&2; return 1; }
      if grep -q '"status": "\(FAIL\|WARN\|ERROR\)"' my-verdict/report.json; then echo "a case is not PASS: $line" >&2; return 1; fi
      grep -q '"status": "PASS"' my-verdict/report.json || { echo "no PASS in my-verdict/report.json: $line" >&2; return 1; }
    done <"$2/commands.sh"
    # Declared light matrices, as an engine that knows its own gives them (the README's "light_views":
    # "declared"): the same renders with each light's views and projections in candidate.json (two
    # point lights' cubes among them), judged from the pack alone: every case PASS, on the declared grid.
    for scene in ground_sphere two_lights; do
      shadowref render --scene "scenes/$scene.json" --technique shadowmap --declare-light-matrices \
        --out "$2/declared/$scene" >/dev/null
      grep -q '"light_views": "declared"' "$2/declared/$scene/candidate.json" ||
        { echo "render --declare-light-matrices declared no matrices for $scene" >&2; return 1; }
    done
    shadowref conform --catalogue scenes --scenes ground_sphere,two_lights --candidate-dir "$2/declared" \
      --technique shadowmap --out declared-verdict >"$2/declared.log" 2>&1 ||
      { cat "$2/declared.log" >&2; echo "conform of the declared matrices failed" >&2; return 1; }
    if grep -q '"status": "\(FAIL\|WARN\|ERROR\)"' declared-verdict/report.json; then
      echo "a case of the declared matrices is not PASS" >&2; return 1
    fi
    grep -q "declared light matrices' grid is not contradicted" declared-verdict/report.json ||
      { echo "the judge did not use the declared matrices' grid" >&2; return 1; }
    # Every pack path the README names, for some exported scene (a soft one among them).
    cd "$2/team"
    shadowref export --out soft-pack --scenes soft_penumbra >/dev/null
    mv soft-pack/soft_penumbra pack/
    cd pack
    { grep -o '`<scene>/[^` ]*`' README.md; grep -o '`reference/[^` ]*`' README.md | sed 's|`|`<scene>/|'; } |
      tr -d '`' | sort -u | while IFS= read -r named; do
      found=no
      for scene in ground_sphere two_lights soft_penumbra; do
        pattern=${named//<scene>/$scene}
        pattern=${pattern//<i>/*}
        pattern=${pattern//<light>/*}
        # shellcheck disable=SC2086
        if compgen -G "${pattern%/}" >/dev/null; then found=yes; break; fi
      done
      [ "$found" = yes ] || { echo "the README names $named, which no exported scene has" >&2; return 1; }
      echo "README path: $named"
    done
    [ -f manifest.json ] || { echo "the README names manifest.json, which the pack lacks" >&2; return 1; }
  }

  if [ "$(id -u)" = 0 ]; then hide=(unshare --mount --propagation private); else hide=(unshare --mount --map-root-user); fi
  mkdir "$outside/probe"
  if "${hide[@]}" mount -t tmpfs none "$outside/probe" 2>/dev/null; then
    "${hide[@]}" bash -c "$(declare -f judge readme_walk); judge '$source_dir' '$outside' '$exe' hide && readme_walk '$source_dir' '$outside'" ||
      fail "export and conform with the installed binary, the source tree hidden, failed"
  else
    echo "install test: no tmpfs in a mount namespace (${hide[*]}): the source tree is not hidden in this run"
    (judge "$source_dir" "$outside" "$exe" show && readme_walk "$source_dir" "$outside") ||
      fail "export and conform with the installed binary failed"
  fi
  grep -q '"status": "PASS"' "$outside/work/pack/verdict/report.json" || fail "the verdict is not a PASS"
  ;;

*)
  fail "unknown mode"
  ;;
esac
