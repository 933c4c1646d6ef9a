#include "optimizer/process/opt_command.h"

#include <fmt/format.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#include "common/atomic_file.h"
#include "common/enum_option.h"
#include "common/hash.h"
#include "common/lcm_url.h"
#include "common/wall_time.h"
#include "gait_controller/gait_file.h"
#include "nn_controller/network_file.h"
#include "optimizer/episode/best_lua_script.h"
#include "optimizer/episode/body_genes.h"
#include "optimizer/episode/controller_genes.h"
#include "optimizer/episode/episode_physics_pool.h"
#include "optimizer/episode/mlp_genes.h"
#include "optimizer/episode/problem_codec.h"
#include "optimizer/episode/task.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_evaluator.h"
#include "optimizer/process/opt_progress_reporter.h"
#include "optimizer/search/algorithm_registry.h"
#include "optimizer/search/local_evaluator.h"
#include "sim_core/export/overlap_check.h"
#include "sim_core/scenario/scenario_xml.h"

namespace fs = std::filesystem;

namespace mrsim {
namespace {

std::string MakeRunId() {
  std::random_device device;
  const auto now = std::chrono::system_clock::now().time_since_epoch().count();
  return HashHex(device() ^ (static_cast<std::uint64_t>(now) << 1) ^
                 (static_cast<std::uint64_t>(getpid()) << 40));
}

// The replay talks where the user asked: --lcm-url, else LCM_DEFAULT_URL,
// else the launch file's default.
std::string ReplayLcmUrl(const std::string& lcm_url) {
  if (!lcm_url.empty()) return lcm_url;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env != nullptr ? env : "";
}

// `controller`: the controller process's line (mrsim-gait or mrsim-lua
// with its arguments but the LCM URL).
void WriteReplayLaunch(const std::string& path, const std::string& dir,
                       const std::string& scenario,
                       const std::string& controller, double duration,
                       const std::string& lcm_url) {
  std::ostringstream out;
  out << "<!-- Written by mrsim-opt: the best individual in the simulator, "
         "its gait\n     controller and the viewer (video in "
         "${out}/replay.mp4; --set view=--window\n     for a window).\n"
         "     Run: mrsim launch "
      << path << " [--without view] -->\n"
      << "<launch name=\"opt-replay\">\n"
      << "  <arg name=\"out\" default=\"" << dir << "\"/>\n"
      << "  <arg name=\"view\" default=\"--out ${out}/replay.mp4\"/>\n"
      << "  <arg name=\"lcm_url\" default=\""
      << (lcm_url.empty() ? "udpm://239.255.76.67:7667?ttl=0" : lcm_url)
      << "\"/>\n"
      << "  <arg name=\"duration\" default=\"" << duration << "\"/>\n"
      << "  <process name=\"view\" program=\"mrsim-view\" delay=\"0.3\"\n"
      << "           args=\"" << scenario
      << " --lcm-url ${lcm_url} --camera follow ${view}\"/>\n"
      << controller
      << "  <process name=\"sim\" program=\"mrsim-sim\" required=\"true\" "
         "delay=\"1.0\"\n"
      << "           args=\"" << scenario
      << " --lcm-url ${lcm_url} --clock realtime --duration ${duration}\"/>\n"
      << "</launch>\n";
  WriteFileAtomically(path, out.str());
}

// The best controller's file: best_gait.xml, best_controller.lua for a
// Lua script, best_network.xml for a network (mrsim-nn). Returns its name.
std::string WriteBestControllerFile(const Problem& problem, const Genome& best,
                                    const std::string& dir) {
  switch (problem.controller.kind) {
    case ControllerSpec::Kind::kGait:
      WriteGaitFile(GaitOfGenome(problem, best), dir + "/best_gait.xml");
      return "best_gait.xml";
    case ControllerSpec::Kind::kLua:
      WriteFileAtomically(
          dir + "/best_controller.lua",
          BestLuaScript(problem.controller, problem.genome, best));
      return "best_controller.lua";
    case ControllerSpec::Kind::kMlp:
      WriteNetworkFile(MlpNetworkOfGenome(MlpShapeOf(problem.controller),
                                          problem.genome, best),
                       dir + "/best_network.xml", "optimised");
      return "best_network.xml";
  }
  throw std::logic_error("unknown controller kind");
}

// The replay launch file's controller process for that file.
std::string ReplayControllerProcess(const Problem& problem,
                                    const std::string& file,
                                    const std::string& robot,
                                    const std::string& scenario) {
  // mrsim-nn reads the joint count from the state: no --scenario.
  const bool mlp = problem.controller.kind == ControllerSpec::Kind::kMlp;
  const std::string program = problem.controller.is_gait() ? "mrsim-gait"
                              : mlp                        ? "mrsim-nn"
                                                           : "mrsim-lua";
  const std::string name = problem.controller.is_gait() ? "gait"
                           : mlp                        ? "nn"
                                                        : "lua";
  const double rate = 1.0 / problem.episode.control_period;
  const std::string what =
      problem.controller.is_gait()
          ? fmt::format(" --scenario {} --gait {}", scenario, file)
      : mlp ? fmt::format(" --net {} --rate {}", file, rate)
            : fmt::format(" --scenario {} --script {} --rate {}", scenario,
                          file, rate);
  return fmt::format(
      "  <process name=\"{0}\" program=\"{1}\" delay=\"0.3\"\n"
      "           args=\"--robot {2}{3} --lcm-url ${{lcm_url}} "
      "--name {0}\"/>\n",
      name, program, robot, what);
}

// The best individual's controller, scenario, genome and replay launch
// file; returns the controller file's name.
std::string WriteBestFiles(const OptCommand& c, const Problem& problem,
                           const RunResult& result, const std::string& dir,
                           const std::string& launch) {
  const std::string controller_file =
      WriteBestControllerFile(problem, result.best, dir);
  const Scenario body =
      ApplyBodyGenes(problem.scenario, problem.genome, result.best);
  WriteScenarioFile(body, dir + "/best_scenario.xml");
  GenomeSpec best_spec = problem.genome;
  for (int i = 0; i < best_spec.size(); ++i) {
    best_spec.genes[i].start = result.best[i];
  }
  WriteFileAtomically(dir + "/best_genome.xml", WriteGenomeString(best_spec));
  const std::string robot =
      body.robots[GenomeRobotIndex(body, problem.genome)].name;
  const std::string scenario = fs::absolute(dir + "/best_scenario.xml");
  WriteReplayLaunch(
      launch, fs::absolute(dir).string(), scenario,
      ReplayControllerProcess(
          problem, fs::absolute(dir + "/" + controller_file), robot, scenario),
      c.episode.duration, ReplayLcmUrl(c.lcm_url));
  return controller_file;
}

// --algorithm's help: one line per algorithm of the registry.
std::string AlgorithmHelp() {
  std::string help = "the search algorithm";
  for (const AlgorithmInfo& info : Algorithms()) {
    help += fmt::format("\n  {}: {}", info.name, info.summary);
  }
  return help + "\n";
}

}  // namespace

void AddOptFlags(CLI::App& app, OptCommand& c) {
  AlgorithmSettings& a = c.algorithm;
  EpisodeSettings& e = c.episode;
  auto* scenario =
      app.add_option("scenario", c.scenario_path, "Scenario XML file");
  auto* task = app.add_option("--task", c.task,
                              "A task of the suite instead of a scenario: "
                              "its world and fitness (mrsim tasks lists them)")
                   ->excludes(scenario);
  auto* world = app.add_option_group("world");
  world->add_options(scenario, task);
  world->require_option(1);
  auto* genome =
      app.add_option("--genome", c.genome_path, "Genome description file");
  auto* genes = app.add_option("--genes", c.genes,
                               "A built-in genome instead of --genome: sine "
                               "(the seven gait genes) | cpg (and the CPG's)")
                    ->excludes(genome);
  auto* gene_source = app.add_option_group("genes");
  gene_source->add_options(genome, genes);
  // At most one; the gait needs one (PrepareOpt says so), a Lua script's
  // parameters are genes of their own.
  gene_source->require_option(0, 1);
  app.add_option("--controller", c.controller,
                 "What the genes drive: gait (the built-in gait, --genome "
                 "or --genes), cpg (the gait with the CPG genes by "
                 "default), lua:FILE (a Lua script; its declared params "
                 "are the genes, plus any body genes of --genome), lua "
                 "(the scenario's own <run> script), mlp:H (a network)")
      ->capture_default_str();
  app.add_option("--out", c.out_dir,
                 "Output directory (checkpoint, CSVs, best); default: "
                 "opt-<scenario or task name> in the working folder");
  app.add_option("--progress-url", c.progress_url,
                 "Also publish opt_progress_t on <prefix>_PROGRESS over this "
                 "LCM URL after every generation and at the end");
  AddEnumOption(app, "--algorithm", &a.algorithm, AlgorithmNames(),
                AlgorithmHelp());
  app.add_option("--generations", c.generations, "Generations to run")
      ->capture_default_str();
  app.add_option("--population", a.population,
                 "Individuals (SA: chains, PSO: particles, CMA-ES: lambda) "
                 "per generation")
      ->capture_default_str();
  app.add_option("--seed", a.seed, "Seed of the run's random engine")
      ->capture_default_str();
  app.add_option("--islands", a.islands,
                 "Independent populations taking turns: a farm hands out one "
                 "while another's last episodes run")
      ->capture_default_str()
      ->check(CLI::Range(1, AlgorithmSettings::kMaxIslands));
  app.add_flag("--no-start-genome", c.no_start,
               "Do not put the start genome in generation 0");
  app.add_option("--episode", e.duration, "Episode length (s of sim time)")
      ->capture_default_str();
  app.add_option("--control-period", e.control_period,
                 "Gait control period (s)")
      ->capture_default_str();
  app.add_option("--gait", c.gait_spec,
                 "Base gait (preset or file) the gait genes modify "
                 "(default: forward, or the task's own gait)");
  AddEnumOption(app, "--distance", &e.fitness.distance_mode, DistanceModes(),
                "distance scored: along +x, in any direction, or up (+z); "
                "--task sets its own");
  app.add_option("--w-distance", e.fitness.w_distance)->capture_default_str();
  app.add_option("--w-speed", e.fitness.w_speed)->capture_default_str();
  app.add_option("--w-energy", e.fitness.w_energy, "Per joule")
      ->capture_default_str();
  app.add_option("--w-drift", e.fitness.w_drift, "Per metre of lateral drift")
      ->capture_default_str();
  app.add_option("--w-fall", e.fitness.w_fall,
                 "Per fraction of the episode upside down")
      ->capture_default_str();
  app.add_option("--robust", e.robust.episodes,
                 "Fitness over K perturbed episodes (reality gap, "
                 "docs/optimizer.md); 0: the nominal episode")
      ->capture_default_str()
      ->check(CLI::Range(0, RobustSettings::kMaxEpisodes));
  app.add_option("--robust-mode", e.robust.mode,
                 "mean | worst of the K perturbed episodes")
      ->capture_default_str()
      ->check(CLI::IsMember({"mean", "worst"}));
  app.add_option("--robust-gap", c.robust_gap,
                 "NAME=VALUE, repeated: a reality gap value of the robust "
                 "episodes (motor_noise=0.2; docs/physics.md, 'The reality "
                 "gap'); the others stay the design's or typical")
      ->allow_extra_args(false);
  AddEnumOption(app, "--selection", &a.selection, SelectionMethods(),
                "the GA's parent selection");
  // Each algorithm's own settings, from the registry (the studio's
  // Optimise section shows the same list).
  for (const AlgorithmInfo& info : Algorithms()) {
    for (const AlgorithmSetting& setting : info.settings) {
      const std::string flag = std::string("--") + setting.flag;
      if (setting.real) {
        app.add_option(flag, a.*setting.real, setting.help)
            ->capture_default_str();
      } else {
        app.add_option(flag, a.*setting.whole, setting.help)
            ->capture_default_str();
      }
    }
  }
  app.add_option("--workers", c.workers,
                 "local:K (K threads; 0 = one per core)")
      ->capture_default_str();
  app.add_flag("--farm", c.farm, "Evaluate on mrsim-worker processes over LCM");
  app.add_option("--lcm-url", c.lcm_url,
                 "LCM URL of the farm (--farm) and of the --replay");
  AddAuthFlags(app, c.auth);
  app.add_flag("--allow-mixed-builds", c.allow_mixed_builds,
               "Farm: take workers whose build (version, compiler, MuJoCo, "
               "CPU floating-point features) differs from this one's; their "
               "results may then differ from a local run's");
  app.add_option("--verify", c.verify,
                 "Farm: run this share of jobs (0..1) again on another "
                 "worker; a worker whose results disagree is dropped for the "
                 "run and all its results are re-done")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--prefix", c.prefix, "Farm channel prefix")
      ->capture_default_str();
  app.add_option("--job-timeout", c.job_timeout,
                 "Farm: re-send a job after this many s (0: automatic)")
      ->capture_default_str();
  app.add_option("--worker-timeout", c.worker_timeout,
                 "Farm: s without heartbeat before a worker counts as gone")
      ->capture_default_str();
  app.add_option("--slurm", c.slurm,
                 "Farm: submit N mrsim-worker processes as one Slurm array "
                 "job, cancelled when the run ends (docs/optimizer.md)")
      ->check(CLI::Range(1, 100000));
  app.add_option("--slurm-opt", c.slurm_options,
                 "Farm: an sbatch option for the array, e.g. partition=debug, "
                 "account=proj, time=2:00:00, cpus-per-task=4 (repeat it)")
      ->allow_extra_args(false);
  app.add_option("--hub", c.hub_port,
                 "Farm: start LCM's TCP hub on this port (the URL is then "
                 "tcpq://THIS_HOST:PORT unless --lcm-url says)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--chunk-size", c.chunk_size,
                 "Farm: payload bytes per chunk, 1..60000; 0: what fits one "
                 "Ethernet frame (a lost frame then loses one chunk only)")
      ->capture_default_str();
  app.add_option("--jump-to", c.jump_to,
                 "Stop after generation N, 1..--generations (replayed from "
                 "the checkpoint when it has them)")
      ->check(CLI::Range(1, 100000000));
  app.add_flag("--replay", c.replay,
               "Afterwards show the best in mrsim-sim + mrsim-gait + "
               "mrsim-view (via mrsim launch)");
  app.add_flag("--quiet", c.quiet, "Only the final summary");
  app.add_flag("--allow-overlap", c.allow_overlap,
               "Optimise a scenario whose parts overlap at the start "
               "(refused otherwise, as mrsim-sim refuses to run it)");
}

void SetGapValues(const std::vector<std::string>& words, RealityGap* gap) {
  const std::pair<const char*, double*> fields[] = {
      {"sensor_noise", &gap->sensor_noise},
      {"sensor_bias", &gap->sensor_bias},
      {"joint_noise", &gap->joint_noise},
      {"motor_noise", &gap->motor_noise},
      {"latency", &gap->latency},
      {"backlash", &gap->backlash},
      {"max_accel", &gap->max_accel},
      {"friction_range", &gap->friction_range},
      {"mass_range", &gap->mass_range},
      {"gain_range", &gap->gain_range},
      {"terrain_range", &gap->terrain_range}};
  for (const std::string& word : words) {
    const size_t eq = word.find('=');
    const std::string name = word.substr(0, eq);
    double* target = nullptr;
    std::string names;
    for (const auto& field : fields) {
      names += (names.empty() ? "" : ", ") + std::string(field.first);
      if (name == field.first) target = field.second;
    }
    size_t used = 0;
    double value = 0;
    try {
      if (eq != std::string::npos)
        value = std::stod(word.substr(eq + 1), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (target == nullptr || used == 0 || used != word.size() - eq - 1) {
      throw OptInputError(fmt::format(
          "--robust-gap: expected NAME=VALUE with NAME one of {}, got '{}'",
          names, word));
    }
    *target = value;
  }
  try {
    gap->Validate();
  } catch (const std::invalid_argument& e) {
    throw OptInputError(std::string("--robust-gap: ") + e.what());
  }
}

OptSetup PrepareOpt(const OptCommand& c) {
  OptSetup setup;
  Problem& problem = setup.problem;
  try {
    if (c.out_dir.empty()) {
      throw OptInputError("--out: expected the run's output folder");
    }
    AlgorithmSettings a = c.algorithm;
    a.include_start = !c.no_start;
    a.Validate();
    if (c.generations < 1) throw OptInputError("--generations must be >= 1");
    if (c.generations < a.islands) {
      throw OptInputError(fmt::format(
          "--generations {} with --islands {}: each island needs a "
          "generation at least (--generations counts every island's)",
          c.generations, a.islands));
    }
    if (c.jump_to > c.generations) {
      throw OptInputError("--jump-to " + std::to_string(c.jump_to) +
                          ": beyond the run's --generations " +
                          std::to_string(c.generations) +
                          " (raise --generations to run further)");
    }
    if (c.farm) {
      // Farm settings a run would otherwise take in silence.
      if (c.workers != OptCommand().workers) {
        throw OptInputError("--workers " + c.workers +
                            ": the farm's workers are mrsim-worker processes; "
                            "give --workers without --farm, or start "
                            "mrsim-worker --threads K on each host");
      }
      if (c.chunk_size < 0 || c.chunk_size > 60000) {
        throw OptInputError(
            "--chunk-size: expected 0 (one Ethernet frame) or "
            "1..60000, got " +
            std::to_string(c.chunk_size));
      }
      if (!(c.worker_timeout > 0) || !std::isfinite(c.worker_timeout)) {
        throw OptInputError(
            "--worker-timeout: expected a number of seconds > "
            "0, got " +
            fmt::format("{}", c.worker_timeout));
      }
      if (!(c.job_timeout >= 0) || !std::isfinite(c.job_timeout)) {
        throw OptInputError(
            "--job-timeout: expected seconds >= 0 (0: "
            "automatic), got " +
            fmt::format("{}", c.job_timeout));
      }
      for (const std::string& o : c.slurm_options) NormaliseSbatchOption(o);
      if (!c.slurm_options.empty() && c.slurm == 0) {
        throw OptInputError("--slurm-opt needs --slurm N");
      }
      if (c.hub_port > 0) {
        FarmClusterOptions cluster;
        cluster.hub_port = c.hub_port;
        cluster.lcm_url = c.lcm_url;
        WorkerLcmUrl(cluster);
      }
    } else {
      if (c.slurm > 0 || c.hub_port > 0 || !c.slurm_options.empty()) {
        throw OptInputError(
            "--slurm, --slurm-opt and --hub start farm workers: add --farm");
      }
      if (c.workers.rfind("local:", 0) != 0) {
        throw OptInputError("--workers: expected local:K, got '" + c.workers +
                            "' (use --farm for worker processes)");
      }
      std::size_t used = 0;
      const std::string k = c.workers.substr(6);
      int threads = -1;
      try {
        threads = std::stoi(k, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != k.size() || threads < 0) {
        throw OptInputError(
            "--workers: K in local:K must be a whole number "
            ">= 0, got '" +
            k + "'");
      }
      setup.threads = threads > 0
                          ? threads
                          : static_cast<int>(std::max(
                                1u, std::thread::hardware_concurrency()));
    }
    EpisodeSettings e = c.episode;
    SetGapValues(c.robust_gap, &e.robust.gap);
    std::optional<Gait> task_gait;
    if (!c.task.empty()) {
      Task task = MakeTask(c.task);
      problem.scenario = std::move(task.scenario);
      e.fitness.distance_mode = ParseDistanceMode(task.distance_mode);
      task_gait = task.gait;
    } else {
      problem.scenario = ReadScenarioFile(c.scenario_path);
    }
    EmbedAssets(problem.scenario);
    bool cpg_genes = false;
    try {
      if (c.controller == "lua") {  // the design's own script
        if (c.lua_source.empty()) {
          throw OptInputError(
              "--controller lua: the scenario has no Lua script in its <run> "
              "element; give lua:FILE");
        }
        problem.controller.kind = ControllerSpec::Kind::kLua;
        problem.controller.source = c.lua_source;
        problem.controller.name = "the design's script";
      } else {
        problem.controller = ParseControllerFlag(c.controller, &cpg_genes);
      }
    } catch (const std::invalid_argument& err) {
      throw OptInputError(err.what());
    }
    if (!problem.controller.is_gait() && !c.genes.empty()) {
      throw OptInputError("--genes " + c.genes +
                          " are the gait's genes; with --controller " +
                          c.controller +
                          " the controller brings its own (add body genes "
                          "with --genome FILE)");
    }
    std::optional<GenomeSpec> user;
    if (!c.genome_path.empty()) {
      user = ReadGenomeFile(c.genome_path);
    } else if (!c.genes.empty()) {
      user = BuiltInGenome(c.genes);
    } else if (!c.genome_text.empty()) {
      user = ReadGenomeString(c.genome_text, c.genome_source);
    } else if (cpg_genes) {
      user = BuiltInGenome("cpg");
    }
    if (problem.controller.kind == ControllerSpec::Kind::kMlp) {
      // The network's size follows the robot's joint count.
      ResolveMlpJoints(&problem.controller, problem.scenario,
                       user ? user->robot : "");
    }
    problem.genome =
        ControllerGenome(problem.controller, user ? &*user : nullptr);
    // A task starts from its own gait unless --gait names one.
    e.base_gait = c.gait_spec.empty() && task_gait ? *task_gait
                  : c.gait_spec.empty()            ? ResolveGait("forward")
                                                   : ResolveGait(c.gait_spec);
    // The perturbed worlds follow from the run's seed: same seed, same
    // worlds, on every worker (the payload carries it).
    e.robust.gap.seed = c.algorithm.seed;
    // Individuals the body genes grow into the scene run too (RunEpisode).
    e.allow_overlap = c.allow_overlap;
    e.Validate();
    problem.episode = e;
    GenomeRobotIndex(problem.scenario, problem.genome);
    ValidateGaitParameters(
        GaitOfGenome(problem, problem.genome.StartGenome()).parameters);
    // The body the genes start from must be clear of the scene, as
    // mrsim-sim requires of a file; individuals that grow into it later
    // are failed ones (RunEpisode). A scenario file is checked whatever
    // the genes (its overlap would score the physics' explosion as
    // distance); a task's world is built to its own rules (the pole task
    // squeezes the pole on purpose).
    const bool checked =
        !c.allow_overlap &&
        (c.task.empty() || GenomeBuildsTheBody(problem.genome));
    if (checked) {
      RefuseOverlaps(ApplyBodyGenes(problem.scenario, problem.genome,
                                    problem.genome.StartGenome()));
    }
  } catch (const OptInputError&) {
    throw;
  } catch (const OverlapError& err) {
    throw OptInputError(
        std::string("the body the genome starts from: ") + err.what() +
        "\nparts must not overlap at the start: move them apart in the "
        "scenario, or change the body genes' start values, or allow overlap "
        "(--allow-overlap) to optimise it anyway");
  } catch (const std::exception& err) {
    throw OptInputError(err.what());
  }
  // Local and farm runs evaluate the same decoded payload.
  setup.payload = EncodeProblem(problem);
  problem = DecodeProblem(setup.payload,
                          c.task.empty() ? c.scenario_path : "task " + c.task);
  setup.hash = HashHex(Fnv1a64(setup.payload));
  std::error_code ec;
  fs::create_directories(c.out_dir, ec);
  if (ec) {
    throw OptInputError("--out " + c.out_dir + ": cannot create (" +
                        ec.message() + ")");
  }
  try {
    setup.lock = std::make_shared<FileLock>(c.out_dir + "/.mrsim-opt.lock");
  } catch (const FileLockBusy& e) {
    throw OptInputError(fmt::format(
        "--out {}: another mrsim-opt (process {}) is writing this run "
        "folder; wait for it to end, stop it, or pass another --out",
        c.out_dir, e.holder() > 0 ? std::to_string(e.holder()) : "unknown"));
  } catch (const std::runtime_error& e) {
    throw OptInputError("--out " + c.out_dir + ": " + e.what());
  }
  return setup;
}

std::unique_ptr<FarmCluster> StartOptCluster(
    const OptCommand& c, std::function<void(const std::string&)> log) {
  if (c.slurm == 0 && c.hub_port == 0) return nullptr;
  FarmClusterOptions o;
  o.hub_port = c.hub_port;
  o.slurm_tasks = c.slurm;
  o.slurm_options = c.slurm_options;
  o.lcm_url = c.lcm_url;
  o.prefix = c.prefix;
  o.key_file = c.auth.key_file;
  o.out_dir = fs::absolute(c.out_dir).string();
  o.worker_program = FindSibling("mrsim-worker");
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  o.host = host;
  try {
    return std::make_unique<FarmCluster>(
        o, std::make_unique<ProcessSlurmRunner>(), std::move(log));
  } catch (const std::exception& e) {
    throw OptInputError(e.what());
  }
}

std::unique_ptr<BatchEvaluator> MakeOptEvaluator(
    const OptCommand& c, const OptSetup& setup, std::function<bool()> stop,
    std::function<void(const std::string&)> log, FarmCluster* cluster) {
  if (!c.farm) {
    const Problem& problem = setup.problem;
    // The threads share one pool of simulations, as long as the evaluator.
    auto physics = std::make_shared<EpisodePhysicsPool>();
    // Episodes poll the stop too: Ctrl-C does not wait for a long one.
    return std::make_unique<LocalEvaluator>(
        [&problem, stop, physics](const Genome& g) {
          return RunEpisode(problem, g, stop, physics.get());
        },
        setup.threads, stop);
  }
  FarmSettings settings;
  settings.prefix = c.prefix;
  settings.auth = c.auth.Load();
  settings.allow_mixed_builds = c.allow_mixed_builds;
  settings.verify = c.verify;
  settings.job_timeout = c.job_timeout;
  settings.worker_timeout = c.worker_timeout;
  settings.chunk_size = c.chunk_size;
  settings.stop = std::move(stop);
  settings.log = log;
  // The farm opens its own connection so it can re-connect (tcpq hub).
  auto farm = std::make_unique<FarmEvaluator>(
      cluster != nullptr ? cluster->master_url() : c.lcm_url, setup.payload,
      MakeRunId(), settings);
  if (log) {
    log(fmt::format("farm on {}_* (payload {}, {} bytes)", c.prefix, setup.hash,
                    setup.payload.size()));
  }
  return farm;
}

std::string FormatDuration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long long t = std::llround(s);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, t / 60 % 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

namespace {

// " (in 2 islands taking turns, 3 generations each)"; "" for one island.
std::string IslandsText(int generations, int islands) {
  if (islands <= 1) return "";
  const int least = generations / islands;
  const int most = least + (generations % islands ? 1 : 0);
  return fmt::format(
      " (in {} islands taking turns, {} generation{} each)", islands,
      least == most ? std::to_string(least) : fmt::format("{}-{}", least, most),
      most == 1 ? "" : "s");
}

}  // namespace

std::string FormatFailedReasons(
    const std::vector<std::pair<std::string, int>>& reasons) {
  constexpr size_t kShown = 2;
  auto said = [](const std::string& reason) {
    return reason.empty() ? std::string("no reason given") : reason;
  };
  if (reasons.empty() || (reasons.size() == 1 && reasons[0].first.empty())) {
    return "";
  }
  if (reasons.size() == 1) return said(reasons[0].first);
  std::string text;
  int others = 0;
  for (size_t i = 0; i < reasons.size(); ++i) {
    if (i < kShown) {
      text += fmt::format("{}{} {}", i == 0 ? "" : "; ", reasons[i].second,
                          said(reasons[i].first));
    } else {
      others += reasons[i].second;
    }
  }
  if (reasons.size() > kShown) {
    text += fmt::format("; {} for {} other reason{}", others,
                        reasons.size() - kShown,
                        reasons.size() - kShown == 1 ? "" : "s");
  }
  return text;
}

std::string FormatProgress(const GenerationReport& r) {
  const std::string why = FormatFailedReasons(r.failed_reasons);
  return fmt::format(
      "generation {} of {}{}: best {:.6g} mean {:.6g} best-so-far {:.6g}{} | "
      "{} | workers {} | ETA {}",
      r.generation, r.generations,
      r.island >= 0 ? fmt::format(" (island {})", r.island) : "", r.best,
      r.mean, r.best_so_far,
      r.failed > 0 ? fmt::format(" failed {}{}", r.failed,
                                 why.empty() ? "" : " (" + why + ")")
                   : "",
      r.replayed ? std::string("from checkpoint")
                 : fmt::format("{:.2f} evals/s", r.evals_per_second),
      r.workers, FormatDuration(r.eta_seconds));
}

OptOutcome RunOpt(const OptCommand& c, const OptSetup& setup,
                  BatchEvaluator& evaluator, std::FILE* out, std::FILE* err,
                  FarmCluster* cluster,
                  const std::function<void(const opt_progress_t&)>& publish) {
  AlgorithmSettings a = c.algorithm;
  OptProgressReporter reporter(MakeRunId(), c.out_dir, ToString(a.algorithm));
  auto report_end = [&](int8_t state, const std::string& error) {
    if (publish) publish(reporter.End(state, WallMicros(), error));
  };
  a.include_start = !c.no_start;
  OptimizationRunOptions options;
  options.generations = c.generations;
  options.stop_after = c.jump_to;
  options.out_dir = c.out_dir;
  options.fingerprint = setup.hash;
  const EpisodeSettings& e = setup.problem.episode;
  options.described = fmt::format(
      "episode={}\ncontrol_period={}\ngait={}\ndistance_mode={}\n"
      "w_distance={}\nw_speed={}\nw_energy={}\nw_drift={}\nw_fall={}\n",
      e.duration, e.control_period, e.base_gait.name,
      ToString(e.fitness.distance_mode), e.fitness.w_distance,
      e.fitness.w_speed, e.fitness.w_energy, e.fitness.w_drift,
      e.fitness.w_fall);
  if (e.robust.episodes > 0) {
    options.described += fmt::format("robust={}\nrobust_mode={}\n",
                                     e.robust.episodes, e.robust.mode);
  }
  // A resume with or without --allow-overlap names it as what changed.
  options.described +=
      fmt::format("allow_overlap={}\n", e.allow_overlap ? 1 : 0);
  const ControllerSpec& controller = setup.problem.controller;
  if (!controller.is_gait()) {
    // A resumed run names the script that differs, not only the hash.
    options.described +=
        fmt::format("controller={}:{}\nscript_hash={}\n",
                    ControllerSpec::Kinds().Name(controller.kind),
                    controller.name, HashHex(Fnv1a64(controller.source)));
    options.error_column = true;
  }
  // Every generation's failed individuals by reason, for the summary.
  std::vector<std::pair<std::string, int>> failed_reasons;
  int failed = 0;
  long long individuals = 0;
  options.progress = [&](const GenerationReport& r) {
    failed += r.failed;
    individuals = r.evaluations;
    for (const auto& [reason, count] : r.failed_reasons) {
      auto it = std::find_if(
          failed_reasons.begin(), failed_reasons.end(),
          [&reason = reason](const auto& f) { return f.first == reason; });
      if (it == failed_reasons.end()) {
        failed_reasons.emplace_back(reason, count);
      } else {
        it->second += count;
      }
    }
    if (publish) publish(reporter.Generation(r, WallMicros()));
    if (c.quiet) return;
    fmt::print(out, "{}{}\n", FormatProgress(r),
               cluster != nullptr ? cluster->ProgressNote() : "");
    std::fflush(out);
  };
  if (setup.lock && setup.lock->stale_holder() > 0) {
    fmt::print(err,
               "mrsim-opt: took over the lock of {} from process {}, which "
               "ended without releasing it\n",
               c.out_dir, setup.lock->stale_holder());
  }
  if (!c.quiet) {
    // Said at once: the first progress line comes only after a generation.
    fmt::print(err,
               "mrsim-opt: {}, {} generation{} of {}{}, {} s episodes, {}; "
               "writing {}\n",
               ToString(a.algorithm), c.generations,
               c.generations == 1 ? "" : "s", a.population,
               IslandsText(c.generations, a.islands),
               setup.problem.episode.duration,
               c.farm ? "on the farm"
                      : fmt::format("{} thread{}", setup.threads,
                                    setup.threads == 1 ? "" : "s"),
               c.out_dir);
    std::fflush(err);
  }
  OptOutcome outcome;
  try {
    outcome.result =
        RunOptimization(setup.problem.genome, a, evaluator, options);
  } catch (const CheckpointError& e) {
    report_end(opt_progress_t::FAILED, e.what());
    throw OptInputError(e.what());
  } catch (const OptimizationInterrupted& stopped) {
    report_end(opt_progress_t::STOPPED, "");
    const RunResult& partial = stopped.partial();
    if (partial.generations_done > 0 && partial.wrote_files) {
      // What the completed generations found, to take away now; the run
      // itself continues from the checkpoint.
      outcome.result = partial;
      outcome.best_dir = c.out_dir;
      outcome.launch = c.out_dir + "/replay.launch";
      const std::string file =
          WriteBestFiles(c, setup.problem, partial, c.out_dir, outcome.launch);
      fmt::print(err,
                 "mrsim-opt: stopped after generation {} of {}; best so far "
                 "{} (generation {}) written to {}/{}, "
                 "best_scenario.xml, best_genome.xml, replay.launch; run the "
                 "same command to continue\n",
                 partial.generations_done, c.generations,
                 partial.best_result.fitness, partial.best_generation + 1,
                 c.out_dir, file);
    } else if (std::filesystem::exists(c.out_dir + "/checkpoint.txt")) {
      fmt::print(err,
                 "mrsim-opt: stopped; completed generations are in {}/"
                 "checkpoint.txt, run the same command to continue\n",
                 c.out_dir);
    } else {
      fmt::print(err,
                 "mrsim-opt: stopped before the first generation completed; "
                 "nothing to continue from, the same command starts again\n");
    }
    outcome.stopped = true;
    return outcome;
  } catch (const std::exception& e) {
    report_end(opt_progress_t::FAILED, e.what());
    throw;
  }
  report_end(opt_progress_t::FINISHED, "");
  const RunResult& result = outcome.result;
  // A --jump-to into an older part of the run writes the best apart,
  // leaving the run's own files alone.
  outcome.best_dir = c.out_dir;
  if (!result.wrote_files) {
    outcome.best_dir =
        fmt::format("{}/jump-{}", c.out_dir, result.generations_done);
    fs::create_directories(outcome.best_dir);
  }
  outcome.launch = outcome.best_dir + "/replay.launch";
  const std::string best_file = WriteBestFiles(
      c, setup.problem, result, outcome.best_dir, outcome.launch);

  // A network's hundreds of weights are no line to read: they are in
  // best_genome.xml.
  constexpr int kGenesPrinted = 24;
  std::string genes;
  for (int i = 0; i < setup.problem.genome.size() && i < kGenesPrinted; ++i) {
    genes += fmt::format(" {}={}", setup.problem.genome.genes[i].name,
                         result.best[i]);
  }
  if (setup.problem.genome.size() > kGenesPrinted) {
    genes += fmt::format(" ... ({} genes in all, in best_genome.xml)",
                         setup.problem.genome.size());
  }
  const EvalResult& b = result.best_result;
  fmt::print(out,
             "best fitness {} in generation {} of {}{} ("
             "generation {}, index {} in evaluations.csv): distance "
             "{:.4f} m, speed {:.4f} m/s, energy {:.4g} J, drift {:.4f} m, "
             "fell {:.2f}\nbest genome:{}\nwrote {}/{}, "
             "best_scenario.xml, best_genome.xml, replay.launch\n",
             b.fitness, result.best_generation + 1, result.generations_done,
             c.algorithm.islands > 1
                 ? fmt::format(", island {}",
                               result.best_generation % c.algorithm.islands)
                 : "",
             result.best_generation, result.best_index, b.distance, b.speed,
             b.energy, b.drift, b.fell, genes, outcome.best_dir, best_file);
  if (failed > 0) {
    std::stable_sort(
        failed_reasons.begin(), failed_reasons.end(),
        [](const auto& x, const auto& y) { return x.second > y.second; });
    const std::string why = FormatFailedReasons(failed_reasons);
    const bool overlap = std::any_of(
        failed_reasons.begin(), failed_reasons.end(), [](const auto& f) {
          return f.first.rfind("overlap at the start", 0) == 0;
        });
    fmt::print(out, "failed individuals: {} of {}{}{}\n", failed, individuals,
               why.empty() ? "" : " (" + why + ")",
               overlap ? "; allow overlap (--allow-overlap) to run the bodies "
                         "the genes grow into the scene anyway"
                       : "");
  }
  if (const auto* farm = dynamic_cast<const FarmEvaluator*>(&evaluator)) {
    const FarmCounters& n = farm->counters();
    fmt::print(out,
               "farm: {} jobs sent, {} re-sent, {} results accepted, {} "
               "ignored (second copies included), {} malformed messages, "
               "{} jobs asked again of their worker\n",
               n.jobs_sent, n.jobs_resent, n.results_accepted,
               n.results_ignored, n.messages_malformed, n.jobs_poked);
    if (c.verify > 0 || n.heartbeats_refused > 0) {
      fmt::print(out,
                 "farm checks: {} results verified by a second worker, {} "
                 "worker(s) dropped, {} results re-done, {} heartbeats "
                 "refused (another build, or dropped)\n",
                 n.results_verified, n.workers_dropped, n.results_redone,
                 n.heartbeats_refused);
    }
  }
  std::fflush(out);
  return outcome;
}

std::function<void(const opt_progress_t&)> MakeProgressPublisher(
    const OptCommand& c, std::unique_ptr<lcm::LCM>* connection) {
  if (c.progress_url.empty()) return {};
  *connection = std::make_unique<lcm::LCM>(c.progress_url);
  if (!(*connection)->good()) {
    throw OptInputError("--progress-url: " + CannotOpenLcm(c.progress_url));
  }
  lcm::LCM* lcm = connection->get();
  const std::string channel = FarmChannels(c.prefix).progress;
  return [lcm, channel](const opt_progress_t& m) { lcm->publish(channel, &m); };
}

std::string FindLauncher() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path root = self.parent_path().parent_path().parent_path();
    for (const fs::path& p :
         {self.parent_path() / "mrsim", root / "bin" / "mrsim",
          root / "launcher" / "mrsim"}) {
      if (fs::exists(p)) return p.string();
    }
  }
  return "mrsim";
}

std::function<void(const std::string&)> OptLog(const OptCommand& command) {
  const bool quiet = command.quiet;
  return [quiet](const std::string& text) {
    if (!quiet) fmt::print(stderr, "mrsim-opt: {}\n", text);
  };
}

int ExecReplay(const OptOutcome& outcome) {
  const std::string launcher = FindLauncher();
  fmt::print("replaying: {} launch {}\n", launcher, outcome.launch);
  std::fflush(stdout);
  execlp(launcher.c_str(), launcher.c_str(), "launch", outcome.launch.c_str(),
         static_cast<char*>(nullptr));
  fmt::print(stderr, "mrsim-opt: cannot start '{}'; run: mrsim launch {}\n",
             launcher, outcome.launch);
  return 1;
}

std::string FindSibling(const std::string& program) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && fs::exists(self.parent_path() / program)) {
    return (self.parent_path() / program).string();
  }
  return program;
}

}  // namespace mrsim
