#!/usr/bin/env bash
# Installs the .deb Package.DebContents made with apt-get (as a user of
# another machine would), then from a folder outside the source tree, with
# only the system's PATH and Python: mrsim-sim --version, import mrsim,
# the bundled demo launch file for 2 s on its own LCM port, mrsim tasks,
# and the studio as the desktop menu starts it (template dialog up). The
# package is removed afterwards, also on failure. Needs root; exits 77
# (reported as skipped) without it, or when an mrsim package is installed
# already (it is not this test's to replace).
set -euo pipefail
binary_dir="$1"
package_dir="$2"
skip() { echo "SKIP: $*"; exit 77; }
[ "$(id -u)" = 0 ] || skip "installing a package needs root"
if dpkg-query -W -f='${Status}' mrsim 2>/dev/null | grep -q 'install ok installed'; then
  skip "an mrsim package is installed on this machine already; not replacing it"
fi
version="$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$binary_dir/CMakeCache.txt")"
deb="$package_dir/mrsim_${version}_$(dpkg --print-architecture).deb"
[ -f "$deb" ] || { echo "FAIL: no $deb (Package.DebContents makes it)" >&2; exit 1; }
if ! ip route get 239.255.76.67 >/dev/null 2>&1; then
  echo "FAIL: no route for multicast 239.255.76.67 (README: Multicast)" >&2
  exit 1
fi
work="$binary_dir/test_tmp/package_install"
rm -rf "$work"
mkdir -p "$work/home"

remove() {
  DEBIAN_FRONTEND=noninteractive apt-get remove -y -qq mrsim >"$work/remove.log" 2>&1 ||
    { cat "$work/remove.log" >&2; echo "FAIL: apt-get remove mrsim" >&2; }
}
trap remove EXIT
started=$SECONDS
# --no-install-recommends: the Java spy and Xvfb are not needed here, and
# a test must not download; every Depends is installed by install_deps.sh.
if ! DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$deb" \
     >"$work/install.log" 2>&1; then
  cat "$work/install.log" >&2
  echo "FAIL: apt-get install $deb" >&2
  exit 1
fi
echo "apt-get install: $((SECONDS - started)) s"

# A user's shell elsewhere: the system's PATH (no build/bin, no pyenv), no
# PYTHONPATH, no data folder override.
port=$((8471 + ${MRSIM_TEST_PORT_OFFSET:-0}))
url="udpm://239.255.76.67:$port?ttl=0"
run() {
  (cd "$work/home" && env -i HOME="$work/home" PATH=/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 "$@")
}
fail=0
bad() { echo "FAIL: $*" >&2; fail=1; }

where="$(run sh -c 'command -v mrsim-sim')"
[ "$where" = /usr/bin/mrsim-sim ] || bad "mrsim-sim is '$where', expected /usr/bin/mrsim-sim"
out="$(run mrsim-sim --version 2>&1)" || bad "mrsim-sim --version: $out"
case "$out" in *"$version"*) ;; *) bad "mrsim-sim --version says '$out', expected $version" ;; esac
echo "$out"

out="$(run python3 -c 'import mrsim; print(mrsim.__file__)' 2>&1)" || bad "import mrsim: $out"
[ "$out" = /usr/lib/python3/dist-packages/mrsim/__init__.py ] || bad "import mrsim found '$out'"

started=$SECONDS
if ! run timeout 120 mrsim launch /usr/share/mrsim/launch/demo.launch \
     --set out="$work/demo" --set duration=2 --set lcm_url="$url" >"$work/demo.log" 2>&1; then
  tail -30 "$work/demo.log" >&2
  bad "mrsim launch /usr/share/mrsim/launch/demo.launch failed (log: $work/demo.log)"
fi
echo "demo launch (2 s): $((SECONDS - started)) s"
for f in final.checkpoint csv/MRSIM_STATE_case_study.csv demo.mp4 front_distance.png; do
  [ -s "$work/demo/$f" ] || bad "the installed demo wrote no $work/demo/$f (log: $work/demo.log)"
done

out="$(run mrsim tasks 2>&1)" || bad "mrsim tasks: $out"
case "$out" in *flat*) ;; *) bad "mrsim tasks lists no flat task: $out" ;; esac
out="$(run mrsim tasks flat --write "$work/flat.xml" 2>&1)" || bad "mrsim tasks flat --write: $out"
out="$(run mrsim-scenario validate "$work/flat.xml" 2>&1)" || bad "the flat task's scenario: $out"

# The desktop entry's command with no file: the template dialog is up.
out="$(run timeout 120 mrsim-studio --screenshot "$work/studio.png" \
  --layout-dump "$work/studio.txt" 2>&1)" || bad "mrsim-studio --screenshot: $out"
grep -qxP 'modal\ttemplate' "$work/studio.txt" 2>/dev/null ||
  bad "the installed studio with no file does not open the template dialog"
if command -v man >/dev/null; then
  run man -w mrsim-sim >/dev/null 2>&1 || bad "man -w mrsim-sim finds no man page"
fi

trap - EXIT
remove
[ ! -e /usr/bin/mrsim-sim ] || bad "apt-get remove left /usr/bin/mrsim-sim"
[ "$fail" = 0 ] && echo "installed package OK"
exit "$fail"
