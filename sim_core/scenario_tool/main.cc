// mrsim-scenario: validate, inspect, convert, export and generate scenario
// files. Exit codes: 0 success, 2 bad input (the error on stderr), 1 when
// an output cannot be written or anything else fails.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/version.h"
#include "sim_core/chain_builder.h"
#include "sim_core/mjcf_builder.h"
#include "sim_core/scenario.h"
#include "sim_core/scenario_tool/scenario_summary.h"
#include "sim_core/scenario_tool/schema_table.h"
#include "sim_core/scenario_xml.h"

namespace {

constexpr int kBadInput = 2;
constexpr int kFailure = 1;

// A usage or input error: exit code 2.
class BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes text to `path`, or stdout when it is empty or "-". Goes through a
// temporary file so a failed write never clobbers an existing file.
void WriteOutput(const std::string& text, const std::string& path) {
  if (path.empty() || path == "-") {
    std::cout << text << std::flush;
    return;
  }
  mrsim::WriteFileAtomically(path, text);
  // Said on stderr, so a script reading stdout is not disturbed.
  std::cerr << "mrsim-scenario: wrote " << path << "\n";
}

// "none", "all" (in front of module 0 and after every module), "between"
// (between consecutive modules) or a comma list of module numbers after
// which a sensor module goes (-1 = in front of module 0).
std::vector<int> ParseSensors(const std::string& spec, int modules) {
  std::vector<int> after;
  if (spec.empty() || spec == "none") return after;
  if (spec == "all" || spec == "between") {
    return mrsim::SensorsAfter(spec == "all" ? mrsim::SensorPlacement::kAll
                                             : mrsim::SensorPlacement::kBetween,
                               modules);
  }
  std::stringstream in(spec);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      size_t used = 0;
      after.push_back(std::stoi(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw BadInput(
          "--sensors: expected none, all, between or a comma "
          "list of module numbers, got '" +
          spec + "'");
    }
  }
  return after;
}

int Run(int argc, char** argv) {
  CLI::App app{
      "Validate, inspect, convert, export and generate mrsim "
      "scenario files (docs/scenario.md)."};
  app.set_version_flag("--version",
                       std::string("mrsim-scenario ") + mrsim::kVersion);
  app.require_subcommand(1);

  std::string file, out_path, in_path;
  auto* validate = app.add_subcommand("validate", "Check a scenario file");
  validate->add_option("FILE", file, "Scenario file")->required();

  auto* info = app.add_subcommand(
      "info", "Summarise robots, sensors, mass, objects and terrain");
  info->add_option("FILE", file, "Scenario file")->required();

  auto* schema = app.add_subcommand(
      "schema", "Print every part's fields: units, limits, defaults, help");

  auto* export_mjcf =
      app.add_subcommand("export-mjcf", "Write the MuJoCo model (MJCF)");
  export_mjcf->add_option("FILE", file, "Scenario file")->required();
  export_mjcf->add_option("-o,--output", out_path,
                          "Output file (default: stdout)");

  double scale = 1.0;
  std::string to_frame = "z-up", from_frame;
  auto* convert = app.add_subcommand(
      "convert",
      "Rewrite a scenario (e.g. a Unity Y-up file) in the native Z-up frame");
  convert->add_option("IN", in_path, "Input scenario file")->required();
  convert->add_option("OUT", out_path, "Output file ('-' for stdout)")
      ->required();
  convert
      ->add_option("--from", from_frame,
                   "Frame of an input file that has no frame attribute "
                   "(files the original MRSim wrote: unity-y-up)")
      ->check(CLI::IsMember({"z-up", "unity-y-up"}));
  convert->add_option("--scale", scale,
                      "Multiply every length by this (scene units to m); "
                      "gravity and masses stay as they are");
  convert->add_option("--frame", to_frame, "Output frame convention")
      ->check(CLI::IsMember({"z-up", "unity-y-up"}));

  mrsim::ChainOptions chain;
  std::string pattern = "pitch", sensors = "none", ground = "ground";
  double frame_size = chain.frame_size.x();
  auto* make = app.add_subcommand("new", "Generate a chain robot scenario");
  make->add_option("--modules", chain.modules, "Number of modules")
      ->capture_default_str();
  make->add_option("--pattern", pattern, "Joint axes")
      ->check(CLI::IsMember({"pitch", "yaw", "pitch-yaw"}))
      ->capture_default_str();
  make->add_option("--sensors", sensors,
                   "Sensor modules: none, all, between, or module numbers "
                   "after which one goes (-1 = in front), e.g. --sensors=-1,2")
      ->capture_default_str();
  make->add_flag("--force-sensors", chain.force_sensors,
                 "A force sensor under each sensor module");
  make->add_flag("--front-distance-sensor", chain.front_distance_sensor,
                 "A distance sensor on the front of the frontmost sensor "
                 "module");
  make->add_option("--name", chain.name, "Robot name")->capture_default_str();
  make->add_option("--module-mass", chain.module_mass, "kg per module")
      ->capture_default_str();
  make->add_option("--frame-size", frame_size, "Edge of each box frame, m")
      ->capture_default_str();
  make->add_option("--kp", chain.kp, "Hinge servo gain")->capture_default_str();
  make->add_option("--max-vel", chain.max_vel, "Hinge speed limit, rad/s")
      ->capture_default_str();
  make->add_option("--joint-limit", chain.joint_limit,
                   "Symmetric hinge range limit, rad")
      ->capture_default_str();
  make->add_option("--material", chain.material, "Material of every part")
      ->capture_default_str();
  make->add_option("--ground-material", ground, "Material of the ground")
      ->capture_default_str();
  std::vector<double> origin;
  make->add_option("--origin", origin,
                   "Ground point under module 0's hinge: X Y Z (default 0 0 0)")
      ->expected(3);
  double friction = -1;
  make->add_option("--friction", friction,
                   "Add a ContactFriction with this friction between the "
                   "robot's and the ground's materials");
  make->add_option("-o,--output", out_path, "Output file (default: stdout)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadInput;
  }

  try {
    if (*validate) {
      const mrsim::Scenario s = mrsim::ReadScenarioFile(file);
      std::cout << fmt::format("{}: ok ({} robots, {} scene objects)\n", file,
                               s.robots.size(), s.scene_objects.size());
    } else if (*info) {
      const mrsim::Scenario s = mrsim::ReadScenarioFile(file);
      std::cout << "file: " << file << "\n" << mrsim::SummarizeScenario(s);
    } else if (*schema) {
      std::cout << mrsim::SchemaMarkdown();
    } else if (*export_mjcf) {
      const mrsim::Scenario s = mrsim::ReadScenarioFile(file);
      std::string mjcf;
      try {
        // Files named relative to the exported file, so the model and its
        // assets move together.
        mrsim::MjcfOptions options;
        if (!out_path.empty() && out_path != "-") {
          options.file_dir =
              std::filesystem::absolute(out_path).parent_path().string();
        }
        mjcf = mrsim::BuildMjcf(s, options);
      } catch (const std::exception& e) {
        throw BadInput(file + ": cannot build the MuJoCo model: " + e.what());
      }
      WriteOutput(mjcf, out_path);
    } else if (*convert) {
      if (!(scale > 0)) {
        throw BadInput(
            fmt::format("--scale: expected a positive number, "
                        "got {}",
                        scale));
      }
      mrsim::ScenarioReadOptions read;
      if (!from_frame.empty()) {
        read.frame = from_frame == "z-up" ? mrsim::FrameConvention::kZUp
                                          : mrsim::FrameConvention::kUnityYUp;
      }
      read.length_scale = scale;
      const mrsim::Scenario s = mrsim::ReadScenarioFile(in_path, read);
      const auto frame = to_frame == "z-up" ? mrsim::FrameConvention::kZUp
                                            : mrsim::FrameConvention::kUnityYUp;
      WriteOutput(mrsim::WriteScenarioString(s, frame), out_path);
    } else if (*make) {
      chain.pattern = pattern == "pitch" ? mrsim::ChainPattern::kPitch
                      : pattern == "yaw" ? mrsim::ChainPattern::kYaw
                                         : mrsim::ChainPattern::kPitchYaw;
      chain.sensor_after = ParseSensors(sensors, chain.modules);
      chain.frame_size.setConstant(frame_size);
      if (!origin.empty()) {
        chain.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
      }
      mrsim::Scenario s;
      try {
        s = mrsim::MakeChainScenario({chain, ground, friction});
      } catch (const std::invalid_argument& e) {
        throw BadInput(e.what());
      }
      // Check what we generate with the same reader users get.
      const std::string text = mrsim::WriteScenarioString(s);
      try {
        mrsim::ReadScenarioString(text, "generated scenario", ".");
      } catch (const mrsim::ScenarioError& e) {
        throw BadInput(e.what());
      }
      WriteOutput(text, out_path);
    }
  } catch (const mrsim::ScenarioError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kBadInput;
  } catch (const BadInput& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kFailure;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return Run(argc, argv); }
