#include "studio/ui/run/live_panel.h"

#include <GLFW/glfw3.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <utility>

#include "lcmtypes/runtime/message_key.h"
#include "studio/ui/run/live_panel_common.h"
#include "studio/ui/widgets/panel_background.h"

namespace mrsim::studio {

LivePanel::LivePanel(std::vector<std::string> search_path,
                     LayoutRecorder* layout)
    : layout_(layout),
      runner_(search_path),
      optimise_(search_path),
      // Ready to start with: a design anywhere, no genome file needed.
      genome_(ForwardGaitGenome()),
      session_(std::make_unique<LiveSession>(LiveSessionOptions{})) {
  // As everywhere in mrsim: the user's LCM_DEFAULT_URL is the default.
  if (const char* url = std::getenv("LCM_DEFAULT_URL"); url && *url) {
    url_ = url;
  }
}

LivePanel::~LivePanel() {
  link_.reset();
  runner_.Stop();
}

void LivePanel::Connect(const std::string& url, const std::string& prefix) {
  link_.reset();
  LiveSessionOptions o;
  o.prefix = prefix;
  o.sender = "mrsim-studio-" + std::to_string(getpid());
  // The plots the user chose stay from run to run (under the new prefix).
  auto fresh = std::make_unique<LiveSession>(o);
  const std::string old_prefix = session_->prefix() + "_";
  for (const auto& plot : session_->plots()) {
    std::string channel = plot->channel();
    if (channel.rfind(old_prefix, 0) == 0) {
      channel = prefix + "_" + channel.substr(old_prefix.size());
    }
    fresh->AddPlot(channel, plot->column(), plot->window_s());
  }
  session_ = std::move(fresh);
  png_note_ = {};      // its plot is gone
  plot_channel_ = -1;  // the pickers start again on the followed robot
  plot_column_ = -1;
  // The studio's --key-file reaches here, and the processes it starts, as
  // MRSIM_KEY_FILE (checked at start-up).
  link_ = std::make_unique<LiveLink>(url, session_.get(),
                                     LoadAuthConfig("", false));
  followed_.clear();
  run_controller_.reset();  // the caller that started the run says who
}

Steering LivePanel::FollowedSteering() const {
  Steering s = session_->SteeringOf(followed_, WallClock::now());
  if (s.state == Steering::State::kAnswered || !run_controller_) return s;
  // This window started the run: it knows who drives the robot, and what
  // the student can change so that steering works.
  if (*run_controller_ == ControllerKind::kLua &&
      s.state == Steering::State::kUnanswered) {
    s.why = "robot '" + followed_ +
            "' is driven by your Lua script, which does not take steering: "
            "to steer with these buttons and the arrow keys, give the script "
            "a function on_gait_command(cmd) (docs/gait.md), or choose the "
            "gait controller above, and press Run again";
  }
  if (*run_controller_ == ControllerKind::kExternal &&
      s.state == Steering::State::kUnanswered) {
    s.why = "robot '" + followed_ +
            "' is driven by your own program, which does not take steering "
            "(a program takes it by publishing a gait status; "
            "docs/gait.md, \"Who takes steering\")";
  }
  return s;
}

void LivePanel::Disconnect() {
  link_.reset();
  if (running_) {
    running_.reset();
    ++replay_revision_;
  }
}

void LivePanel::Send(const std::function<void(StudioOutbox*)>& request) {
  if (!link_) {
    message_ = "not connected: Run or Attach first";
    message_is_note_ = false;
    return;
  }
  try {
    request(&outbox_);
    link_->Publish(&outbox_);
    message_.clear();
  } catch (const std::exception& e) {
    outbox_.clear();
    message_ = e.what();
    message_is_note_ = false;
  }
}

void LivePanel::Poll() {
  runner_.Poll();
  optimise_.Poll();
  if (const auto row = optimise_.TakeReplay()) Play(*row);
  if (layout_ != nullptr && layout_->enabled()) {
    const OptimiseProgress& p = optimise_.progress();
    layout_->State("optimise settings", fmt::format("{} {} {:g}", generations_,
                                                    population_, episode_));
    layout_->State("optimise",
                   fmt::format("{} of {} {}", p.rows.size(), p.generations,
                               p.running    ? "running"
                               : p.finished ? "finished"
                                            : "idle"));
    layout_->State("optimise watching", watching_);
    layout_->State("optimise stall", optimise_.StallWarning());
    std::string busy;
    for (const std::string& b : InProgress())
      busy += (busy.empty() ? "" : ", ") + b;
    layout_->State("live busy", busy.empty() ? "idle" : busy);
  }
  if (!link_) return;
  try {
    link_->Poll(0);
  } catch (const std::exception& e) {
    message_ = e.what();
    message_is_note_ = false;
    link_.reset();
    return;
  }
  if (followed_.empty() || session_->robot(followed_) == nullptr) {
    const auto robots = session_->robots();
    followed_ = robots.empty() ? "" : robots.front()->name;
  }
  if (layout_ != nullptr && layout_->enabled()) {
    if (const LiveRobot* r = session_->robot(followed_)) {
      char buf[128];
      std::snprintf(buf, sizeof(buf), "%.17g %.17g %.17g", r->state.sim_time,
                    r->state.com[0], r->state.com[1]);
      layout_->State("live " + followed_, buf);
    }
    layout_->State("live recording", runner_.recording() ? "1" : "0");
    layout_->State("live message", message_);
    layout_->State("live dropped", fmt::format("{} {}", session_->malformed(),
                                               session_->foreign()));
    if (const auto& st = session_->sim_status()) {
      char buf[96];
      std::snprintf(buf, sizeof(buf), "%.17g %s", st->sim_time,
                    st->mode == sim_status_t::PAUSED ? "paused" : "running");
      layout_->State("live status", buf);
    }
    if (!session_->requests().empty()) {
      const LiveRequest& r = session_->requests().back();
      layout_->State("live request", r.what + ": " + RequestText(r.state));
    }
    if (const LiveRobot* r = session_->robot(followed_); r && r->gait) {
      layout_->State("live gait", r->gait->motion);
    }
    if (!followed_.empty()) {
      const Steering steering = FollowedSteering();
      const char* state = steering.state == Steering::State::kAnswered ? "on"
                          : steering.state == Steering::State::kUnknown
                              ? "waiting"
                              : "off";
      layout_->State("live steering",
                     state + (steering.why.empty() ? "" : ": " + steering.why));
    }
  }
}

bool LivePanel::OnKey(int key) {
  if (!link_ || followed_.empty()) return false;
  const char* motion = nullptr;
  switch (key) {
    case GLFW_KEY_UP:
      motion = "forward";
      break;
    case GLFW_KEY_DOWN:
      motion = "backward";
      break;
    case GLFW_KEY_LEFT:
      motion = "turn-left";
      break;
    case GLFW_KEY_RIGHT:
      motion = "turn-right";
      break;
    case GLFW_KEY_SPACE:
      motion = "stop";
      break;
    default:
      return false;
  }
  // Nothing would answer: say why rather than send into a timeout.
  if (const Steering s = FollowedSteering();
      s.state == Steering::State::kUnanswered) {
    message_ = s.why;
    message_is_note_ = false;
    return true;
  }
  Send([&](StudioOutbox* out) {
    session_->Steer(followed_, motion, strength_, WallClock::now(), out);
  });
  return true;
}

void LivePanel::Draw(float x, float y, float w, float h,
                     const LiveDesign& design) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
  SkipPanelBackground();
  ImGui::Begin("Run", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                   ImGuiWindowFlags_NoCollapse);
  DrawRun(design);
  if (!message_.empty()) {
    // Wrapped: an error names a path and what is wrong, often wider than
    // the panel.
    ImGui::PushStyleColor(ImGuiCol_Text,
                          message_is_note_
                              ? ImGui::GetStyleColorVec4(ImGuiCol_Text)
                              : ImVec4(1, 0.5f, 0.4f, 1));
    ImGui::TextWrapped("%s", message_.c_str());
    ImGui::PopStyleColor();
  }
  // Optimise is the other way to run a design: right under Run, so at
  // 1280x800 its header and its Start button are on screen without
  // scrolling past the sections a run fills (Simulator, Steering).
  if (RecordedHeader(layout_, "Optimise", false)) DrawOptimise(design, w);
  if (RecordedHeader(layout_, "Simulator", true)) {
    DrawControls();
  }
  if (RecordedHeader(layout_, "Steering", true)) {
    DrawSteering();
  }
  DrawCamera(design.camera, w);
  if (RecordedHeader(layout_, "Locks", false)) DrawLocks();
  if (RecordedHeader(layout_, "Recording", false)) DrawRecording();
  if (RecordedHeader(layout_, "Plots", false)) DrawPlots(w);
  if (RecordedHeader(layout_, "Console", false)) DrawConsole(240);
  ImGui::End();
}

void LivePanel::DrawOverlay(float x, float y) {
  if (!link_) return;
  const LiveRobot* robot = session_->robot(followed_);
  const auto& status = session_->sim_status();
  if (robot == nullptr && !status) return;
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowBgAlpha(0.55f);
  ImGui::Begin("live overlay", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_AlwaysAutoResize |
                   ImGuiWindowFlags_NoSavedSettings |
                   ImGuiWindowFlags_NoFocusOnAppearing);
  if (status) {
    ImGui::Text("time   %.2f s%s", status->sim_time,
                status->mode == sim_status_t::PAUSED ? "  (paused)" : "");
    ImGui::Text("rate   x%.2f", status->real_time_factor);
  }
  if (robot != nullptr && robot->states > 0) {
    const auto& v = robot->state.com_velocity;
    ImGui::Text("speed  %.3f m/s",
                std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    // Where the head faces (docs/sim.md): 0 along +x, 90 along +y.
    ImGui::Text("heading %.0f deg", robot->state.heading * 180.0 / M_PI);
  }
  if (robot != nullptr && robot->gait) {
    ImGui::Text("gait   %s (%s)", robot->gait->gait.c_str(),
                robot->gait->motion.c_str());
  }
  ImGui::End();
}

}  // namespace mrsim::studio
