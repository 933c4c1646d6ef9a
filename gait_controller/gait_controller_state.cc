// GaitController::SaveState / LoadState: the controller's evolving state as
// whitespace-separated tokens (doubles as hex floats, strings
// length-prefixed), version-tagged.
#include <optional>
#include <sstream>
#include <stdexcept>

#include "common/exact_number.h"
#include "gait_controller/gait_controller.h"

namespace mrsim {
namespace {

// Version 2 adds the CPG settings of each gait and the oscillators' state;
// version 1 (no CPG) is still read.
constexpr const char* kTag = "mrsim-gait-controller-state-2";
constexpr const char* kTagV1 = "mrsim-gait-controller-state-1";

class Writer {
 public:
  void Double(double v) { out_ << ExactNumber(v) << ' '; }
  void Int(long long v) { out_ << v << ' '; }
  void Text(const std::string& s) { out_ << s.size() << ':' << s << ' '; }
  void Optional(const std::optional<double>& v) {
    if (v) {
      Double(*v);
    } else {
      out_ << "- ";
    }
  }
  std::string str() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

class Reader {
 public:
  explicit Reader(const std::string& text) : in_(text) {}
  std::string Token() {
    std::string t;
    if (!(in_ >> t)) throw std::invalid_argument("gait state: truncated");
    return t;
  }
  double Double() { return Number(Token()); }
  long long Int() {
    const std::string t = Token();
    char* end = nullptr;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (t.empty() || *end != '\0') {
      throw std::invalid_argument("gait state: bad integer");
    }
    return v;
  }
  std::string Text() {
    in_ >> std::ws;
    size_t n = 0;
    char colon = 0;
    if (!(in_ >> n) || !in_.get(colon) || colon != ':' || n > 4096) {
      throw std::invalid_argument("gait state: bad text");
    }
    std::string s(n, '\0');
    if (n > 0 && !in_.read(&s[0], static_cast<std::streamsize>(n))) {
      throw std::invalid_argument("gait state: truncated text");
    }
    return s;
  }
  std::optional<double> Optional() {
    in_ >> std::ws;
    if (in_.peek() == '-') {
      const std::string t = Token();
      if (t == "-") return std::nullopt;
      return Number(t);
    }
    return Double();
  }

 private:
  static double Number(const std::string& t) {
    const std::optional<double> v = ParseWholeNumber(t);
    if (!v) throw std::invalid_argument("gait state: bad number");
    return *v;
  }
  std::istringstream in_;
};

int Enum(Reader& r, int max) {
  const long long v = r.Int();
  if (v < 0 || v > max) throw std::invalid_argument("gait state: bad enum");
  return static_cast<int>(v);
}

void WriteWaves(Writer& w, const std::vector<JointWave>& waves) {
  w.Int(static_cast<long long>(waves.size()));
  for (const JointWave& j : waves) {
    w.Double(j.amplitude);
    w.Double(j.shift);
    w.Double(j.offset);
  }
}

std::vector<JointWave> ReadWaves(Reader& r, size_t expected) {
  const long long n = r.Int();
  if (n < 0 || static_cast<size_t>(n) != expected) {
    throw std::invalid_argument("gait state: for another joint count");
  }
  std::vector<JointWave> waves(expected);
  for (JointWave& j : waves) {
    j.amplitude = r.Double();
    j.shift = r.Double();
    j.offset = r.Double();
  }
  return waves;
}

}  // namespace

std::string GaitController::SaveState() const {
  Writer w;
  w.Text(kTag);
  w.Int(static_cast<long long>(axes_.size()));
  for (const Gait& g : gaits_) {
    w.Text(g.name);
    w.Int(static_cast<int>(g.kind));
    const GaitParameters& p = g.parameters;
    for (double v : p.ToArray()) w.Double(v);
    w.Double(p.pitch_yaw_lag);
    w.Double(p.amplitude_taper);
    w.Int(static_cast<long long>(p.overrides.size()));
    for (const JointOverride& o : p.overrides) {
      w.Int(o.joint);
      w.Optional(o.amplitude);
      w.Optional(o.phase);
      w.Optional(o.offset);
    }
    w.Int(g.cpg ? 1 : 0);
    if (g.cpg) {
      w.Double(g.cpg->coupling);
      w.Double(g.cpg->convergence);
      w.Double(g.cpg->feedback_gain);
      w.Double(g.cpg->force_scale);
      w.Double(g.cpg->distance_range);
    }
  }
  w.Int(static_cast<int>(kind_));
  w.Int(static_cast<int>(motion_));
  w.Double(strength_);
  w.Int(stopped_ ? 1 : 0);
  w.Double(drive_goal_);
  w.Double(turn_);
  WriteWaves(w, goal_);
  WriteWaves(w, waves_);
  w.Int(static_cast<long long>(targets_.size()));
  for (double t : targets_) w.Double(t);
  w.Double(drive_);
  w.Double(phase_);
  w.Double(time_);
  w.Int(cpg_running_ ? 1 : 0);
  const std::vector<double> network = cpg_.ToNumbers();
  w.Int(static_cast<long long>(network.size()));
  for (double v : network) w.Double(v);
  for (double f : feedback_) w.Double(f);
  return w.str();
}

void GaitController::LoadState(const std::string& text) {
  Reader r(text);
  const std::string tag = r.Text();
  if (tag != kTag && tag != kTagV1) {
    throw std::invalid_argument("gait state: not a gait controller state");
  }
  const bool v2 = tag == kTag;
  if (r.Int() != static_cast<long long>(axes_.size())) {
    throw std::invalid_argument("gait state: for another joint count");
  }
  GaitController next = *this;
  for (Gait& g : next.gaits_) {
    g.name = r.Text();
    g.kind = static_cast<GaitKind>(Enum(r, 2));
    std::vector<double> seven(GaitParameters::kVectorSize);
    for (double& v : seven) v = r.Double();
    g.parameters = GaitParameters::FromVector(seven);
    g.parameters.pitch_yaw_lag = r.Double();
    if (v2) g.parameters.amplitude_taper = r.Double();
    const long long n = r.Int();
    if (n < 0 || n > 1000) throw std::invalid_argument("gait state: overrides");
    for (long long i = 0; i < n; ++i) {
      JointOverride o;
      o.joint = static_cast<int>(r.Int());
      o.amplitude = r.Optional();
      o.phase = r.Optional();
      o.offset = r.Optional();
      g.parameters.overrides.push_back(o);
    }
    g.cpg.reset();
    if (v2 && r.Int() != 0) {
      CpgParameters c;
      c.coupling = r.Double();
      c.convergence = r.Double();
      c.feedback_gain = r.Double();
      c.force_scale = r.Double();
      c.distance_range = r.Double();
      ValidateCpgParameters(c);
      g.cpg = c;
    }
  }
  next.kind_ = static_cast<GaitKind>(Enum(r, 2));
  next.motion_ = static_cast<Motion>(Enum(r, static_cast<int>(Motion::kStop)));
  next.strength_ = r.Double();
  next.stopped_ = r.Int() != 0;
  next.drive_goal_ = r.Double();
  next.turn_ = r.Double();
  next.goal_ = ReadWaves(r, axes_.size());
  next.waves_ = ReadWaves(r, axes_.size());
  if (r.Int() != static_cast<long long>(axes_.size())) {
    throw std::invalid_argument("gait state: for another joint count");
  }
  for (double& t : next.targets_) t = r.Double();
  next.drive_ = r.Double();
  next.phase_ = r.Double();
  next.time_ = r.Double();
  next.cpg_running_ = false;
  if (v2) {
    next.cpg_running_ = r.Int() != 0;
    const long long n = r.Int();
    if (n != static_cast<long long>(axes_.size()) * 6 + 2) {
      throw std::invalid_argument("gait state: for another joint count");
    }
    std::vector<double> network(static_cast<size_t>(n));
    for (double& v : network) v = r.Double();
    next.cpg_.FromNumbers(network);
    for (double& f : next.feedback_) f = r.Double();
  }
  *this = std::move(next);
}

}  // namespace mrsim
