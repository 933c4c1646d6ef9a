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
exec lua5.2 "$here/caterpillar.lua" "$@"
