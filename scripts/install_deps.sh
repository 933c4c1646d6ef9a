#!/usr/bin/env bash
# Installs the Debian packages mrsim needs. Idempotent: only missing packages
# are fetched, so a second run costs one dpkg query.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  liblcm-dev liblcm-bin liblcm-java libjchart2d-java liblcm-lua lua5.2 liblua5.4-dev libglib2.0-dev default-jdk-headless
  libmujoco-dev libqhull-dev libmujoco-samples
  libeigen3-dev libtinyxml2-dev libstb-dev zlib1g-dev libopencv-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libfmt-dev libssl-dev
  libosmesa6-dev libglfw3-dev libegl-dev libegl-mesa0 xvfb
  libimgui-dev xdotool fonts-dejavu-core
  clang-format clang libfuzzer-14-dev lld
  iproute2 nftables
  dpkg-dev help2man desktop-file-utils
  slurm-wlm munge
  python3-dev python3-numpy python3-pytest pybind11-dev python3-matplotlib
  libzstd-dev libdeflate-dev libprotobuf-dev python3-protobuf nodejs
  libwebsocketpp-dev libasio-dev nlohmann-json3-dev
  chromium
)
# npm: Debian's package, unless the nodejs installed brings its own (as
# NodeSource's does, which conflicts with Debian's npm).
if ! command -v npm >/dev/null 2>&1; then packages+=(npm); fi

# The npm packages the MCAP and Foxglove tests use (tests/mcap: MCAP's
# reference reader; tests/foxglove: Foxglove's WebSocket client) and
# three.js for mrsim-foxglove's browser page (foxglove/web), each pinned
# by its package-lock.json: fetched once, then nothing is fetched again
# until a lock file changes, so later runs work offline.
npm_packages() {
  local root dir
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  for dir in "$root/tests/mcap" "$root/tests/foxglove" "$root/foxglove/web"; do
    if [ -f "$dir/node_modules/.package-lock.json" ] &&
       [ ! "$dir/package-lock.json" -nt "$dir/node_modules/.package-lock.json" ]; then
      continue
    fi
    echo "install_deps: npm ci in ${dir#"$root"/}"
    (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error)
  done
}

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages present"
  npm_packages
  exit 0
fi

echo "install_deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
npm_packages
echo "install_deps: done"
