// mrsim-opt: optimises a gait (and body) for a scenario, generation by
// generation, on local threads or a farm of mrsim-worker processes over
// LCM; checkpoints every generation and continues when run again
// (docs/optimizer.md).
#include <fmt/format.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "gait_controller/gait_file.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "optimizer/body_genes.h"
#include "optimizer/episode.h"
#include "optimizer/farm/farm_channels.h"
#include "optimizer/farm/farm_evaluator.h"
#include "optimizer/hash.h"
#include "optimizer/local_evaluator.h"
#include "optimizer/optimization_run.h"
#include "optimizer/problem_codec.h"
#include "sim_core/scenario_xml.h"

namespace fs = std::filesystem;

namespace {

// Bad input from the command line or a file: exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string FormatDuration(double s) {
  if (!std::isfinite(s) || s < 0) return "?";
  const long long t = std::llround(s);
  if (t >= 3600) return fmt::format("{}h{:02}m", t / 3600, t / 60 % 60);
  if (t >= 60) return fmt::format("{}m{:02}s", t / 60, t % 60);
  return fmt::format("{}s", t);
}

std::string MakeRunId() {
  std::random_device device;
  const auto now = std::chrono::system_clock::now().time_since_epoch().count();
  return mrsim::HashHex(device() ^ (static_cast<std::uint64_t>(now) << 1) ^
                        (static_cast<std::uint64_t>(getpid()) << 40));
}

// mrsim (the launcher) next to this program, in build/bin, or on PATH.
std::string FindLauncher() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& p :
         {self.parent_path() / "mrsim",
          self.parent_path().parent_path().parent_path() / "bin" / "mrsim",
          self.parent_path().parent_path().parent_path() / "launcher" /
              "mrsim"}) {
      if (fs::exists(p)) return p.string();
    }
  }
  return "mrsim";
}

// The replay talks where the user asked: --lcm-url, else LCM_DEFAULT_URL,
// else the launch file's default.
std::string ReplayLcmUrl(const std::string& lcm_url) {
  if (!lcm_url.empty()) return lcm_url;
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return env != nullptr ? env : "";
}

void WriteReplayLaunch(const std::string& path, const std::string& dir,
                       const std::string& scenario, const std::string& gait,
                       const std::string& robot, double duration,
                       const std::string& lcm_url) {
  std::ofstream out(path);
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
      << "  <process name=\"gait\" program=\"mrsim-gait\" delay=\"0.3\"\n"
      << "           args=\"--robot " << robot << " --scenario " << scenario
      << " --gait " << gait << " --lcm-url ${lcm_url} --name gait\"/>\n"
      << "  <process name=\"sim\" program=\"mrsim-sim\" required=\"true\" "
         "delay=\"1.0\"\n"
      << "           args=\"" << scenario
      << " --lcm-url ${lcm_url} --clock realtime --duration ${duration}\"/>\n"
      << "</launch>\n";
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mrsim-opt: optimise a gait and body for a scenario"};
  std::string scenario_path, genome_path, out_dir, workers = "local:0";
  std::string lcm_url, prefix = mrsim::kDefaultFarmPrefix,
                       gait_spec = "forward";
  bool farm = false, replay = false, no_start = false, quiet = false;
  int generations = 20, jump_to = -1;
  mrsim::AlgorithmSettings a;
  mrsim::EpisodeSettings e;
  mrsim::FarmSettings farm_settings;
  app.add_option("scenario", scenario_path, "Scenario XML file")->required();
  app.add_option("--genome", genome_path, "Genome description file")
      ->required();
  app.add_option("--out", out_dir, "Output directory (checkpoint, CSVs, best)")
      ->required();
  app.add_option("--algorithm", a.algorithm, "ga | sa | pso | random")
      ->capture_default_str();
  app.add_option("--generations", generations, "Generations to run")
      ->capture_default_str();
  app.add_option("--population", a.population,
                 "Individuals (SA: chains, PSO: particles) per generation")
      ->capture_default_str();
  app.add_option("--seed", a.seed, "Seed of the run's random engine")
      ->capture_default_str();
  app.add_flag("--no-start-genome", no_start,
               "Do not put the start genome in generation 0");
  app.add_option("--episode", e.duration, "Episode length (s of sim time)")
      ->capture_default_str();
  app.add_option("--control-period", e.control_period,
                 "Gait control period (s)")
      ->capture_default_str();
  app.add_option("--gait", gait_spec,
                 "Base gait (preset or file) the gait genes modify")
      ->capture_default_str();
  app.add_option("--distance", e.fitness.distance_mode,
                 "forward (+x) | net (any direction)")
      ->capture_default_str();
  app.add_option("--w-distance", e.fitness.w_distance)->capture_default_str();
  app.add_option("--w-speed", e.fitness.w_speed)->capture_default_str();
  app.add_option("--w-energy", e.fitness.w_energy, "Per joule")
      ->capture_default_str();
  app.add_option("--w-drift", e.fitness.w_drift, "Per metre of lateral drift")
      ->capture_default_str();
  app.add_option("--w-fall", e.fitness.w_fall,
                 "Per fraction of the episode upside down")
      ->capture_default_str();
  app.add_option("--selection", a.selection, "GA: tournament | truncation")
      ->capture_default_str();
  app.add_option("--tournament-size", a.tournament_size)->capture_default_str();
  app.add_option("--truncation", a.truncation_fraction,
                 "GA: fraction that may breed")
      ->capture_default_str();
  app.add_option("--crossover-rate", a.crossover_rate)->capture_default_str();
  app.add_option("--mutation-rate", a.mutation_rate)->capture_default_str();
  app.add_option("--mutation-scale", a.mutation_scale,
                 "Std dev as a fraction of the gene's range")
      ->capture_default_str();
  app.add_option("--elites", a.elites)->capture_default_str();
  app.add_option("--sa-t0", a.sa_t0, "SA start temperature (0: automatic)")
      ->capture_default_str();
  app.add_option("--sa-cooling", a.sa_cooling)->capture_default_str();
  app.add_option("--sa-rate", a.sa_rate)->capture_default_str();
  app.add_option("--sa-step", a.sa_step)->capture_default_str();
  app.add_option("--pso-inertia", a.pso_inertia)->capture_default_str();
  app.add_option("--pso-c1", a.pso_c1)->capture_default_str();
  app.add_option("--pso-c2", a.pso_c2)->capture_default_str();
  app.add_option("--pso-vmax", a.pso_vmax)->capture_default_str();
  app.add_option("--workers", workers, "local:K (K threads; 0 = one per core)")
      ->capture_default_str();
  app.add_flag("--farm", farm, "Evaluate on mrsim-worker processes over LCM");
  app.add_option("--lcm-url", lcm_url, "LCM URL for --farm");
  app.add_option("--prefix", prefix, "Farm channel prefix")
      ->capture_default_str();
  app.add_option("--job-timeout", farm_settings.job_timeout,
                 "Farm: re-send a job after this many s (0: automatic)")
      ->capture_default_str();
  app.add_option("--worker-timeout", farm_settings.worker_timeout,
                 "Farm: s without heartbeat before a worker counts as gone")
      ->capture_default_str();
  app.add_option("--chunk-size", farm_settings.chunk_size,
                 "Farm: payload bytes per chunk (1..60000; 0: one packet)")
      ->capture_default_str();
  app.add_option("--jump-to", jump_to,
                 "Stop after generation N (replayed from the checkpoint "
                 "when it has them)");
  app.add_flag("--replay", replay,
               "Afterwards show the best in mrsim-sim + mrsim-gait + "
               "mrsim-view (via mrsim launch)");
  app.add_flag("--quiet", quiet, "Only the final summary");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    const int code = app.exit(err);
    return code == 0 ? 0 : 2;
  }

  try {
    mrsim::InstallStopHandlers();
    mrsim::Problem problem;
    int threads = 0;
    try {
      a.include_start = !no_start;
      a.Validate();
      if (generations < 1) throw InputError("--generations must be >= 1");
      if (!farm) {
        if (workers.rfind("local:", 0) != 0) {
          throw InputError("--workers: expected local:K, got '" + workers +
                           "' (use --farm for worker processes)");
        }
        threads = std::stoi(workers.substr(6));
        if (threads < 0) throw InputError("--workers: K must be >= 0");
        if (threads == 0) {
          threads = std::max(1u, std::thread::hardware_concurrency());
        }
      }
      problem.scenario = mrsim::ReadScenarioFile(scenario_path);
      mrsim::EmbedAssets(problem.scenario);
      problem.genome = mrsim::ReadGenomeFile(genome_path);
      e.base_gait = mrsim::ResolveGait(gait_spec);
      e.Validate();
      problem.episode = e;
      mrsim::GenomeRobotIndex(problem.scenario, problem.genome);
      mrsim::ValidateGaitParameters(
          mrsim::GaitOfGenome(problem, problem.genome.StartGenome())
              .parameters);
    } catch (const std::exception& err) {
      throw InputError(err.what());
    }
    // Local and farm runs evaluate the same decoded payload.
    const std::string payload = mrsim::EncodeProblem(problem);
    problem = mrsim::DecodeProblem(payload, scenario_path);
    const std::string hash = mrsim::HashHex(mrsim::Fnv1a64(payload));
    fs::create_directories(out_dir);

    std::unique_ptr<mrsim::BatchEvaluator> evaluator;
    auto log = [&](const std::string& text) {
      if (!quiet) fmt::print(stderr, "mrsim-opt: {}\n", text);
    };
    if (farm) {
      signal(SIGPIPE, SIG_IGN);  // a tcpq hub that goes away: re-connect
      farm_settings.prefix = prefix;
      farm_settings.stop = [] { return mrsim::StopRequested(); };
      farm_settings.log = log;
      evaluator = std::make_unique<mrsim::FarmEvaluator>(
          lcm_url, payload, MakeRunId(), farm_settings);
      log(fmt::format("farm on {}_* (payload {}, {} bytes)", prefix, hash,
                      payload.size()));
    } else {
      evaluator = std::make_unique<mrsim::LocalEvaluator>(
          [&problem](const mrsim::Genome& g) {
            return mrsim::RunEpisode(problem, g);
          },
          threads, [] { return mrsim::StopRequested(); });
    }

    mrsim::RunOptions options;
    options.generations = generations;
    options.stop_after = jump_to;
    options.out_dir = out_dir;
    options.fingerprint = hash;
    options.progress = [&](const mrsim::GenerationReport& r) {
      if (quiet) return;
      fmt::print(
          "generation {} of {}: best {:.6g} mean {:.6g} best-so-far {:.6g} | "
          "{} | workers {} | ETA {}\n",
          r.generation, r.generations, r.best, r.mean, r.best_so_far,
          r.replayed ? std::string("from checkpoint")
                     : fmt::format("{:.2f} evals/s", r.evals_per_second),
          r.workers, FormatDuration(r.eta_seconds));
      std::fflush(stdout);
    };
    mrsim::RunResult result;
    try {
      result = mrsim::RunOptimization(problem.genome, a, *evaluator, options);
    } catch (const mrsim::CheckpointError& err) {
      throw InputError(err.what());
    } catch (const mrsim::EvaluationInterrupted&) {
      fmt::print(stderr,
                 "mrsim-opt: stopped; completed generations are in {}/"
                 "checkpoint.txt, run the same command to continue\n",
                 out_dir);
      return 0;
    }

    // The best individual's files. A --jump-to into an older part of the
    // run writes them apart, leaving the run's own files alone.
    std::string best_dir = out_dir;
    if (!result.wrote_files) {
      best_dir = fmt::format("{}/jump-{}", out_dir, result.generations_done);
      fs::create_directories(best_dir);
    }
    const mrsim::Gait gait = mrsim::GaitOfGenome(problem, result.best);
    const mrsim::Scenario body =
        mrsim::ApplyBodyGenes(problem.scenario, problem.genome, result.best);
    mrsim::WriteGaitFile(gait, best_dir + "/best_gait.xml");
    mrsim::WriteScenarioFile(body, best_dir + "/best_scenario.xml");
    mrsim::GenomeSpec best_spec = problem.genome;
    for (int i = 0; i < best_spec.size(); ++i) {
      best_spec.genes[i].start = result.best[i];
    }
    {
      std::ofstream out(best_dir + "/best_genome.xml");
      out << mrsim::WriteGenomeString(best_spec);
    }
    const std::string robot =
        body.robots[mrsim::GenomeRobotIndex(body, problem.genome)].name;
    const std::string launch = best_dir + "/replay.launch";
    WriteReplayLaunch(launch, fs::absolute(best_dir).string(),
                      fs::absolute(best_dir + "/best_scenario.xml"),
                      fs::absolute(best_dir + "/best_gait.xml"), robot,
                      e.duration, ReplayLcmUrl(lcm_url));
    std::string genes;
    for (int i = 0; i < best_spec.size(); ++i) {
      genes += fmt::format(" {}={}", best_spec.genes[i].name, result.best[i]);
    }
    const mrsim::EvalResult& b = result.best_result;
    fmt::print(
        "best fitness {} (generation {}, individual {}): distance {:.4f} m, "
        "speed {:.4f} m/s, energy {:.4g} J, drift {:.4f} m, fell {:.2f}\n"
        "best genome:{}\nwrote {}/best_gait.xml, best_scenario.xml, "
        "best_genome.xml, replay.launch\n",
        b.fitness, result.best_generation, result.best_index, b.distance,
        b.speed, b.energy, b.drift, b.fell, genes, best_dir);
    if (auto* f = dynamic_cast<mrsim::FarmEvaluator*>(evaluator.get())) {
      const mrsim::FarmCounters& c = f->counters();
      fmt::print(
          "farm: {} jobs sent, {} re-sent, {} results accepted, {} ignored, "
          "{} malformed messages\n",
          c.jobs_sent, c.jobs_resent, c.results_accepted, c.results_ignored,
          c.messages_malformed);
    }
    std::fflush(stdout);
    if (replay) {
      evaluator.reset();
      const std::string launcher = FindLauncher();
      fmt::print("replaying: {} launch {}\n", launcher, launch);
      std::fflush(stdout);
      execlp(launcher.c_str(), launcher.c_str(), "launch", launch.c_str(),
             static_cast<char*>(nullptr));
      throw std::runtime_error("cannot start '" + launcher +
                               "' (the mrsim launcher); run: mrsim launch " +
                               launch);
    }
    return 0;
  } catch (const InputError& err) {
    fmt::print(stderr, "mrsim-opt: {}\n", err.what());
    return 2;
  } catch (const std::exception& err) {
    fmt::print(stderr, "mrsim-opt: {}\n", err.what());
    return 1;
  }
}
