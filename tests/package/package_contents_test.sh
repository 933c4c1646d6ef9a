#!/usr/bin/env bash
# Packs this build with scripts/package.sh and checks the packages: every
# program with its man page, the Python package for Debian's python3, the
# data under /usr/share/mrsim, a valid desktop entry with its icon,
# Depends on the system's libraries (not bundled copies), the -dev
# package's headers and CMake package, and that the unpacked programs find
# their data relative to themselves.
set -euo pipefail
source_dir="$1"
binary_dir="$2"
out="$3"
rm -rf "$out"
mkdir -p "$out"
fail=0
bad() { echo "FAIL: $*" >&2; fail=1; }

started=$SECONDS
MRSIM_BUILD_DIR="$binary_dir" "$source_dir/scripts/package.sh" --out "$out" >"$out/package.log" 2>&1 || {
  cat "$out/package.log" >&2
  echo "FAIL: scripts/package.sh failed" >&2
  exit 1
}
echo "package.sh: $((SECONDS - started)) s"
deb="$(tail -1 "$out/package.log")"
version="$(sed -n 's/^CMAKE_PROJECT_VERSION:STATIC=//p' "$binary_dir/CMakeCache.txt")"
arch="$(dpkg --print-architecture)"
[ "$deb" = "$out/mrsim_${version}_$arch.deb" ] || bad "last line is '$deb', expected $out/mrsim_${version}_$arch.deb"
[ -f "$deb" ] || { echo "FAIL: no $deb" >&2; exit 1; }
dev="$out/mrsim-dev_${version}_$arch.deb"
[ -f "$dev" ] || bad "no $dev"
echo "sizes: $(du -h "$deb" | cut -f1) mrsim, $(du -h "$dev" | cut -f1) mrsim-dev"

# Contents: `dpkg-deb -c` lines end with the path (./usr/...).
dpkg-deb -c "$deb" | awk '{print $NF}' | sed 's|^\./|/|' >"$out/contents.txt"
has() { grep -qx -- "$1" "$out/contents.txt" || bad "mrsim.deb has no $1"; }
programs=0
for p in "$binary_dir"/bin/*; do
  name="$(basename "$p")"
  has "/usr/bin/$name"
  has "/usr/share/man/man1/$name.1.gz"
  programs=$((programs + 1))
done
[ "$programs" -ge 10 ] || bad "only $programs programs in $binary_dir/bin"
has /usr/lib/python3/dist-packages/mrsim/__init__.py
grep -q '^/usr/lib/python3/dist-packages/mrsim/_core\..*\.so$' "$out/contents.txt" ||
  bad "mrsim.deb has no Python extension /usr/lib/python3/dist-packages/mrsim/_core*.so"
has /usr/share/mrsim/scenarios/case_study.xml
has /usr/share/mrsim/scenarios/forward_gait.genome.xml
has /usr/share/mrsim/launch/demo.launch
has /usr/share/mrsim/launch/optimize_local.launch
has /usr/share/mrsim/README.md
has /usr/share/mrsim/docs/scaling.md
has /usr/share/applications/mrsim-studio.desktop
has /usr/share/icons/hicolor/scalable/apps/mrsim-studio.svg
has /usr/share/icons/hicolor/48x48/apps/mrsim-studio.png
if grep -E '\.(a|h)$|^/usr/local' "$out/contents.txt" | grep -q .; then
  bad "mrsim.deb holds libraries, headers or /usr/local: $(grep -E '\.(a|h)$|^/usr/local' "$out/contents.txt" | head -3)"
fi

# Depends: the system's libraries, found from the binaries, and what the
# Python package and the renderer need.
depends="$(dpkg-deb -f "$deb" Depends)"
echo "Depends: $depends"
for want in 'libmujoco' 'liblcm1' 'libopencv-' 'libglfw3' 'liblua5' 'libc6 (>= ' \
            'python3 (>= ' 'python3 (<< ' 'python3-numpy' 'fonts-dejavu-core' 'libegl-mesa0'; do
  case "$depends" in *"$want"*) ;; *) bad "Depends lacks $want" ;; esac
done
[ "$(dpkg-deb -f "$deb" Package)" = mrsim ] || bad "Package is not mrsim"
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || bad "Version is not $version"
# No library of the Depends is bundled.
if grep -E '/lib(mujoco|lcm|opencv|glfw|lua)[^/]*\.so' "$out/contents.txt" | grep -q .; then
  bad "mrsim.deb bundles a library: $(grep -E '/lib(mujoco|lcm|opencv|glfw|lua)[^/]*\.so' "$out/contents.txt" | head -3)"
fi

# Unpacked: desktop entry, icon, man pages.
tree="$out/tree"
dpkg-deb -x "$deb" "$tree"
desktop="$tree/usr/share/applications/mrsim-studio.desktop"
if command -v desktop-file-validate >/dev/null; then
  desktop-file-validate "$desktop" || bad "desktop-file-validate refuses mrsim-studio.desktop"
else
  echo "note: desktop-file-validate missing (desktop-file-utils), entry checked by hand only"
fi
exec_program="$(sed -n 's/^Exec=\([^ ]*\).*/\1/p' "$desktop")"
[ -x "$tree/usr/bin/$exec_program" ] || bad "the desktop entry runs '$exec_program', not in /usr/bin"
grep -qx 'Terminal=false' "$desktop" || bad "the desktop entry opens a terminal"
icon="$(sed -n 's/^Icon=//p' "$desktop")"
[ -f "$tree/usr/share/icons/hicolor/48x48/apps/$icon.png" ] || bad "no 48x48 icon named $icon"
head -c 8 "$tree/usr/share/icons/hicolor/48x48/apps/$icon.png" | grep -q PNG || bad "the icon is not a PNG"
page="$(gzip -dc "$tree/usr/share/man/man1/mrsim-sim.1.gz")"
echo "$page" | grep -q '^\.TH MRSIM-SIM "1"' || bad "mrsim-sim.1 has no .TH header"
echo "$page" | grep -qF -- '\-\-lcm\-url' || bad "mrsim-sim.1 does not list --lcm-url (not made from --help?)"

# The unpacked programs find their data beside them (../share/mrsim), from
# any folder: the launcher resolves the demo's ${launch_dir}/../scenarios.
mkdir -p "$out/elsewhere"
dry="$(cd "$out/elsewhere" && env -u MRSIM_DATA_DIR PATH="$tree/usr/bin:/usr/bin:/bin" \
  "$tree/usr/bin/mrsim" launch "$tree/usr/share/mrsim/launch/demo.launch" --dry-run 2>&1)" ||
  bad "mrsim launch --dry-run of the packaged demo failed: $dry"
echo "$dry" | grep -q "$tree/usr/share/mrsim/launch/../scenarios/case_study.xml\|$tree/usr/share/mrsim/scenarios/case_study.xml" ||
  bad "the packaged demo does not use the packaged scenario: $dry"
echo "$dry" | grep -q "^sim (required): $tree/usr/bin/mrsim-sim " ||
  bad "the packaged launcher does not start the packaged mrsim-sim: $dry"

# mrsim-dev: headers, static libraries and the CMake package.
dpkg-deb -c "$dev" | awk '{print $NF}' | sed 's|^\./|/|' >"$out/dev_contents.txt"
# (lib/ or lib/<multiarch>/, as the tree was configured.)
for want in /usr/include/mrsim/sim_core/scenario/scenario.h /usr/include/mrsim/common/data_dir.h \
            '/usr/lib/(.*/)?cmake/mrsim/mrsimConfig.cmake' '/usr/lib/(.*/)?cmake/mrsim/mrsimTargets.cmake' \
            '/usr/lib/(.*/)?libmrsim_sim_physics.a'; do
  grep -qxE -- "$want" "$out/dev_contents.txt" || bad "mrsim-dev.deb has no $want"
done
case "$(dpkg-deb -f "$dev" Depends)" in
  "mrsim (= $version), "*libmujoco-dev*) ;;
  *) bad "mrsim-dev Depends: $(dpkg-deb -f "$dev" Depends)" ;;
esac

rm -rf "$tree"
[ "$fail" = 0 ] && echo "packages OK: $deb"
exit "$fail"
