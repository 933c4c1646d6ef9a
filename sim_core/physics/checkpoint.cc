#include "sim_core/physics/checkpoint.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "common/atomic_file.h"
#include "common/input_limits.h"
#include "sim_core/mesh/base64.h"
#include "sim_core/scenario/scenario_xml.h"
#include "sim_core/scenario/terrain.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[] = "mrsim-checkpoint 1";

// The scenario as the checkpoint stores it: a terrain file is embedded and
// mesh paths made absolute, so the checkpoint does not depend on where it
// is loaded.
Scenario Portable(const Scenario& in) {
  Scenario s = in;
  std::string path;
  if (TerrainImageIsFile(s.scene, s.base_dir, &path)) {
    std::ifstream file(path, std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    if (!file.good() && !file.eof()) {
      throw std::runtime_error("checkpoint: cannot read terrain image '" +
                               path + "'");
    }
    s.scene.height_image = "base64:" + Base64Encode(bytes);
  }
  auto absolute = [&](std::string& shape) {
    if (shape == "Box" || shape.empty()) return;
    fs::path p(shape);
    if (p.is_relative() && !s.base_dir.empty()) p = fs::path(s.base_dir) / p;
    shape = fs::absolute(p).lexically_normal().string();
  };
  for (Robot& r : s.robots) {
    for (Module& m : r.modules) {
      for (Frame& f : m.frames) absolute(f.shape);
    }
  }
  for (Frame& f : s.loose_frames) absolute(f.shape);
  return s;
}

}  // namespace

std::string SaveCheckpointString(const Physics& physics) {
  const Scenario scenario = Portable(physics.scenario());
  const std::string xml = WriteScenarioString(scenario);
  std::ostringstream out;
  out << kMagic << "\n";
  char time[64];
  std::snprintf(time, sizeof(time), "%.17g", physics.time());
  out << "time: " << time << "\n";
  const std::string& dir = physics.scenario().base_dir;
  out << "base_dir: "
      << Base64Encode(std::vector<unsigned char>(dir.begin(), dir.end()))
      << "\n";
  out << "state: " << Base64Encode(physics.SaveState()) << "\n";
  out << "scenario-bytes: " << xml.size() << "\n\n";
  out << xml;
  return out.str();
}

void SaveCheckpoint(const std::string& path, const Physics& physics) {
  try {
    WriteFileAtomically(path, SaveCheckpointString(physics));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("checkpoint: ") + e.what());
  }
}

std::unique_ptr<Physics> LoadCheckpointString(const std::string& text,
                                              const std::string& name) {
  auto fail = [&](const std::string& what) -> CheckpointError {
    return CheckpointError(name + ": not a valid checkpoint: " + what);
  };
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kMagic) {
    throw fail("the first line must be '" + std::string(kMagic) + "'");
  }
  std::string state_b64, dir_b64;
  long long scenario_bytes = -1;
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) break;
    const size_t colon = line.find(": ");
    if (colon == std::string::npos) {
      throw fail("line " + std::to_string(line_no) + ": expected 'key: value'");
    }
    const std::string key = line.substr(0, colon);
    const std::string value = line.substr(colon + 2);
    if (key == "state") {
      state_b64 = value;
    } else if (key == "base_dir") {
      dir_b64 = value;
    } else if (key == "scenario-bytes") {
      try {
        scenario_bytes = std::stoll(value);
      } catch (const std::exception&) {
        throw fail("line " + std::to_string(line_no) +
                   ": scenario-bytes is not a number");
      }
    }
    // Other keys (time) are informational.
  }
  if (state_b64.empty()) throw fail("no 'state' line");
  if (scenario_bytes < 0) throw fail("no 'scenario-bytes' line");
  const std::streamoff offset = in.tellg();
  if (offset < 0 || text.size() - static_cast<size_t>(offset) !=
                        static_cast<size_t>(scenario_bytes)) {
    throw fail("the scenario is truncated or longer than scenario-bytes");
  }
  const std::string xml = text.substr(static_cast<size_t>(offset));
  std::vector<unsigned char> state, dir;
  try {
    state = Base64Decode(state_b64);
    dir = Base64Decode(dir_b64);
  } catch (const std::exception& e) {
    throw fail(std::string("bad base64: ") + e.what());
  }
  const std::string base_dir(dir.begin(), dir.end());
  Scenario scenario;
  try {
    scenario = ReadScenarioString(xml, name, base_dir);
  } catch (const std::exception& e) {
    throw CheckpointError(std::string(e.what()));
  }
  scenario.base_dir = base_dir;
  auto physics = std::make_unique<Physics>(scenario);
  try {
    physics->LoadState(state);
  } catch (const std::exception& e) {
    throw fail(e.what());
  }
  return physics;
}

std::unique_ptr<Physics> LoadCheckpoint(const std::string& path) {
  std::optional<std::string> text;
  try {
    // The scenario (at most kMaxInputFileBytes) and the physics state.
    text = ReadFileAtMost(path, 2 * kMaxInputFileBytes);
  } catch (const InputLimitError& e) {
    throw CheckpointError(e.what());
  }
  if (!text) throw CheckpointError(path + ": cannot open the checkpoint");
  return LoadCheckpointString(*text, path);
}

}  // namespace mrsim
