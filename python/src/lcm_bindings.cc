// mrsim._core.LcmTransport: LCM for the Python node (mrsim/node.py). It
// subscribes raw, decodes every message with the C++ generated types and
// the project's checked decoding (DecodeMessage; a message that does not
// decode is counted and dropped), and hands decoded messages to Python as
// State objects and dicts of every field (python_messages.h, generated from
// the .lcm files; meaning added below where a field needs it). It
// publishes every message type from such dicts. Waiting happens with the GIL
// released. With a key it is a SignedLcm, the C++ programs' transport: it signs
// what it publishes and drops (and counts) unsigned, forged and replayed
// messages.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "camera/camera_image_codec.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/decode.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/signed_lcm.h"
#include "lcmtypes/runtime/usage_error.h"
#include "python/src/bindings.h"
#include "python/src/python_messages.h"
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

using Message = AnyMessage;

// The index of an .lcm type name in kMessageTypeNames.
size_t TypeIndex(const std::string& type) {
  for (size_t t = 0; t < std::size(kMessageTypeNames); ++t) {
    if (type == kMessageTypeNames[t]) return t;
  }
  std::string known;
  for (const char* name : kMessageTypeNames) {
    known += (known.empty() ? "" : ", ") + std::string(name);
  }
  throw std::invalid_argument("unknown message type '" + type +
                              "' (the .lcm files define " + known + ")");
}

template <size_t I = 0>
bool DecodeAs(size_t type, const lcm::ReceiveBuffer* rbuf, Message* out) {
  if constexpr (I < std::variant_size_v<Message>) {
    if (type == I) {
      std::variant_alternative_t<I, Message> msg{};
      if (!DecodeMessage(rbuf, &msg)) return false;
      *out = std::move(msg);
      return true;
    }
    return DecodeAs<I + 1>(type, rbuf, out);
  }
  return false;
}

// Every field as the generated conversion gives it, plus meaning where a
// field needs it (below).
template <class T>
py::object ToPython(const T& m) {
  return MessageToDict(m);
}

// An enum field as the lower-case name of its const ("paused").
template <class T>
std::string ConstLabel(const T& m, int64_t value) {
  const char* name = ConstName(&m, value);
  if (name == nullptr) return "unknown";
  std::string label = name;
  for (char& c : label) c = static_cast<char>(std::tolower(c));
  return label;
}

// Poses as rows x, y, z, qw, qx, qy, qz (as State and the logger have
// them); time: sim_time.
py::object ToPython(const scene_state_t& m) {
  py::dict d = MessageToDict(m);
  d["time"] = m.sim_time;
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

// mode in words ("running", "paused", "stopping"); time: sim_time.
py::object ToPython(const sim_status_t& m) {
  py::dict d = MessageToDict(m);
  d["time"] = m.sim_time;
  d["mode"] = ConstLabel(m, m.mode);
  return d;
}

// command_result in words ("none", "applied", "rejected", "queued");
// time: sim_time.
py::object ToPython(const gait_status_t& m) {
  py::dict d = MessageToDict(m);
  d["time"] = m.sim_time;
  d["command_result"] = ConstLabel(m, m.command_result);
  return d;
}

// The picture as an (H, W, 3) uint8 array.
py::array_t<std::uint8_t> ImageArray(const CameraPicture& p) {
  py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(p.height),
                                 static_cast<py::ssize_t>(p.width),
                                 py::ssize_t{3}});
  std::copy(p.rgb.begin(), p.rgb.end(), out.mutable_data());
  return out;
}

// Every field, plus image: the picture DecodeCameraImage checked (and
// decoded, for a JPEG); time: sim_time.
py::object ToPython(const camera_image_t& m, const CameraPicture& picture) {
  py::dict d = MessageToDict(m);
  d["time"] = m.sim_time;
  d["image"] = ImageArray(picture);
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

  // as_state: robot_state_t as a State object (answered again when
  // re-sent, handed once), as mrsim-gait takes states; else as a dict.
  void Subscribe(const std::string& channel, const std::string& type,
                 bool as_state) {
    const size_t t = TypeIndex(type);
    if (as_state && std::string(kMessageTypeNames[t]) != "robot_state_t") {
      throw std::invalid_argument("as_state: only for robot_state_t");
    }
    auto sub = std::make_unique<Sub>(Sub{this, t, as_state});
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
      const auto* state = std::get_if<robot_state_t>(&item.message);
      const auto* image = std::get_if<camera_image_t>(&item.message);
      if (image != nullptr && item.picture) {
        out.append(py::make_tuple(item.channel, "camera_image_t",
                                  ToPython(*image, *item.picture)));
      } else if (item.as_state && state != nullptr) {
        out.append(py::make_tuple(
            item.channel, "state",
            std::make_shared<StateObject>(StateObject::FromMessage(*state))));
      } else {
        py::object obj =
            std::visit([](const auto& m) -> py::object { return ToPython(m); },
                       item.message);
        out.append(py::make_tuple(
            item.channel, kMessageTypeNames[item.message.index()], obj));
      }
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

  // Any message type from a dict of its fields (MessageFromDict: every
  // field checked, lengths from the arrays).
  void PublishFields(const std::string& channel, const std::string& type,
                     const py::handle& fields) {
    PublishAs(TypeIndex(type), channel, fields);
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
    bool as_state;
  };
  struct Item {
    std::string channel;
    Message message;
    bool as_state;
    std::optional<CameraPicture> picture;  // of a camera_image_t
  };

  template <size_t I = 0>
  void PublishAs(size_t type, const std::string& channel,
                 const py::handle& fields) {
    if constexpr (I < std::variant_size_v<Message>) {
      if (type != I) return PublishAs<I + 1>(type, channel, fields);
      std::variant_alternative_t<I, Message> m{};
      MessageFromDict(fields, &m, kMessageTypeNames[I]);
      Publish(channel, m);
    }
  }

  static void OnMessage(const lcm::ReceiveBuffer* rbuf,
                        const std::string& channel, Sub* sub) {
    Transport* self = sub->owner;
    Item item{channel, Message{}, sub->as_state, std::nullopt};
    if (!DecodeAs(sub->type, rbuf, &item.message)) {
      ++self->malformed_;
      return;
    }
    // A picture whose sizes, bytes or JPEG disagree is malformed too (the
    // GIL is released here: JPEGs decode while Python runs).
    if (const auto* image = std::get_if<camera_image_t>(&item.message)) {
      try {
        item.picture = DecodeCameraImage(*image);
      } catch (const std::exception&) {
        ++self->malformed_;
        return;
      }
    }
    const auto* state = std::get_if<robot_state_t>(&item.message);
    if (item.as_state && state != nullptr && !self->FirstTime(*state)) return;
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
        py::arg("as_state") = false,
        "Subscribes a channel (regex) decoded as an .lcm type (one of "
        "message_types()); as_state: robot_state_t as State objects, each "
        "handed once and a re-sent one answered again (lockstep).");
  c.def("handle", &Transport::Handle, py::arg("timeout_ms"),
        "Waits up to timeout_ms for traffic (GIL released); returns a list of "
        "(channel, type, message) for every message decoded: type 'state' "
        "with a State, else the .lcm type with a dict of every field.");
  c.def("publish_joint_command", &Transport::PublishJointCommand,
        py::arg("channel"), py::arg("fields"),
        "Publishes a joint_command_t from a dict of its fields.");
  c.def("publish", &Transport::PublishFields, py::arg("channel"),
        py::arg("type"), py::arg("fields"),
        "Publishes a message of an .lcm type from a dict of its fields (left "
        "out: zero or empty; length members: from the arrays). A field of "
        "the wrong type, size or beyond its // max: raises TypeError or "
        "ValueError naming it.");
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

  m.attr("DEFAULT_CHANNEL_PREFIX") = kDefaultChannelPrefix;
  m.def(
      "channels",
      [] {
        py::list out;
        for (const ChannelSpec& spec : kChannels) {
          py::dict d;
          d["type"] = spec.type;
          d["name"] = spec.name;
          d["pattern"] = spec.pattern;
          d["infix"] = spec.infix;
          d["suffix"] = spec.suffix;
          d["default_prefix"] = spec.default_prefix;
          out.append(d);
        }
        return out;
      },
      "The channel of every message type, from the '// channel:' lines of "
      "the .lcm files: dicts of type, name ('state'), pattern "
      "('<prefix>_STATE_<robot>'), infix ('_STATE_'), suffix ('robot', "
      "'shard' or '') and default_prefix.");
  m.def("message_types", &MessageTypes,
        "Every message type of the .lcm files: {type: {'fields': [{name, "
        "type, dims, max}], 'consts': {NAME: value}}}; dims holds sizes and "
        "the names of length members.");
}

}  // namespace mrsim::python
