// mrsim._core.LcmTransport: LCM for the Python node (mrsim/node.py). It
// subscribes raw, decodes every message with the C++ generated types and
// the project's checked decoding (DecodeMessage; a message that does not
// decode is counted and dropped), and hands decoded messages to Python as
// State objects and dicts. Waiting happens with the GIL released. With a
// key it is a SignedLcm, the C++ programs' transport: it signs what it
// publishes and drops (and counts) unsigned, forged and replayed messages.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <cstdlib>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/usage_error.h"
#include "mrsim/gait_command_t.hpp"
#include "mrsim/gait_status_t.hpp"
#include "mrsim/joint_command_t.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/scene_state_t.hpp"
#include "mrsim/sim_control_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "python/src/bindings.h"
#include "python/src/state_object.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

// A key file the transport cannot use; mrsim.KeyFileError in Python.
class KeyFileError : public std::runtime_error {
 public:
  KeyFileError(const std::string& what, std::string path)
      : std::runtime_error(what), path_(std::move(path)) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

using Message =
    std::variant<robot_state_t, scene_state_t, sim_status_t, gait_status_t,
                 joint_command_t, sim_control_t, gait_command_t>;

const char* const kTypeNames[] = {"robot_state", "scene_state",   "sim_status",
                                  "gait_status", "joint_command", "sim_control",
                                  "gait_command"};

template <size_t I = 0>
bool DecodeAs(size_t type, const lcm::ReceiveBuffer* rbuf, Message* out) {
  if constexpr (I < std::variant_size_v<Message>) {
    if (type == I) {
      std::variant_alternative_t<I, Message> msg;
      if (!DecodeMessage(rbuf, &msg)) return false;
      *out = std::move(msg);
      return true;
    }
    return DecodeAs<I + 1>(type, rbuf, out);
  }
  return false;
}

py::array_t<double> Doubles(const double* d, size_t n) {
  return py::array_t<double>(n, d);
}

py::object ToPython(const robot_state_t& m) {
  return py::cast(std::make_shared<StateObject>(StateObject::FromMessage(m)));
}

py::object ToPython(const scene_state_t& m) {
  py::dict d;
  d["utime"] = m.utime;
  d["seq"] = m.seq;
  d["time"] = m.sim_time;
  d["object_index"] = m.object_index;
  py::array_t<double> poses(
      {static_cast<py::ssize_t>(m.poses.size()), py::ssize_t{7}});
  double* p = poses.mutable_data();
  for (size_t i = 0; i < m.poses.size(); ++i) {
    for (int k = 0; k < 3; ++k) p[7 * i + k] = m.poses[i].position[k];
    for (int k = 0; k < 4; ++k) p[7 * i + 3 + k] = m.poses[i].orientation[k];
  }
  d["poses"] = poses;
  return d;
}

py::object ToPython(const sim_status_t& m) {
  static const char* const kModes[] = {"running", "paused", "stopping"};
  py::dict d;
  d["utime"] = m.utime;
  d["seq"] = m.seq;
  d["time"] = m.sim_time;
  d["real_time_factor"] = m.real_time_factor;
  d["mode"] = (m.mode >= 0 && m.mode <= 2) ? kModes[m.mode] : "unknown";
  d["clock"] = m.clock;
  d["speed"] = m.speed;
  d["control_rate"] = m.control_rate;
  d["steps_per_period"] = m.steps_per_period;
  d["steps"] = m.steps;
  d["state_seq"] = m.state_seq;
  d["states_published"] = m.states_published;
  d["actuation_delay"] = m.actuation_delay;
  d["commands_applied"] = m.commands_applied;
  d["commands_rejected"] = m.commands_rejected;
  d["rejected_joint_count"] = m.rejected_joint_count;
  d["rejected_value"] = m.rejected_value;
  d["rejected_robot"] = m.rejected_robot;
  d["rejected_seq"] = m.rejected_seq;
  d["rejected_sender"] = m.rejected_sender;
  d["messages_malformed"] = m.messages_malformed;
  d["messages_dropped"] = m.messages_dropped;
  d["control_seq"] = m.control_seq;
  d["control_sender"] = m.control_sender;
  d["control_ok"] = m.control_ok;
  d["waiting_for"] = m.waiting_for;
  d["last_error"] = m.last_error;
  return d;
}

py::object ToPython(const gait_status_t& m) {
  static const char* const kResults[] = {"none", "applied", "rejected",
                                         "queued"};
  py::dict d;
  d["utime"] = m.utime;
  d["seq"] = m.seq;
  d["robot"] = m.robot;
  d["sender"] = m.sender;
  d["time"] = m.sim_time;
  d["running"] = m.running;
  d["gait"] = m.gait;
  d["kind"] = m.kind;
  d["parameters"] = Doubles(m.parameters, std::size(m.parameters));
  d["motion"] = m.motion;
  d["strength"] = m.strength;
  d["stopped"] = m.stopped;
  d["states_answered"] = m.states_answered;
  d["commands_applied"] = m.commands_applied;
  d["commands_rejected"] = m.commands_rejected;
  d["messages_malformed"] = m.messages_malformed;
  d["command_seq"] = m.command_seq;
  d["command_sender"] = m.command_sender;
  d["command_result"] = (m.command_result >= 0 && m.command_result <= 3)
                            ? kResults[m.command_result]
                            : "unknown";
  d["command_error"] = m.command_error;
  d["warning"] = m.warning;
  return d;
}

py::object ToPython(const joint_command_t& m) {
  py::dict d;
  d["utime"] = m.utime;
  d["seq"] = m.seq;
  d["robot"] = m.robot;
  d["sender"] = m.sender;
  d["state_seq"] = m.state_seq;
  d["target"] = Doubles(m.target.data(), m.target.size());
  return d;
}

py::object ToPython(const sim_control_t& m) {
  py::dict d;
  d["utime"] = m.utime;
  d["seq"] = m.seq;
  d["sender"] = m.sender;
  d["command"] = m.command;
  d["steps"] = m.steps;
  d["speed"] = m.speed;
  d["path"] = m.path;
  d["robot"] = m.robot;
  d["lock"] = m.lock;
  return d;
}

py::object ToPython(const gait_command_t& m) {
  py::dict d;
  d["utime"] = m.utime;
  d["seq"] = m.seq;
  d["sender"] = m.sender;
  d["robot"] = m.robot;
  d["gait"] = m.gait;
  d["has_parameters"] = m.has_parameters;
  d["parameters"] = Doubles(m.parameters, std::size(m.parameters));
  d["motion"] = m.motion;
  d["strength"] = m.strength;
  d["has_direction"] = m.has_direction;
  d["forward"] = m.forward;
  d["turn"] = m.turn;
  return d;
}

template <class T>
T Get(const py::dict& d, const char* key, T fallback) {
  return d.contains(key) ? d[key].cast<T>() : fallback;
}

class Transport {
 public:
  static constexpr size_t kMaxQueued = 100000;
  static constexpr size_t kRecentAnswers = 8;

  // key_file: as --key-file ('' falls back to $MRSIM_KEY_FILE, else
  // unsigned). A key file that cannot be used throws KeyFileError.
  Transport(const std::string& url, const std::string& key_file,
            bool accept_replays)
      : lcm_(url, LoadKey(key_file, accept_replays)) {
    if (!lcm_.good()) {
      throw std::runtime_error("LCM: cannot open '" + url +
                               "' (for multicast on loopback see README.md, "
                               "'Multicast')");
    }
  }

  void Subscribe(const std::string& channel, const std::string& type) {
    size_t t = 0;
    while (t < std::size(kTypeNames) && type != kTypeNames[t]) ++t;
    if (t == std::size(kTypeNames)) {
      throw std::invalid_argument("unknown message type '" + type + "'");
    }
    auto sub = std::make_unique<Sub>(Sub{this, t});
    if (lcm_.subscribeFunction(channel, &Transport::OnMessage, sub.get()) ==
        nullptr) {
      throw std::runtime_error("LCM: cannot subscribe to " + channel);
    }
    subs_.push_back(std::move(sub));
  }

  // Waits up to timeout_ms for traffic (GIL released), then returns every
  // message decoded so far as (channel, type, object) tuples.
  py::list Handle(int timeout_ms) {
    if (queue_.empty()) {
      py::gil_scoped_release release;
      HandleFor(lcm_, timeout_ms);
    } else {
      py::gil_scoped_release release;
      HandleFor(lcm_, 0);
    }
    py::list out;
    while (!queue_.empty()) {
      Item& item = queue_.front();
      py::object obj =
          std::visit([](const auto& m) { return ToPython(m); }, item.message);
      out.append(
          py::make_tuple(item.channel, kTypeNames[item.message.index()], obj));
      queue_.pop_front();
    }
    return out;
  }

  void PublishJointCommand(const std::string& channel, const py::dict& d) {
    joint_command_t m{};
    m.utime = Get<int64_t>(d, "utime", 0);
    m.seq = Get<int64_t>(d, "seq", ++command_seq_);
    m.robot = Get<std::string>(d, "robot", "");
    m.sender = Get<std::string>(d, "sender", "");
    m.state_seq = Get<int64_t>(d, "state_seq", -1);
    m.target = d["target"].cast<std::vector<double>>();
    m.num_joints = static_cast<int32_t>(m.target.size());
    Publish(channel, m);
  }

  void PublishSimControl(const std::string& channel, const py::dict& d) {
    sim_control_t m{};
    m.utime = Get<int64_t>(d, "utime", 0);
    m.seq = Get<int64_t>(d, "seq", 0);
    m.sender = Get<std::string>(d, "sender", "");
    m.command = Get<int8_t>(d, "command", 0);
    m.steps = Get<int32_t>(d, "steps", 0);
    m.speed = Get<double>(d, "speed", 0.0);
    m.path = Get<std::string>(d, "path", "");
    m.robot = Get<std::string>(d, "robot", "");
    m.lock = Get<std::string>(d, "lock", "");
    Publish(channel, m);
  }

  void PublishGaitCommand(const std::string& channel, const py::dict& d) {
    gait_command_t m{};
    m.utime = Get<int64_t>(d, "utime", 0);
    m.seq = Get<int64_t>(d, "seq", 0);
    m.sender = Get<std::string>(d, "sender", "");
    m.robot = Get<std::string>(d, "robot", "");
    m.gait = Get<std::string>(d, "gait", "");
    if (d.contains("parameters") && !d["parameters"].is_none()) {
      const auto p = d["parameters"].cast<std::vector<double>>();
      if (p.size() != std::size(m.parameters)) {
        throw std::invalid_argument("parameters: expected the seven values");
      }
      m.has_parameters = true;
      std::copy(p.begin(), p.end(), m.parameters);
    }
    m.motion = Get<std::string>(d, "motion", "");
    m.strength = Get<double>(d, "strength", 1.0);
    if (d.contains("direction") && !d["direction"].is_none()) {
      const auto v = d["direction"].cast<std::vector<double>>();
      if (v.size() != 2) {
        throw std::invalid_argument("direction: expected (forward, turn)");
      }
      m.has_direction = true;
      m.forward = v[0];
      m.turn = v[1];
    }
    Publish(channel, m);
  }

  // The joint command answering state `state_seq` of `robot` (lockstep),
  // remembered so that a re-sent state is answered again with it, as
  // mrsim-gait does (GaitNode::kRecentAnswers).
  void Answer(const std::string& channel, const std::string& robot,
              const std::string& sender, int64_t state_seq, int64_t utime,
              std::vector<double> targets) {
    joint_command_t m{};
    m.utime = utime;
    m.seq = ++command_seq_;
    m.robot = robot;
    m.sender = sender;
    m.state_seq = state_seq;
    m.num_joints = static_cast<int32_t>(targets.size());
    m.target = std::move(targets);
    Publish(channel, m);
    Answers& a = answers_[robot];
    a.channel = channel;
    a.by_seq[state_seq] = std::move(m);
    while (a.by_seq.size() > kRecentAnswers) a.by_seq.erase(a.by_seq.begin());
  }

  // Bytes as they are (tests of what the node does with foreign traffic).
  void PublishRaw(const std::string& channel, const py::bytes& data) {
    const std::string bytes = data;
    if (lcm_.publish(channel, bytes.data(),
                     static_cast<unsigned>(bytes.size())) != 0) {
      throw std::runtime_error("LCM: publishing on " + channel + " failed");
    }
  }

  // A state as mrsim-sim publishes it (tests, replays, fake simulators).
  void PublishState(const std::string& channel, const StateObject& s) {
    Publish(channel, s.ToMessage());
  }

  int64_t malformed() const { return malformed_; }
  bool signing() const { return lcm_.signing(); }
  std::string describe() const { return lcm_.Describe(); }
  py::dict auth_counts() const {
    const MessageAuth::Counts c = lcm_.counts();
    py::dict d;
    d["accepted"] = c.accepted;
    d["unsigned"] = c.unsigned_;
    d["forged"] = c.forged;
    d["replayed"] = c.replayed;
    return d;
  }
  int64_t repeated() const { return repeated_; }
  int64_t command_seq() const { return command_seq_; }
  void set_command_seq(int64_t seq) { command_seq_ = seq; }
  int64_t dropped() const { return dropped_; }
  int fileno() { return lcm_.getFileno(); }

 private:
  struct Sub {
    Transport* owner;
    size_t type;
  };
  struct Item {
    std::string channel;
    Message message;
  };

  static void OnMessage(const lcm::ReceiveBuffer* rbuf,
                        const std::string& channel, Sub* sub) {
    Transport* self = sub->owner;
    Item item{channel, Message{}};
    if (!DecodeAs(sub->type, rbuf, &item.message)) {
      ++self->malformed_;
      return;
    }
    if (const auto* state = std::get_if<robot_state_t>(&item.message)) {
      if (!self->FirstTime(*state)) return;
    }
    if (self->queue_.size() >= kMaxQueued) {
      self->queue_.pop_front();
      ++self->dropped_;
    }
    self->queue_.push_back(std::move(item));
  }

  // False for a state already handed over: answered ones are answered
  // again (the simulator waits for them), older ones dropped, as
  // mrsim-gait does.
  bool FirstTime(const robot_state_t& state) {
    auto a = answers_.find(state.robot);
    if (a != answers_.end()) {
      auto it = a->second.by_seq.find(state.seq);
      if (it != a->second.by_seq.end()) {
        ++repeated_;
        lcm_.publish(a->second.channel, &it->second);
        return false;
      }
    }
    auto last = delivered_.find(state.robot);
    if (last != delivered_.end() && state.seq <= last->second) return false;
    delivered_[state.robot] = state.seq;
    return true;
  }

  template <class T>
  void Publish(const std::string& channel, const T& m) {
    if (lcm_.publish(channel, &m) != 0) {
      throw std::runtime_error("LCM: publishing on " + channel + " failed");
    }
  }

  static AuthConfig LoadKey(const std::string& key_file, bool accept_replays) {
    try {
      return LoadAuthConfig(key_file, accept_replays);
    } catch (const UsageError& e) {
      const char* env = std::getenv(kKeyFileEnv);
      throw KeyFileError(e.what(), key_file.empty() && env != nullptr
                                       ? std::string(env)
                                       : key_file);
    }
  }

  SignedLcm lcm_;
  std::vector<std::unique_ptr<Sub>> subs_;
  struct Answers {
    std::string channel;
    std::map<int64_t, joint_command_t> by_seq;
  };
  std::deque<Item> queue_;
  std::map<std::string, Answers> answers_;    // by robot
  std::map<std::string, int64_t> delivered_;  // newest state seq by robot
  int64_t command_seq_ = 0;
  int64_t repeated_ = 0;
  int64_t malformed_ = 0;
  int64_t dropped_ = 0;
};

}  // namespace

void BindLcm(py::module_& m) {
  static py::exception<KeyFileError> key_error(m, "KeyFileError",
                                               PyExc_ValueError);
  key_error.attr("__doc__") =
      "A key file that cannot be used for message signing (missing, "
      "readable or writable by group or others, not a key, too short). "
      "str() names the file and what is wrong; the attribute path holds it.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const KeyFileError& e) {
      py::object exc = py::reinterpret_borrow<py::object>(key_error)(e.what());
      exc.attr("path") = e.path();
      PyErr_SetObject(key_error.ptr(), exc.ptr());
    }
  });
  py::class_<Transport> c(m, "LcmTransport", R"doc(
The LCM connection of mrsim.Node (use Node): subscriptions decoded with
the C++ message types and checked decoding, messages that do not decode
counted in `malformed` and dropped.)doc");
  c.def(py::init<const std::string&, const std::string&, bool>(),
        py::arg("url"), py::arg("key_file") = "",
        py::arg("accept_replays") = false,
        "Opens LCM at url ('' for LCM's default or $LCM_DEFAULT_URL). "
        "key_file: sign and check messages with this key, as --key-file "
        "('': $MRSIM_KEY_FILE, else unsigned); raises KeyFileError naming "
        "the file when it cannot be used. accept_replays: as "
        "--accept-replays.");
  c.def("subscribe", &Transport::Subscribe, py::arg("channel"), py::arg("type"),
        "Subscribes a channel (regex) decoded as one of robot_state, "
        "scene_state, sim_status, gait_status, joint_command, sim_control, "
        "gait_command.");
  c.def("handle", &Transport::Handle, py::arg("timeout_ms"),
        "Waits up to timeout_ms for traffic (GIL released); returns a list of "
        "(channel, type, message) for every message decoded.");
  c.def("publish_joint_command", &Transport::PublishJointCommand,
        py::arg("channel"), py::arg("fields"),
        "Publishes a joint_command_t from a dict of its fields.");
  c.def("publish_sim_control", &Transport::PublishSimControl,
        py::arg("channel"), py::arg("fields"),
        "Publishes a sim_control_t from a dict of its fields.");
  c.def("publish_gait_command", &Transport::PublishGaitCommand,
        py::arg("channel"), py::arg("fields"),
        "Publishes a gait_command_t from a dict (parameters: seven values, "
        "direction: (forward, turn)).");
  c.def("answer", &Transport::Answer, py::arg("channel"), py::arg("robot"),
        py::arg("sender"), py::arg("state_seq"), py::arg("utime"),
        py::arg("targets"),
        "Publishes the joint_command_t answering a state (next command seq) "
        "and answers that state again with it if the simulator re-sends it.");
  c.def_property("command_seq", &Transport::command_seq,
                 &Transport::set_command_seq,
                 "The seq of the last joint command published.");
  c.def_property_readonly("repeated", &Transport::repeated,
                          "Re-sent states answered again.");
  c.def("publish_raw", &Transport::PublishRaw, py::arg("channel"),
        py::arg("data"),
        "Publishes bytes as they are, signed when the transport has a key "
        "(for tests).");
  c.def("publish_state", &Transport::PublishState, py::arg("channel"),
        py::arg("state"), "Publishes a State as a robot_state_t.");
  c.def_property_readonly("malformed", &Transport::malformed,
                          "Messages that did not decode (dropped).");
  c.def_property_readonly("dropped", &Transport::dropped,
                          "Decoded messages dropped because nobody read them.");
  c.def_property_readonly("signing", &Transport::signing,
                          "True when messages are signed and checked.");
  c.def("describe", &Transport::describe,
        "'messages signed with KEYFILE' or 'messages unsigned (no key)'.");
  c.def("auth_counts", &Transport::auth_counts,
        "Signed messages accepted and messages dropped as unsigned, forged or "
        "replayed, as a dict (all zero without a key).");
  c.def("fileno", &Transport::fileno,
        "LCM's file descriptor, readable when traffic waits (select/poll).");
}

}  // namespace mrsim::python
