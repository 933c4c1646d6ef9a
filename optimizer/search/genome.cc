#include "optimizer/search/genome.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "common/input_limits.h"
#include "common/xml_error_text.h"
#include "gait_controller/cpg_parameters.h"
#include "gait_controller/gait_parameters.h"
#include "sim_core/scenario/scenario_schema.h"
#include "sim_core/scenario/xml_writer.h"

namespace mrsim {
namespace {

// Genes in one genome: far more than the gait and body genes there are
// (farm problems may name their own).
constexpr size_t kMaxGenes = 1000;

}  // namespace

bool IsIntegerGene(const std::string& name) {
  return name == "module_count" || name == "sensor_after";
}

int GenomeSpec::Find(const std::string& name) const {
  for (int i = 0; i < size(); ++i) {
    if (genes[i].name == name) return i;
  }
  return -1;
}

Genome GenomeSpec::StartGenome() const {
  Genome g(genes.size());
  for (int i = 0; i < size(); ++i) g[i] = genes[i].start;
  return g;
}

Genome GenomeSpec::RandomGenome(Random& random) const {
  Genome g(genes.size());
  for (int i = 0; i < size(); ++i) {
    const GeneSpec& gene = genes[i];
    if (!gene.enabled) {
      g[i] = gene.start;
    } else if (gene.integer) {
      g[i] = static_cast<double>(
          random.UniformInt(static_cast<long long>(std::ceil(gene.lower)),
                            static_cast<long long>(std::floor(gene.upper))));
    } else {
      g[i] = random.Uniform(gene.lower, gene.upper);
    }
  }
  return g;
}

double GenomeSpec::Legal(int i, double value) const {
  const GeneSpec& gene = genes[i];
  if (!gene.enabled) return gene.start;
  if (!std::isfinite(value)) value = gene.start;
  if (gene.integer) {
    value = std::round(value);
    return std::clamp(value, std::ceil(gene.lower), std::floor(gene.upper));
  }
  return std::clamp(value, gene.lower, gene.upper);
}

void GenomeSpec::Check(const Genome& genome) const {
  if (genome.size() != genes.size()) {
    throw GenomeError(fmt::format("genome has {} values, the spec {} genes",
                                  genome.size(), genes.size()));
  }
  for (int i = 0; i < size(); ++i) {
    if (!std::isfinite(genome[i]) || Legal(i, genome[i]) != genome[i]) {
      throw GenomeError(fmt::format("gene '{}' = {} is outside [{}, {}]",
                                    genes[i].name, genome[i], genes[i].lower,
                                    genes[i].upper));
    }
  }
}

std::optional<GeneRange> GeneRangeOf(const std::string& name) {
  static const std::map<std::string, GeneRange> kRanges = {
      {"A_pitch", {0, kMaxGaitAmplitude, false}},
      {"A_yaw", {0, kMaxGaitAmplitude, false}},
      {"phi_pitch", {-kMaxGaitPhase, kMaxGaitPhase, false}},
      {"phi_yaw", {-kMaxGaitPhase, kMaxGaitPhase, false}},
      {"T", {kMinGaitPeriod, kMaxGaitPeriod, false}},
      {"offset_pitch", {-kMaxGaitOffset, kMaxGaitOffset, false}},
      {"offset_yaw", {-kMaxGaitOffset, kMaxGaitOffset, false}},
      {"cpg_coupling", {0, kMaxCpgCoupling, false}},
      {"cpg_convergence", {kMinCpgConvergence, kMaxCpgConvergence, false}},
      {"cpg_feedback", {-kMaxCpgFeedbackGain, kMaxCpgFeedbackGain, false}},
      // The scenario's physical bounds (scenario_schema.h): a genome must
      // not make a body the validator refuses, or a billion modules.
      {"module_count", {1, kMaxModules, false, kMaxModulesWhy}},
      {"module_mass", {0, kMaxMass, true}},
      {"module_scale", {0, kMaxLength, true}},
      {"joint_kp", {0, kMaxAnyValue, false}},
      {"joint_max_vel", {0, kMaxAnyValue, true}},
      {"sensor_after", {-1, kMaxModules - 1, false, kMaxModulesWhy}}};
  const auto it = kRanges.find(name);
  if (it == kRanges.end()) return std::nullopt;
  return it->second;
}

void GenomeSpec::Validate(const std::string& source) const {
  if (genes.empty()) throw GenomeError(source + ": the genome has no genes");
  std::set<std::string> seen;
  for (const GeneSpec& g : genes) {
    const std::string where = source + ": gene '" + g.name + "'";
    if (g.name.empty()) throw GenomeError(source + ": a gene has no name");
    if (!seen.insert(g.name).second) throw GenomeError(where + " is repeated");
    if (!std::isfinite(g.lower) || !std::isfinite(g.upper) ||
        !std::isfinite(g.start)) {
      throw GenomeError(where + ": lower, upper and start must be finite");
    }
    if (g.lower > g.upper) {
      throw GenomeError(where +
                        fmt::format(": lower {} > upper {}", g.lower, g.upper));
    }
    if (g.enabled && (g.start < g.lower || g.start > g.upper)) {
      throw GenomeError(where + fmt::format(": start {} is outside [{}, {}]",
                                            g.start, g.lower, g.upper));
    }
    // Values the simulator or the gait would refuse, refused here, naming
    // the gene, rather than as failed individuals mid-run.
    if (const std::optional<GeneRange> range = GeneRangeOf(g.name)) {
      const auto outside = [&](double v) {
        return v < range->min || (range->min_exclusive && v == range->min) ||
               v > range->max;
      };
      const std::string can_take = fmt::format(
          "{} {}{}", range->min_exclusive ? ">" : ">=", range->min,
          std::isfinite(range->max) ? fmt::format(" and <= {}", range->max)
                                    : "");
      const std::vector<std::pair<const char*, double>> checked =
          g.enabled
              ? std::vector<std::pair<const char*, double>>{{"lower", g.lower},
                                                            {"upper", g.upper}}
              : std::vector<std::pair<const char*, double>>{{"start", g.start}};
      for (const auto& [what, v] : checked) {
        if (outside(v)) {
          throw GenomeError(
              where + fmt::format(": {} {} is outside what {} can take ({}{})",
                                  what, v, g.name, can_take,
                                  range->why != nullptr && v > range->max
                                      ? std::string("; ") + range->why
                                      : std::string()));
        }
      }
    }
    if (g.integer && (std::ceil(g.lower) > std::floor(g.upper) ||
                      std::round(g.start) != g.start)) {
      throw GenomeError(where +
                        ": an integer gene needs whole start and a whole "
                        "number within its limits");
    }
  }
}

namespace {

double ReadNumber(const tinyxml2::XMLElement* e, const char* attribute,
                  const std::string& where, bool required, double fallback) {
  const char* text = e->Attribute(attribute);
  if (!text) {
    if (required) {
      throw GenomeError(
          fmt::format("{}: missing attribute '{}'", where, attribute));
    }
    return fallback;
  }
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v)) {
    throw GenomeError(
        fmt::format("{}: attribute '{}': expected a number, got "
                    "'{}'",
                    where, attribute, text));
  }
  return v;
}

bool ReadBool(const tinyxml2::XMLElement* e, const char* attribute,
              const std::string& where, bool fallback) {
  const char* text = e->Attribute(attribute);
  if (!text) return fallback;
  const std::string s = text;
  if (s == "true" || s == "1" || s == "on" || s == "yes") return true;
  if (s == "false" || s == "0" || s == "off" || s == "no") return false;
  throw GenomeError(
      fmt::format("{}: attribute '{}': expected true or false, got '{}'", where,
                  attribute, s));
}

}  // namespace

GenomeSpec ForwardGaitGenome() {
  GenomeSpec spec;
  spec.genes = {{"A_pitch", 0, 1.57, 1, true, false},
                {"A_yaw", 0, 1.57, 0, false, false},
                {"phi_pitch", 0, 3.14, 2.5, true, false},
                {"phi_yaw", 0, 3.14, 0, false, false},
                {"T", 1, 6, 4, true, false},
                {"offset_pitch", -0.3, 0.3, 0, true, false},
                {"offset_yaw", -0.3, 0.3, 0, false, false}};
  return spec;
}

GenomeSpec BuiltInGenome(const std::string& name) {
  constexpr double kPi = 3.14159265358979323846;
  GenomeSpec spec;
  spec.genes = {{"A_pitch", 0, 1.5, 0.5, true, false},
                {"A_yaw", 0, 1.5, 0.5, true, false},
                {"phi_pitch", -kPi, kPi, 1.0, true, false},
                {"phi_yaw", -kPi, kPi, 1.0, true, false},
                {"T", 1, 6, 3, true, false},
                {"offset_pitch", -0.3, 0.3, 0, true, false},
                {"offset_yaw", -0.3, 0.3, 0, true, false}};
  if (name == "sine") return spec;
  if (name == "cpg") {
    spec.genes.push_back({"cpg_coupling", 0.5, 20, 4, true, false});
    spec.genes.push_back({"cpg_convergence", 1, 40, 10, true, false});
    return spec;
  }
  throw GenomeError("--genes: expected sine or cpg, got '" + name + "'");
}

GenomeSpec ReadGenomeString(const std::string& xml, const std::string& name,
                            bool allow_any_name) {
  try {
    CheckXmlLimits(xml, name);
  } catch (const InputLimitError& e) {
    throw GenomeError(e.what());
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    throw GenomeError(fmt::format("{}:{}: not well-formed XML: {}", name,
                                  doc.ErrorLineNum(), XmlErrorText(doc)));
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "genome") {
    throw GenomeError(name + ": expected a root element <genome>");
  }
  GenomeSpec spec;
  if (const char* robot = root->Attribute("robot")) spec.robot = robot;
  for (const tinyxml2::XMLElement* e = root->FirstChildElement(); e;
       e = e->NextSiblingElement()) {
    const std::string where = fmt::format("{}:{}", name, e->GetLineNum());
    if (spec.genes.size() >= kMaxGenes) {
      throw GenomeError(
          fmt::format("{}: more than {} genes", where, kMaxGenes));
    }
    if (std::string(e->Name()) != "gene") {
      throw GenomeError(
          fmt::format("{}: unexpected element <{}>, expected "
                      "<gene>",
                      where, e->Name()));
    }
    GeneSpec gene;
    const char* gene_name = e->Attribute("name");
    if (!gene_name || !*gene_name) {
      throw GenomeError(where + ": <gene> needs a name attribute");
    }
    gene.name = gene_name;
    const auto& gait = GaitGeneNames();
    const auto& body = BodyGeneNames();
    const auto& cpg = CpgGeneNames();
    if (!allow_any_name &&
        std::find(gait.begin(), gait.end(), gene.name) == gait.end() &&
        std::find(cpg.begin(), cpg.end(), gene.name) == cpg.end() &&
        std::find(body.begin(), body.end(), gene.name) == body.end()) {
      std::string known;
      for (const auto& n : gait) known += " " + n;
      for (const auto& n : cpg) known += " " + n;
      for (const auto& n : body) known += " " + n;
      throw GenomeError(fmt::format("{}: unknown gene '{}'; known genes:{}",
                                    where, gene.name, known));
    }
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a;
         a = a->Next()) {
      static const std::set<std::string> kAttributes = {
          "name", "lower", "upper", "start", "enabled", "integer"};
      if (!kAttributes.count(a->Name())) {
        throw GenomeError(fmt::format(
            "{}: unknown attribute '{}' (expected name, lower, upper, start, "
            "enabled, integer)",
            where, a->Name()));
      }
    }
    gene.lower = ReadNumber(e, "lower", where, true, 0);
    gene.upper = ReadNumber(e, "upper", where, true, 0);
    gene.start = ReadNumber(e, "start", where, true, 0);
    gene.enabled = ReadBool(e, "enabled", where, true);
    gene.integer = ReadBool(e, "integer", where, IsIntegerGene(gene.name));
    spec.genes.push_back(gene);
    GenomeSpec one;  // so the message names this gene's line
    one.genes = {gene};
    one.Validate(where);
  }
  spec.Validate(name);
  return spec;
}

GenomeSpec ReadGenomeFile(const std::string& path, bool allow_any_name) {
  std::optional<std::string> text;
  try {
    text = ReadFileAtMost(path);
  } catch (const InputLimitError& e) {
    throw GenomeError(e.what());
  }
  if (!text) throw GenomeError(path + ": cannot open the genome file");
  return ReadGenomeString(*text, path, allow_any_name);
}

std::string WriteGenomeString(const GenomeSpec& spec) {
  XmlWriter w;
  w.Open("genome");
  if (!spec.robot.empty()) w.Attribute("robot", spec.robot);
  for (const GeneSpec& g : spec.genes) {
    w.Open("gene");
    w.Attribute("name", g.name);
    w.Attribute("lower", g.lower);
    w.Attribute("upper", g.upper);
    w.Attribute("start", g.start);
    w.Attribute("enabled", g.enabled ? "true" : "false");
    if (g.integer != IsIntegerGene(g.name)) {
      w.Attribute("integer", g.integer ? "true" : "false");
    }
    w.Close();
  }
  w.Close();
  return w.str();
}

}  // namespace mrsim
