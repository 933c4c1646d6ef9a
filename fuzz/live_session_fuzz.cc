// The studio's live session (LiveSession, what mrsim-studio's window reads)
// fed every channel's messages, decodable but hostile (other robots, NaN
// and 1e308, shapes changing from message to message, a type on another
// type's channel) or raw bytes, with its plots on, requests in flight and
// clock jumps. It must never crash and never hold more than a bounded
// number of channels and robots.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz/hostile_input.h"
#include "studio/live/live_session.h"

namespace {

template <class Message>
std::vector<uint8_t> Encode(const Message& msg) {
  std::vector<uint8_t> bytes(static_cast<size_t>(msg.getEncodedSize()));
  if (msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())) < 0) {
    bytes.clear();
  }
  return bytes;
}

// One request from the window, with hostile arguments.
void Request(mrsim::fuzz::HostileInput& in,
             const std::vector<std::string>& robots, mrsim::WallTime now,
             mrsim::studio::LiveSession* session,
             mrsim::studio::StudioOutbox* out) {
  switch (in.Byte() % 4) {
    case 0:
      session->Pause(now, out);
      break;
    case 1:
      session->Step(static_cast<int>(in.Int(1)), now, out);
      break;
    case 2:
      session->Steer(in.Text(robots), in.Text({"forward", "stop"}), in.Double(),
                     now, out);
      break;
    default:
      session->SetSpeed(in.Double(), now, out);
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace mrsim;
  using namespace mrsim::studio;
  fuzz::HostileInput in(data, size);
  LiveSession session(LiveSessionOptions{});
  session.AddPlot("MRSIM_STATE_snake", "module0.x");
  session.AddPlot("MRSIM_SIM_STATUS", "sim_time");
  const std::vector<std::string> channels = {"MRSIM_STATE_snake",
                                             "MRSIM_STATE_other",
                                             "MRSIM_GAIT_STATUS_snake",
                                             "MRSIM_SCENE",
                                             "MRSIM_SIM_STATUS",
                                             "MRSIM_GAIT_snake",
                                             "MRSIM_STATE_",
                                             "MRSIM_X"};
  const std::vector<std::string> robots = {"snake", "other", ""};
  WallTime now{};
  StudioOutbox out;
  int64_t seq = 0;
  for (int op = 0; op < 64 && !in.empty(); ++op) {
    const uint8_t what = in.Byte();
    std::string channel = channels[in.Byte() % channels.size()];
    if (what % 16 == 15) channel = "MRSIM_STATE_" + std::to_string(in.Int());
    std::vector<uint8_t> bytes;
    switch (what % 8) {
      case 0:
        bytes = Encode(in.RobotState(robots, 3, seq++));
        break;
      case 1:
        bytes = Encode(in.GaitStatus(robots));
        break;
      case 2:
        bytes = Encode(in.SceneState(2));
        break;
      case 3:
        bytes = Encode(in.SimStatus(seq));
        break;
      case 4:
        bytes.resize(in.Byte());
        for (uint8_t& b : bytes) b = in.Byte();
        break;
      case 5:
        // Requests come from the window, which checks them; a bad one is
        // refused by exception, never sent.
        try {
          Request(in, robots, now, &session, &out);
        } catch (const std::invalid_argument&) {
        }
        out.clear();
        continue;
      default:
        now = AfterSeconds(now, in.Step());
        session.Tick(now);
        continue;
    }
    session.OnMessage(channel, bytes.data(), bytes.size(), now);
  }
  return 0;
}
