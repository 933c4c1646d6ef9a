#!/usr/bin/env bash
# The decoder targets' checked-in seeds (fuzz/corpus/lcm_decode and
# log_flatten) are exactly what mrsim_fuzz_seed_writer writes now. Their
# first byte picks the message type by its place in the generated type
# list, so a type added or renamed shifts every later seed onto another
# type: this fails until the corpus is rewritten (see seed_writer.cc).
set -euo pipefail
writer=$1
corpus=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
mkdir -p "$out/lcm_decode" "$out/log_flatten"
"$writer" "$out"
bad=0
for target in lcm_decode log_flatten; do
  for f in "$out/$target"/*; do
    name=$(basename "$f")
    if ! cmp -s "$f" "$corpus/$target/$name"; then
      echo "fuzz/corpus/$target/$name is not what the seed writer writes now"
      bad=1
    fi
  done
done
if [ "$bad" = 1 ]; then
  echo "rewrite it: cmake --build build --target mrsim_fuzz_seed_writer &&" \
       "build/fuzz/mrsim_fuzz_seed_writer fuzz/corpus"
fi
exit $bad
