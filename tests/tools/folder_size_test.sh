#!/usr/bin/env bash
# No product folder holds more than 40 source files directly: a folder that
# grows past that is split into rooms by role (docs/architecture.md). Tests,
# fuzz corpora and generated files are not product folders.
set -euo pipefail
root=$1
limit=${2:-40}
cd "$root"
bad=0
while read -r count folder; do
  if (( count > limit )); then
    echo "$folder holds $count source files directly, at most $limit: split it into rooms (docs/architecture.md)"
    bad=1
  fi
done < <(git ls-files -- '*.cc' '*.h' '*.hpp' '*.py' '*.pyi' '*.js' '*.lua' \
           ':!:tests/**' ':!:**/corpus/**' ':!:**/regressions/**' |
         xargs -r -n1 dirname | sort | uniq -c)
exit $bad
