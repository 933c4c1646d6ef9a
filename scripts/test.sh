#!/usr/bin/env bash
# Installs what is missing, builds everything with warnings as errors and
# runs the whole test suite. ctest's summary line is the last thing printed.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${MRSIM_BUILD_DIR:-$root/build}"
jobs="$(nproc)"

bash "$root/scripts/install_deps.sh"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMRSIM_WERROR=ON >/dev/null
if ! cmake --build "$build" -j"$jobs" >"$build/build.log" 2>&1; then
  grep -E -A5 'error|Error' "$build/build.log" | head -80
  echo "build failed (full log: $build/build.log)"
  exit 1
fi

cd "$build"
summary_re='tests passed, [0-9]+ tests? failed out of'
set +e
ctest -j"$jobs" --output-on-failure --timeout 600 2>&1 | tee ctest.log | grep --line-buffered -vE "$summary_re"
rc=${PIPESTATUS[0]}
set -e
grep -E "$summary_re" ctest.log || echo "0 passed, 1 failed: ctest printed no summary"
exit "$rc"
