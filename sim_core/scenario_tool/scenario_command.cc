#include "sim_core/scenario_tool/scenario_command.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/atomic_file.h"
#include "sim_core/mjcf/mjcf_builder.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/scenario/scenario.h"
#include "sim_core/scenario_tool/scenario_summary.h"
#include "sim_core/scenario_tool/schema_table.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/export/stl_export.h"

namespace mrsim {
namespace {

// Writes text to `path`, or `out` when it is empty or "-". Goes through a
// temporary file so a failed write never clobbers an existing file.
void WriteOutput(const std::string& text, const std::string& path,
                 std::ostream& out, std::ostream& info) {
  if (path.empty() || path == "-") {
    out << text << std::flush;
    return;
  }
  WriteFileAtomically(path, text);
  // Said apart from the output, so a script reading stdout is not disturbed.
  info << "mrsim-scenario: wrote " << path << "\n";
}

// MakeChain's refusal ("MakeChain: modules must be at least 1, got 0")
// named by the flag that set the option ("--modules: ...").
std::string FlagNamed(const std::string& message) {
  static const std::pair<const char*, const char*> kFlags[] = {
      {"modules", "--modules"},
      {"sensor module", "--sensors"},
      {"two sensor modules", "--sensors"},
      {"a front distance sensor", "--front-distance-sensor"},
      {"frame_size", "--frame-size"},
      {"module_mass", "--module-mass"},
      {"joint_limit", "--joint-limit"}};
  const std::string prefix = "MakeChain: ";
  std::string text =
      message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
  for (const auto& [starts, flag] : kFlags) {
    if (text.rfind(starts, 0) == 0) return std::string(flag) + ": " + text;
  }
  return text;
}

FrameConvention FrameNamed(const std::string& name) {
  return name == "unity-y-up" ? FrameConvention::kUnityYUp
                              : FrameConvention::kZUp;
}

// The second step of validate: parts overlapping at the start, all of
// them named, one per line.
void CheckNoOverlaps(const Scenario& s, const ScenarioSource& source) {
  try {
    RefuseOverlaps(s, &source);
  } catch (const OverlapError& e) {
    throw ScenarioInputError(e.what());
  } catch (const std::exception& e) {
    throw ScenarioInputError(source.file +
                             ": cannot build the MuJoCo model: " + e.what());
  }
}

// What runs but is likely not meant (a ray starting inside the robot),
// one "file:line: path: warning: ..." line each.
void TellWarnings(const Scenario& s, const ScenarioSource& source,
                  std::ostream& info) {
  for (const ScenarioWarning& w : ScenarioWarnings(s, &source)) {
    info << "mrsim-scenario: " << w.text << "\n";
  }
}

void Run(const ScenarioCommand& c, std::ostream& out, std::ostream& info) {
  switch (c.action) {
    case ScenarioAction::kNone:
      throw ScenarioInputError("no subcommand given");
    case ScenarioAction::kValidate: {
      ScenarioSource source;
      ScenarioReadOptions read;
      read.source_out = &source;
      const Scenario s = ReadScenarioFile(c.file, read);
      TellWarnings(s, source, info);
      CheckNoOverlaps(s, source);
      out << fmt::format("{}: ok ({}, {})\n", c.file,
                         Counted(s.robots.size(), "robot"),
                         Counted(s.scene_objects.size(), "scene object"));
      return;
    }
    case ScenarioAction::kInfo: {
      const std::string summary = SummarizeScenario(ReadScenarioFile(c.file));
      out << "file: " << c.file << "\n" << summary;
      return;
    }
    case ScenarioAction::kSchema:
      out << SchemaMarkdown();
      return;
    case ScenarioAction::kExport: {
      const Scenario s = ReadScenarioFile(c.file);
      // Files named relative to the exported file, so the model and its
      // assets move together.
      MjcfOptions options;
      if (!c.out_path.empty() && c.out_path != "-") {
        options.file_dir =
            std::filesystem::absolute(c.out_path).parent_path().string();
      }
      std::string mjcf;
      try {
        mjcf = BuildMjcf(s, options);
      } catch (const std::exception& e) {
        throw ScenarioInputError(
            c.file + ": cannot build the MuJoCo model: " + e.what());
      }
      WriteOutput(mjcf, c.out_path, out, info);
      return;
    }
    case ScenarioAction::kExportStl: {
      const Scenario s = ReadScenarioFile(c.file);
      StlExport result;
      try {
        result = ExportStl(s);
      } catch (const std::exception& e) {
        throw ScenarioInputError(c.file + ": " + e.what());
      }
      WriteStlExport(result, c.out_path);
      int printed = 0;
      for (const PrintedPart& p : result.parts) printed += p.count;
      out << fmt::format("{}: {} ({} distinct) in {}\n", c.file,
                         Counted(static_cast<size_t>(printed), "part"),
                         result.parts.size(), c.out_path);
      for (const PrintedPart& p : result.parts) {
        out << fmt::format("  {} x {}\n", p.count,
                           p.file.empty() ? p.name + " (not printed)" : p.file);
      }
      return;
    }
    case ScenarioAction::kConvert: {
      if (!(c.scale > 0)) {
        throw ScenarioInputError(fmt::format(
            "--scale: expected a positive number, got {}", c.scale));
      }
      ScenarioReadOptions read;
      if (!c.from_frame.empty()) read.frame = FrameNamed(c.from_frame);
      read.length_scale = c.scale;
      ScenarioSource source;
      read.source_out = &source;
      const Scenario s = ReadScenarioFile(c.file, read);
      TellWarnings(s, source, info);
      if (c.scale == 1.0 && IsOriginalMrsimFile(c.file)) {
        info << "mrsim-scenario: note: " << c.file
             << " was written by the original MRSim, whose lengths are "
                "usually centimetres; without --scale 0.01 they stay as "
                "they are\n";
      }
      WriteOutput(WriteScenarioString(s, FrameNamed(c.to_frame)), c.out_path,
                  out, info);
      return;
    }
    case ScenarioAction::kNew: {
      ChainOptions chain = c.chain;
      chain.pattern = c.pattern == "pitch" ? ChainPattern::kPitch
                      : c.pattern == "yaw" ? ChainPattern::kYaw
                                           : ChainPattern::kPitchYaw;
      chain.sensor_after = ParseSensorSpec(c.sensors, chain.modules);
      chain.frame_size.setConstant(c.frame_size);
      if (c.origin.size() == 3) {
        chain.origin = Eigen::Vector3d(c.origin[0], c.origin[1], c.origin[2]);
      }
      if (c.friction && !(std::isfinite(*c.friction) && *c.friction >= 0)) {
        throw ScenarioInputError(fmt::format(
            "--friction: expected a number >= 0, got {}", *c.friction));
      }
      Scenario s;
      try {
        s = MakeChainScenario({chain, c.ground, c.friction.value_or(-1)});
      } catch (const std::invalid_argument& e) {
        throw ScenarioInputError(FlagNamed(e.what()));
      }
      // Check what we generate with the same reader users get.
      const std::string text = WriteScenarioString(s);
      ReadScenarioString(text, "generated scenario", ".");
      WriteOutput(text, c.out_path, out, info);
      return;
    }
  }
}

}  // namespace

void AddScenarioFlags(CLI::App& app, ScenarioCommand& c) {
  app.require_subcommand(1);
  const auto on = [&c](CLI::App* sub, ScenarioAction action) {
    sub->callback([&c, action] { c.action = action; });
    return sub;
  };
  auto* validate = on(app.add_subcommand("validate", "Check a scenario file"),
                      ScenarioAction::kValidate);
  validate->add_option("FILE", c.file, "Scenario file")->required();

  auto* info =
      on(app.add_subcommand(
             "info", "Summarise robots, sensors, mass, objects and terrain"),
         ScenarioAction::kInfo);
  info->add_option("FILE", c.file, "Scenario file")->required();

  on(app.add_subcommand(
         "schema", "Print every part's fields: units, limits, defaults, help"),
     ScenarioAction::kSchema);

  auto* export_mjcf =
      on(app.add_subcommand("export-mjcf", "Write the MuJoCo model (MJCF)"),
         ScenarioAction::kExport);
  export_mjcf->add_option("FILE", c.file, "Scenario file")->required();
  export_mjcf->add_option("-o,--output", c.out_path,
                          "Output file (default: stdout)");

  auto* export_stl =
      on(app.add_subcommand("export-stl",
                            "Write each distinct robot part as a binary STL "
                            "in mm, each robot assembled and parts.csv"),
         ScenarioAction::kExportStl);
  export_stl->add_option("FILE", c.file, "Scenario file")->required();
  export_stl->add_option("OUT_DIR", c.out_path, "Output directory")->required();

  auto* convert = on(app.add_subcommand("convert",
                                        "Rewrite a scenario (e.g. a Unity "
                                        "Y-up file) in the native Z-up frame"),
                     ScenarioAction::kConvert);
  convert->add_option("IN", c.file, "Input scenario file")->required();
  convert->add_option("OUT", c.out_path, "Output file ('-' for stdout)")
      ->required();
  convert
      ->add_option("--from", c.from_frame,
                   "Frame of an input file that has no frame attribute "
                   "(files the original MRSim wrote: unity-y-up)")
      ->check(CLI::IsMember({"z-up", "unity-y-up"}));
  convert->add_option("--scale", c.scale,
                      "Multiply every length by this (scene units to m); "
                      "gravity and masses stay as they are");
  convert->add_option("--frame", c.to_frame, "Output frame convention")
      ->check(CLI::IsMember({"z-up", "unity-y-up"}));

  ChainOptions& chain = c.chain;
  auto* make = on(app.add_subcommand("new", "Generate a chain robot scenario"),
                  ScenarioAction::kNew);
  make->add_option("--modules", chain.modules, "Number of modules")
      ->capture_default_str();
  make->add_option("--pattern", c.pattern, "Joint axes")
      ->check(CLI::IsMember({"pitch", "yaw", "pitch-yaw"}))
      ->capture_default_str();
  make->add_option("--sensors", c.sensors,
                   "Sensor modules: none, all, between, or module numbers "
                   "after which one goes (-1 = in front), e.g. --sensors=-1,2")
      ->capture_default_str();
  make->add_flag("--force-sensors", chain.force_sensors,
                 "A force sensor under each sensor module");
  make->add_flag("--front-distance-sensor", chain.front_distance_sensor,
                 "A distance sensor looking ahead from the sensor module in "
                 "front of module 0 (needs --sensors=-1,... or all)");
  make->add_option("--name", chain.name, "Robot name")->capture_default_str();
  make->add_option("--module-mass", chain.module_mass, "kg per module")
      ->capture_default_str();
  make->add_option("--frame-size", c.frame_size, "Edge of each box frame, m")
      ->capture_default_str();
  make->add_option("--kp", chain.kp, "Hinge servo gain")->capture_default_str();
  make->add_option("--max-vel", chain.max_vel, "Hinge speed limit, rad/s")
      ->capture_default_str();
  make->add_option("--joint-limit", chain.joint_limit,
                   "Symmetric hinge range limit, rad")
      ->capture_default_str();
  make->add_option("--material", chain.material, "Material of every part")
      ->capture_default_str();
  make->add_option("--ground-material", c.ground, "Material of the ground")
      ->capture_default_str();
  make->add_option("--origin", c.origin,
                   "Ground point under module 0's hinge: X Y Z (default 0 0 0)")
      ->expected(3);
  make->add_option("--friction", c.friction,
                   "Add a ContactFriction with this friction between the "
                   "robot's and the ground's materials");
  make->add_option("-o,--output", c.out_path, "Output file (default: stdout)");
}

void RunScenarioCommand(const ScenarioCommand& command, std::ostream& out,
                        std::ostream& info) {
  try {
    Run(command, out, info);
  } catch (const ScenarioError& e) {
    throw ScenarioInputError(e.what());
  }
}

std::vector<int> ParseSensorSpec(const std::string& spec, int modules) {
  if (spec.empty() || spec == "none") return {};
  if (spec == "all" || spec == "between") {
    return SensorsAfter(
        spec == "all" ? SensorPlacement::kAll : SensorPlacement::kBetween,
        modules);
  }
  std::vector<int> after;
  std::stringstream in(spec);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      size_t used = 0;
      after.push_back(std::stoi(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw ScenarioInputError(
          "--sensors: expected none, all, between or a comma list of module "
          "numbers, got '" +
          spec + "'");
    }
  }
  return after;
}

}  // namespace mrsim
