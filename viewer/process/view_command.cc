#include "viewer/process/view_command.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "common/lcm_url.h"
#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/simulator_watch.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "sim_core/scenario/scenario_xml.h"
#include "viewer/frame_pump.h"
#include "viewer/gl_context.h"
#include "viewer/live_window.h"
#include "viewer/process/state_inbox.h"
#include "viewer/state_viewer.h"

namespace mrsim {
namespace {

using Clock = std::chrono::steady_clock;

// Listens on its own thread so the socket is always drained while frames
// render: the scheduler keeps what frames still to render need (up to
// --queue per robot), instead of LCM dropping states while we are busy.
class Receiver {
 public:
  Receiver(SignedLcm* lcm, StateInbox* inbox, std::mutex* mutex)
      : lcm_(lcm), inbox_(inbox), mutex_(mutex) {
    // The inbox's own list: a channel it handles but nobody subscribed to
    // (the gait status once) leaves the overlay silently empty.
    for (const std::string& channel : inbox->AllChannels()) {
      lcm->subscribe(channel, &Receiver::On, this)->setQueueCapacity(kLcmQueue);
    }
    thread_ = std::thread([this] { Loop(); });
  }
  ~Receiver() { Stop(); }
  Receiver(const Receiver&) = delete;
  Receiver& operator=(const Receiver&) = delete;

  void Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  // Waits up to timeout_ms for a message to arrive.
  void Wait(int timeout_ms) {
    std::unique_lock<std::mutex> lock(*mutex_);
    arrived_.wait_for(lock, std::chrono::milliseconds(timeout_ms),
                      [this] { return fresh_ || stop_ || failed_; });
    fresh_ = false;
  }
  // The LCM error that stopped the thread, or empty.
  std::string error() {
    std::lock_guard<std::mutex> lock(*mutex_);
    return error_;
  }

 private:
  static constexpr int kLcmQueue = 1000;

  void On(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    std::lock_guard<std::mutex> lock(*mutex_);
    inbox_->Receive(channel, buffer->data, static_cast<int>(buffer->data_size));
    fresh_ = true;
    arrived_.notify_one();
  }

  void Loop() {
    try {
      while (!stop_ && !StopRequested()) HandleFor(*lcm_, 50);
    } catch (const std::exception& e) {
      std::lock_guard<std::mutex> lock(*mutex_);
      error_ = e.what();
      failed_ = true;
      arrived_.notify_one();
    }
  }

  SignedLcm* lcm_;
  StateInbox* inbox_;
  std::mutex* mutex_;
  std::condition_variable arrived_;
  std::atomic<bool> stop_{false};
  bool fresh_ = false;
  bool failed_ = false;
  std::string error_;
  std::thread thread_;
};

void Progress(const FramePump& pump, const StateInbox& inbox,
              Clock::time_point* next, std::FILE* err) {
  const Clock::time_point now = Clock::now();
  if (now < *next) return;
  *next = now + std::chrono::seconds(2);
  std::fprintf(err,
               "mrsim-view: %lld frames (sim time %.2f s), %lld states, %lld "
               "malformed\n",
               static_cast<long long>(pump.frames()), pump.last_time(),
               static_cast<long long>(inbox.accepted()),
               static_cast<long long>(inbox.malformed()));
}

// Replays the log through the pump. A file with no LCM event (not a log)
// or with no state of the scenario's robots is bad input.
void ReplayLog(const ViewOptions& opt, StateInbox& inbox, FramePump& pump,
               LiveWindow* window, std::FILE* err) {
  lcm::LogFile log(opt.from_log, "r");
  if (!log.good()) {
    throw ViewInputError(opt.from_log + ": cannot read the LCM log");
  }
  Clock::time_point next_progress = Clock::now() + std::chrono::seconds(2);
  int64_t events = 0;
  while (!StopRequested() && !pump.Done()) {
    const lcm::LogEvent* event = log.readNextEvent();
    if (event == nullptr) break;
    ++events;
    inbox.Receive(event->channel, event->data, event->datalen);
    pump.Drain();  // with a window, its input is handled between pictures
    if (window != nullptr) {
      window->PollEvents();
      if (window->ShouldClose()) break;
    }
    Progress(pump, inbox, &next_progress, err);
  }
  if (StopRequested() || pump.frames() > 0) return;
  if (events == 0) {
    throw ViewInputError(opt.from_log +
                         ": not an LCM log (no LCM event found in it)");
  }
  std::string channels;
  for (const auto& [channel, robot] : inbox.channels()) {
    (void)robot;
    channels += (channels.empty() ? "" : ", ") + channel;
  }
  throw ViewInputError(
      opt.from_log + ": no state of the scenario's robots in " +
      std::to_string(events) + " messages (channels " + channels + "; " +
      std::to_string(inbox.malformed()) + " malformed" +
      (inbox.last_error().empty() ? "" : ", last: " + inbox.last_error()) +
      "); is it a log of " + opt.scenario + " with --prefix " + opt.prefix +
      "? Nothing was written");
}

// --exit-with-sim: tells `watch` what the inbox heard since the last call
// (under the inbox's mutex) and whether the simulator is now gone.
class SimulatorFollower {
 public:
  SimulatorFollower(const StateInbox& inbox, bool exit_with_sim)
      : watch_(Describe(inbox), exit_with_sim, WallClock::now()) {}

  bool Stopped(const StateInbox& inbox, std::FILE* err) {
    const WallTime now = WallClock::now();
    std::vector<std::string> log;
    if (inbox.accepted() != states_) watch_.Heard(now);
    states_ = inbox.accepted();
    if (inbox.statuses() != statuses_ && inbox.last_status()) {
      watch_.OnStatus(*inbox.last_status(), now, &log);
    }
    statuses_ = inbox.statuses();
    watch_.Tick(now, &log);
    for (const std::string& line : log) {
      std::fprintf(err, "mrsim-view: %s\n", line.c_str());
    }
    return watch_.stopped();
  }

 private:
  static std::string Describe(const StateInbox& inbox) {
    std::string channels;
    for (const auto& entry : inbox.channels()) {
      channels += (channels.empty() ? "" : ", ") + entry.first;
    }
    return channels;
  }

  SimulatorWatch watch_;
  int64_t states_ = 0;
  int64_t statuses_ = 0;
};

}  // namespace

void CheckViewOptions(const ViewOptions& opt) {
  if (opt.window && !LiveWindow::DisplayAvailable()) {
    throw ViewInputError(
        "--window: no display (DISPLAY and WAYLAND_DISPLAY are unset); run "
        "it on a desktop, over ssh -X, or under xvfb-run, or leave out "
        "--window to write --out/--frames-dir only");
  }
}

int RunView(const ViewOptions& opt, SignedLcm* lcm, std::FILE* err) {
  CheckViewOptions(opt);
  const Scenario scenario = ReadScenarioFile(opt.scenario);

  // The window's context serves off-screen frames too; without a display
  // an EGL context does.
  std::unique_ptr<LiveWindow> window;
  std::unique_ptr<GlContext> gl;
  if (opt.window) {
    try {
      window = std::make_unique<LiveWindow>("mrsim-view: " + opt.scenario,
                                            opt.viewer.width, opt.viewer.height,
                                            nullptr);
    } catch (const std::runtime_error& e) {
      throw ViewInputError(std::string("--window: ") + e.what() +
                           " (is the display reachable?)");
    }
  } else {
    gl = std::make_unique<GlContext>();
  }
  StateViewer viewer(scenario, opt.viewer);
  if (window) window->SetCamera(viewer.camera());

  FrameScheduler scheduler(opt.fps, viewer.robot_count(),
                           static_cast<size_t>(opt.QueueOrDefault()));
  std::mutex mutex;
  StateInbox inbox(viewer, opt.prefix, &scheduler);
  FramePump::WriterFactory make_writer;
  if (!opt.out.empty()) {
    make_writer = [&opt] {
      return FrameWriter::Video(opt.out, opt.fps, opt.viewer.width,
                                opt.viewer.height);
    };
  } else if (!opt.frames_dir.empty()) {
    make_writer = [&opt] { return FrameWriter::Pngs(opt.frames_dir); };
  }
  // Without --overlay the overlay follows the followed robot's gait commands.
  std::function<std::string()> gait_text;
  if (opt.viewer.gait.empty())
    gait_text = [&inbox] { return inbox.gait_text(); };
  FramePump pump(&viewer, &scheduler, make_writer, window.get(), opt.max_frames,
                 gait_text, &mutex);
  auto announce = [&](const std::string& source) {
    std::fprintf(err, "mrsim-view: %s, %d robot(s), %dx%d at %g fps, %s\n",
                 gl ? gl->description().c_str() : "window context",
                 viewer.robot_count(), opt.viewer.width, opt.viewer.height,
                 opt.fps, source.c_str());
  };

  if (!opt.from_log.empty()) {
    announce("replaying " + opt.from_log);
    ReplayLog(opt, inbox, pump, window.get(), err);
  } else {
    if (lcm == nullptr || !lcm->good()) {
      throw std::runtime_error(CannotOpenLcm(opt.lcm_url));
    }
    Receiver receiver(lcm, &inbox, &mutex);
    announce("listening on " + std::to_string(inbox.channels().size()) +
             " state channel(s)");
    Clock::time_point next_progress = Clock::now() + std::chrono::seconds(2);
    SimulatorFollower follower(inbox, opt.exit_with_sim);
    bool sim_gone = false;
    while (!StopRequested() && !pump.Done() && !sim_gone) {
      receiver.Wait(window ? 10 : 100);
      if (!receiver.error().empty()) {
        throw std::runtime_error("LCM: " + receiver.error());
      }
      // With a window, one picture at a time: its input (q, Esc, drags)
      // is handled between pictures however slow they are.
      // Without one, a backlog of frames to write still yields to a stop
      // signal after each frame.
      pump.Drain(window ? 1 : std::numeric_limits<int64_t>::max(),
                 [] { return StopRequested(); });
      if (window) {
        pump.Refresh();
        if (window->ShouldClose()) break;
      }
      std::lock_guard<std::mutex> lock(mutex);
      Progress(pump, inbox, &next_progress, err);
      sim_gone = opt.exit_with_sim && follower.Stopped(inbox, err);
    }
    receiver.Stop();
    // The simulator's last states may have arrived while the frames before
    // them were drawn: they are due now.
    if (sim_gone)
      pump.Drain(std::numeric_limits<int64_t>::max(), StopRequested);
  }
  pump.Close();
  std::fprintf(err,
               "mrsim-view: done: %lld frames (%lld rendered, first index "
               "%lld, last at %.3f s), %lld states, %lld malformed, %lld "
               "stale, %lld scene states%s%s\n",
               static_cast<long long>(pump.frames()),
               static_cast<long long>(pump.rendered()),
               static_cast<long long>(pump.first_index()), pump.last_time(),
               static_cast<long long>(inbox.accepted()),
               static_cast<long long>(inbox.malformed()),
               static_cast<long long>(inbox.stale()),
               static_cast<long long>(inbox.scenes()),
               inbox.last_error().empty() ? "" : "; last problem: ",
               inbox.last_error().c_str());
  if (pump.writer() != nullptr) {
    std::fprintf(err, "mrsim-view: wrote %s (%s)\n",
                 pump.writer()->path().c_str(), pump.writer()->codec().c_str());
  } else if (make_writer && pump.frames() == 0 && opt.from_log.empty()) {
    // Asked for a video or frames and got none: say so, and fail, so a
    // script or a launch does not take the missing file for a success.
    std::string channels;
    for (const auto& entry : inbox.channels()) {
      channels += (channels.empty() ? "" : ", ") + entry.first;
    }
    std::fprintf(err,
                 "mrsim-view: nothing written: no state arrived on %s (is "
                 "mrsim-sim running, with the same --lcm-url and --prefix?)\n",
                 channels.c_str());
    return 1;
  }
  return 0;
}

}  // namespace mrsim
