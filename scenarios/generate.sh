#!/bin/sh
# Regenerates the example scenarios with `mrsim-scenario new` plus the few
# additions `new` does not make (the ball, the terrain, the obstacles), then
# rewrites each file in canonical form with `mrsim-scenario convert`.
# Usage: scenarios/generate.sh [path/to/mrsim-scenario]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
tool=${1:-$here/../build/sim_core/scenario_tool/mrsim-scenario}
cd "$here"

# Replaces the line `<sceneObjects xmlns="Assembly" />` of $1 with the
# SceneObject elements read from stdin.
add_objects() {
  objects=$(mktemp)
  { echo '  <sceneObjects xmlns="Assembly">'; cat; echo '  </sceneObjects>'; } >"$objects"
  sed -i -e "/<sceneObjects xmlns=\"Assembly\" \/>/{r $objects" -e 'd}' "$1"
  rm -f "$objects"
}

# Writes one SceneObject: guid shape sx sy sz x y z mass isStatic.
object() {
  cat <<OBJ
    <SceneObject>
      <guid>$1</guid>
      <size><x>$3</x><y>$4</y><z>$5</z></size>
      <position><x>$6</x><y>$7</y><z>$8</z></position>
      <materialName>plastic</materialName>
      <shape>$2</shape>
      <mass>$9</mass>
      <isStatic>${10}</isStatic>
    </SceneObject>
OBJ
}

# An 11-module pitch snake on flat ground.
"$tool" new --modules 11 --pattern pitch --name snake --friction 0.5 \
  -o snake11.xml

# The original's case study: 5 pitch-yaw modules of 100 g, a sensor module
# in front of, between and behind them (6), a force sensor under each, a
# distance sensor at the front, plastic everywhere, a ball 0.6 m ahead.
"$tool" new --modules 5 --pattern pitch-yaw --sensors all --force-sensors \
  --front-distance-sensor --module-mass 0.1 --material plastic \
  --ground-material plastic --friction 0.5 --name case_study \
  -o case_study.xml
object ball Sphere 0.1 0.1 0.1 0.6 0 0.05 0.05 false | add_objects case_study.xml
"$tool" convert case_study.xml case_study.xml

# An 8-module pitch-yaw snake on the flat middle of a 3.2 m height field
# (terrain.png, made by make_terrain_png.py) with static box obstacles.
"$tool" new --modules 8 --pattern pitch-yaw --name snake --friction 0.6 \
  --origin 0.4 0 0 -o terrain.xml
{
  object rock1 Box 0.1 0.1 0.1 0.9 0.25 0.05 1 true
  object rock2 Box 0.1 0.1 0.1 0.9 -0.3 0.05 1 true
  object wall Box 0.2 0.05 0.08 0.2 0.45 0.04 1 true
} | add_objects terrain.xml
sed -i -e 's|<height_Image />|<height_Image>terrain.png</height_Image>|' \
  -e 's|<height>0</height>|<height>0.3</height>|' terrain.xml
# The scene's corner: the first <position> after <scene>.
sed -i -e '/<scene>/,/<\/position>/{s|<x>0</x>|<x>-1.6</x>|;s|<y>0</y>|<y>-1.6</y>|}' \
  terrain.xml
"$tool" convert terrain.xml terrain.xml
# A 5-module pitch-yaw snake with a sensor module between each pair of
# modules, each carrying an IMU (<imu/>: accelerometer and gyroscope at the
# module's centre, no noise), for the IMU's columns, plots and marker.
"$tool" new --modules 5 --pattern pitch-yaw --sensors between \
  --friction 0.5 --name imu_snake -o imu_snake.xml
sed -i -e 's|</SensorModule>|<imu /></SensorModule>|' imu_snake.xml
"$tool" convert imu_snake.xml imu_snake.xml

# A 6-module pitch-yaw snake with a camera looking ahead from a sensor
# module in front of module 0 (160x120 at 30 pictures per simulated
# second, turned 10 degrees down), a red ball 1.2 m ahead and 0.5 m to its
# left to see and steer to (docs/camera.md), and two boxes to its right.
"$tool" new --modules 6 --pattern pitch-yaw --sensors=-1 --friction 0.5 \
  --name camera_snake -o camera_snake.xml
sed -i -e 's|</SensorModule>|<cameras><Camera><sensorPosition>4</sensorPosition><tilt>10</tilt></Camera></cameras></SensorModule>|' \
  camera_snake.xml
{
  object ball Sphere 0.15 0.15 0.15 1.2 0.5 0.075 0.2 true
  object box1 Box 0.1 0.1 0.2 0.9 -0.6 0.1 1 true
  object box2 Box 0.1 0.1 0.2 1.6 -0.3 0.1 1 true
} | add_objects camera_snake.xml
"$tool" convert camera_snake.xml camera_snake.xml

# snake11 with how to run it saved (<run>): lockstep at 100 Hz, driven by
# the serpenoid Lua template carried in the file (docs/sim.md, "A design's
# saved run settings").
script=$here/../lua_controller/templates/serpenoid.lua
{
  echo '  <run>'
  echo '    <clock>lockstep</clock>'
  echo '    <controller>lua</controller>'
  printf '    <luaScript><![CDATA['
  cat "$script"
  echo ']]></luaScript>'
  echo '  </run>'
} >run.part
sed -e '/<\/settings>/r run.part' snake11.xml >lua_serpenoid.xml
rm -f run.part
"$tool" convert lua_serpenoid.xml lua_serpenoid.xml

# snake11 with how to optimise it saved (<optimization>): mrsim-opt
# optimise_snake.xml runs CMA-ES on the seven sine genes for a short budget
# (docs/optimizer.md, "The setup in the design file").
{
  echo '  <optimization>'
  echo '    <algorithm>cmaes</algorithm>'
  echo '    <generations>4</generations>'
  echo '    <population>4</population>'
  echo '    <seed>3</seed>'
  echo '    <episode>2</episode>'
  echo '    <genes>sine</genes>'
  echo '    <wEnergy>0.01</wEnergy>'
  echo '  </optimization>'
} >opt.part
sed -e '/<\/settings>/r opt.part' snake11.xml >optimise_snake.xml
rm -f opt.part
"$tool" convert optimise_snake.xml optimise_snake.xml

"$tool" validate snake11.xml
"$tool" validate lua_serpenoid.xml
"$tool" validate optimise_snake.xml
"$tool" validate case_study.xml
"$tool" validate terrain.xml
"$tool" validate imu_snake.xml
"$tool" validate camera_snake.xml
