// The worlds of the task suite. Geometry in metres; the robot (MakeChain,
// pitch-yaw, 12 modules of 0.1 m) lies along x with its head at x = 0 and
// its tail at x = -1.2 unless a task says otherwise.
#include "optimizer/episode/task.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <utility>

#include "gait_controller/gait_presets.h"
#include "sim_core/mesh/base64.h"
#include "sim_core/scenario/chain_builder.h"

namespace mrsim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr const char* kRobotMaterial = "plastic";

// The obstacle fields (stairs, rubble) reach kReach from where the robot
// starts, to either side and ahead (the pegs are walled in instead), so a
// gait scores there only by meeting the obstacles. Fields 2 m wide let a
// gait that drifted sideways go round them and score to 16 digits as on
// flat (the start genome of mrsim-opt --genes cpg drifts 2.5 m). 4 m is
// 0.2 m/s for the 20 s episode, faster than anything in docs/tasks.md
// moves (the fastest, optimised genomes and that drifting one, about
// 0.14 m/s).
constexpr double kReach = 4.0;
constexpr double kRobotLength = 0.1 * kTaskModules;  // tail at x = -1.2

// Distance in the ground plane from (x, y) to the robot's body as it
// starts (the segment from its tail to its head along x).
double FromStartBody(double x, double y) {
  return std::hypot(std::max({-kRobotLength - x, x, 0.0}), y);
}

ChainOptions TaskChain() {
  ChainOptions c;
  c.name = kTaskRobot;
  c.modules = kTaskModules;
  c.pattern = ChainPattern::kPitchYaw;
  c.material = kRobotMaterial;
  return c;
}

void AddFriction(Scenario& s, const std::string& material, double friction) {
  ContactFriction f;
  f.material1 = kRobotMaterial;
  f.material2 = material;
  f.friction = friction;
  s.contact_frictions.push_back(f);
}

// A flat world with the robot and plastic-on-ground friction 0.6.
Scenario Base() {
  Scenario s;
  s.robots.push_back(MakeChain(TaskChain()));
  s.scene.guid = "scene";
  s.scene.material_name = "ground";
  AddFriction(s, "ground", 0.6);
  return s;
}

SceneObject StaticBox(
    const std::string& guid, const Eigen::Vector3d& size,
    const Eigen::Vector3d& centre,
    const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  SceneObject o;
  o.guid = guid;
  o.shape = PrimitiveShape::kBox;
  o.size = size;
  o.position = centre;
  o.quat_rotation = q;
  // The Euler angles (degrees) of the same rotation, for readers of the
  // file; quatRotation is what the builder uses.
  const Eigen::Vector3d e = q.toRotationMatrix().eulerAngles(0, 1, 2);
  o.rotation = e * 180.0 / kPi;
  o.material_name = "ground";
  o.is_static = true;
  o.mass = 1.0;
  return o;
}

Task Flat() {
  Task t;
  t.name = "flat";
  t.world = "flat ground, robot-ground friction 0.6";
  t.scenario = Base();
  t.gait = *FindGaitPreset("forward");
  return t;
}

Task Slope() {
  Task t;
  t.name = "slope";
  t.world =
      "a 10 degree slope, uphill along +x (the ground stays flat, gravity is "
      "tilted by 10 degrees)";
  t.scenario = Base();
  // The ground plane is infinite, so tilting gravity is the same as tilting
  // the ground, without the edge of a ramp (a thin static box at 10 degrees
  // made MuJoCo's box contacts unstable where the robot met it).
  const double a = 10.0 * kPi / 180.0;
  t.scenario.settings.gravity =
      9.81 * Eigen::Vector3d(-std::sin(a), 0, -std::cos(a));
  t.gait = *FindGaitPreset("forward");
  return t;
}

Task Stairs() {
  Task t;
  t.name = "stairs";
  t.world = "eight 2 cm steps, 0.3 m deep, from 0.1 m ahead, 10 m wide";
  t.scenario = Base();
  // Each step is five 2 m boxes side by side, out to 5 m either side (past
  // kReach). One box 8 m wide made MuJoCo's box-box contact with the robot
  // blow up (the forward gait at 0.999 of its amplitude; boxes 2 or 4 m
  // wide did not); the middle box is the old 2 m step.
  for (int i = 0; i < 8; ++i) {
    const double h = 0.02 * (i + 1);
    const double x0 = 0.1 + 0.3 * i;
    // The top step is a landing out to kReach and a little more.
    const double depth = i == 7 ? kReach + 0.2 - x0 : 0.3;
    for (int k = -2; k <= 2; ++k) {
      t.scenario.scene_objects.push_back(StaticBox(
          k == 0 ? fmt::format("step{}", i) : fmt::format("step{}_{}", i, k),
          Eigen::Vector3d(depth, 2.0, h),
          Eigen::Vector3d(x0 + depth / 2, 2.0 * k, h / 2)));
    }
  }
  t.gait = *FindGaitPreset("forward");
  return t;
}

Task Pegs() {
  Task t;
  t.name = "pegs";
  t.world =
      "rigid 4 cm pegs on a 0.25 m grid (rows staggered) round the robot, from "
      "1.5 m behind its head to 3 m ahead, between walls 2.1 m apart "
      "(obstacle-aided locomotion)";
  t.scenario = Base();
  // Every peg is a body, and a model of 1167 (a field out to kReach) took
  // over ten times as long an episode; so the field is 2 m wide
  // and walls keep the robot in it: a gait that drifts sideways meets the
  // walls and then the pegs beside them, not open ground. Pegs beside and
  // behind the robot too, not only ahead: the task's own gait (serpenoid)
  // slips backwards by itself, and with pegs only ahead it never met one.
  // The robot starts in a lane clear of pegs for 0.1 m round its body.
  constexpr double kHalfWidth = 1.0;  // the outermost pegs' centres
  int n = 0;
  for (int row = -7; row < 12; ++row) {  // x from -1.5 to 3 m
    const double x = 0.25 + 0.25 * row;
    const double shift = row % 2 ? 0.125 : 0.0;
    for (int k = -4; k <= 4; ++k) {
      const double y = 0.25 * k + shift;
      if (std::abs(y) > kHalfWidth || FromStartBody(x, y) < 0.1) continue;
      SceneObject peg;
      peg.guid = fmt::format("peg{}", n++);
      peg.shape = PrimitiveShape::kCylinder;
      peg.size = Eigen::Vector3d(0.04, 0.04, 0.2);
      peg.position = Eigen::Vector3d(x, y, 0.1);
      peg.material_name = "ground";
      peg.is_static = true;
      peg.mass = 1.0;
      t.scenario.scene_objects.push_back(peg);
    }
  }
  // The walls' inner faces 3 cm outside the outermost pegs: less than a
  // module's width, so no way round the pegs along a wall.
  const double wall_y = kHalfWidth + 0.02 + 0.03;
  const double x0 = -kRobotLength - kReach, x1 = kReach;
  for (int side : {-1, 1}) {
    t.scenario.scene_objects.push_back(
        StaticBox(side < 0 ? "wall_right" : "wall_left",
                  Eigen::Vector3d(x1 - x0, 0.1, 0.2),
                  Eigen::Vector3d((x0 + x1) / 2, side * (wall_y + 0.05), 0.1)));
  }
  t.gait = *FindGaitPreset("serpenoid");
  return t;
}

Task Pipe() {
  Task t;
  t.name = "pipe";
  t.world =
      "inside a horizontal pipe of 0.2 m inner diameter (12 flat staves) along "
      "x";
  t.scenario = Base();
  const double r = 0.1;  // inner radius; the axis is at z = r
  const double thickness = 0.02;
  const int staves = 12;
  const double width = 2 * r * std::tan(kPi / staves) * 1.1;
  for (int k = 0; k < staves; ++k) {
    const double phi = 2 * kPi * k / staves;
    // Stave 0 is the floor; each is turned about x by phi.
    const Eigen::Vector3d radial(0, std::sin(phi), -std::cos(phi));
    const Eigen::Vector3d centre =
        Eigen::Vector3d(0.5, 0, r) + radial * (r + thickness / 2);
    t.scenario.scene_objects.push_back(StaticBox(
        fmt::format("stave{}", k), Eigen::Vector3d(4.0, width, thickness),
        centre,
        Eigen::Quaterniond(Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()))));
  }
  t.gait = *FindGaitPreset("helical-pipe");
  return t;
}

// Bends a straight MakeChain robot (no sensor modules) so that hinge i
// sits at angles[i]: that pose becomes the joints' zero. Each hinge turns
// everything behind it about its axis (y: pitch, z: yaw, in the frame in
// front of it), positive as the physics measures a joint angle.
void Bend(Robot& robot, const std::vector<double>& angles) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  for (size_t i = 0; i < robot.modules.size(); ++i) {
    Module& mod = robot.modules[i];
    const Eigen::Vector3d hinge = mod.position;
    Frame& front = mod.frames[0];
    front.position = m * front.position;
    front.quat_rotation =
        Eigen::Quaterniond(m.rotation()) * front.quat_rotation;
    const Eigen::Vector3d axis = mod.axis == Axis::kPitch
                                     ? Eigen::Vector3d::UnitY()
                                     : Eigen::Vector3d::UnitZ();
    m = m * Eigen::Translation3d(hinge) * Eigen::AngleAxisd(angles[i], axis) *
        Eigen::Translation3d(-hinge);
    Frame& back = mod.frames[1];
    back.position = m * back.position;
    back.quat_rotation = Eigen::Quaterniond(m.rotation()) * back.quat_rotation;
    mod.position = m * hinge;
  }
}

// The pole task's robot: bent in the ground plane into an arc round the
// z axis (every yaw hinge at kPoleArcAngle), hugging the pole; arc_radius
// gets the distance from the axis to the middle of the polygon's sides.
constexpr double kPoleArcAngle = 1.0;  // rad

Robot WrappedChain(double* arc_radius) {
  Robot robot = MakeChain(TaskChain());
  std::vector<double> angles(robot.modules.size(), 0.0);
  for (size_t i = 0; i < angles.size(); ++i) {
    if (robot.modules[i].axis == Axis::kYaw) angles[i] = kPoleArcAngle;
  }
  Bend(robot, angles);
  // The bent pose is the joints' zero, but a module's range is about its
  // straight pose: the yaw range moves with the bend. Left at +-90 degrees
  // about the arc, the range stopped the yaw hinges 0.57 rad short of the
  // reversed bend that rolling needs half a cycle later, the arc opened
  // and let go of the pole once a cycle (it rose 0.15 m and fell back).
  for (size_t i = 0; i < angles.size(); ++i) {
    robot.modules[i].joint.lower_range_limit -= angles[i];
    robot.modules[i].joint.upper_range_limit -= angles[i];
  }
  // The yaw hinges are the corners of a regular polygon: the centre of
  // the circle through three of them.
  const Eigen::Vector2d a = robot.modules[1].position.head<2>();
  const Eigen::Vector2d b = robot.modules[5].position.head<2>();
  const Eigen::Vector2d c = robot.modules[9].position.head<2>();
  const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) +
                        c.x() * (a.y() - b.y()));
  const Eigen::Vector2d centre(
      (a.squaredNorm() * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) +
       c.squaredNorm() * (a.y() - b.y())) /
          d,
      (a.squaredNorm() * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) +
       c.squaredNorm() * (b.x() - a.x())) /
          d);
  // The sides (0.2 m between yaw hinges) are nearest the centre in their
  // middle.
  const double corner = (a - centre).norm();
  const double side = (b - robot.modules[4].position.head<2>()).norm() * 2;
  *arc_radius = std::sqrt(corner * corner - side * side / 4);
  const Eigen::Vector3d shift(-centre.x(), -centre.y(), 0);
  for (Module& m : robot.modules) {
    m.position += shift;
    for (Frame& f : m.frames) f.position += shift;
  }
  return robot;
}

Task Pole() {
  Task t;
  t.name = "pole";
  t.world =
      "a vertical pole (friction 2); the robot starts wrapped round its foot";
  Scenario s;
  double arc_radius = 0;
  s.robots.push_back(WrappedChain(&arc_radius));
  // The pole's surface 12 mm inside the chain's inner side: the servos
  // holding the arc squeeze it (a tighter squeeze climbed higher, up to
  // about 15 mm where the chain slips off).
  const double pole_radius = arc_radius - 0.025 + 0.012;
  s.scene.guid = "scene";
  s.scene.material_name = "ground";
  AddFriction(s, "ground", 0.6);
  AddFriction(s, "pole", 2.0);
  SceneObject pole;
  pole.guid = "pole";
  pole.shape = PrimitiveShape::kCylinder;
  pole.size = Eigen::Vector3d(2 * pole_radius, 2 * pole_radius, 3.0);
  pole.position = Eigen::Vector3d(0, 0, 1.5);
  pole.material_name = "pole";
  pole.is_static = true;
  pole.mass = 10.0;
  s.scene_objects.push_back(pole);
  t.scenario = std::move(s);
  t.distance_mode = "up";
  t.duration = 30.0;
  // Helical rolling relative to the wrapped start: the yaw offset takes
  // the arc back out, so the targets start at 0.
  t.gait = *FindGaitPreset("helical-pole");
  t.gait.name = "helical-pole-wrapped";
  t.gait.parameters.offset_yaw = -kPoleArcAngle;
  return t;
}

// An 8-bit binary PGM (which the terrain loader reads like a PNG).
std::string Pgm(int cols, int rows, const std::vector<unsigned char>& grey) {
  const std::string header = fmt::format("P5\n{} {}\n255\n", cols, rows);
  std::vector<unsigned char> bytes(header.begin(), header.end());
  bytes.insert(bytes.end(), grey.begin(), grey.end());
  return "base64:" + Base64Encode(bytes);
}

Task Rubble() {
  Task t;
  t.name = "rubble";
  t.world =
      "seeded random stones up to 4 cm high round the robot (flat under it), a "
      "height map 9.6 m by 8.4 m";
  t.scenario = Base();
  // Stones beside and behind the robot as well as ahead, like the pegs: a
  // gait that went backwards or sideways left the stones (ahead only)
  // behind and scored as on flat. The height map is the whole ground, so
  // it reaches kReach and a little more (past its edge there is nothing).
  const double mpp = 0.04;
  const double x0 = -kRobotLength - kReach - 0.2;  // image x = 0
  const double y0 = -kReach - 0.2;
  const int cols = static_cast<int>(std::lround((kReach + 0.2 - x0) / mpp));
  const int rows = static_cast<int>(std::lround(-2 * y0 / mpp));
  Scene& scene = t.scenario.scene;
  scene.meters_per_pixel = mpp;
  scene.height = 0.04;
  scene.position = Eigen::Vector3d(x0, y0, 0);
  // World x and y of a pixel's centre (row 0 is the +y edge).
  const auto world_x = [&](int col) { return x0 + (col + 0.5) * mpp; };
  const auto world_y = [&](int row) { return -y0 - (row + 0.5) * mpp; };
  std::vector<double> h(static_cast<size_t>(rows) * cols, 0.0);
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u(0, 1);
  // 33 stones a square metre, as many as the first rubble had.
  const int stones = static_cast<int>(33 * cols * mpp * rows * mpp);
  for (int stone = 0; stone < stones; ++stone) {
    const double cx = x0 + u(rng) * cols * mpp;
    const double cy = y0 + u(rng) * rows * mpp;
    const double radius = 0.05 + 0.1 * u(rng);
    const double top = 0.3 + 0.7 * u(rng);
    // Only the pixels near the stone: the map is large.
    const int c0 = std::max(0, static_cast<int>((cx - radius - x0) / mpp) - 1);
    const int c1 =
        std::min(cols - 1, static_cast<int>((cx + radius - x0) / mpp) + 1);
    const int r0 = std::max(0, static_cast<int>((-y0 - cy - radius) / mpp) - 1);
    const int r1 =
        std::min(rows - 1, static_cast<int>((-y0 - cy + radius) / mpp) + 1);
    for (int row = r0; row <= r1; ++row) {
      for (int col = c0; col <= c1; ++col) {
        const double d =
            std::hypot(world_x(col) - cx, world_y(row) - cy) / radius;
        if (d < 1) {
          double& v = h[static_cast<size_t>(row) * cols + col];
          v = std::max(v, top * std::sqrt(1 - d * d));
        }
      }
    }
  }
  std::vector<unsigned char> grey(h.size());
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      // Flat where the robot lies and 0.1 m round it.
      const size_t i = static_cast<size_t>(row) * cols + col;
      const double v =
          FromStartBody(world_x(col), world_y(row)) < 0.1 ? 0.0 : h[i];
      grey[i] = static_cast<unsigned char>(std::lround(255 * std::min(1.0, v)));
    }
  }
  // One pixel at full white, so the brightest is 4 cm whatever the stones.
  grey.back() = 255;
  scene.height_image = Pgm(cols, rows, grey);
  t.gait = *FindGaitPreset("forward");
  return t;
}

Task Water() {
  Task t;
  t.name = "water";
  t.world =
      "a pool of water 0.3 m deep (buoyancy and drag, docs/sim.md); the "
      "modules float";
  t.scenario = Base();
  FluidRegion pool;
  pool.guid = "pool";
  pool.kind = FluidKind::kWater;
  pool.position = Eigen::Vector3d(0, 0, 0.15);
  pool.size = Eigen::Vector3d(10, 10, 0.3);
  t.scenario.fluid_regions.push_back(pool);
  t.gait = *FindGaitPreset("serpenoid");
  return t;
}

const std::vector<std::pair<std::string, std::function<Task()>>>& Builders() {
  static const std::vector<std::pair<std::string, std::function<Task()>>>
      kBuilders = {{"flat", Flat},     {"slope", Slope}, {"stairs", Stairs},
                   {"pegs", Pegs},     {"pipe", Pipe},   {"pole", Pole},
                   {"rubble", Rubble}, {"water", Water}};
  return kBuilders;
}

}  // namespace

const std::vector<std::string>& TaskNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const auto& [name, build] : Builders()) names.push_back(name);
    return names;
  }();
  return kNames;
}

std::string TaskNamesText() {
  std::string text;
  for (const std::string& n : TaskNames()) {
    text += (text.empty() ? "" : ", ") + n;
  }
  return text;
}

std::string TaskFitnessText(const Task& task) {
  return task.distance_mode == "up" ? "CoM rise along +z"
                                    : "CoM travel along +x";
}

Task MakeTask(const std::string& name) {
  std::string key = name;
  std::replace(key.begin(), key.end(), '_', '-');
  for (const auto& [n, build] : Builders()) {
    if (n != key) continue;
    Task t = build();
    t.description = t.world + ": " + TaskFitnessText(t);
    return t;
  }
  throw TaskError(fmt::format("unknown task '{}': expected one of {}", name,
                              TaskNamesText()));
}

Problem TaskProblem(const Task& task, const Gait& gait,
                    const GenomeSpec& genome, double seconds) {
  Problem p;
  p.scenario = task.scenario;
  p.genome = genome;
  p.episode.duration = seconds > 0 ? seconds : task.duration;
  p.episode.fitness.distance_mode = ParseDistanceMode(task.distance_mode);
  p.episode.base_gait = gait;
  p.episode.Validate();
  return p;
}

EvalResult EvaluateTask(const Task& task, const Gait& gait, double seconds) {
  const Problem p = TaskProblem(task, gait, GenomeSpec{}, seconds);
  return RunEpisode(p, Genome{});
}

}  // namespace mrsim
