#include "launcher/launch_file.h"

#include <tinyxml2.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <regex>
#include <set>

#include "common/input_limits.h"
#include "common/xml_error_text.h"

namespace mrsim {
namespace {

constexpr char kLcmJar[] = "/usr/share/java/lcm.jar";  // Debian liblcm-java

std::string Where(const std::string& path, int line) {
  return path + ":" + std::to_string(line) + ": ";
}

// The longest value a substitution may make: a command line.
constexpr size_t kMaxValueBytes = size_t{64} << 10;
// More processes than one launch can mean.
constexpr size_t kMaxProcesses = 1000;

std::string Substitute(const std::string& text,
                       const std::map<std::string, std::string>& vars,
                       const std::string& where) {
  std::string out;
  size_t i = 0;
  while (i < text.size()) {
    if (text.compare(i, 2, "${") == 0) {
      const size_t end = text.find('}', i + 2);
      if (end == std::string::npos) {
        throw LaunchError(where + "unterminated '${' in '" + text + "'");
      }
      const std::string name = text.substr(i + 2, end - i - 2);
      const auto it = vars.find(name);
      if (it == vars.end()) {
        throw LaunchError(where + "unknown variable ${" + name +
                          "}: declare it with <arg name=\"" + name +
                          "\" .../>");
      }
      out += it->second;
      i = end + 1;
      // Each arg may use the ones before it twice or more: thirty such
      // lines would otherwise make a value of 2^30 copies.
      if (out.size() > kMaxValueBytes) {
        throw LaunchError(where + "'" + text.substr(0, 60) +
                          "' expands to more than " +
                          std::to_string(kMaxValueBytes >> 10) + " KiB");
      }
    } else {
      out += text[i++];
    }
  }
  return out;
}

bool ParseBool(const char* text, bool fallback, const std::string& where,
               const char* attribute) {
  if (text == nullptr) return fallback;
  const std::string s(text);
  if (s == "true" || s == "1") return true;
  if (s == "false" || s == "0") return false;
  throw LaunchError(where + "attribute " + attribute +
                    ": expected true or false, got '" + s + "'");
}

// A misspelled attribute would otherwise be ignored without a word
// (requried="true" left a process optional).
void CheckAttributes(const tinyxml2::XMLElement* e,
                     std::initializer_list<const char*> allowed,
                     const std::string& where) {
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr;
       a = a->Next()) {
    bool known = false;
    std::string list;
    for (const char* name : allowed) {
      known = known || std::string(a->Name()) == name;
      list += (list.empty() ? "" : ", ") + std::string(name);
    }
    if (!known) {
      throw LaunchError(where + "unknown attribute '" + a->Name() + "' on <" +
                        e->Name() + ">: expected " + list);
    }
  }
}

// The longest wait a launch can mean (an hour).
constexpr double kMaxSeconds = 3600;

// A delay or finish attribute: the whole text ("1.0s" and "1,0" are not 1)
// and a wait a launch can mean. Absent: 0.
double ParseSeconds(const char* text, const std::string& where,
                    const std::string& process, const char* attribute) {
  if (text == nullptr) return 0.0;
  char* end = nullptr;
  const double seconds = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(seconds >= 0) || seconds > kMaxSeconds) {
    throw LaunchError(where + "process '" + process + "': attribute " +
                      attribute + ": expected seconds from 0 to " +
                      std::to_string(static_cast<int>(kMaxSeconds)) +
                      ", got '" + text + "'");
  }
  return seconds;
}

// A ready attribute: a regular expression that compiles and is short (a
// launch file is input, and std::regex recurses on long patterns).
std::string ParseReadyLine(const char* text, const std::string& where,
                           const std::string& process) {
  if (text == nullptr) return "";
  constexpr size_t kMaxReadyLength = 200;
  const std::string pattern = text;
  const std::string what =
      where + "process '" + process + "': attribute ready: expected ";
  if (pattern.empty() || pattern.size() > kMaxReadyLength) {
    throw LaunchError(what + "a regular expression of 1 to " +
                      std::to_string(kMaxReadyLength) + " characters, got " +
                      std::to_string(pattern.size()));
  }
  try {
    std::regex{pattern};
  } catch (const std::regex_error& e) {
    throw LaunchError(what + "a regular expression, got '" + pattern + "' (" +
                      e.what() + ")");
  }
  return pattern;
}

// <hub port="7667"/>: LCM's TCP hub, for networks without multicast;
// clients then use tcpq://HOST:PORT as their LCM URL.

ProcessSpec HubProcess(const tinyxml2::XMLElement* e,
                       const std::map<std::string, std::string>& vars,
                       const std::string& where) {
  CheckAttributes(e, {"name", "port", "jar", "enabled"}, where);
  ProcessSpec spec;
  spec.line = e->GetLineNum();
  spec.name = e->Attribute("name") ? e->Attribute("name") : "hub";
  const char* port_text = e->Attribute("port");
  if (port_text == nullptr) {
    throw LaunchError(where + "<hub> needs a port attribute");
  }
  const std::string port = Substitute(port_text, vars, where);
  char* end = nullptr;
  const long value = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || value < 1 || value > 65535) {
    throw LaunchError(where + "<hub> attribute port: expected 1..65535, got '" +
                      port + "'");
  }
  const char* jar = e->Attribute("jar");
  spec.program = "java";
  spec.args = {"-cp", jar ? Substitute(jar, vars, where) : kLcmJar,
               "lcm.lcm.TCPService", port};
  spec.ready_port = static_cast<int>(value);
  spec.stop_last = true;
  spec.enabled =
      ParseBool(e->Attribute("enabled")
                    ? Substitute(e->Attribute("enabled"), vars, where).c_str()
                    : nullptr,
                true, where, "enabled");
  return spec;
}

}  // namespace

std::vector<std::string> SplitArgs(const std::string& text) {
  std::vector<std::string> args;
  std::string current;
  bool in_word = false;
  char quote = 0;
  for (char c : text) {
    if (quote != 0) {
      if (c == quote) {
        quote = 0;
      } else {
        current += c;
      }
    } else if (c == '\'' || c == '"') {
      quote = c;
      in_word = true;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      if (in_word) args.push_back(current);
      current.clear();
      in_word = false;
    } else {
      current += c;
      in_word = true;
    }
  }
  if (quote != 0) throw std::invalid_argument("unterminated quote");
  if (in_word) args.push_back(current);
  return args;
}

LaunchFile ReadLaunchFile(const std::string& path,
                          const std::map<std::string, std::string>& overrides) {
  namespace fs = std::filesystem;
  tinyxml2::XMLDocument doc;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw LaunchError(path + ": is a folder, not a launch file");
  }
  std::optional<std::string> text;
  try {
    text = ReadFileAtMost(path);
    if (text) CheckXmlLimits(*text, path);
  } catch (const InputLimitError& e) {
    throw LaunchError(e.what());
  }
  if (!text) {
    throw LaunchError(path + ": cannot read the launch file: " +
                      (errno == ENOENT ? std::string("no such file")
                                       : std::string(std::strerror(errno))));
  }
  if (doc.Parse(text->data(), text->size()) != tinyxml2::XML_SUCCESS) {
    const int line = doc.ErrorLineNum();
    // No line to point at when the file could not be read at all.
    throw LaunchError((line > 0 ? Where(path, line) : path + ": ") +
                      "cannot read the launch file: " + XmlErrorText(doc));
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  if (root == nullptr || std::string(root->Name()) != "launch") {
    throw LaunchError(Where(path, root ? root->GetLineNum() : 1) +
                      "expected a <launch> root element");
  }

  CheckAttributes(root, {"name"}, Where(path, root->GetLineNum()));
  LaunchFile file;
  file.path = path;
  file.name = root->Attribute("name") ? root->Attribute("name")
                                      : fs::path(path).stem().string();
  file.variables["launch_dir"] =
      fs::absolute(fs::path(path)).parent_path().lexically_normal().string();
  file.variables["cwd"] = fs::current_path().string();

  std::set<std::string> used_overrides;
  for (const auto* e = root->FirstChildElement("arg"); e != nullptr;
       e = e->NextSiblingElement("arg")) {
    const std::string where = Where(path, e->GetLineNum());
    CheckAttributes(e, {"name", "default", "env"}, where);
    const char* name = e->Attribute("name");
    if (name == nullptr || *name == '\0') {
      throw LaunchError(where + "<arg> needs a name attribute");
    }
    const auto it = overrides.find(name);
    const char* env = e->Attribute("env");
    const char* env_value = env != nullptr ? std::getenv(env) : nullptr;
    if (it != overrides.end()) {
      file.variables[name] = it->second;
      used_overrides.insert(name);
    } else if (env_value != nullptr && *env_value != '\0') {
      // The user's environment (e.g. LCM_DEFAULT_URL) beats the file's
      // default; --set beats both.
      file.variables[name] = env_value;
    } else if (const char* def = e->Attribute("default")) {
      file.variables[name] = Substitute(def, file.variables, where);
    } else {
      throw LaunchError(where + "arg '" + name +
                        "' has no default: give it with --set " + name +
                        "=VALUE");
    }
  }
  for (const auto& [name, value] : overrides) {
    if (used_overrides.count(name) == 0) {
      throw LaunchError(path + ": --set " + name +
                        ": the launch file declares no <arg name=\"" + name +
                        "\">");
    }
  }

  std::set<std::string> names;
  for (const auto* e = root->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    const std::string where = Where(path, e->GetLineNum());
    if (tag == "arg") continue;
    if (file.processes.size() >= kMaxProcesses) {
      throw LaunchError(where + "more than " + std::to_string(kMaxProcesses) +
                        " processes");
    }
    if (tag == "hub") {
      file.processes.push_back(HubProcess(e, file.variables, where));
      if (!names.insert(file.processes.back().name).second) {
        throw LaunchError(where + "a process named '" +
                          file.processes.back().name + "' is declared twice");
      }
      continue;
    }
    if (tag != "process") {
      throw LaunchError(where + "unexpected <" + tag +
                        ">: expected <arg>, <hub> or <process>");
    }
    CheckAttributes(e,
                    {"name", "program", "args", "required", "enabled", "delay",
                     "finish", "ready"},
                    where);
    ProcessSpec spec;
    spec.line = e->GetLineNum();
    const char* name = e->Attribute("name");
    const char* program = e->Attribute("program");
    if (name == nullptr || *name == '\0') {
      throw LaunchError(where + "<process> needs a name attribute");
    }
    if (program == nullptr || *program == '\0') {
      throw LaunchError(where + "process '" + name +
                        "' needs a program attribute");
    }
    spec.name = name;
    if (!names.insert(spec.name).second) {
      throw LaunchError(where + "a process named '" + spec.name +
                        "' is declared twice");
    }
    spec.program = Substitute(program, file.variables, where);
    try {
      spec.args =
          SplitArgs(Substitute(e->Attribute("args") ? e->Attribute("args") : "",
                               file.variables, where));
    } catch (const std::invalid_argument&) {
      throw LaunchError(where + "process '" + spec.name +
                        "': unterminated quote in args");
    }
    spec.required =
        ParseBool(e->Attribute("required"), false, where, "required");
    spec.enabled = ParseBool(
        e->Attribute("enabled")
            ? Substitute(e->Attribute("enabled"), file.variables, where).c_str()
            : nullptr,
        true, where, "enabled");
    spec.delay_s =
        ParseSeconds(e->Attribute("delay"), where, spec.name, "delay");
    spec.finish_s =
        ParseSeconds(e->Attribute("finish"), where, spec.name, "finish");
    spec.ready_line = ParseReadyLine(e->Attribute("ready"), where, spec.name);
    file.processes.push_back(std::move(spec));
  }
  if (file.processes.empty()) {
    throw LaunchError(path + ": no <process> to start");
  }
  return file;
}

}  // namespace mrsim
