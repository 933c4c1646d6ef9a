#include "gait_controller/gait_file.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/input_limits.h"
#include "common/xml_error_text.h"
#include "gait_controller/gait_presets.h"
#include "sim_core/scenario/xml_writer.h"

namespace mrsim {

namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLDocument;

// More joints than any chain has (MakeChain's kMaxModules).
constexpr size_t kMaxJointOverrides = 1000;
using tinyxml2::XMLElement;

[[noreturn]] void Fail(const std::string& source, int line,
                       const std::string& what) {
  throw GaitFileError(fmt::format("{}:{}: {}", source, line, what));
}

double ParseNumber(const std::string& source, int line,
                   const std::string& field, const char* text) {
  const std::string s = text ? text : "";
  const char* begin = s.c_str();
  while (*begin == ' ' || *begin == '\t' || *begin == '\n') ++begin;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(begin, &end);
  while (end && (*end == ' ' || *end == '\t' || *end == '\n')) ++end;
  if (end == begin || (end && *end != '\0') || errno == ERANGE ||
      !std::isfinite(v)) {
    Fail(source, line,
         fmt::format("{}: expected a number, got '{}'", field, s));
  }
  return v;
}

std::optional<double> OptionalAttribute(const std::string& source,
                                        const XMLElement* e, const char* name) {
  const char* text = e->Attribute(name);
  if (!text) return std::nullopt;
  return ParseNumber(source, e->GetLineNum(),
                     fmt::format("gait/joint/@{}", name), text);
}

}  // namespace

Gait ReadGaitString(const std::string& xml, const std::string& source) {
  try {
    CheckXmlLimits(xml, source);
  } catch (const InputLimitError& e) {
    throw GaitFileError(e.what());
  }
  XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    Fail(source, doc.ErrorLineNum(),
         fmt::format("malformed XML: {}", XmlErrorText(doc)));
  }
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "gait") {
    Fail(source, root ? root->GetLineNum() : 1,
         fmt::format("expected the root element <gait>, got <{}>",
                     root ? root->Name() : ""));
  }
  Gait gait;
  gait.name = fs::path(source).stem().string();
  if (const char* name = root->Attribute("name")) gait.name = name;
  if (gait.name.empty()) Fail(source, root->GetLineNum(), "gait/@name: empty");
  if (const char* kind = root->Attribute("kind")) {
    const auto k = ParseGaitKind(kind);
    if (!k) {
      Fail(source, root->GetLineNum(),
           fmt::format("gait/@kind: expected linear, sidewind or roll, got "
                       "'{}'",
                       kind));
    }
    gait.kind = *k;
  }

  const auto& names = GaitParameterNames();
  std::array<std::optional<double>, GaitParameters::kVectorSize> seven;
  std::array<int, GaitParameters::kVectorSize> lines{};
  int lag_line = 0;
  int taper_line = 0;
  std::vector<int> override_lines;
  for (const XMLElement* e = root->FirstChildElement(); e;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    const int line = e->GetLineNum();
    if (tag == "joint") {
      if (gait.parameters.overrides.size() >= kMaxJointOverrides) {
        Fail(source, line,
             fmt::format("gait/joint: more than {} joint overrides",
                         kMaxJointOverrides));
      }
      JointOverride o;
      const char* index = e->Attribute("index");
      if (!index) Fail(source, line, "gait/joint: missing attribute index");
      const double i = ParseNumber(source, line, "gait/joint/@index", index);
      if (i != std::floor(i) || i < 0 || i > 1e6) {
        Fail(source, line,
             fmt::format("gait/joint/@index: expected a joint number >= 0, "
                         "got '{}'",
                         index));
      }
      o.joint = static_cast<int>(i);
      o.amplitude = OptionalAttribute(source, e, "amplitude");
      o.phase = OptionalAttribute(source, e, "phase");
      o.offset = OptionalAttribute(source, e, "offset");
      gait.parameters.overrides.push_back(o);
      override_lines.push_back(line);
      continue;
    }
    if (tag == "cpg") {
      if (gait.cpg) Fail(source, line, "gait/cpg: repeated");
      CpgParameters c;
      const std::pair<const char*, double*> fields[] = {
          {"coupling", &c.coupling},
          {"convergence", &c.convergence},
          {"feedback", &c.feedback_gain},
          {"force_scale", &c.force_scale},
          {"distance_range", &c.distance_range}};
      for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a;
           a = a->Next()) {
        bool known = false;
        for (const auto& [name, value] : fields) {
          if (std::string(a->Name()) == name) {
            *value = ParseNumber(source, line,
                                 fmt::format("gait/cpg/@{}", name), a->Value());
            known = true;
          }
        }
        if (!known) {
          Fail(source, line,
               fmt::format("gait/cpg/@{}: unknown attribute (expected "
                           "coupling, convergence, feedback, force_scale or "
                           "distance_range)",
                           a->Name()));
        }
      }
      try {
        ValidateCpgParameters(c);
      } catch (const std::invalid_argument& err) {
        Fail(source, line, err.what());
      }
      gait.cpg = c;
      continue;
    }
    if (tag == "amplitude_taper") {
      gait.parameters.amplitude_taper =
          ParseNumber(source, line, "gait/" + tag, e->GetText());
      taper_line = line;
      continue;
    }
    if (tag == "pitch_yaw_lag") {
      gait.parameters.pitch_yaw_lag =
          ParseNumber(source, line, "gait/" + tag, e->GetText());
      lag_line = line;
      continue;
    }
    bool known = false;
    for (size_t n = 0; n < names.size(); ++n) {
      if (tag == names[n]) {
        if (seven[n]) Fail(source, line, fmt::format("gait/{}: repeated", tag));
        seven[n] = ParseNumber(source, line, "gait/" + tag, e->GetText());
        lines[n] = line;
        known = true;
      }
    }
    if (!known) {
      Fail(source, line,
           fmt::format("gait/{}: unknown element (expected A_pitch, A_yaw, "
                       "phi_pitch, phi_yaw, T, offset_pitch, offset_yaw, "
                       "pitch_yaw_lag, amplitude_taper, joint or cpg)",
                       tag));
    }
  }
  std::vector<double> values;
  for (size_t n = 0; n < names.size(); ++n) {
    if (!seven[n]) {
      Fail(source, root->GetLineNum(),
           fmt::format("gait/{}: missing (a gait file gives all seven "
                       "parameters)",
                       names[n]));
    }
    values.push_back(*seven[n]);
  }
  gait.parameters = gait.parameters.WithVector(values);
  try {
    ValidateGaitParameters(gait.parameters);
  } catch (const std::invalid_argument& e) {
    // "gait parameter T: ..." or "gait parameter joint override 2 ...":
    // the line of the element that holds the value.
    const std::string what = e.what();
    const std::string kPrefix = "gait parameter ";
    int line = root->GetLineNum();
    if (what.rfind(kPrefix, 0) == 0) {
      const std::string rest = what.substr(kPrefix.size());
      for (size_t n = 0; n < names.size(); ++n) {
        if (rest.rfind(std::string(names[n]) + ":", 0) == 0) line = lines[n];
      }
      if (rest.rfind("pitch_yaw_lag:", 0) == 0 && lag_line > 0) line = lag_line;
      if (rest.rfind("amplitude_taper:", 0) == 0 && taper_line > 0) {
        line = taper_line;
      }
      int k = -1;
      if (std::sscanf(rest.c_str(), "joint override %d", &k) == 1 && k >= 0 &&
          k < static_cast<int>(override_lines.size())) {
        line = override_lines[k];
      }
    }
    Fail(source, line, what);
  }
  return gait;
}

Gait ReadGaitFile(const std::string& path) {
  std::optional<std::string> text;
  try {
    text = ReadFileAtMost(path);
  } catch (const InputLimitError& e) {
    throw GaitFileError(e.what());
  }
  if (!text)
    throw GaitFileError(fmt::format("{}: cannot open gait file", path));
  return ReadGaitString(*text, path);
}

std::string WriteGaitString(const Gait& gait) {
  const GaitParameters& p = gait.parameters;
  const auto& names = GaitParameterNames();
  const auto values = p.ToArray();
  XmlWriter w;
  w.Open("gait");
  w.Attribute("name", gait.name);
  w.Attribute("kind", ToString(gait.kind));
  for (size_t n = 0; n < names.size(); ++n) w.Number(names[n], values[n]);
  w.Number("pitch_yaw_lag", p.pitch_yaw_lag);
  if (p.amplitude_taper != 0) w.Number("amplitude_taper", p.amplitude_taper);
  if (gait.cpg) {
    w.Open("cpg");
    w.Attribute("coupling", gait.cpg->coupling);
    w.Attribute("convergence", gait.cpg->convergence);
    w.Attribute("feedback", gait.cpg->feedback_gain);
    w.Attribute("force_scale", gait.cpg->force_scale);
    w.Attribute("distance_range", gait.cpg->distance_range);
    w.Close();
  }
  for (const JointOverride& o : p.overrides) {
    w.Open("joint");
    w.Attribute("index", std::to_string(o.joint));
    if (o.amplitude) w.Attribute("amplitude", *o.amplitude);
    if (o.phase) w.Attribute("phase", *o.phase);
    if (o.offset) w.Attribute("offset", *o.offset);
    w.Close();
  }
  w.Close();
  return w.str();
}

void WriteGaitFile(const Gait& gait, const std::string& path) {
  try {
    WriteFileAtomically(path, WriteGaitString(gait));
  } catch (const std::runtime_error& e) {
    throw GaitFileError(fmt::format("gait file: {}", e.what()));
  }
}

std::vector<std::string> GaitSearchPath() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("MRSIM_GAIT_PATH")) {
    std::stringstream ss(env);
    std::string dir;
    while (std::getline(ss, dir, ':')) {
      if (!dir.empty()) dirs.push_back(dir);
    }
  }
  dirs.push_back("gaits");
  return dirs;
}

Gait ResolveGait(const std::string& spec) {
  if (auto preset = FindGaitPreset(spec)) return *preset;
  std::error_code ec;
  if (fs::is_regular_file(spec, ec)) return ReadGaitFile(spec);
  for (const std::string& dir : GaitSearchPath()) {
    const fs::path candidate = fs::path(dir) / (spec + ".xml");
    if (fs::is_regular_file(candidate, ec)) {
      return ReadGaitFile(candidate.string());
    }
  }
  std::string dirs;
  for (const std::string& d : GaitSearchPath()) {
    dirs += (dirs.empty() ? "" : ", ") + d;
  }
  throw GaitFileError(fmt::format(
      "unknown gait '{}': not a preset ({}), not a gait file, and no {}.xml "
      "in the gait search path ({}; MRSIM_GAIT_PATH adds folders)",
      spec, GaitPresetNames(), spec, dirs));
}

}  // namespace mrsim
