// mrsim-view: subscribes to the robot states of a scenario (or replays an
// .lcmlog), poses the model rebuilt from the same scenario and renders
// frames at fixed simulation-time steps to MP4 / PNG, off-screen; with
// --window and a display, live too. It only listens, so it never slows the
// simulator.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "lcmtypes/runtime/lcm_loop.h"
#include "lcmtypes/runtime/stop_signal.h"
#include "sim_core/scenario_xml.h"
#include "viewer/frame_scheduler.h"
#include "viewer/frame_writer.h"
#include "viewer/gl_context.h"
#include "viewer/live_window.h"
#include "viewer/process/state_inbox.h"
#include "viewer/process/view_options.h"
#include "viewer/state_viewer.h"

namespace mrsim {
namespace {

using Clock = std::chrono::steady_clock;

// Renders due frames and hands them to the writer and the window. The
// scheduler and inbox may be fed by another thread: they are only touched
// under `mutex`, and rendering works on copies of the states.
class FramePump {
 public:
  FramePump(StateViewer* viewer, FrameScheduler* scheduler, FrameWriter* writer,
            LiveWindow* window, int64_t max_frames,
            const StateInbox* gait_source, std::mutex* mutex)
      : viewer_(viewer),
        gait_source_(gait_source),
        scheduler_(scheduler),
        writer_(writer),
        window_(window),
        max_frames_(max_frames),
        mutex_(mutex) {}

  // Renders every frame that is due. Returns false once max_frames is
  // reached.
  bool Drain() {
    while (!Done()) {
      FrameScheduler::Frame frame;
      bool changed = window_ != nullptr && window_->TakeCameraChanged();
      {
        std::lock_guard<std::mutex> lock(*mutex_);
        if (gait_source_ != nullptr && gait_source_->gait_text() != gait_) {
          gait_ = gait_source_->gait_text();
          viewer_->set_gait(gait_);
          changed = true;
        }
        if (!scheduler_->NextFrame(&frame)) return true;
        // A repeated state (lost or late messages) gives the same picture.
        changed = changed || !have_image_ || frame.key != last_key_ ||
                  frame.scene_key != last_scene_key_;
        if (changed) {
          last_scene_valid_ = frame.scene != nullptr;
          last_scene_ =
              frame.scene ? *frame.scene : std::vector<SceneObjectState>();
          last_states_.clear();
          last_valid_.clear();
          for (const RobotState* s : frame.states) {
            last_states_.push_back(s ? *s : RobotState());
            last_valid_.push_back(s != nullptr);
          }
        }
      }
      if (changed) {
        RenderLast();
        last_key_ = frame.key;
        last_scene_key_ = frame.scene_key;
        ++rendered_;
      }
      if (first_index_ < 0) first_index_ = frame.index;
      last_time_ = frame.utime * 1e-6;
      if (writer_ != nullptr) writer_->Write(image_, frame.index);
      ++frames_;
    }
    return false;
  }

  // Window only: handle input and redraw after camera moves while no new
  // frame is due.
  void Refresh() {
    if (window_ == nullptr) return;
    window_->PollEvents();
    if (!have_image_ || !window_->TakeCameraChanged()) return;
    RenderLast();
  }

  bool Done() const { return max_frames_ > 0 && frames_ >= max_frames_; }
  int64_t frames() const { return frames_; }
  int64_t rendered() const { return rendered_; }
  int64_t first_index() const { return first_index_; }
  double last_time() const { return last_time_; }

 private:
  void RenderLast() {
    std::vector<const RobotState*> states;
    for (size_t r = 0; r < last_states_.size(); ++r) {
      states.push_back(last_valid_[r] ? &last_states_[r] : nullptr);
    }
    viewer_->Render(states, &image_,
                    last_scene_valid_ ? &last_scene_ : nullptr);
    have_image_ = true;
    if (window_ != nullptr) {
      viewer_->RenderToWindow(window_->width(), window_->height());
      window_->SwapBuffers();
    }
  }

  StateViewer* viewer_;
  const StateInbox* gait_source_;  // null: the gait text is fixed
  std::string gait_;
  FrameScheduler* scheduler_;
  FrameWriter* writer_;
  LiveWindow* window_;
  int64_t max_frames_;
  std::mutex* mutex_;
  cv::Mat image_;
  bool have_image_ = false;
  std::vector<int64_t> last_key_;
  std::vector<RobotState> last_states_;
  std::vector<bool> last_valid_;
  int64_t last_scene_key_ = -1;
  std::vector<SceneObjectState> last_scene_;
  bool last_scene_valid_ = false;
  int64_t frames_ = 0;
  int64_t rendered_ = 0;
  int64_t first_index_ = -1;
  double last_time_ = 0.0;
};

// Listens on its own thread so the socket is always drained while frames
// render: the scheduler keeps the newest --queue states per robot and drops
// older ones, instead of LCM dropping the newest while we are busy.
class Receiver {
 public:
  Receiver(lcm::LCM* lcm, StateInbox* inbox, std::mutex* mutex)
      : lcm_(lcm), inbox_(inbox), mutex_(mutex) {
    for (const auto& [channel, robot] : inbox->channels()) {
      (void)robot;
      lcm->subscribe(channel, &Receiver::On, this)->setQueueCapacity(kLcmQueue);
    }
    lcm->subscribe(inbox->gait_channel(), &Receiver::On, this)
        ->setQueueCapacity(kLcmQueue);
    lcm->subscribe(inbox->gait_status_channel(), &Receiver::On, this)
        ->setQueueCapacity(kLcmQueue);
    lcm->subscribe(inbox->scene_channel(), &Receiver::On, this)
        ->setQueueCapacity(kLcmQueue);
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

  lcm::LCM* lcm_;
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
              Clock::time_point* next) {
  const Clock::time_point now = Clock::now();
  if (now < *next) return;
  *next = now + std::chrono::seconds(2);
  std::fprintf(stderr,
               "mrsim-view: %lld frames (sim time %.2f s), %lld states, %lld "
               "malformed\n",
               static_cast<long long>(pump.frames()), pump.last_time(),
               static_cast<long long>(inbox.accepted()),
               static_cast<long long>(inbox.malformed()));
}

int Run(const ViewOptions& opt) {
  const Scenario scenario = ReadScenarioFile(opt.scenario);

  // The window's context serves off-screen frames too; without a display
  // an EGL context does.
  std::unique_ptr<LiveWindow> window;
  std::unique_ptr<GlContext> gl;
  if (opt.window && !LiveWindow::DisplayAvailable()) {
    std::fprintf(stderr,
                 "mrsim-view: --window: no display (DISPLAY unset); "
                 "rendering off-screen only\n");
  }
  if (opt.window && LiveWindow::DisplayAvailable()) {
    try {
      window = std::make_unique<LiveWindow>("mrsim-view: " + opt.scenario,
                                            opt.viewer.width, opt.viewer.height,
                                            nullptr);
    } catch (const std::exception& e) {
      // The video matters more than the window: carry on without it.
      std::fprintf(stderr, "mrsim-view: %s; rendering off-screen only\n",
                   e.what());
    }
  }
  if (!window) gl = std::make_unique<GlContext>();
  StateViewer viewer(scenario, opt.viewer);
  if (window) window->SetCamera(viewer.camera());

  // Only the newest --queue states per robot are kept: a slow viewer drops
  // old ones and shows the newest.
  FrameScheduler scheduler(opt.fps, viewer.robot_count(),
                           static_cast<size_t>(opt.queue));
  std::mutex mutex;
  StateInbox inbox(viewer, opt.prefix, &scheduler);
  std::unique_ptr<FrameWriter> writer;
  if (!opt.out.empty()) {
    writer = FrameWriter::Video(opt.out, opt.fps, opt.viewer.width,
                                opt.viewer.height);
  } else if (!opt.frames_dir.empty()) {
    writer = FrameWriter::Pngs(opt.frames_dir);
  }
  // Without --overlay the overlay follows the followed robot's gait commands.
  FramePump pump(&viewer, &scheduler, writer.get(), window.get(),
                 opt.max_frames, opt.viewer.gait.empty() ? &inbox : nullptr,
                 &mutex);
  auto announce = [&](const std::string& source) {
    std::fprintf(stderr, "mrsim-view: %s, %d robot(s), %dx%d at %g fps, %s\n",
                 gl ? gl->description().c_str() : "window context",
                 viewer.robot_count(), opt.viewer.width, opt.viewer.height,
                 opt.fps, source.c_str());
  };

  Clock::time_point next_progress = Clock::now() + std::chrono::seconds(2);
  if (!opt.from_log.empty()) {
    lcm::LogFile log(opt.from_log, "r");
    if (!log.good()) {
      throw std::runtime_error(opt.from_log + ": cannot read the LCM log");
    }
    announce("replaying " + opt.from_log);
    while (!StopRequested() && !pump.Done()) {
      const lcm::LogEvent* event = log.readNextEvent();
      if (event == nullptr) break;
      inbox.Receive(event->channel, event->data, event->datalen);
      pump.Drain();
      if (window) {
        window->PollEvents();
        if (window->ShouldClose()) break;
      }
      Progress(pump, inbox, &next_progress);
    }
  } else {
    lcm::LCM lcm(opt.lcm_url);
    if (!lcm.good()) {
      throw std::runtime_error("cannot open LCM at '" + opt.lcm_url + "'");
    }
    Receiver receiver(&lcm, &inbox, &mutex);
    announce("listening on " + std::to_string(inbox.channels().size()) +
             " state channel(s)");
    while (!StopRequested() && !pump.Done()) {
      receiver.Wait(window ? 10 : 100);
      if (!receiver.error().empty()) {
        throw std::runtime_error("LCM: " + receiver.error());
      }
      pump.Drain();
      if (window) {
        pump.Refresh();
        if (window->ShouldClose()) break;
      }
      std::lock_guard<std::mutex> lock(mutex);
      Progress(pump, inbox, &next_progress);
    }
    receiver.Stop();
  }
  if (writer) writer->Close();
  std::fprintf(stderr,
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
  if (writer) {
    std::fprintf(stderr, "mrsim-view: wrote %s\n", writer->path().c_str());
  }
  return 0;
}

}  // namespace
}  // namespace mrsim

int main(int argc, char** argv) {
  mrsim::ViewOptions options;
  const int parsed = mrsim::ParseViewOptions(argc, argv, &options);
  if (parsed >= 0) return parsed;
  mrsim::InstallStopHandlers();
  try {
    return mrsim::Run(options);
  } catch (const mrsim::ScenarioError& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrsim-view: %s\n", e.what());
    return 1;
  }
}
