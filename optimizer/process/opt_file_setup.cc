#include "optimizer/process/opt_file_setup.h"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <optional>
#include <sstream>

#include "gait_controller/gait_file.h"
#include "optimizer/episode/task.h"
#include "optimizer/search/algorithm_registry.h"
#include "optimizer/search/genome.h"
#include "sim_core/scenario/scenario_validate.h"
#include "sim_core/scenario/scenario_xml.h"

namespace fs = std::filesystem;

namespace mrsim {
namespace {

constexpr const char* kPath = "Scenario/optimization/";

// A path written in the design, as seen from the working folder: beside
// the design when it is there.
std::string BesideDesign(const std::string& dir, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute() || dir.empty()) return path;
  std::error_code ec;
  const fs::path beside = fs::path(dir) / path;
  return fs::exists(beside, ec) ? beside.string() : path;
}

}  // namespace

void ApplyOptimizationSettings(
    const OptimizationSettings& o,
    const std::function<bool(const std::string&)>& given,
    const std::string& file, const std::string& dir,
    const std::function<int(const std::string&)>& line_of, OptCommand* c) {
  const auto fail = [&](const char* field, const std::string& what) {
    const std::string path = kPath + std::string(field);
    throw OptInputError(ScenarioError(file, line_of(path), path, what).what());
  };
  const auto unless = [&](const char* flag, auto apply) {
    if (!given(flag)) apply();
  };
  unless("--algorithm", [&] {
    try {
      c->algorithm.algorithm = ParseAlgorithm(o.algorithm);
    } catch (const std::invalid_argument& e) {
      fail("algorithm", e.what());
    }
  });
  unless("--generations", [&] { c->generations = o.generations; });
  unless("--population", [&] { c->algorithm.population = o.population; });
  unless("--seed", [&] { c->algorithm.seed = o.seed; });
  unless("--episode", [&] { c->episode.duration = o.episode; });
  unless("--controller", [&] {
    const std::string lua = "lua:";
    c->controller = o.controller.rfind(lua, 0) == 0
                        ? lua + BesideDesign(dir, o.controller.substr(4))
                        : o.controller;
  });
  // The file's genes go with the gait; a script or a network brings its
  // own, but may take body genes from a genome.
  const bool gait = c->controller == "gait" || c->controller == "cpg";
  if (!given("--genes") && !given("--genome")) {
    if (!o.genes.empty() && gait) {
      try {
        BuiltInGenome(o.genes);
      } catch (const std::exception& e) {
        fail("genes", e.what());
      }
      c->genes = o.genes;
    }
    if (!o.genome.empty()) {
      const std::string name = file + " <optimization><genome>";
      try {
        ReadGenomeString(o.genome, name);
      } catch (const std::exception& e) {
        fail("genome", e.what());
      }
      c->genome_text = o.genome;
      c->genome_source = name;
    }
  }
  if (!o.task.empty() && c->task.empty()) {
    const std::vector<std::string>& names = TaskNames();
    if (std::find(names.begin(), names.end(), o.task) == names.end()) {
      fail("task", "expected a task of the suite (" + TaskNamesText() +
                       "), got '" + o.task + "'");
    }
    c->task = o.task;
  }
  unless("--gait", [&] {
    if (o.base_gait.empty()) return;
    const std::string spec = BesideDesign(dir, o.base_gait);
    try {
      ResolveGait(spec);
    } catch (const std::exception& e) {
      fail("baseGait", e.what());
    }
    c->gait_spec = spec;
  });
  unless("--distance", [&] {
    try {
      c->episode.fitness.distance_mode = ParseDistanceMode(o.distance);
    } catch (const std::exception& e) {
      fail("distance", e.what());
    }
  });
  FitnessSettings& f = c->episode.fitness;
  unless("--w-distance", [&] { f.w_distance = o.w_distance; });
  unless("--w-speed", [&] { f.w_speed = o.w_speed; });
  unless("--w-energy", [&] { f.w_energy = o.w_energy; });
  unless("--w-drift", [&] { f.w_drift = o.w_drift; });
  unless("--w-fall", [&] { f.w_fall = o.w_fall; });
  unless("--robust", [&] { c->episode.robust.episodes = o.robust; });
  unless("--robust-mode", [&] {
    if (o.robust_mode != "mean" && o.robust_mode != "worst") {
      fail("robustMode", "expected mean or worst, got '" + o.robust_mode + "'");
    }
    c->episode.robust.mode = o.robust_mode;
  });
  // The reality gap has no flags: the file's values (RealityGap::Typical()
  // when left out; the validator held them to RealityGap::Validate's
  // limits) are the robust episodes' gap. The seed stays the run's.
  RealityGap& gap = c->episode.robust.gap;
  gap.sensor_noise = o.gap_sensor_noise;
  gap.sensor_bias = o.gap_sensor_bias;
  gap.joint_noise = o.gap_joint_noise;
  gap.motor_noise = o.gap_motor_noise;
  gap.latency = o.gap_latency;
  gap.backlash = o.gap_backlash;
  gap.max_accel = o.gap_max_accel;
  gap.friction_range = o.gap_friction_range;
  gap.mass_range = o.gap_mass_range;
  gap.gain_range = o.gap_gain_range;
  gap.terrain_range = o.gap_terrain_range;
  unless("--allow-overlap", [&] { c->allow_overlap = o.allow_overlap; });
  // "flag=value" words, each an algorithm setting of the registry.
  std::istringstream words(o.algorithm_settings);
  std::string word;
  while (words >> word) {
    const size_t eq = word.find('=');
    const std::string flag = word.substr(0, eq);
    const AlgorithmSetting* found = nullptr;
    for (const AlgorithmInfo& info : Algorithms()) {
      for (const AlgorithmSetting& s : info.settings) {
        if (flag == s.flag) found = &s;
      }
    }
    const auto value = [&]() -> std::optional<double> {
      if (found == nullptr || eq == std::string::npos) return std::nullopt;
      try {
        size_t used = 0;
        const double v = std::stod(word.substr(eq + 1), &used);
        if (used == word.size() - eq - 1) return v;
      } catch (const std::exception&) {
      }
      return std::nullopt;
    }();
    if (!value) {
      fail("algorithmSettings",
           "expected flag=value words, each flag an algorithm setting of "
           "mrsim-opt (cmaes-sigma=0.2), got '" +
               word + "'");
    }
    if (!given("--" + flag)) found->Set(&c->algorithm, *value);
  }
}

void ApplyFileSetup(const CLI::App& app, OptCommand* c) {
  const auto given = [&](const std::string& flag) {
    try {
      return app.count(flag) > 0;
    } catch (const CLI::Error&) {
      return false;
    }
  };
  const std::string name =
      !c->task.empty() ? c->task : fs::path(c->scenario_path).stem().string();
  if (c->out_dir.empty() && !name.empty()) c->out_dir = "opt-" + name;
  if (!c->task.empty() || c->scenario_path.empty()) return;
  ScenarioSource source;
  ScenarioReadOptions read;
  read.source_out = &source;
  Scenario scenario;
  try {
    scenario = ReadScenarioFile(c->scenario_path, read);
  } catch (const std::exception&) {
    return;  // PrepareOpt reads it again and says what is wrong
  }
  if (scenario.run && !scenario.run->lua_script.empty()) {
    c->lua_source = scenario.run->lua_script;
  }
  if (!scenario.optimization) return;
  ApplyOptimizationSettings(
      *scenario.optimization, given, c->scenario_path, scenario.base_dir,
      [&](const std::string& path) { return source.LineOf(path); }, c);
}

}  // namespace mrsim
