#include "nn_controller/network_file.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <cmath>
#include <optional>

#include "common/atomic_file.h"
#include "common/exact_number.h"
#include "common/input_limits.h"
#include "common/printable.h"
#include "common/xml_error_text.h"

namespace mrsim {
namespace {

using tinyxml2::XMLElement;

// Weights per line in a written file: short lines diff well.
constexpr int kWeightsPerLine = 8;
// Longer than any number written in its shortest form.
constexpr size_t kMaxNumberChars = 64;

[[noreturn]] void Fail(const std::string& source, int line,
                       const std::string& what) {
  throw NetworkFileError(fmt::format("{}:{}: {}", source, line, what));
}

std::string Quoted(std::string_view text) {
  return Printable(text.substr(0, kMaxNumberChars));
}

const char* Required(const std::string& source, const XMLElement* e,
                     const char* name) {
  const char* text = e->Attribute(name);
  if (!text) {
    Fail(source, e->GetLineNum(),
         fmt::format("network/@{}: missing (docs/nn.md)", name));
  }
  return text;
}

double Number(const std::string& source, const XMLElement* e,
              const char* name) {
  const char* text = Required(source, e, name);
  const std::optional<double> v = ParseWholeNumber(text);
  if (!v || !std::isfinite(*v)) {
    Fail(source, e->GetLineNum(),
         fmt::format("network/@{}: expected a finite number, got '{}'", name,
                     Quoted(text)));
  }
  return *v;
}

int Count(const std::string& source, const XMLElement* e, const char* name,
          int lo, long hi) {
  const char* text = Required(source, e, name);
  const std::string s = text;
  const bool digits = !s.empty() && s.size() <= 9 &&
                      s.find_first_not_of("0123456789") == std::string::npos;
  const long v = digits ? std::stol(s) : -1;
  if (v < lo || v > hi) {
    Fail(source, e->GetLineNum(),
         fmt::format("network/@{}: expected a whole number {} to {}, got '{}'",
                     name, lo, hi, Quoted(s)));
  }
  return static_cast<int>(v);
}

bool Flag(const std::string& source, const XMLElement* e, const char* name) {
  const std::string s = Required(source, e, name);
  if (s != "0" && s != "1") {
    Fail(
        source, e->GetLineNum(),
        fmt::format("network/@{}: expected 0 or 1, got '{}'", name, Quoted(s)));
  }
  return s == "1";
}

// The name is the only free text of a network file.
std::string EscapeAttribute(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\n':
        out += "&#10;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

NetworkFile ReadNetworkString(const std::string& xml,
                              const std::string& source) {
  try {
    CheckXmlLimits(xml, source);
  } catch (const InputLimitError& e) {
    throw NetworkFileError(e.what());
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    Fail(source, doc.ErrorLineNum(),
         fmt::format("malformed XML: {}", XmlErrorText(doc)));
  }
  const XMLElement* root = doc.RootElement();
  if (!root || std::string(root->Name()) != "network") {
    Fail(source, root ? root->GetLineNum() : 1,
         fmt::format("expected the root element <network>, got <{}>",
                     root ? Quoted(root->Name()) : ""));
  }
  const int line = root->GetLineNum();
  std::string name = "network";
  if (const char* n = root->Attribute("name")) name = n;
  MlpShape shape;
  shape.joints = Count(source, root, "joints", 1, MlpShape::kMaxJoints);
  shape.sensors = Count(source, root, "sensors", 0, MlpShape::kMaxSensors);
  shape.clock = Flag(source, root, "clock");
  shape.imu = Flag(source, root, "imu");
  const std::string hidden = Required(source, root, "hidden");
  try {
    if (!hidden.empty()) shape.hidden = ParseHiddenLayers(hidden, "hidden");
  } catch (const std::invalid_argument& e) {
    Fail(source, line, fmt::format("network/@{}", e.what()));
  }
  shape.output_range = Number(source, root, "range");
  const double period = Number(source, root, "period");
  try {
    shape.Validate();
  } catch (const std::invalid_argument& e) {
    Fail(source, line, fmt::format("network: {}", e.what()));
  }
  const XMLElement* w = root->FirstChildElement("weights");
  if (!w) Fail(source, line, "network/weights: missing");
  if (w->NextSiblingElement("weights")) {
    Fail(source, w->NextSiblingElement("weights")->GetLineNum(),
         "network/weights: given twice");
  }
  const long expected = shape.WeightCount();
  const int count = Count(source, w, "count", 0, MlpShape::kMaxWeights);
  if (count != expected) {
    Fail(source, w->GetLineNum(),
         fmt::format("network/weights/@count: this shape has {} weights, "
                     "the file says {}",
                     expected, count));
  }
  // The count is bounded and checked against the shape: now allocate.
  std::vector<double> weights;
  weights.reserve(static_cast<size_t>(expected));
  const char* text = w->GetText();
  const std::string_view all = text ? text : "";
  int text_line = w->GetLineNum();
  size_t i = 0;
  for (;;) {
    while (i < all.size() && std::isspace(static_cast<unsigned char>(all[i]))) {
      if (all[i] == '\n') ++text_line;
      ++i;
    }
    if (i >= all.size()) break;
    size_t end = i;
    while (end < all.size() &&
           !std::isspace(static_cast<unsigned char>(all[end]))) {
      ++end;
    }
    const std::string_view token = all.substr(i, end - i);
    const std::string field =
        fmt::format("network/weights[{}]", weights.size());
    if (static_cast<long>(weights.size()) >= expected) {
      Fail(source, text_line,
           fmt::format("{}: more weights than count=\"{}\"", field, expected));
    }
    const std::optional<double> v = token.size() > kMaxNumberChars
                                        ? std::nullopt
                                        : ParseWholeNumber(std::string(token));
    if (!v || !std::isfinite(*v)) {
      Fail(source, text_line,
           fmt::format("{}: expected a finite number, got '{}'", field,
                       Quoted(token)));
    }
    weights.push_back(*v);
    i = end;
  }
  if (static_cast<long>(weights.size()) != expected) {
    Fail(source, text_line,
         fmt::format("network/weights: {} numbers, count=\"{}\" says {}",
                     weights.size(), expected, expected));
  }
  try {
    return NetworkFile{name, MlpNetwork(shape, std::move(weights), period)};
  } catch (const std::invalid_argument& e) {
    Fail(source, line, fmt::format("network: {}", e.what()));
  }
}

NetworkFile ReadNetworkFile(const std::string& path) {
  std::optional<std::string> text;
  try {
    text = ReadFileAtMost(path);
  } catch (const InputLimitError& e) {
    throw NetworkFileError(e.what());
  }
  if (!text) {
    throw NetworkFileError(fmt::format("{}: cannot open network file", path));
  }
  return ReadNetworkString(*text, path);
}

std::string WriteNetworkString(const MlpNetwork& network,
                               const std::string& name) {
  const MlpShape& s = network.shape();
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out +=
      "<!-- mrsim neural-network controller (docs/nn.md); run it with "
      "mrsim-nn --net FILE -->\n";
  out += fmt::format(
      "<network name=\"{}\" joints=\"{}\" hidden=\"{}\" clock=\"{}\" "
      "imu=\"{}\" sensors=\"{}\" "
      "range=\"{}\" period=\"{}\">\n",
      EscapeAttribute(name), s.joints, HiddenLayersText(s.hidden),
      s.clock ? 1 : 0, s.imu ? 1 : 0, s.sensors, s.output_range,
      network.period());
  const std::vector<double>& w = network.weights();
  out += fmt::format("  <weights count=\"{}\">", w.size());
  for (size_t i = 0; i < w.size(); ++i) {
    out += i % kWeightsPerLine == 0 ? "\n    " : " ";
    out += fmt::format("{}", w[i]);
  }
  out += "\n  </weights>\n</network>\n";
  return out;
}

void WriteNetworkFile(const MlpNetwork& network, const std::string& path,
                      const std::string& name) {
  try {
    WriteFileAtomically(path, WriteNetworkString(network, name));
  } catch (const std::runtime_error& e) {
    throw NetworkFileError(fmt::format("network file: {}", e.what()));
  }
}

}  // namespace mrsim
