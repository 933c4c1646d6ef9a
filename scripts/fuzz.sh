#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan+UBSan, build-fuzz/) and runs
# each for SECONDS (default 60). Out-of-memory counts as a crash
# (-rss_limit_mb=2048), as does a single input taking over 10 s.
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]
#
# Each target starts from its checked-in seed corpus (fuzz/corpus/<t>/) and
# its regressions (fuzz/regressions/<t>/); what it learns goes to
# build-fuzz/corpus/<t>/, never into the source tree. A crash leaves its
# input in build-fuzz/artifacts/<t>/: copy it to fuzz/regressions/<t>/ and
# fix the reader; the unit tests (fuzz_replay.<t>) then replay it forever.
# Prints one `BENCH fuzz_execs_per_s_<t> N execs/s` line per target.
set -uo pipefail
root="$(cd "$(dirname "$(readlink -f "$0")")/.." && pwd)"
seconds="${1:-60}"
shift || true
case "$seconds" in ''|*[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS] [TARGET...]" >&2; exit 2 ;; esac
build="${MRSIM_FUZZ_BUILD_DIR:-$root/build-fuzz}"

bash "$root/scripts/install_deps.sh" >/dev/null || exit 1
mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DMRSIM_FUZZ=ON -DMRSIM_BUILD_BENCH=OFF >"$build/configure.log" 2>&1 ||
  { tail -30 "$build/configure.log"; echo "fuzz: configure failed"; exit 1; }
if ! cmake --build "$build" -j"$(nproc)" --target mrsim_fuzz_targets >"$build/build.log" 2>&1; then
  grep -E -A5 'error' "$build/build.log" | head -60
  echo "fuzz: build failed (full log: $build/build.log)"
  exit 1
fi

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$root"/fuzz/*_fuzz.cc; do t="$(basename "$f" _fuzz.cc)"; targets+=("$t"); done
fi

failed=()
for t in "${targets[@]}"; do
  exe="$(find "$build" -name "${t}_fuzz" -type f -perm -u+x | head -1)"
  if [ -z "$exe" ]; then echo "fuzz: no program for target $t"; failed+=("$t"); continue; fi
  corpus="$build/corpus/$t"
  artifacts="$build/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  args=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
        -artifact_prefix="$artifacts/")
  # XML readers get the XML dictionary; a target may name its own.
  if [ -f "$root/fuzz/$t.dict" ]; then args+=(-dict="$root/fuzz/$t.dict")
  elif grep -q 'fuzz-dict: xml' "$root/fuzz/${t}_fuzz.cc"; then args+=(-dict="$root/fuzz/xml.dict"); fi
  seeds=()
  for d in "$root/fuzz/corpus/$t" "$root/fuzz/regressions/$t"; do [ -d "$d" ] && seeds+=("$d"); done
  log="$build/$t.log"
  (cd "$build" && ASAN_OPTIONS="detect_leaks=1" \
    "$exe" "${args[@]}" "$corpus" "${seeds[@]}") >"$log" 2>&1
  rc=$?
  runs="$(grep -E '^stat::number_of_executed_units:' "$log" | awk '{print $2}' | tail -1)"
  secs="$(grep -E '^Done [0-9]+ runs in [0-9]+ second' "$log" | awk '{print $5}' | tail -1)"
  [ -z "$secs" ] || [ "$secs" = 0 ] && secs="$seconds"
  if [ -n "$runs" ]; then echo "BENCH fuzz_execs_per_s_$t $(( runs / secs )) execs/s"; fi
  if [ "$rc" != 0 ]; then
    grep -E -A25 'ERROR: |==[0-9]+==|SUMMARY|Test unit written' "$log" | head -60
    echo "fuzz: $t FAILED (log: $log, input in $artifacts/)"
    failed+=("$t")
  else
    echo "fuzz: $t ok ($runs runs in ${secs}s, corpus $(ls "$corpus" | wc -l) inputs)"
  fi
done
if [ ${#failed[@]} -gt 0 ]; then echo "fuzz: failed: ${failed[*]}"; exit 1; fi
echo "fuzz: ${#targets[@]} targets ran ${seconds}s each, no crash"
