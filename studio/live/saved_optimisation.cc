#include "studio/live/saved_optimisation.h"

#include <fmt/format.h>

#include <sstream>
#include <stdexcept>

#include "optimizer/search/algorithm_registry.h"
#include "optimizer/search/genome.h"

namespace mrsim::studio {

OptimizationSettings SavedOptimisation(const OptimiseOptions& o) {
  OptimizationSettings s;
  s.algorithm = o.algorithm;
  s.generations = o.generations;
  s.population = o.population;
  s.seed = static_cast<int>(o.seed);
  s.episode = o.episode_s;
  s.controller = o.controller;
  if (o.controller == "gait" && !o.genome.genes.empty()) {
    s.genome = WriteGenomeString(o.genome);
  }
  s.task = o.task;
  s.base_gait = o.base_gait;
  s.distance = ToString(o.fitness.distance_mode);
  s.w_distance = o.fitness.w_distance;
  s.w_speed = o.fitness.w_speed;
  s.w_energy = o.fitness.w_energy;
  s.w_drift = o.fitness.w_drift;
  s.w_fall = o.fitness.w_fall;
  s.robust = o.robust.episodes;
  s.robust_mode = o.robust.mode;
  const RealityGap& g = o.robust.gap;
  s.gap_sensor_noise = g.sensor_noise;
  s.gap_sensor_bias = g.sensor_bias;
  s.gap_joint_noise = g.joint_noise;
  s.gap_motor_noise = g.motor_noise;
  s.gap_latency = g.latency;
  s.gap_backlash = g.backlash;
  s.gap_max_accel = g.max_accel;
  s.gap_friction_range = g.friction_range;
  s.gap_mass_range = g.mass_range;
  s.gap_gain_range = g.gain_range;
  s.gap_terrain_range = g.terrain_range;
  s.allow_overlap = o.allow_overlap;
  for (const auto& [flag, value] : o.algorithm_settings) {
    s.algorithm_settings += fmt::format(
        "{}{}={:g}", s.algorithm_settings.empty() ? "" : " ", flag, value);
  }
  return s;
}

OptimiseOptions OptionsFromSaved(const OptimizationSettings& s,
                                 OptimiseOptions o) {
  const auto field = [](const char* name, const std::exception& e) {
    return std::invalid_argument(
        fmt::format("the design's <optimization><{}>: {}", name, e.what()));
  };
  try {
    ParseAlgorithm(s.algorithm);
  } catch (const std::exception& e) {
    throw field("algorithm", e);
  }
  o.algorithm = s.algorithm;
  o.generations = s.generations;
  o.population = s.population;
  o.seed = static_cast<unsigned>(s.seed);
  o.episode_s = s.episode;
  // The form knows the gait, the design's script and networks; cpg is the
  // gait with the CPG's genes.
  o.controller = s.controller == "cpg" ? "gait" : s.controller;
  o.genome = GenomeSpec{};
  try {
    if (!s.genome.empty()) {
      o.genome = ReadGenomeString(s.genome, "the design's genome");
    } else if (!s.genes.empty()) {
      o.genome = BuiltInGenome(s.genes);
    } else if (s.controller == "cpg") {
      o.genome = BuiltInGenome("cpg");
    }
  } catch (const std::exception& e) {
    throw field(s.genome.empty() ? "genes" : "genome", e);
  }
  o.task = s.task;
  o.base_gait = s.base_gait;
  try {
    o.fitness.distance_mode = ParseDistanceMode(s.distance);
  } catch (const std::exception& e) {
    throw field("distance", e);
  }
  o.fitness.w_distance = s.w_distance;
  o.fitness.w_speed = s.w_speed;
  o.fitness.w_energy = s.w_energy;
  o.fitness.w_drift = s.w_drift;
  o.fitness.w_fall = s.w_fall;
  o.robust.episodes = s.robust;
  o.robust.mode = s.robust_mode;
  RealityGap& g = o.robust.gap;
  g.sensor_noise = s.gap_sensor_noise;
  g.sensor_bias = s.gap_sensor_bias;
  g.joint_noise = s.gap_joint_noise;
  g.motor_noise = s.gap_motor_noise;
  g.latency = s.gap_latency;
  g.backlash = s.gap_backlash;
  g.max_accel = s.gap_max_accel;
  g.friction_range = s.gap_friction_range;
  g.mass_range = s.gap_mass_range;
  g.gain_range = s.gap_gain_range;
  g.terrain_range = s.gap_terrain_range;
  o.allow_overlap = s.allow_overlap;
  o.algorithm_settings.clear();
  std::istringstream words(s.algorithm_settings);
  std::string word;
  while (words >> word) {
    const size_t eq = word.find('=');
    try {
      if (eq == std::string::npos) throw std::invalid_argument("no '='");
      o.algorithm_settings[word.substr(0, eq)] = std::stod(word.substr(eq + 1));
    } catch (const std::exception&) {
      throw std::invalid_argument(fmt::format(
          "the design's <optimization><algorithmSettings>: expected "
          "flag=value, got '{}'",
          word));
    }
  }
  return o;
}

}  // namespace mrsim::studio
