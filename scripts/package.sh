#!/usr/bin/env bash
# Packs a build into Debian packages for another machine:
#   mrsim_<version>_<arch>.deb      the programs (/usr/bin) with man pages,
#                                   the Python package for Debian's python3,
#                                   scenarios, launch files and docs
#                                   (/usr/share/mrsim), the studio's desktop
#                                   entry and icon
#   mrsim-dev_<version>_<arch>.deb  headers, static libraries and the CMake
#                                   package, for find_package(mrsim)
#
#   scripts/package.sh [--out DIR] [--no-dev]
#
# It packs build/ (or the tree MRSIM_BUILD_DIR names) as it is and builds
# nothing: run scripts/demo.sh, scripts/test.sh or cmake --build first.
# Packages go to DIR (default: <build>/deb). The last line printed is the
# path of the mrsim .deb.
#
# Why `cmake --install` into a staging folder and dpkg-deb, not CPack:
# cpack builds the `all` target before it installs (about 20 minutes on 2
# cores here, a thousand tests and the benchmarks included) and needs
# include(CPack) configured into the tree, while the install rules alone
# copy what is already built; and what Debian wants beyond the install
# (Python in dist-packages, man pages from each program's --help, Depends
# from dpkg-shlibdeps, md5sums) is a few plain commands below.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${MRSIM_BUILD_DIR:-$root/build}"
out=""
dev=1
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="${2:?--out needs a folder}"; shift 2 ;;
    --out=*) out="${1#*=}"; shift ;;
    --no-dev) dev=0; shift ;;
    *) echo "usage: scripts/package.sh [--out DIR] [--no-dev]" >&2; exit 2 ;;
  esac
done

# What the packages need beyond the shared libraries their programs link
# (those dpkg-shlibdeps computes from the binaries: MuJoCo, LCM, OpenCV,
# GLFW, Lua, GLib, OpenSSL, ...). The one list of hand-picked dependencies.
runtime_depends=(
  python3-numpy      # the Python package's arrays
  fonts-dejavu-core  # the studio's text
  libegl-mesa0       # off-screen rendering (mrsim-view, studio --screenshot):
  libgl1-mesa-dri    #   Mesa's EGL and its software renderer, no GPU needed
)
runtime_recommends=(
  liblcm-bin         # lcm-logger, lcm-logplayer (README)
  liblcm-java        # mrsim-lcm-spy and the TCP hub of launch files
  libjchart2d-java   # mrsim-lcm-spy's plots
  default-jre        # mrsim-lcm-spy is a Java window
  xvfb               # the studio and the live viewer on a host without a display
)
# Building on the libraries: what mrsimConfig.cmake finds and what the
# static libraries link.
dev_depends=(
  cmake pkg-config
  libmujoco-dev libeigen3-dev libtinyxml2-dev libfmt-dev libcli11-dev
  libssl-dev zlib1g-dev liblcm-dev libglib2.0-dev libstb-dev libopencv-dev
  liblua5.4-dev libglfw3-dev libosmesa6-dev libegl-dev
)

need() {
  command -v "$1" >/dev/null || {
    echo "package.sh: $1 not found (Debian package $2; scripts/install_deps.sh installs it)" >&2
    exit 2
  }
}
need dpkg-deb dpkg
need dpkg-shlibdeps dpkg-dev
need help2man help2man
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "package.sh: no build in $build (run scripts/demo.sh or scripts/test.sh first, or set MRSIM_BUILD_DIR)" >&2
  exit 2
fi
cache() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
version="$(cache CMAKE_PROJECT_VERSION)"
python="$(cache Python3_EXECUTABLE)"
arch="$(dpkg --print-architecture)"
out="${out:-$build/deb}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
work="$out/stage"
rm -rf "$work"
mkdir -p "$work"
started=$SECONDS

# --- mrsim: what a user runs ---------------------------------------------
stage="$work/mrsim"
if ! cmake --install "$build" --prefix "$stage/usr" >"$work/install.log" 2>&1; then
  tail -5 "$work/install.log" >&2
  echo "package.sh: cmake --install $build failed (is the build complete? cmake --build $build; log: $work/install.log)" >&2
  exit 1
fi
# The Python package goes where Debian's python3 looks
# (/usr/lib/python3/dist-packages), whatever prefix the tree was
# configured for.
py_src="$(find "$stage/usr/lib" -path '*-packages/mrsim/__init__.py' -printf '%h\n' 2>/dev/null | head -1)"
if [ -z "$py_src" ]; then
  echo "package.sh: the build has no Python package (configure needs python3-dev and pybind11-dev)" >&2
  exit 1
fi
dist="$stage/usr/lib/python3/dist-packages"
if [ "$py_src" != "$dist/mrsim" ]; then
  mkdir -p "$dist"
  mv "$py_src" "$dist/mrsim"
  find "$stage/usr/lib" -depth -type d -empty -delete
fi
find "$dist" -name __pycache__ -prune -exec rm -rf {} +
py_version="$("$python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
py_next="$("$python" -c 'import sys; print("%d.%d" % (sys.version_info[0], sys.version_info[1] + 1))')"

# The studio in the desktop menu.
install -D -m 644 "$root/packaging/mrsim-studio.desktop" \
  "$stage/usr/share/applications/mrsim-studio.desktop"
"$python" "$root/packaging/make_icon.py" "$work/icon"
icons="$stage/usr/share/icons/hicolor"
install -D -m 644 "$work/icon/mrsim-studio.svg" "$icons/scalable/apps/mrsim-studio.svg"
for size in 48 128; do
  install -D -m 644 "$work/icon/mrsim-studio-$size.png" "$icons/${size}x$size/apps/mrsim-studio.png"
done

# A man page per program, from its --help and --version.
man="$stage/usr/share/man/man1"
mkdir -p "$man"
for program in "$stage"/usr/bin/*; do
  name="$(basename "$program")"
  # The first line of --help says what it does ("mrsim-sim: simulate a
  # scenario ..." or a sentence): the man page's NAME line. (sed reads all
  # of it: head would stop the program with SIGPIPE.)
  what="$({ "$program" --help 2>&1 || true; } |
    sed -n '1{s/^mrsim[-a-z ]*: *//; s/\. .*//; s/\.$//; s/^\(.\)/\L\1/; p}')"
  if ! help2man --no-info --no-discard-stderr --section 1 --source "mrsim $version" \
       --name "${what:-part of mrsim, a simulator for modular robots}" \
       --output "$man/$name.1" "$program" 2>"$work/help2man.log"; then
    cat "$work/help2man.log" >&2
    echo "package.sh: help2man could not make a man page from $name --help" >&2
    exit 1
  fi
  gzip -9n "$man/$name.1"
done

# Shared-library dependencies from the binaries themselves, as Debian's
# own packages get them (dpkg-shlibdeps reads a debian/control).
mkdir -p "$work/shlibs/debian"
printf 'Source: mrsim\n\nPackage: mrsim\nArchitecture: any\n' >"$work/shlibs/debian/control"
mapfile -t elves < <(find "$stage/usr/bin" "$stage/usr/lib" -type f -exec sh -c \
  'head -c 4 "$1" | grep -q "ELF" && echo "$1"' _ {} \;)
shlibs="$(cd "$work/shlibs" && dpkg-shlibdeps -O "${elves[@]}" 2>"$work/shlibdeps.log" |
  sed -n 's/^shlibs:Depends=//p')" || {
  cat "$work/shlibdeps.log" >&2
  echo "package.sh: dpkg-shlibdeps failed" >&2
  exit 1
}
join() { local IFS=,; echo "$*" | sed 's/,/, /g'; }
depends="$shlibs, python3 (>= $py_version), python3 (<< $py_next), $(join "${runtime_depends[@]}")"

maintainer="${MRSIM_MAINTAINER:-mrsim maintainers <mrsim@localhost>}"
# Writes DEBIAN/control and md5sums for the staged tree $1, builds $2.
pack() {
  local tree="$1" deb="$2"
  (cd "$tree" && find usr -type f -print0 | sort -z | xargs -0 md5sum >DEBIAN/md5sums)
  # Fast compression: the test suite packs on every run (gzip -1 is a few
  # seconds; xz would be minutes for a few MB less).
  dpkg-deb --root-owner-group -Zgzip -z1 --build "$tree" "$deb" >/dev/null
}
mkdir -p "$stage/DEBIAN"
cat >"$stage/DEBIAN/control" <<EOF
Package: mrsim
Version: $version
Architecture: $arch
Maintainer: $maintainer
Installed-Size: $(du -sk "$stage/usr" | cut -f1)
Depends: $depends
Recommends: $(join "${runtime_recommends[@]}")
Section: science
Priority: optional
Description: simulator for chain-based modular robots
 Describe a snake or caterpillar robot in one XML scenario, run it in
 MuJoCo physics, drive it with gait controllers, log and plot its sensors,
 record it to video and optimise its gait and body on a farm of hosts.
 Every part is its own process talking LCM: mrsim-sim, mrsim-gait,
 mrsim-log, mrsim-view, mrsim-camera, mrsim-opt and mrsim-worker, mrsim launch for
 launch files, and mrsim-studio to design robots in a window. Includes
 the mrsim Python package, the bundled scenarios and launch files
 (/usr/share/mrsim) and the documentation.
EOF
deb="$out/mrsim_${version}_$arch.deb"
pack "$stage" "$deb"

# --- mrsim-dev: building on the libraries ---------------------------------
if [ "$dev" = 1 ]; then
  stage_dev="$work/mrsim-dev"
  cmake --install "$build" --prefix "$stage_dev/usr" --component development \
    >>"$work/install.log" 2>&1
  # Debug information is nine tenths of the static libraries (193 MB with,
  # README: Installing); a package for building on them does without.
  find "$stage_dev/usr" -name '*.a' -exec strip --strip-debug {} +
  mkdir -p "$stage_dev/DEBIAN"
  cat >"$stage_dev/DEBIAN/control" <<EOF
Package: mrsim-dev
Version: $version
Architecture: $arch
Maintainer: $maintainer
Installed-Size: $(du -sk "$stage_dev/usr" | cut -f1)
Depends: mrsim (= $version), $(join "${dev_depends[@]}")
Section: libdevel
Priority: optional
Description: simulator for chain-based modular robots - libraries and headers
 Static libraries, headers and the CMake package of mrsim:
 find_package(mrsim) gives mrsim::sim_core (scenarios and MuJoCo physics),
 mrsim::gait, mrsim::optimizer, mrsim::logger, mrsim::viewer,
 mrsim::lcmtypes and mrsim::runtime for programs of your own.
EOF
  pack "$stage_dev" "$out/mrsim-dev_${version}_$arch.deb"
  echo "mrsim-dev: $out/mrsim-dev_${version}_$arch.deb ($(du -h "$out/mrsim-dev_${version}_$arch.deb" | cut -f1))"
fi
rm -rf "$work"
echo "packed in $((SECONDS - started)) s; install with: sudo apt install $deb"
echo "$deb"
