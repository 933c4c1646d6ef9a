#!/usr/bin/env bash
# Installs mrsim from the build tree into a fresh prefix, builds
# examples/distance against the installed package only, and runs it.
set -euo pipefail
source_dir="$1"
binary_dir="$2"
work="$binary_dir/test_tmp/install_example"
rm -rf "$work"
mkdir -p "$work"

cmake --install "$binary_dir" --prefix "$work/prefix" >"$work/install.log"
# The default install is what a user runs: stripped programs and their
# data, a few tens of MB (README: Install); no static library or header.
size_mb="$(du -sm "$work/prefix" | cut -f1)"
echo "default install: $size_mb MB"
if [ "$size_mb" -ge 100 ]; then
  echo "default install is $size_mb MB (expected under 100)" >&2
  exit 1
fi
if find "$work/prefix" -name '*.a' -o -name '*.h' | grep -q .; then
  echo "default install holds libraries or headers:" >&2
  find "$work/prefix" -name '*.a' -o -name '*.h' | head >&2
  exit 1
fi
if file "$work/prefix/bin/mrsim-sim" | grep -q 'not stripped'; then
  echo "default install: programs not stripped" >&2
  exit 1
fi
# The libraries for building on mrsim, on request.
cmake --install "$binary_dir" --prefix "$work/prefix" --component development \
  >>"$work/install.log"
cmake -S "$source_dir/examples/distance" -B "$work/build" \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log"
cmake --build "$work/build" -j2 >"$work/build.log"
out="$("$work/build/distance" "$work/prefix/share/mrsim/scenarios/snake11.xml" forward 4)"
echo "$out"
# The 11-module snake must really have moved forward (+x) under the preset.
echo "$out" | awk '{ for (i = 1; i <= NF; ++i) if ($i == "(dx") { gsub(",", "", $(i+1)); exit !($(i+1) > 0.02) } exit 1 }'

# mrsim's optimiser as a library for a problem of one's own, no simulator
# (examples/optimise_function): it must climb Rosenbrock's valley from its
# start at (-1.5, ...) (fitness below -4000) to near its top (0), and the
# same seed must give the same run.
cmake -S "$source_dir/examples/optimise_function" -B "$work/build-opt" \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure-opt.log"
cmake --build "$work/build-opt" -j2 >"$work/build-opt.log"
first="$("$work/build-opt/optimise_function" cmaes 80 7)"
second="$("$work/build-opt/optimise_function" cmaes 80 7)"
echo "$first" | tail -n 2
if [ "$first" != "$second" ]; then
  echo "optimise_function: the same seed gave two different runs" >&2
  exit 1
fi
echo "$first" | tail -n 1 | awk '{ exit !($3 > -1.0) }' || {
  echo "optimise_function: CMA-ES did not get near the valley's best" >&2
  exit 1
}
