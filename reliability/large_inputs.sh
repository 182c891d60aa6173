#!/usr/bin/env bash
# large_inputs.sh — a 5M-triangle mesh through `shadowref math mesh-report`,
# `math silhouette`, `reference` and `render`, each under /usr/bin/time -v: wall time and peak
# RSS, printed as Markdown rows for bench/README.md's peak-memory table.
#
#   reliability/large_inputs.sh [--exe build/release/shadowref] [--triangles 5000000] [--work DIR]
# The mesh is a closed UV sphere (make_large_mesh.py), written once into WORK (default
# /tmp/shadowref-large); the scene puts it over a ground plane at 256 x 256 with one point light.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
exe="$root/build/release/shadowref"
tris=5000000
work=/tmp/shadowref-large
while [ $# -gt 0 ]; do
  case "$1" in
    --exe) exe="$2"; shift ;;
    --triangles) tris="$2"; shift ;;
    --work) work="$2"; shift ;;
    -h|--help) sed -n 2,9p "$0"; exit 0 ;;
    *) echo "large_inputs.sh: unknown argument $1" >&2; exit 4 ;;
  esac
  shift
done
mkdir -p "$work"
mesh="$work/sphere_${tris}.obj"
[ -f "$mesh" ] || python3 "$root/reliability/make_large_mesh.py" "$tris" "$mesh"
cat >"$work/large_mesh.json" <<JSON
{"name": "large_mesh", "resolution": [256, 256],
 "camera": {"position": [0, 4, 8], "target": [0, 0.5, 0], "fovy_deg": 45, "near": 0.1},
 "lights": [{"type": "point", "position": [2, 6, 1]}],
 "objects": [{"name": "ground", "shape": {"type": "plane", "size": [20, 20]}, "receiver": true},
             {"name": "ball", "shape": {"type": "mesh", "file": "$(basename "$mesh")"}, "transform": {"translate": [0, 1.5, 0]}}]}
JSON
triangles_label="$(python3 -c "print(f'{$tris/1e6:g}M')")"
echo "| tool | input | wall s | peak RSS MiB | exit |"
echo "| --- | --- | ---: | ---: | ---: |"
run() {
  local label="$1"; shift
  local log="$work/time_$(echo "$label" | tr ' /' '__').log"
  set +e
  /usr/bin/time -v "$@" >"$work/stdout.txt" 2>"$log"
  local rc=$?
  set -e
  local wall rss
  wall=$(grep 'Elapsed (wall clock)' "$log" | awk '{print $NF}' | awk -F: '{ if (NF==3) print $1*3600+$2*60+$3; else print $1*60+$2 }')
  rss=$(grep 'Maximum resident set size' "$log" | awk '{printf "%.0f", $NF/1024}')
  echo "| $label | ${triangles_label}-triangle sphere | $wall | $rss | $rc |"
}
run "math mesh-report" "$exe" math mesh-report --mesh "$mesh" --json
run "math silhouette" "$exe" math silhouette --mesh "$mesh" --light 2,6,1,1 --json
run "reference (spp 1)" "$exe" reference --scene "$work/large_mesh.json" --out "$work/reference" --spp 1 --quiet
for t in planar volume-zfail shadowmap; do
  run "render $t" "$exe" render --scene "$work/large_mesh.json" --technique "$t" --out "$work/render_$t"
done
