// mrsim.Optimizer: mrsim-opt's algorithms (optimizer/search/algorithm.h) in
// ask/tell form for an objective written in Python. The algorithms are
// built as RunOptimization builds them (one per island, seeded by
// IslandSeed), so the same seed, settings and fitness values give the
// generations mrsim-opt gives.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "optimizer/search/algorithm.h"
#include "optimizer/search/algorithm_registry.h"
#include "optimizer/episode/episode.h"
#include "optimizer/search/eval_result.h"
#include "optimizer/search/genome.h"
#include "python/src/bindings.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

double Number(const py::handle& value, const std::string& where) {
  if (py::isinstance<py::bool_>(value) || py::isinstance<py::str>(value)) {
    throw py::type_error(where + ": expected a number, got " +
                         std::string(py::repr(value)));
  }
  try {
    return value.cast<double>();
  } catch (const py::cast_error&) {
    throw py::type_error(where + ": expected a number, got " +
                         std::string(py::repr(value)));
  }
}

bool Flag(const py::handle& value, const std::string& where) {
  if (!py::isinstance<py::bool_>(value)) {
    throw py::type_error(where + ": expected True or False, got " +
                         std::string(py::repr(value)));
  }
  return value.cast<bool>();
}

// Unless given, a gene starts in the middle of its range (a whole number
// for an integer gene).
void DefaultStart(GeneSpec* gene) {
  gene->start = 0.5 * (gene->lower + gene->upper);
  if (gene->integer) gene->start = std::floor(gene->start);
  if (gene->integer && gene->start < gene->lower) gene->start += 1;
}

// (lower, upper) or (lower, upper, start) from limits[first].
void ReadLimits(const py::sequence& limits, size_t first, GeneSpec* gene,
                const std::string& where) {
  const size_t n = limits.size() - first;
  if (n != 2 && n != 3) {
    throw py::value_error(where +
                          ": expected (lower, upper) or (lower, upper, "
                          "start), got " +
                          std::to_string(n) + " values");
  }
  gene->lower = Number(limits[first], where + " lower");
  gene->upper = Number(limits[first + 1], where + " upper");
  if (n == 3) {
    gene->start = Number(limits[first + 2], where + " start");
  } else {
    DefaultStart(gene);
  }
}

// {"lower": .., "upper": .., "start": .., "integer": .., "enabled": ..}.
void ReadFields(const py::dict& fields, GeneSpec* gene,
                const std::string& where) {
  bool have_lower = false, have_upper = false, have_start = false;
  for (const auto& [key, value] : fields) {
    const std::string k = py::str(key);
    if (k == "lower") {
      gene->lower = Number(value, where + " lower");
      have_lower = true;
    } else if (k == "upper") {
      gene->upper = Number(value, where + " upper");
      have_upper = true;
    } else if (k == "start") {
      gene->start = Number(value, where + " start");
      have_start = true;
    } else if (k == "integer") {
      gene->integer = Flag(value, where + " integer");
    } else if (k == "enabled") {
      gene->enabled = Flag(value, where + " enabled");
    } else if (k != "name") {
      throw py::value_error(
          where + ": unknown field '" + k +
          "' (expected lower, upper, start, integer, enabled)");
    }
  }
  if (!have_lower || !have_upper) {
    throw py::value_error(where + ": needs lower and upper");
  }
  if (!have_start) DefaultStart(gene);
}

GeneSpec ReadGene(const std::string& name, const py::handle& value,
                  const std::string& where) {
  GeneSpec gene;
  gene.name = name;
  gene.integer = IsIntegerGene(name);
  if (py::isinstance<py::dict>(value)) {
    ReadFields(value.cast<py::dict>(), &gene, where);
  } else if (py::isinstance<py::sequence>(value) &&
             !py::isinstance<py::str>(value)) {
    ReadLimits(value.cast<py::sequence>(), 0, &gene, where);
  } else {
    throw py::type_error(
        where +
        ": expected (lower, upper[, start]) or a dict of lower, "
        "upper, start, integer, enabled; got " +
        std::string(py::repr(value)));
  }
  return gene;
}

// genes: a built-in genome's name, a genome file, {name: limits} or
// [(name, lower, upper[, start]) or {"name": .., "lower": .., ...}].
GenomeSpec ReadGenes(const py::object& genes) {
  GenomeSpec spec;
  if (py::isinstance<py::str>(genes)) {
    const std::string text = genes.cast<std::string>();
    if (text == "sine" || text == "cpg") return BuiltInGenome(text);
    return ReadGenomeFile(text, /*allow_any_name=*/true);
  }
  if (py::isinstance<py::dict>(genes)) {
    for (const auto& [key, value] : genes.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key)) {
        throw py::type_error("genes: a gene name must be a str, got " +
                             std::string(py::repr(key)));
      }
      const std::string name = key.cast<std::string>();
      spec.genes.push_back(ReadGene(name, value, "gene '" + name + "'"));
    }
  } else if (py::isinstance<py::sequence>(genes)) {
    const py::sequence items = genes.cast<py::sequence>();
    for (size_t i = 0; i < items.size(); ++i) {
      const py::object item = items[i];
      const std::string at = "genes[" + std::to_string(i) + "]";
      if (py::isinstance<py::dict>(item)) {
        const py::dict fields = item.cast<py::dict>();
        if (!fields.contains("name") ||
            !py::isinstance<py::str>(fields["name"])) {
          throw py::value_error(at + ": needs a 'name' (str)");
        }
        const std::string name = fields["name"].cast<std::string>();
        spec.genes.push_back(ReadGene(name, fields, "gene '" + name + "'"));
        continue;
      }
      if (!py::isinstance<py::sequence>(item) ||
          py::isinstance<py::str>(item) ||
          item.cast<py::sequence>().size() < 1 ||
          !py::isinstance<py::str>(item.cast<py::sequence>()[0])) {
        throw py::type_error(at +
                             ": expected (name, lower, upper[, start]) or a "
                             "dict with a name, got " +
                             std::string(py::repr(item)));
      }
      const py::sequence tuple = item.cast<py::sequence>();
      GeneSpec gene;
      gene.name = tuple[0].cast<std::string>();
      gene.integer = IsIntegerGene(gene.name);
      ReadLimits(tuple, 1, &gene, "gene '" + gene.name + "'");
      spec.genes.push_back(gene);
    }
  } else {
    throw py::type_error(
        "genes: expected a list of (name, lower, upper[, start]), a dict "
        "{name: (lower, upper[, start])}, 'sine', 'cpg' or a genome file; "
        "got " +
        std::string(py::repr(genes)));
  }
  spec.Validate("genes");
  return spec;
}

// The registry's settings (AlgorithmSetting::flag, '-' as '_') of the
// chosen algorithm, plus the GA's selection.
void ApplySettings(const py::kwargs& kwargs, AlgorithmSettings* settings) {
  const AlgorithmInfo& info = AlgorithmInfoOf(settings->algorithm);
  std::string known;
  for (const AlgorithmSetting& s : info.settings) {
    std::string name = s.flag;
    for (char& c : name) c = c == '-' ? '_' : c;
    known += (known.empty() ? "" : ", ") + name;
  }
  if (settings->algorithm == AlgorithmKind::kGa) known += ", selection";
  if (known.empty()) known = "none";
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    std::string flag = name;
    for (char& c : flag) c = c == '_' ? '-' : c;
    const AlgorithmSetting* setting = nullptr;
    for (const AlgorithmSetting& s : info.settings) {
      if (flag == s.flag) setting = &s;
    }
    if (settings->algorithm == AlgorithmKind::kGa && name == "selection") {
      settings->selection =
          ParseSelectionMethod(py::str(value).cast<std::string>());
      continue;
    }
    if (!setting) {
      const AlgorithmSetting* other = FindAlgorithmSetting(flag);
      throw py::type_error("Optimizer: '" + name + "' is not a setting of " +
                           info.name +
                           (other ? " (it is another algorithm's)" : "") +
                           "; its settings: " + known);
    }
    setting->Set(settings, Number(value, name));
  }
}

// One optimisation in ask/tell form. Calls from several threads are
// refused rather than raced (the GIL is released inside Ask and Tell).
class PyOptimizer {
 public:
  PyOptimizer(GenomeSpec spec, AlgorithmSettings settings)
      : spec_(std::move(spec)), settings_(settings) {
    settings_.Validate();
    for (int i = 0; i < settings_.islands; ++i) {
      AlgorithmSettings island = settings_;
      island.seed = IslandSeed(settings_.seed, i);
      algorithms_.push_back(MakeAlgorithm(spec_, island));
    }
  }

  py::array_t<double> Ask() {
    std::unique_lock<std::mutex> lock(busy_, std::try_to_lock);
    if (!lock) throw std::runtime_error("Optimizer: in use by another thread");
    if (!asked_) {
      Algorithm& algorithm = Island();
      std::vector<Genome> batch;
      {
        py::gil_scoped_release release;
        batch = algorithm.Ask();
      }
      batch_ = std::move(batch);
      asked_ = true;
    }
    const py::ssize_t rows = static_cast<py::ssize_t>(batch_.size());
    const py::ssize_t cols = spec_.size();
    py::array_t<double> out({rows, cols});
    auto view = out.mutable_unchecked<2>();
    for (py::ssize_t r = 0; r < rows; ++r) {
      for (py::ssize_t c = 0; c < cols; ++c) view(r, c) = batch_[r][c];
    }
    return out;
  }

  void Tell(const py::object& fitness) {
    std::unique_lock<std::mutex> lock(busy_, std::try_to_lock);
    if (!lock) throw std::runtime_error("Optimizer: in use by another thread");
    if (!asked_) {
      throw py::value_error(
          "Optimizer.tell: nothing asked; call ask() for the generation "
          "first");
    }
    if (py::isinstance<py::str>(fitness) ||
        !py::isinstance<py::sequence>(fitness)) {
      throw py::type_error(
          "Optimizer.tell: expected a sequence of fitness values (list or "
          "numpy array), got " +
          std::string(py::repr(fitness)));
    }
    const py::sequence values = fitness.cast<py::sequence>();
    if (values.size() != batch_.size()) {
      throw py::value_error("Optimizer.tell: " + std::to_string(values.size()) +
                            " fitness values for the " +
                            std::to_string(batch_.size()) +
                            " individuals ask() gave (one per row, in order)");
    }
    std::vector<EvalResult> results(batch_.size());
    for (size_t i = 0; i < results.size(); ++i) {
      const py::object v = values[i];
      const std::string where =
          "Optimizer.tell: fitness[" + std::to_string(i) + "]";
      EvalResult& r = results[i];
      double f = NAN;
      if (py::isinstance<py::dict>(v)) {
        // run_episode's and run_task's result as it is.
        const py::dict d = v.cast<py::dict>();
        if (!d.contains("fitness")) {
          throw py::value_error(where + ": a dict needs a 'fitness'");
        }
        f = Number(d["fitness"], where + "['fitness']");
        if (d.contains("failed") && Flag(d["failed"], where + "['failed']")) {
          f = NAN;
        }
      } else if (!v.is_none()) {
        f = Number(v, where);
      }
      // A failed evaluation scores as mrsim-opt scores a failed episode.
      if (std::isfinite(f)) {
        r.fitness = f;
      } else {
        r.fitness = kFailedFitness;
        r.failed = true;
      }
    }
    Algorithm& algorithm = Island();
    {
      py::gil_scoped_release release;
      algorithm.Tell(results);
    }
    // The best so far as RunOptimization keeps it: the first of the
    // highest fitness.
    for (size_t i = 0; i < results.size(); ++i) {
      if (best_generation_ < 0 || results[i].fitness > best_result_.fitness) {
        best_ = batch_[i];
        best_result_ = results[i];
        best_generation_ = generation_;
        best_index_ = static_cast<int>(i);
      }
    }
    ++generation_;
    asked_ = false;
  }

  py::object Best() const {
    if (best_generation_ < 0) return py::none();
    py::dict d;
    d["genes"] = py::array_t<double>(static_cast<py::ssize_t>(best_.size()),
                                     best_.data());
    d["fitness"] = best_result_.fitness;
    d["failed"] = best_result_.failed;
    d["generation"] = best_generation_;
    d["index"] = best_index_;
    return d;
  }

  const GenomeSpec& spec() const { return spec_; }
  const AlgorithmSettings& settings() const { return settings_; }
  int generation() const { return generation_; }

 private:
  // Generation k is island k % islands's, as in mrsim-opt.
  Algorithm& Island() {
    return *algorithms_[static_cast<size_t>(generation_ % settings_.islands)];
  }

  GenomeSpec spec_;
  AlgorithmSettings settings_;
  std::vector<std::unique_ptr<Algorithm>> algorithms_;
  std::mutex busy_;
  std::vector<Genome> batch_;
  bool asked_ = false;
  int generation_ = 0;
  Genome best_;
  EvalResult best_result_;
  int best_generation_ = -1;
  int best_index_ = -1;
};

}  // namespace

void BindOptimizer(py::module_& m) {
  py::class_<PyOptimizer> c(m, "Optimizer", R"doc(
mrsim-opt's search algorithms in ask/tell form, for an objective written in
Python (any simulation, any controller):

    opt = mrsim.Optimizer("cmaes", genes=[("x", -5, 5, 4), ("y", -5, 5)],
                          seed=1, population=8)
    for _ in range(50):
        genomes = opt.ask()                  # one row per individual
        opt.tell([-(g ** 2).sum() for g in genomes])
    opt.best["genes"], opt.best["fitness"]

Higher fitness is better (mrsim-opt maximises); return -cost to minimise
a cost. The algorithms are mrsim-opt's C++ ones with its random streams:
the same seed, settings and fitness values give the very generations
mrsim-opt gives. The GIL is released while the algorithm works.)doc");
  c.def(py::init([](const std::string& algorithm, const py::object& genes,
                    std::uint64_t seed, int population, bool include_start,
                    int islands, const py::kwargs& kwargs) {
          AlgorithmSettings settings;
          settings.algorithm = ParseAlgorithm(algorithm);
          settings.seed = seed;
          settings.population = population;
          settings.include_start = include_start;
          settings.islands = islands;
          ApplySettings(kwargs, &settings);
          GenomeSpec spec = ReadGenes(genes);
          return std::make_unique<PyOptimizer>(std::move(spec), settings);
        }),
        py::arg("algorithm") = "cmaes", py::kw_only(), py::arg("genes"),
        py::arg("seed") = 1, py::arg("population") = 16,
        py::arg("include_start") = true, py::arg("islands") = 1, R"doc(
algorithm: ga, sa, pso, cmaes or random (mrsim-opt --algorithm).
genes: the genome, in order: a list of (name, lower, upper) or
(name, lower, upper, start) tuples, a dict {name: (lower, upper[, start])}, or
per gene a dict of lower, upper, start, integer (whole numbers) and enabled
(False: fixed at start); start defaults to the middle of the range. Or
'sine' / 'cpg' (mrsim-opt --genes) or a genome file's path.
seed, population, include_start (generation 0 holds the start genome;
mrsim-opt --no-start-genome is False), islands: as mrsim-opt's flags.
Further keywords are the algorithm's settings, mrsim-opt's flags with
'_' for '-': cmaes_sigma; tournament_size, truncation, crossover_rate,
mutation_rate, mutation_scale, elites, selection ('tournament' or
'truncation'); sa_t0, sa_cooling, sa_rate, sa_step; pso_inertia, pso_c1,
pso_c2, pso_vmax. GenomeError or ValueError names the bad gene, field or
setting; TypeError names a keyword the algorithm does not take.)doc");
  c.def("ask", &PyOptimizer::Ask, R"doc(
The next generation to evaluate: a float64 array, one row per individual
and one column per gene (gene_names order), each value within its gene's
limits. Asking again before tell() gives the same generation.)doc");
  c.def("tell", &PyOptimizer::Tell, py::arg("fitness"), R"doc(
The fitness of each row of the last ask(), in the same order (a list or a
numpy array; higher is better), or per row the dict run_episode and
run_task return. None, NaN, an infinity or failed=True marks a failed
evaluation: it scores as a failed mrsim-opt episode does (-1e6, failed).
ValueError for another count or nothing asked.)doc");
  c.def_property_readonly("best", &PyOptimizer::Best, R"doc(
The best individual told so far (the first of the highest fitness), as
mrsim-opt reports it: {'genes': array, 'fitness': float, 'failed': bool,
'generation': int, 'index': int (its row in that generation)}; None before
the first tell().)doc");
  c.def_property_readonly("generation", &PyOptimizer::generation,
                          "Generations told so far (the next ask()'s "
                          "generation, as in mrsim-opt's CSV files).");
  c.def_property_readonly(
      "gene_names",
      [](const PyOptimizer& o) {
        std::vector<std::string> names;
        for (const GeneSpec& g : o.spec().genes) names.push_back(g.name);
        return names;
      },
      "The genes' names: the columns of ask()'s rows.");
  c.def_property_readonly(
      "genes",
      [](const PyOptimizer& o) {
        py::list genes;
        for (const GeneSpec& g : o.spec().genes) {
          py::dict d;
          d["name"] = g.name;
          d["lower"] = g.lower;
          d["upper"] = g.upper;
          d["start"] = g.start;
          d["integer"] = g.integer;
          d["enabled"] = g.enabled;
          genes.append(d);
        }
        return genes;
      },
      "Each gene as a dict of name, lower, upper, start, integer, enabled.");
  c.def_property_readonly(
      "algorithm",
      [](const PyOptimizer& o) {
        return std::string(ToString(o.settings().algorithm));
      },
      "The algorithm's word (cmaes, ga, ...).");
  c.def_property_readonly(
      "population",
      [](const PyOptimizer& o) { return o.settings().population; },
      "Individuals per generation.");
  c.def_property_readonly(
      "settings", [](const PyOptimizer& o) { return o.settings().Describe(); },
      "Every setting as mrsim-opt records it ('key=value' lines).");
  c.def("__repr__", [](const PyOptimizer& o) {
    return "<mrsim.Optimizer " + std::string(ToString(o.settings().algorithm)) +
           ", " + std::to_string(o.spec().size()) + " genes, population " +
           std::to_string(o.settings().population) + ", generation " +
           std::to_string(o.generation()) + ">";
  });
}

}  // namespace mrsim::python
