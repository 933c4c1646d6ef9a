#!/usr/bin/env bash
# The docs runner passes a document whose blocks work and fails one where a
# snippet was changed to be wrong, naming the file and line; a block
# without a language is an error.
set -uo pipefail
source_dir="$1"
binary_dir="$2"
work="$binary_dir/test_tmp/docs_runner"
rm -rf "$work"
mkdir -p "$work"
runner=(/usr/bin/python3 "$source_dir/scripts/docs_runner.py" --build "$binary_dir"
  --port 7992 --scratch "$work/scratch")
fixture="$source_dir/tests/docs/fixture.md"
fail() { echo "FAILED: $*" >&2; exit 1; }

"${runner[@]}" "$fixture" >"$work/good.log" 2>&1 || { cat "$work/good.log"; fail "the good document failed"; }
grep -q "3 passed, 0 failed" "$work/good.log" || { cat "$work/good.log"; fail "not 3 passed"; }
grep -q "fixture.md:[0-9]* (sh): manual: shown, never run" "$work/good.log" ||
  { cat "$work/good.log"; fail "the manual block was not reported"; }

# One word of the snippet changed: the runner fails at that block.
sed 's/validate scenarios/valdate scenarios/' "$fixture" >"$work/wrong.md"
"${runner[@]}" "$work/wrong.md" >"$work/wrong.log" 2>&1
rc=$?
cat "$work/wrong.log"
[ "$rc" = 1 ] || fail "a wrong snippet gave exit status $rc, not 1"
grep -q "^FAIL .*wrong.md:5 (sh" "$work/wrong.log" || fail "the failing block is not named"
grep -q "valdate" "$work/wrong.log" || fail "the block's output is not shown"

# A Lua snippet changed to be wrong fails too.
sed "s/require('mrsim')/require('mrsim_nope')/" "$fixture" >"$work/wrong_lua.md"
"${runner[@]}" "$work/wrong_lua.md" >"$work/wrong_lua.log" 2>&1
[ $? = 1 ] || { cat "$work/wrong_lua.log"; fail "a wrong Lua snippet passed"; }

# A block nobody labelled is an error, not silently skipped.
printf '# x\n\n```\nls\n```\n' >"$work/unlabelled.md"
"${runner[@]}" "$work/unlabelled.md" >"$work/unlabelled.log" 2>&1
[ $? = 2 ] || { cat "$work/unlabelled.log"; fail "an unlabelled block was not an error"; }
grep -q "unlabelled.md:3: a block without a language" "$work/unlabelled.log" ||
  fail "the unlabelled block is not named"
echo "docs runner test: passed"
