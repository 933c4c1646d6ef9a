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
cmake -S "$source_dir/examples/distance" -B "$work/build" \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log"
cmake --build "$work/build" -j2 >"$work/build.log"
out="$("$work/build/distance" "$work/prefix/share/mrsim/scenarios/snake11.xml" forward 4)"
echo "$out"
# The 11-module snake must really have moved forward (+x) under the preset.
echo "$out" | awk '{ for (i = 1; i <= NF; ++i) if ($i == "(dx") { gsub(",", "", $(i+1)); exit !($(i+1) > 0.02) } exit 1 }'
