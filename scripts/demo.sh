#!/usr/bin/env bash
# The demo: installs what is missing, builds, and runs the original MRSim
# case study as separate processes over LCM (simulator, gait controller,
# logger, viewer): the 5-module robot drives forward into the ball for 20 s
# of simulated time. Needs no display.
# Usage: scripts/demo.sh [OUT_DIR]   (default out/demo)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${MRSIM_BUILD_DIR:-$root/build}"
out="$(mkdir -p "${1:-$root/out/demo}" && cd "${1:-$root/out/demo}" && pwd)"

bash "$root/scripts/install_deps.sh"
echo "== building the demo's programs (first time: a few minutes)"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
# Only what the demo runs (target mrsim_demo: the programs demo.launch
# starts, the launcher and the summary); scripts/test.sh builds the rest.
if ! cmake --build "$build" -j"$(nproc)" --target mrsim_demo >"$build/build.log" 2>&1; then
  grep -E -A5 'error' "$build/build.log" | head -60
  echo "demo: build failed (full log: $build/build.log)" >&2
  exit 1
fi

# LCM multicast needs a route; on a machine without a network add one on lo.
if ! ip route get 239.255.76.67 >/dev/null 2>&1; then
  echo "demo: no route for multicast; run: sudo ip route add 239.255.0.0/16 dev lo" >&2
  exit 1
fi

rm -rf "$out"/csv "$out"/*.png "$out"/demo.mp4 "$out"/final.checkpoint
echo "== running the case study (20 s of simulated time)"
"$build/bin/mrsim" launch "$root/launch/demo.launch" --set "out=$out"

echo
echo "== outputs"
for f in "$out"/csv/*.csv "$out"/*.png "$out"/demo.mp4 "$out"/final.checkpoint; do
  [ -e "$f" ] && printf '  %-60s %s\n' "$f" "$(du -h "$f" | cut -f1)"
done
echo
echo "== summary"
"$build/bin/mrsim-summary" "$root/scenarios/case_study.xml" "$out/final.checkpoint"
