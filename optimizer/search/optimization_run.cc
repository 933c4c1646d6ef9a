#include "optimizer/search/optimization_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/exact_number.h"
#include "common/hash.h"

namespace mrsim {
namespace {

constexpr const char* kCheckpointMagic = "mrsim-opt-checkpoint 1";

struct FileCloser {
  void operator()(FILE* f) const {
    if (f) std::fclose(f);
  }
};
using FilePtr = std::unique_ptr<FILE, FileCloser>;

struct RecordedGeneration {
  std::string genomes_hash;
  std::vector<EvalResult> results;
};

std::string HashGenomes(const std::vector<Genome>& genomes) {
  std::uint64_t h = Fnv1a64("", 0);
  for (const Genome& g : genomes) {
    h = Fnv1a64(g.data(), g.size() * sizeof(double), h);
  }
  return HashHex(h);
}

double ParseDouble(const std::string& token, const std::string& where) {
  const std::optional<double> parsed = ParseWholeNumber(token);
  if (!parsed) {
    throw CheckpointError(where + ": expected a number, got '" + token + "'");
  }
  return *parsed;
}

// "population=8 (this run: 6), seed=1 (this run: 2)": the settings lines
// recorded in a checkpoint that differ from this run's; empty when none
// differ or none were recorded (an older checkpoint).
std::string SettingsDiff(const std::vector<std::string>& recorded,
                         const std::string& now) {
  std::map<std::string, std::string> mine;
  // Settings written only when not their default: absent means the default.
  const std::map<std::string, std::string> unwritten = {
      {"islands", std::to_string(AlgorithmSettings().islands)}};
  std::istringstream lines(now);
  for (std::string l; std::getline(lines, l);) {
    const size_t eq = l.find('=');
    if (eq != std::string::npos) mine[l.substr(0, eq)] = l.substr(eq + 1);
  }
  for (const auto& [key, value] : unwritten) mine.emplace(key, value);
  std::map<std::string, std::string> theirs = unwritten;
  for (const std::string& l : recorded) {
    const size_t eq = l.find('=');
    if (eq != std::string::npos) theirs[l.substr(0, eq)] = l.substr(eq + 1);
  }
  if (recorded.empty()) theirs.clear();  // an older checkpoint: no settings
  std::string diff;
  for (const auto& [key, value] : theirs) {
    const auto it = mine.find(key);
    const std::string here = it == mine.end() ? "unset" : it->second;
    if (here != value) {
      diff += fmt::format("{}{}={} (this run: {})", diff.empty() ? "" : ", ",
                          key, value, here);
    }
  }
  return diff;
}

std::vector<RecordedGeneration> ReadCheckpoint(const std::string& path,
                                               const std::string& fingerprint,
                                               const std::string& settings) {
  std::ifstream in(path);
  std::vector<RecordedGeneration> gens;
  if (!in) return gens;
  std::string line;
  int line_no = 0;
  auto where = [&]() { return fmt::format("{}:{}", path, line_no); };
  if (!std::getline(in, line) || line != kCheckpointMagic) {
    ++line_no;
    throw CheckpointError(where() + ": not an mrsim-opt checkpoint");
  }
  ++line_no;
  bool ended = false;
  std::vector<std::string> recorded_settings;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "setting") {
      std::string value;
      words >> value;
      recorded_settings.push_back(value);
    } else if (key == "fingerprint") {
      std::string value;
      words >> value;
      if (value != fingerprint) {
        const std::string diff = SettingsDiff(recorded_settings, settings);
        throw CheckpointError(fmt::format(
            "{}: the checkpoint was made with {} (fingerprint {}, this run "
            "{}); use the same, another --out directory, or remove it",
            path,
            diff.empty() ? "another scenario, genome or episode settings"
                         : "other settings: " + diff,
            value, fingerprint));
      }
    } else if (key == "gen") {
      int index = -1;
      size_t count = 0;
      RecordedGeneration g;
      words >> index >> count >> g.genomes_hash;
      if (index != static_cast<int>(gens.size()) || g.genomes_hash.empty()) {
        throw CheckpointError(where() + ": generations out of order");
      }
      for (size_t i = 0; i < count; ++i) {
        if (!std::getline(in, line)) {
          throw CheckpointError(where() + ": truncated");
        }
        ++line_no;
        std::istringstream r(line);
        std::string tag, t[7];
        r >> tag >> t[0] >> t[1] >> t[2] >> t[3] >> t[4] >> t[5] >> t[6];
        if (tag != "r" || t[6].empty()) {
          throw CheckpointError(where() + ": expected a result line");
        }
        EvalResult e;
        e.fitness = ParseDouble(t[0], where());
        e.distance = ParseDouble(t[1], where());
        e.speed = ParseDouble(t[2], where());
        e.energy = ParseDouble(t[3], where());
        e.drift = ParseDouble(t[4], where());
        e.fell = ParseDouble(t[5], where());
        e.failed = t[6] == "1";
        // A failed evaluation's message, when it has one: the rest.
        std::string message;
        std::getline(r, message);
        if (message.size() > 1 && message[0] == ' ')
          e.error = message.substr(1);
        g.results.push_back(e);
      }
      gens.push_back(std::move(g));
    } else if (key == "end") {
      ended = true;
    } else if (!key.empty()) {
      throw CheckpointError(where() + ": unexpected '" + key + "'");
    }
  }
  if (!ended) throw CheckpointError(path + ": truncated (no end line)");
  return gens;
}

// A message on one line (the checkpoint's records are lines).
std::string OneLine(std::string text) {
  for (char& ch : text) {
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  return text;
}

// A CSV field: quoted, its quotes doubled.
std::string CsvField(const std::string& text) {
  std::string out = "\"";
  for (char ch : OneLine(text)) {
    if (ch == '"') out += '"';
    out += ch;
  }
  return out + "\"";
}

void WriteCheckpoint(const std::string& path, const std::string& fingerprint,
                     const std::string& settings,
                     const std::vector<RecordedGeneration>& gens) {
  std::string text = kCheckpointMagic + std::string("\n");
  // Each setting in words, so a refusal can say which one changed.
  std::istringstream lines(settings);
  for (std::string l; std::getline(lines, l);) {
    if (!l.empty() && l.find(' ') == std::string::npos) {
      text += "setting " + l + "\n";
    }
  }
  text += fmt::format("fingerprint {}\n", fingerprint);
  for (size_t k = 0; k < gens.size(); ++k) {
    text += fmt::format("gen {} {} {}\n", k, gens[k].results.size(),
                        gens[k].genomes_hash);
    for (const EvalResult& e : gens[k].results) {
      text += fmt::format("r {} {} {} {} {} {} {}{}\n", ExactNumber(e.fitness),
                          ExactNumber(e.distance), ExactNumber(e.speed),
                          ExactNumber(e.energy), ExactNumber(e.drift),
                          ExactNumber(e.fell), e.failed ? 1 : 0,
                          e.error.empty() ? "" : " " + OneLine(e.error));
    }
  }
  text += "end\n";
  WriteFileAtomically(path, text);
}

std::vector<std::pair<std::string, int>> CountFailedReasons(
    const std::vector<EvalResult>& results) {
  std::vector<std::pair<std::string, int>> reasons;
  for (const EvalResult& e : results) {
    if (!e.failed) continue;
    auto it = std::find_if(reasons.begin(), reasons.end(),
                           [&](const auto& r) { return r.first == e.error; });
    if (it == reasons.end()) {
      reasons.emplace_back(e.error, 1);
    } else {
      ++it->second;
    }
  }
  std::stable_sort(
      reasons.begin(), reasons.end(),
      [](const auto& a, const auto& b) { return a.second > b.second; });
  return reasons;
}

FilePtr OpenCsv(const std::string& path) {
  FilePtr f(std::fopen(path.c_str(), "w"));
  if (!f) throw std::runtime_error(path + ": cannot write");
  return f;
}

}  // namespace

RunResult RunOptimization(const GenomeSpec& spec,
                          const AlgorithmSettings& settings,
                          BatchEvaluator& evaluator,
                          const OptimizationRunOptions& options) {
  using Clock = std::chrono::steady_clock;
  if (options.stop_after == 0) {
    // Nothing run has no best to write.
    throw std::invalid_argument(
        "stop after generation 0: generations are counted from 1");
  }
  settings.Validate();
  const int islands = settings.islands;
  if (options.generations < islands) {
    throw std::invalid_argument(fmt::format(
        "{} generations for {} islands: each island needs one at least "
        "(generations count every island's)",
        options.generations, islands));
  }
  std::vector<std::unique_ptr<Algorithm>> algorithms;
  for (int i = 0; i < islands; ++i) {
    AlgorithmSettings island = settings;
    island.seed = IslandSeed(settings.seed, i);
    algorithms.push_back(MakeAlgorithm(spec, island));
  }
  const int planned = options.stop_after >= 0
                          ? std::min(options.stop_after, options.generations)
                          : options.generations;
  const std::string fingerprint =
      HashHex(Fnv1a64(WriteGenomeString(spec) + "\n" + settings.Describe() +
                      "\n" + options.fingerprint));

  // Every setting in words, the genes' limits too, for refusals that say
  // what differs.
  std::string described = settings.Describe();
  for (const GeneSpec& g : spec.genes) {
    described += fmt::format("gene.{}={}:{}:{}:{}\n", g.name, g.lower, g.upper,
                             g.start, g.enabled ? "on" : "off");
  }
  described += options.described;
  const bool use_files = !options.out_dir.empty();
  const std::string checkpoint_path = options.out_dir + "/checkpoint.txt";
  std::vector<RecordedGeneration> recorded;
  if (use_files) {
    recorded = ReadCheckpoint(checkpoint_path, fingerprint, described);
  }

  RunResult result;
  result.wrote_files =
      use_files && static_cast<int>(recorded.size()) <= planned;
  FilePtr gens_csv, evals_csv;
  if (result.wrote_files) {
    gens_csv = OpenCsv(options.out_dir + "/generations.csv");
    evals_csv = OpenCsv(options.out_dir + "/evaluations.csv");
    std::string genes;
    for (const GeneSpec& g : spec.genes) genes += "," + g.name;
    // With islands, each row's island last (after the genes, so readers
    // of one-population files see the same columns).
    const char* island = islands > 1 ? ",island" : "";
    std::fprintf(gens_csv.get(),
                 "generation,best,mean,worst,best_so_far,failed%s%s\n",
                 genes.c_str(), island);
    std::fprintf(evals_csv.get(),
                 "generation,index,fitness,distance,speed,energy,drift,fell,"
                 "failed%s%s%s\n",
                 genes.c_str(), island, options.error_column ? ",error" : "");
  }

  std::map<Genome, EvalResult> cache;  // results are a function of the genome
  // Generations asked but not told yet, oldest first: with islands, the
  // next island's generation is on the evaluator while one is told.
  struct Asked {
    std::vector<Genome> batch;
    std::vector<Genome> todo;  // submitted to the evaluator
    bool replay = false;
  };
  std::deque<Asked> asked;
  std::set<Genome> in_flight;  // submitted, not collected
  auto ask = [&](int gen) {
    Asked a;
    a.batch = algorithms[static_cast<size_t>(gen % islands)]->Ask();
    a.replay = gen < static_cast<int>(recorded.size());
    if (a.replay) {
      if (recorded[gen].genomes_hash != HashGenomes(a.batch) ||
          recorded[gen].results.size() != a.batch.size()) {
        throw CheckpointError(fmt::format(
            "{}: generation {} does not match what this program generates; "
            "use another --out directory",
            checkpoint_path, gen));
      }
    } else {
      for (const Genome& g : a.batch) {
        spec.Check(g);
        if (!cache.count(g) && in_flight.insert(g).second) a.todo.push_back(g);
      }
      if (!a.todo.empty()) evaluator.Submit(a.todo);
    }
    asked.push_back(std::move(a));
  };
  double evaluated_seconds = 0;
  int evaluated_generations = 0;
  long long evaluated_count = 0;
  // The first evaluated generation's (one per island: the next islands'
  // were on their way with it).
  double first_seconds = 0;
  long long first_count = 0;
  auto t0 = Clock::now();  // since the last generation was told
  // A stop inside the evaluator ends the run with what was completed.
  try {
    for (int gen = 0; gen < std::min(islands, planned); ++gen) ask(gen);
    for (int gen = 0; gen < planned; ++gen) {
      Asked a = std::move(asked.front());
      asked.pop_front();
      const std::vector<Genome>& batch = a.batch;
      const bool replay = a.replay;
      std::vector<EvalResult> results;
      if (replay) {
        results = recorded[gen].results;
        for (size_t i = 0; i < batch.size(); ++i) cache[batch[i]] = results[i];
      } else {
        if (!a.todo.empty()) {
          const std::vector<EvalResult> fresh = evaluator.Collect();
          if (fresh.size() != a.todo.size()) {
            throw std::runtime_error("evaluator returned the wrong count");
          }
          for (size_t i = 0; i < a.todo.size(); ++i) {
            cache[a.todo[i]] = fresh[i];
            in_flight.erase(a.todo[i]);
          }
          evaluated_count += static_cast<long long>(a.todo.size());
        }
        // A genome another generation in flight holds was collected with it.
        for (const Genome& g : batch) results.push_back(cache.at(g));
      }
      algorithms[static_cast<size_t>(gen % islands)]->Tell(results);
      // On its way before the files are written.
      if (gen + islands < planned) ask(gen + islands);

      double best = -INFINITY, worst = INFINITY, sum = 0;
      int best_i = 0, failed = 0;
      for (size_t i = 0; i < results.size(); ++i) {
        const double f = results[i].fitness;
        sum += f;
        failed += results[i].failed ? 1 : 0;
        if (f > best) {
          best = f;
          best_i = static_cast<int>(i);
        }
        worst = std::min(worst, f);
        if (result.best_generation < 0 || f > result.best_result.fitness) {
          result.best = batch[i];
          result.best_result = results[i];
          result.best_generation = gen;
          result.best_index = static_cast<int>(i);
        }
      }
      result.evaluations += static_cast<long long>(batch.size());
      result.generations_done = gen + 1;
      if (replay) {
        ++result.generations_replayed;
        t0 = Clock::now();
      } else {
        const auto now = Clock::now();
        const double seconds = std::chrono::duration<double>(now - t0).count();
        t0 = now;
        if (evaluated_generations < islands) {
          first_seconds += seconds;
          first_count = evaluated_count;
        }
        evaluated_seconds += seconds;
        ++evaluated_generations;
        recorded.push_back({HashGenomes(batch), results});
      }
      const double mean = sum / results.size();

      if (result.wrote_files) {
        std::string genes;
        for (double v : batch[best_i]) genes += fmt::format(",{}", v);
        const std::string island =
            islands > 1 ? fmt::format(",{}", gen % islands) : "";
        genes += island;
        std::fprintf(gens_csv.get(), "%s\n",
                     fmt::format("{},{},{},{},{},{}{}", gen, best, mean, worst,
                                 result.best_result.fitness, failed, genes)
                         .c_str());
        for (size_t i = 0; i < results.size(); ++i) {
          const EvalResult& e = results[i];
          std::string line = fmt::format(
              "{},{},{},{},{},{},{},{},{}", gen, i, e.fitness, e.distance,
              e.speed, e.energy, e.drift, e.fell, e.failed ? 1 : 0);
          for (double v : batch[i]) line += fmt::format(",{}", v);
          line += island;
          if (options.error_column) line += "," + CsvField(e.error);
          std::fprintf(evals_csv.get(), "%s\n", line.c_str());
        }
        std::fflush(gens_csv.get());
        std::fflush(evals_csv.get());
        if (!replay) {
          WriteCheckpoint(checkpoint_path, fingerprint, described, recorded);
        }
      }

      if (options.progress) {
        GenerationReport report;
        report.generation = gen + 1;
        report.generations = planned;
        report.island = islands > 1 ? gen % islands : -1;
        report.best = best;
        report.mean = mean;
        report.best_so_far = result.best_result.fitness;
        report.failed = failed;
        report.failed_reasons = CountFailedReasons(results);
        report.evaluations = result.evaluations;
        // Past the first generation (of each island), the pace leaves out
        // its start-up.
        const bool steady = evaluated_generations > islands;
        const double seconds =
            steady ? evaluated_seconds - first_seconds : evaluated_seconds;
        const double count = static_cast<double>(
            steady ? evaluated_count - first_count : evaluated_count);
        const int generations =
            steady ? evaluated_generations - islands : evaluated_generations;
        report.evals_per_second = seconds > 0 ? count / seconds : 0.0;
        report.workers = evaluator.workers_alive();
        report.eta_seconds = generations > 0
                                 ? seconds / generations * (planned - gen - 1)
                             : gen + 1 == planned ? 0.0
                                                  : -1.0;
        report.replayed = replay;
        options.progress(report);
      }
    }
  } catch (const EvaluationInterrupted&) {
    throw OptimizationInterrupted(result);
  }
  return result;
}

}  // namespace mrsim
