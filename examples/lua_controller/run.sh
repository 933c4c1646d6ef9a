#!/usr/bin/env bash
# Generates the Lua message types (lcm-gen --lua) and runs caterpillar.lua
# with Debian's liblcm-lua (built for Lua 5.2). Arguments go to the script.
#   examples/lua_controller/run.sh --robot snake [--lcm-url URL] ...
# The types go to $MRSIM_LUA_TYPES (default ~/.cache/mrsim/lua_types) and
# are regenerated on every start, so they always match lcmtypes/mrsim/.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
types="${MRSIM_LUA_TYPES:-${XDG_CACHE_HOME:-$HOME/.cache}/mrsim/lua_types}"
for tool in lcm-gen lua5.2; do
  command -v "$tool" >/dev/null || {
    echo "run.sh: $tool not found (scripts/install_deps.sh installs it)" >&2
    exit 2
  }
done
mkdir -p "$types"
lcm-gen --lua --lpath "$types" "$root"/lcmtypes/mrsim/*.lcm >/dev/null
export LUA_PATH="$types/?.lua;$types/?/init.lua;;"
# Ctrl-C: lua5.2 stops at its next Lua instruction, but liblcm-lua's
# timedhandle answers an interrupted select() by blocking in lcm_handle()
# until a message comes, so with no simulator running it would not stop.
# Lua gets the interrupt from here (in its own session, so a terminal's
# Ctrl-C does not reach it twice), and is terminated if it is not done
# within two seconds.
setsid lua5.2 "$here/caterpillar.lua" "$@" &
pid=$!
stop() {
  kill -INT "$pid" 2>/dev/null || return 0
  for _ in $(seq 20); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  kill -TERM "$pid" 2>/dev/null || true
  echo "caterpillar.lua: stopped (no message arrived to end it cleanly)" >&2
  forced=1
}
forced=
trap stop INT TERM
status=0
wait "$pid" || status=$?
# A trapped signal ends the first wait early; the second gets lua's status.
if kill -0 "$pid" 2>/dev/null || [ "$status" -gt 128 ]; then
  wait "$pid" 2>/dev/null && status=0 || status=$?
fi
[ -n "$forced" ] && exit 130
exit "$status"
