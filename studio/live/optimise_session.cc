#include "studio/live/optimise_session.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "common/atomic_file.h"
#include "common/data_dir.h"
#include "common/lcm_url.h"
#include "launcher/program_locator.h"
#include "logger/csv_columns.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/search/algorithm_registry.h"

namespace mrsim::studio {
namespace {

constexpr size_t kConsoleLines = 500;

double Number(const std::string& cell, int line, const std::string& column) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(cell, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != cell.size() || cell.empty()) {
    throw std::runtime_error(
        fmt::format("generations.csv line {}: {} is '{}' (expected a number)",
                    line, column, cell));
  }
  return v;
}

}  // namespace

OptimiseSession::OptimiseSession(std::vector<std::string> search_path)
    : search_path_(std::move(search_path)) {}

OptimiseSession::~OptimiseSession() { Stop(); }

ProcessSpec OptimiseSession::Spec(const OptimiseOptions& o,
                                  const std::string& genome_path) {
  if (o.scenario_path.empty() && o.task.empty()) {
    throw std::invalid_argument("optimise: save the design to a file first");
  }
  if (o.out_dir.empty()) throw std::invalid_argument("optimise: no folder");
  ParseAlgorithm(o.algorithm, "optimise: algorithm");
  if (o.generations < 1 || o.population < 1 || !(o.episode_s > 0)) {
    throw std::invalid_argument(fmt::format(
        "optimise: {} generations of {} over {} s episodes (expected at "
        "least 1 generation, 1 individual and a positive episode)",
        o.generations, o.population, o.episode_s));
  }
  ProcessSpec spec;
  spec.name = "opt";
  spec.program = "mrsim-opt";
  spec.required = true;
  // The gait's genes are the genome's; a script or a network brings its own.
  const bool gait = o.controller == "gait";
  const std::string controller =
      o.controller == "lua" ? "lua:" + ScriptPath(o) : o.controller;
  spec.args = {o.scenario_path,
               gait ? "--genome" : "--controller",
               gait ? genome_path : controller,
               "--out",
               o.out_dir,
               "--algorithm",
               o.algorithm,
               "--generations",
               std::to_string(o.generations),
               "--population",
               std::to_string(o.population),
               "--seed",
               std::to_string(o.seed),
               "--episode",
               fmt::format("{:g}", o.episode_s)};
  if (!o.task.empty()) {
    spec.args[0] = "--task";
    spec.args.insert(spec.args.begin() + 1, o.task);
  }
  if (o.task.empty() || !o.base_gait.empty()) {
    spec.args.insert(spec.args.end(), {"--gait", o.base_gait});
  }
  const FitnessSettings& f = o.fitness;
  spec.args.insert(spec.args.end(),
                   {"--distance", ToString(f.distance_mode), "--w-distance",
                    fmt::format("{:g}", f.w_distance), "--w-speed",
                    fmt::format("{:g}", f.w_speed), "--w-energy",
                    fmt::format("{:g}", f.w_energy), "--w-drift",
                    fmt::format("{:g}", f.w_drift), "--w-fall",
                    fmt::format("{:g}", f.w_fall)});
  if (o.allow_overlap) spec.args.push_back("--allow-overlap");
  if (o.robust.episodes != 0) {
    o.robust.Validate();
    spec.args.insert(spec.args.end(),
                     {"--robust", std::to_string(o.robust.episodes),
                      "--robust-mode", o.robust.mode});
    // The form's gap, not the saved file's: every value, so an unsaved
    // edit is what runs.
    const RealityGap& g = o.robust.gap;
    for (const auto& [name, value] :
         std::initializer_list<std::pair<const char*, double>>{
             {"sensor_noise", g.sensor_noise},
             {"sensor_bias", g.sensor_bias},
             {"joint_noise", g.joint_noise},
             {"motor_noise", g.motor_noise},
             {"latency", g.latency},
             {"backlash", g.backlash},
             {"max_accel", g.max_accel},
             {"friction_range", g.friction_range},
             {"mass_range", g.mass_range},
             {"gain_range", g.gain_range},
             {"terrain_range", g.terrain_range}}) {
      spec.args.insert(spec.args.end(),
                       {"--robust-gap", fmt::format("{}={}", name, value)});
    }
  }
  const AlgorithmInfo& info = AlgorithmInfoOf(ParseAlgorithm(o.algorithm));
  for (const auto& setting : o.algorithm_settings) {
    // A named copy: C++17 lambdas cannot capture a structured binding.
    const std::string& flag = setting.first;
    const double value = setting.second;
    const bool own =
        std::any_of(info.settings.begin(), info.settings.end(),
                    [&](const AlgorithmSetting& s) { return flag == s.flag; });
    if (!own || !std::isfinite(value)) {
      throw std::invalid_argument(
          fmt::format("optimise: '{}' = {} is not a setting of {}", flag, value,
                      info.title));
    }
    spec.args.insert(spec.args.end(), {"--" + flag, fmt::format("{}", value)});
  }
  if (o.farm) {
    spec.args.push_back("--farm");
    if (!o.lcm_url.empty())
      spec.args.insert(spec.args.end(), {"--lcm-url", o.lcm_url});
  }
  if (o.islands != 1) {
    spec.args.insert(spec.args.end(), {"--islands", std::to_string(o.islands)});
  }
  if (o.jump_to >= 0) {
    spec.args.insert(spec.args.end(), {"--jump-to", std::to_string(o.jump_to)});
  }
  spec.args.insert(spec.args.end(), {"--progress-url", ProgressUrl(o)});
  return spec;
}

std::string OptimiseSession::ProgressUrl(const OptimiseOptions& o) {
  return ResolveLcmUrl(o.progress_url.empty() ? o.lcm_url : o.progress_url);
}

std::string OptimiseSession::ScriptPath(const OptimiseOptions& o) {
  return o.out_dir + "/studio.controller.lua";
}

std::string OptimiseSession::BestFileName(const OptimiseOptions& o) {
  if (o.controller == "lua") return "best_controller.lua";
  if (o.controller.rfind("mlp", 0) == 0) return "best_network.xml";
  return "best_gait.xml";
}

void OptimiseSession::Start(const OptimiseOptions& options, WallTime now) {
  Stop();
  pending_replay_ = -1;
  const bool gait = options.controller == "gait";
  if (gait) options.genome.Validate("the studio's genome");
  if (options.controller == "lua" && options.lua_source.empty()) {
    throw std::invalid_argument(
        "optimise: the design has no Lua script (write one under Run's "
        "controller: Lua script)");
  }
  std::filesystem::create_directories(options.out_dir);
  const std::string genome_path = options.out_dir + "/studio.genome.xml";
  const ProcessSpec spec = Spec(options, genome_path);
  if (gait) {
    WriteFileAtomically(genome_path, WriteGenomeString(options.genome));
  } else if (options.controller == "lua") {
    WriteFileAtomically(ScriptPath(options), options.lua_source);
  }
  options_ = options;
  command_ = spec.args;
  progress_ = OptimiseProgress{};
  progress_.generations = options.generations;
  csv_size_ = -1;
  progress_lines_ = 0;
  stall_.Start(0, now);
  console_.clear();
  last_line_.clear();
  // Listening before mrsim-opt starts: no message is missed.
  std::error_code ec;
  const auto dir = std::filesystem::absolute(options.out_dir, ec);
  progress_dir_ = ec ? options.out_dir : dir.lexically_normal().string();
  progress_link_ = std::make_unique<OptProgressLink>(
      ProgressUrl(options), FarmChannels(kDefaultFarmPrefix).progress,
      [this](const opt_progress_t& m) { OnProgress(m); });
  group_ = std::make_unique<ProcessGroup>(
      [this](const std::string& name, const std::string& line) {
        // The group's own lines ("opt exited with code 2") come as
        // "launch"; the reason is mrsim-opt's.
        if (name != "launch") {
          last_line_ = line;
          if (std::string note = FailedNote(line); !note.empty()) {
            progress_.failed_note = std::move(note);
          }
        }
        Line("[" + name + "] " + line);
      });
  group_->Start(spec, FindProgram(spec.program, search_path_));
  progress_.running = true;
}

void OptimiseSession::Stop() {
  if (group_) {
    group_->StopAll(5.0);  // mrsim-opt keeps its checkpoint: Start resumes
    progress_.stopped = progress_.running;
    progress_.running = false;
    group_.reset();
  }
}

std::string OptimiseSession::FailedNote(const std::string& line) {
  const std::string kGeneration = "generation ";
  if (line.rfind(kGeneration, 0) != 0) return "";
  const size_t number_end = line.find(' ', kGeneration.size());
  const size_t failed = line.find(" failed ");
  if (number_end == std::string::npos || failed == std::string::npos) {
    return "";
  }
  // The reasons run to the rate column, " | ".
  const size_t end = line.find(" | ", failed);
  return line.substr(0, number_end) + ":" +
         line.substr(failed, end == std::string::npos ? std::string::npos
                                                      : end - failed);
}

void OptimiseSession::Line(const std::string& line) {
  console_.push_back(line);
  if (console_.size() > kConsoleLines) console_.erase(console_.begin());
}

bool TakeOptProgress(const opt_progress_t& m, const std::string& out_dir,
                     OptimiseProgress* progress) {
  if (m.out_dir != out_dir) return false;  // another run's
  progress->workers = m.workers;
  if (m.replayed) return true;  // read back on resuming: no rate, no ETA
  progress->evals_per_s = m.evals_per_second;
  progress->eta = m.eta;
  return true;
}

void OptimiseSession::OnProgress(const opt_progress_t& m, WallTime) {
  if (TakeOptProgress(m, progress_dir_, &progress_)) ++progress_lines_;
}

std::vector<GenerationRow> OptimiseSession::ParseGenerations(
    const std::string& csv) {
  std::vector<GenerationRow> rows;
  std::stringstream in(csv);
  std::string line;
  if (!std::getline(in, line)) return rows;
  const std::vector<std::string> header = SplitCsvRecord(line);
  if (header.size() < 6 || header[0] != "generation") {
    throw std::runtime_error("generations.csv: unexpected header '" + line +
                             "'");
  }
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> cells = SplitCsvRecord(line);
    if (cells.size() != header.size()) {
      // A line still being written: stop here, read it next time.
      break;
    }
    GenerationRow r;
    r.generation = static_cast<int>(Number(cells[0], number, header[0]));
    r.best = Number(cells[1], number, header[1]);
    r.mean = Number(cells[2], number, header[2]);
    r.worst = Number(cells[3], number, header[3]);
    r.best_so_far = Number(cells[4], number, header[4]);
    r.failed = static_cast<int>(Number(cells[5], number, header[5]));
    for (size_t i = 6; i < cells.size(); ++i) {
      if (header[i] == "island") continue;  // mrsim-opt --islands: not a gene
      r.genes[header[i]] = Number(cells[i], number, header[i]);
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

void OptimiseSession::Poll(int timeout_ms, WallTime now) {
  // Messages first: those sent before mrsim-opt ended count for its run.
  if (progress_link_) progress_link_->Poll();
  if (group_) {
    group_->Poll(timeout_ms);
    if (progress_.running && !group_->AnyRunning()) {
      progress_.running = false;
      progress_.finished = true;
      progress_.exit_code = group_->AllClean() ? 0 : 1;
      if (progress_.exit_code != 0) {
        // "mrsim-opt: o/checkpoint.txt: ...": the words after its name.
        const std::string kName = "mrsim-opt: ";
        progress_.failure = last_line_.rfind(kName, 0) == 0
                                ? last_line_.substr(kName.size())
                                : last_line_;
      }
    }
  }
  if (!options_.out_dir.empty()) ReadGenerations();
  stall_.Update(std::max<long>(progress_lines_, progress_.rows.size()), now);
  if (pending_replay_ >= 0 && Row(pending_replay_) == nullptr &&
      !progress_.running) {
    Line(
        fmt::format("[studio] generation {} was not reached: nothing to "
                    "replay",
                    pending_replay_ + 1));
    pending_replay_ = -1;
  }
}

void OptimiseSession::ReadGenerations() {
  const std::string path = options_.out_dir + "/generations.csv";
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || static_cast<long long>(size) == csv_size_) return;
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  try {
    progress_.rows = ParseGenerations(ss.str());
    csv_size_ = static_cast<long long>(size);
  } catch (const std::exception& e) {
    Line(std::string("[studio] ") + e.what());
    csv_size_ = static_cast<long long>(size);
  }
}

std::optional<GenerationRow> OptimiseSession::Best() const {
  const GenerationRow* best = nullptr;
  for (const GenerationRow& r : progress_.rows) {
    // After a jump to N, the best of the first N (generations 0..N-1).
    if (options_.jump_to >= 0 && r.generation >= options_.jump_to) break;
    if (best == nullptr || r.best > best->best) best = &r;
  }
  if (best == nullptr) return std::nullopt;
  return *best;
}

const GenerationRow* OptimiseSession::Row(int generation) const {
  for (const GenerationRow& r : progress_.rows) {
    if (r.generation == generation) return &r;
  }
  return nullptr;
}

void OptimiseSession::Jump(int n, OptimiseOptions options, WallTime now) {
  if (n < 1) {
    throw std::invalid_argument(fmt::format(
        "jump to generation {} (expected 1 or more: generations count from "
        "1)",
        n));
  }
  if (options.out_dir == options_.out_dir && Row(n - 1) != nullptr) {
    pending_replay_ = n - 1;  // there already: the run goes on
    return;
  }
  options.jump_to = n;
  Start(options, now);
  pending_replay_ = n - 1;
}

std::optional<GenerationRow> OptimiseSession::TakeReplay() {
  if (pending_replay_ < 0) return std::nullopt;
  const GenerationRow* row = Row(pending_replay_);
  if (row == nullptr) return std::nullopt;
  pending_replay_ = -1;
  return *row;
}

std::string OptimiseSession::StallWarning(WallTime now) const {
  if (!progress_.running) return "";
  const auto silent = stall_.Stalled(now);
  if (!silent) return "";
  // Workers are known from mrsim-opt's first progress line on.
  const std::string workers = progress_lines_ > 0
                                  ? fmt::format("workers {}", progress_.workers)
                                  : std::string("no workers reported yet");
  return fmt::format(
      "no progress for {:.0f} s: are workers alive? ({}; a generation was "
      "expected within {:.0f} s)",
      *silent, workers, stall_.Bound());
}

std::map<std::string, double> OptimiseSession::BestGenes() const {
  const auto best = Best();
  return best ? best->genes : std::map<std::string, double>{};
}

std::string GenomePathFor(const std::string& genome_path,
                          const std::string& design_path) {
  namespace fs = std::filesystem;
  const fs::path genome(genome_path);
  std::error_code ec;
  if (genome.empty() || genome.is_absolute() || fs::exists(genome, ec)) {
    return genome_path;
  }
  if (!design_path.empty()) {
    const fs::path beside = fs::path(design_path).parent_path() / genome;
    if (fs::exists(beside, ec)) return beside.string();
    // The default names its folder (scenarios/...): try the file name too.
    const fs::path named =
        fs::path(design_path).parent_path() / genome.filename();
    if (fs::exists(named, ec)) return named.string();
  }
  // An installed studio: the bundled genomes are in its data folder
  // (/usr/share/mrsim/scenarios/...).
  const std::string installed = FindDataFile(genome.string());
  return installed.empty() ? genome_path  // the error names what was typed
                           : installed;
}

}  // namespace mrsim::studio
