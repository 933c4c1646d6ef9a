#include "optimizer/episode/problem_codec.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "common/exact_number.h"
#include "common/input_limits.h"
#include "gait_controller/gait_file.h"
#include "optimizer/episode/body_genes.h"
#include "sim_core/mesh/base64.h"
#include "sim_core/mesh/embedded_mesh.h"
#include "sim_core/scenario/scenario_xml.h"

namespace mrsim {
namespace {

constexpr const char* kMagic = "mrsim-opt-problem 1\n";

bool IsEmbedded(const std::string& image) {
  return image.empty() || image.rfind("base64:", 0) == 0;
}

// Robust fitness: only when on, so a nominal problem's payload (and its
// hash) is what it was. The seed is an integer of 64 bits, exact.
std::string EncodeRobust(const RobustSettings& r) {
  if (r.episodes <= 0) return "";
  const RealityGap& g = r.gap;
  return fmt::format(
      "robust_episodes={}\nrobust_mode={}\nrobust_seed={}\n"
      "gap_sensor_noise={}\ngap_sensor_bias={}\ngap_joint_noise={}\n"
      "gap_motor_noise={}\ngap_latency={}\ngap_backlash={}\n"
      "gap_max_accel={}\ngap_friction_range={}\ngap_mass_range={}\n"
      "gap_gain_range={}\ngap_terrain_range={}\n",
      r.episodes, r.mode, g.seed, g.sensor_noise, g.sensor_bias, g.joint_noise,
      g.motor_noise, g.latency, g.backlash, g.max_accel, g.friction_range,
      g.mass_range, g.gain_range, g.terrain_range);
}

std::string EncodeEpisode(const EpisodeSettings& e) {
  const FitnessSettings& f = e.fitness;
  return fmt::format(
             "duration={}\ncontrol_period={}\ndistance_mode={}\nw_distance={}\n"
             "w_speed={}\nw_energy={}\nw_drift={}\nw_fall={}\n",
             e.duration, e.control_period, ToString(f.distance_mode),
             f.w_distance, f.w_speed, f.w_energy, f.w_drift, f.w_fall) +
         EncodeRobust(e.robust) +
         // Only when on: a payload without it (and its hash) is as before.
         (e.allow_overlap ? "allow_overlap=1\n" : "");
}

EpisodeSettings DecodeEpisode(const std::string& text,
                              const std::string& source) {
  std::map<std::string, std::string> kv;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    kv[line.substr(0, eq)] = line.substr(eq + 1);
  }
  auto number = [&](const char* key) {
    auto it = kv.find(key);
    if (it == kv.end()) {
      throw ProblemError(source + ": episode settings lack " + key);
    }
    const std::optional<double> v = ParseWholeNumber(it->second);
    if (!v) {
      throw ProblemError(source + ": episode setting " + key +
                         ": expected a number");
    }
    return *v;
  };
  EpisodeSettings e;
  e.duration = number("duration");
  e.control_period = number("control_period");
  try {
    e.fitness.distance_mode =
        ParseDistanceMode(kv["distance_mode"], "episode setting distance_mode");
  } catch (const std::invalid_argument& err) {
    throw ProblemError(source + ": " + err.what());
  }
  e.fitness.w_distance = number("w_distance");
  e.fitness.w_speed = number("w_speed");
  e.fitness.w_energy = number("w_energy");
  e.fitness.w_drift = number("w_drift");
  e.fitness.w_fall = number("w_fall");
  if (kv.count("robust_episodes")) {
    RobustSettings& r = e.robust;
    const double episodes = number("robust_episodes");
    if (episodes != std::floor(episodes) || episodes < 1 ||
        episodes > RobustSettings::kMaxEpisodes) {
      throw ProblemError(source + ": episode setting robust_episodes: " +
                         "expected a whole number 1.." +
                         std::to_string(RobustSettings::kMaxEpisodes));
    }
    r.episodes = static_cast<int>(episodes);
    r.mode = kv["robust_mode"];
    const std::string seed = kv["robust_seed"];
    if (seed.empty() || seed.size() > 20 ||
        seed.find_first_not_of("0123456789") != std::string::npos) {
      throw ProblemError(source +
                         ": episode setting robust_seed: expected a whole "
                         "number of up to 64 bits");
    }
    errno = 0;
    r.gap.seed = std::strtoull(seed.c_str(), nullptr, 10);
    if (errno == ERANGE) {
      throw ProblemError(source + ": episode setting robust_seed: too large");
    }
    RealityGap& g = r.gap;
    g.sensor_noise = number("gap_sensor_noise");
    g.sensor_bias = number("gap_sensor_bias");
    g.joint_noise = number("gap_joint_noise");
    g.motor_noise = number("gap_motor_noise");
    g.latency = number("gap_latency");
    g.backlash = number("gap_backlash");
    g.max_accel = number("gap_max_accel");
    g.friction_range = number("gap_friction_range");
    g.mass_range = number("gap_mass_range");
    g.gain_range = number("gap_gain_range");
    g.terrain_range = number("gap_terrain_range");
  } else {
    e.robust.episodes = 0;
  }
  if (kv.count("allow_overlap")) {
    const std::string& flag = kv["allow_overlap"];
    if (flag != "0" && flag != "1") {
      throw ProblemError(source +
                         ": episode setting allow_overlap: expected 0 or 1");
    }
    e.allow_overlap = flag == "1";
  }
  try {
    e.Validate();
  } catch (const std::invalid_argument& err) {
    throw ProblemError(source + ": " + err.what());
  }
  return e;
}

// Refuses a scenario text that names a file before it is parsed (parsing
// would open the image to validate it).
void CheckNamesNoFile(const std::string& xml, const std::string& source) {
  // tinyxml2 parses recursively: a payload from the network is held to the
  // same size and depth limits as a file before it is parsed.
  try {
    CheckXmlLimits(xml, source);
  } catch (const InputLimitError& err) {
    throw ProblemError(err.what());
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw ProblemError(source + ": scenario is not well-formed XML");
  }
  std::vector<const tinyxml2::XMLElement*> stack = {doc.RootElement()};
  while (!stack.empty()) {
    const tinyxml2::XMLElement* e = stack.back();
    stack.pop_back();
    if (!e) continue;
    const std::string name = e->Name();
    const char* text = e->GetText();
    if (name == "height_Image" && text && !IsEmbedded(text)) {
      throw ProblemError(source + ": the scenario names an image file");
    }
    if (name == "shape" && text && std::string(text) != "Box" &&
        !IsEmbeddedMesh(text) &&
        std::string(e->Parent()->ToElement()->Name()) == "Frame") {
      throw ProblemError(source + ": the scenario names a mesh file");
    }
    for (const tinyxml2::XMLElement* c = e->FirstChildElement(); c;
         c = c->NextSiblingElement()) {
      stack.push_back(c);
    }
  }
}

}  // namespace

void EmbedAssets(Scenario& scenario) {
  // Mesh files travel inside the scenario (embedded_mesh.h).
  auto embed = [&scenario](Frame& f, const std::string& what) {
    if (!f.is_mesh() || IsEmbeddedMesh(f.shape)) return;
    std::string path = f.shape;
    if (!path.empty() && path[0] != '/' && !scenario.base_dir.empty()) {
      path = scenario.base_dir + "/" + path;
    }
    try {
      f.shape = EmbedMeshFile(path);
    } catch (const std::exception& e) {
      throw ProblemError(what + " '" + f.guid + "': " + e.what());
    }
  };
  for (Robot& r : scenario.robots) {
    for (Module& m : r.modules) {
      for (Frame& f : m.frames) embed(f, "frame");
    }
  }
  for (Frame& f : scenario.loose_frames) embed(f, "loose frame");
  std::string& image = scenario.scene.height_image;
  if (IsEmbedded(image)) return;
  std::string path = image;
  if (!path.empty() && path[0] != '/' && !scenario.base_dir.empty()) {
    path = scenario.base_dir + "/" + path;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // not a file: bare base64 bytes
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  image = "base64:" + Base64Encode(bytes);
}

std::string EncodeProblem(const Problem& problem) {
  Scenario scenario = problem.scenario;
  EmbedAssets(scenario);
  std::vector<std::array<std::string, 2>> sections = {
      {"episode", EncodeEpisode(problem.episode)},
      {"genome", WriteGenomeString(problem.genome)},
      {"gait", WriteGaitString(problem.episode.base_gait)},
      {"scenario", WriteScenarioString(scenario)},
  };
  // Only for another controller than the gait: a gait problem's payload
  // (and its hash, the run's fingerprint) is what it always was.
  if (!problem.controller.is_gait()) {
    sections.push_back(
        {"controller", EncodeControllerSpec(problem.controller)});
  }
  std::string out = kMagic;
  for (const auto& s : sections) {
    out += fmt::format("{} {}\n", s[0], s[1].size());
    out += s[1];
    out += "\n";
  }
  return out;
}

Problem DecodeProblem(const std::string& payload, const std::string& source) {
  if (payload.rfind(kMagic, 0) != 0) {
    throw ProblemError(source + ": not an mrsim-opt problem");
  }
  std::map<std::string, std::string> sections;
  size_t pos = std::string(kMagic).size();
  while (pos < payload.size()) {
    const size_t eol = payload.find('\n', pos);
    if (eol == std::string::npos) throw ProblemError(source + ": truncated");
    std::istringstream head(payload.substr(pos, eol - pos));
    std::string name;
    size_t size = 0;
    if (!(head >> name >> size) || eol + 1 + size + 1 > payload.size()) {
      throw ProblemError(source + ": bad section header");
    }
    sections[name] = payload.substr(eol + 1, size);
    pos = eol + 1 + size + 1;
  }
  for (const char* need : {"episode", "genome", "gait", "scenario"}) {
    if (!sections.count(need)) {
      throw ProblemError(source + ": no " + need + " section");
    }
  }
  Problem p;
  p.episode = DecodeEpisode(sections["episode"], source);
  if (sections.count("controller")) {
    try {
      p.controller = DecodeControllerSpec(sections["controller"], source);
    } catch (const std::invalid_argument& e) {
      throw ProblemError(e.what());
    }
  }
  try {
    // A script's parameters are genes of its own names.
    p.genome = ReadGenomeString(sections["genome"], source + " genome",
                                !p.controller.is_gait());
    p.episode.base_gait = ReadGaitString(sections["gait"], source + " gait");
    CheckNamesNoFile(sections["scenario"], source);
    p.scenario = ReadScenarioString(sections["scenario"], source + " scenario",
                                    "/nonexistent");
  } catch (const ProblemError&) {
    throw;
  } catch (const std::exception& e) {
    throw ProblemError(e.what());
  }
  try {
    GenomeRobotIndex(p.scenario, p.genome);
  } catch (const GenomeError& e) {
    throw ProblemError(source + ": " + e.what());
  }
  return p;
}

}  // namespace mrsim
