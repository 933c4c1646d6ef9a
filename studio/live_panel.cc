#include "studio/live_panel.h"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>
#include <imgui_stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <functional>
#include <utility>

#include "gait_controller/gait_file.h"
#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/message_key.h"
#include "sim_core/scenario_xml.h"
#include "studio/live/best_replay.h"
#include "studio/live/plot_export.h"

namespace mrsim::studio {
namespace {

const char* const kClocks[] = {"realtime", "fast", "lockstep"};
// A click in a number field selects it whole: typing replaces the value.
constexpr ImGuiInputTextFlags kNumberFlags = ImGuiInputTextFlags_AutoSelectAll;

const char* RequestText(LiveRequest::State s) {
  switch (s) {
    case LiveRequest::State::kPending:
      return "sent";
    case LiveRequest::State::kDone:
      return "done";
    case LiveRequest::State::kRefused:
      return "refused";
    case LiveRequest::State::kNoAnswer:
      return "no answer";
  }
  return "";
}

}  // namespace

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

bool LivePanel::Button(const char* label, float width) {
  const bool pressed = ImGui::Button(label, ImVec2(width, 0));
  Record(label);
  return pressed;
}

void LivePanel::Record(const std::string& name) {
  if (layout_ != nullptr && layout_->enabled()) {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    layout_->Widget(name, a.x, a.y, b.x - a.x, b.y - a.y);
    // Which field takes typed text: a test types only once it is this one.
    if (ImGui::IsItemActive()) layout_->State("active", name);
  }
}

bool LivePanel::Header(const char* label, bool open_at_start) {
  const bool open = ImGui::CollapsingHeader(
      label, open_at_start ? ImGuiTreeNodeFlags_DefaultOpen : 0);
  Record(std::string("header ") + label);
  return open;
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
  Send([&](StudioOutbox* out) {
    session_->Steer(followed_, motion, strength_, WallClock::now(), out);
  });
  return true;
}

void LivePanel::DrawRun(const LiveDesign& design) {
  ImGui::TextUnformatted("Run this design");
  ImGui::SetNextItemWidth(110);
  ImGui::Combo("clock", &clock_, kClocks, IM_ARRAYSIZE(kClocks));
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputFloat("Hz", &rate_, 0, 0, "%.0f");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputFloat("speed", &speed_, 0, 0, "%.2f");
  if (!runner_.running()) {
    // mrsim-sim runs the file: what is on screen is saved first.
    const bool saved = !design.path.empty() && !design.dirty;
    if (Button(saved ? "Run" : "Save and Run")) {
      const std::string path =
          saved ? design.path : (design.save ? design.save() : "");
      if (path.empty()) {
        message_ =
            "the design is not saved yet: choose where to save it, then "
            "press Run";
        message_is_note_ = false;
      } else {
        try {
          RunOptions o = FormRun();
          o.scenario_path = path;
          o.robots = design.robots;
          runner_.Start(o);
          Connect(url_, prefix_);
          EndReplay();
          running_ = ReadScenarioFile(path);
          ++replay_revision_;
          message_.clear();
        } catch (const std::exception& e) {
          message_ = e.what();
          message_is_note_ = false;
        }
      }
    }
  } else if (Button("Stop")) {
    // Back to the design: the view, the camera and the simulator section
    // leave the stopped run (its last pose and counters would look live).
    runner_.Stop();
    EndReplay();
    Disconnect();
  }
  ImGui::SameLine();
  if (!link_) {
    if (Button("Attach")) {
      try {
        Connect(url_, prefix_);
      } catch (const std::exception& e) {
        message_ = e.what();
        message_is_note_ = false;
      }
    }
  } else if (Button("Detach")) {
    Disconnect();
  }
  // A run on this computer needs neither; attaching to a simulation or a
  // farm elsewhere does. Folded, so a first look is not an LCM URL.
  if (ImGui::TreeNode("network (LCM URL, prefix)")) {
    ImGui::SetNextItemWidth(-60);
    ImGui::InputText("URL", &url_);
    ImGui::SetNextItemWidth(-60);
    ImGui::InputText("prefix", &prefix_);
    ImGui::TreePop();
  }
}

void LivePanel::DrawControls() {
  // Detached or stopped: the last run's figures would read as live ones.
  const std::optional<sim_status_t> none;
  const auto& status = link_ ? session_->sim_status() : none;
  if (status) {
    ImGui::Text("sim %.2f s  x%.2f  %s%s", status->sim_time,
                status->real_time_factor, status->clock.c_str(),
                status->mode == sim_status_t::PAUSED ? "  paused" : "");
    if (!status->waiting_for.empty()) {
      ImGui::Text("lockstep waits for %s", status->waiting_for.c_str());
    }
    ImGui::Text("applied %lld  rejected %lld  malformed %lld",
                static_cast<long long>(status->commands_applied),
                static_cast<long long>(status->commands_rejected),
                static_cast<long long>(status->messages_malformed));
  } else {
    ImGui::TextDisabled(link_ ? "waiting for the simulator..."
                              : "not connected");
  }
  // What this window itself dropped: bytes that were not the channel's
  // type (someone else's traffic, or a hostile host on the group).
  if (link_ && session_->malformed() + session_->foreign() > 0) {
    ImGui::TextDisabled("studio dropped %lld malformed, %lld foreign",
                        static_cast<long long>(session_->malformed()),
                        static_cast<long long>(session_->foreign()));
  }
  const bool paused = status && status->mode == sim_status_t::PAUSED;
  if (Button(paused ? "Play" : "Pause")) {
    Send([&](StudioOutbox* out) {
      paused ? session_->Resume(WallClock::now(), out)
             : session_->Pause(WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  if (Button("Step")) {
    Send([&](StudioOutbox* out) {
      session_->Step(step_periods_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(70);
  ImGui::InputInt("periods", &step_periods_);
  ImGui::SameLine();
  if (Button("Reset")) {
    Send([&](StudioOutbox* out) { session_->Reset(WallClock::now(), out); });
  }
  ImGui::SetNextItemWidth(120);
  if (ImGui::SliderFloat("real-time factor", &speed_, 0.1f, 4.0f, "%.2f",
                         ImGuiSliderFlags_Logarithmic) &&
      link_) {
    Send([&](StudioOutbox* out) {
      session_->SetSpeed(speed_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  ImGui::Checkbox("camera follows", &camera_follows_);
  Record("camera follows");
  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##checkpoint", &checkpoint_);
  ImGui::SameLine();
  if (Button("Save##ckpt")) {
    Send([&](StudioOutbox* out) {
      session_->SaveCheckpoint(checkpoint_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  if (Button("Load##ckpt")) {
    Send([&](StudioOutbox* out) {
      session_->LoadCheckpoint(checkpoint_, WallClock::now(), out);
    });
  }
  const auto& requests = session_->requests();
  if (!requests.empty()) {
    const LiveRequest& r = requests.back();
    ImGui::Text("%s: %s%s%s", r.what.c_str(), RequestText(r.state),
                r.error.empty() ? "" : " - ", r.error.c_str());
  }
}

void LivePanel::DrawSteering() {
  std::vector<std::string> names;
  if (link_) {
    for (const LiveRobot* r : session_->robots()) names.push_back(r->name);
  }
  if (names.empty()) {
    ImGui::TextDisabled("no robot heard yet");
    return;
  }
  if (ImGui::BeginCombo("robot", followed_.c_str())) {
    for (const std::string& n : names) {
      if (ImGui::Selectable(n.c_str(), n == followed_)) followed_ = n;
    }
    ImGui::EndCombo();
  }
  const LiveRobot* robot = session_->robot(followed_);
  if (robot != nullptr && robot->gait) {
    ImGui::Text("gait %s (%s %.2f)%s", robot->gait->gait.c_str(),
                robot->gait->motion.c_str(), robot->gait->strength,
                robot->silent ? "  silent" : "");
  }
  ImGui::SetNextItemWidth(150);
  ImGui::SliderFloat("strength", &strength_, -1.0f, 1.0f, "%.2f");
  const char* const motions[] = {
      "forward",       "backward",       "turn-left", "turn-right",
      "sidewind-left", "sidewind-right", "roll",      "stop"};
  // Four to a row, as wide as the panel allows (fixed widths ran past its
  // edge beside the scroll bar).
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const float button =
      std::floor((ImGui::GetContentRegionAvail().x - 3 * spacing) / 4);
  // Narrow padding: "sidewind-right" is the widest name and must fit.
  ImGui::PushStyleVar(ImGuiStyleVar_FramePadding,
                      ImVec2(1, ImGui::GetStyle().FramePadding.y));
  for (int i = 0; i < IM_ARRAYSIZE(motions); ++i) {
    if (i % 4 != 0) ImGui::SameLine();
    if (Button(motions[i], button)) {
      Send([&](StudioOutbox* out) {
        session_->Steer(followed_, motions[i], strength_, WallClock::now(),
                        out);
      });
    }
  }
  ImGui::PopStyleVar();
  ImGui::SetNextItemWidth(-170);
  ImGui::InputText("##gaitfile", &gait_file_);
  ImGui::SameLine();
  if (Button("Load gait")) {
    // A preset name or a gait file mrsim-gait can read (on its machine).
    Send([&](StudioOutbox* out) {
      session_->SetGait(followed_, gait_file_, WallClock::now(), out);
    });
  }
  ImGui::SameLine();
  if (Button("Save gait")) {
    try {
      if (robot == nullptr || !robot->gait) {
        throw std::runtime_error("no gait heard yet");
      }
      Gait gait;
      gait.name = std::filesystem::path(gait_file_).stem().string();
      gait.kind = ParseGaitKind(robot->gait->kind).value_or(GaitKind::kLinear);
      gait.parameters = GaitParameters::FromVector(std::vector<double>(
          robot->gait->parameters, robot->gait->parameters + 7));
      WriteGaitFile(gait, gait_file_);
      message_ = "wrote " + gait_file_;
      message_is_note_ = true;
    } catch (const std::exception& e) {
      message_ = e.what();
      message_is_note_ = false;
    }
  }
  if (ImGui::TreeNode("gait parameters")) {
    const char* const names7[] = {"A_pitch",   "A_yaw", "phi_pitch",
                                  "phi_yaw",   "T (s)", "offset_pitch",
                                  "offset_yaw"};
    bool changed = false;
    for (int i = 0; i < 7; ++i) {
      ImGui::SetNextItemWidth(150);
      changed |= ImGui::DragFloat(names7[i], &parameters_[i], 0.01f);
    }
    if (changed) {
      Send([&](StudioOutbox* out) {
        session_->SetGaitParameters(
            followed_, std::vector<double>(parameters_, parameters_ + 7),
            WallClock::now(), out);
      });
    }
    ImGui::TreePop();
  }
}

void LivePanel::DrawRecording() {
  ImGui::SetNextItemWidth(-110);
  ImGui::InputText("##recdir", &record_dir_);
  ImGui::SameLine();
  if (!runner_.recording()) {
    if (Button("Record")) {
      try {
        runner_.StartRecording(
            NewRecordingFolder(record_dir_, std::time(nullptr)));
      } catch (const std::exception& e) {
        message_ = e.what();
        message_is_note_ = false;
      }
    }
  } else if (Button("Stop recording")) {
    runner_.StopRecording();
  }
  if (!runner_.record_dir().empty()) {
    // In full: a student looks for it in a file manager.
    std::error_code ec;
    const std::string folder =
        std::filesystem::absolute(runner_.record_dir(), ec).string();
    ImGui::TextWrapped("%s %s",
                       runner_.recording() ? "recording to" : "recorded in",
                       folder.c_str());
  }
  for (const RecordedFile& f : runner_.RecordedFiles()) {
    ImGui::Text("  %s  %lld rows",
                std::filesystem::path(f.path).filename().string().c_str(),
                static_cast<long long>(f.rows));
  }
}

void LivePanel::DrawPlots(float width) {
  const std::vector<std::string> channels = session_->Channels();
  if (!channels.empty()) {
    if (plot_channel_ < 0) {
      // What a user plots first: the followed robot's state.
      const auto it = std::find(channels.begin(), channels.end(),
                                StateChannel(session_->prefix(), followed_));
      plot_channel_ =
          it == channels.end() ? 0 : static_cast<int>(it - channels.begin());
    }
    plot_channel_ =
        std::clamp(plot_channel_, 0, static_cast<int>(channels.size()) - 1);
    const std::vector<std::string> columns =
        session_->Columns(channels[plot_channel_]);
    if (plot_column_ < 0 && !columns.empty()) {
      for (const char* preferred : {"sensor_module0.force", "com.x"}) {
        const auto it = std::find(columns.begin(), columns.end(), preferred);
        if (it != columns.end() && plot_column_ < 0) {
          plot_column_ = static_cast<int>(it - columns.begin());
        }
      }
    }
    ImGui::SetNextItemWidth(width * 0.4f);
    if (ImGui::BeginCombo("##channel", channels[plot_channel_].c_str())) {
      for (int i = 0; i < static_cast<int>(channels.size()); ++i) {
        if (ImGui::Selectable(channels[i].c_str(), i == plot_channel_)) {
          plot_channel_ = i;
          plot_column_ = 0;
        }
      }
      ImGui::EndCombo();
    }
    if (!columns.empty()) {
      plot_column_ =
          std::clamp(plot_column_, 0, static_cast<int>(columns.size()) - 1);
      ImGui::SameLine();
      ImGui::SetNextItemWidth(width * 0.35f);
      if (ImGui::BeginCombo("##column", columns[plot_column_].c_str(),
                            ImGuiComboFlags_HeightLarge)) {
        // Hundreds of columns: typing part of a name narrows the list.
        if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
        ImGui::InputTextWithHint("##filter", "type to filter (force, angle)",
                                 &column_filter_);
        for (int i = 0; i < static_cast<int>(columns.size()); ++i) {
          if (!column_filter_.empty() &&
              columns[i].find(column_filter_) == std::string::npos) {
            continue;
          }
          if (ImGui::Selectable(columns[i].c_str(), i == plot_column_)) {
            plot_column_ = i;
          }
        }
        ImGui::EndCombo();
      }
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%s", columns[plot_column_].c_str());
      }
      ImGui::SameLine();
      if (Button("Add plot")) {
        session_->AddPlot(channels[plot_channel_], columns[plot_column_]);
      }
    }
  }
  std::vector<float> values;
  const auto& plots = session_->plots();
  for (size_t i = 0; i < plots.size(); ++i) {
    PlotSeries& p = *plots[i];
    values.assign(p.values().begin(), p.values().end());
    ImGui::PushID(static_cast<int>(i));
    // The name and the numbers above the curve (written on it they hid
    // it): the newest value, and the range the curve spans, top to bottom.
    ImGui::TextUnformatted(p.column().c_str());
    if (!values.empty()) {
      const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
      ImGui::TextDisabled("now %.4g   curve from %.4g to %.4g", values.back(),
                          *lo, *hi);
    }
    ImGui::PlotLines("##curve", values.data(), static_cast<int>(values.size()),
                     0, nullptr, FLT_MAX, FLT_MAX, ImVec2(width * 0.95f, 90));
    if (ImGui::IsItemHovered() && values.size() >= 2) {
      // ImGui's own tooltip names the sample's index; a student wants the
      // time. The same point as ImGui picks (imgui_widgets.cpp, PlotEx).
      const ImVec2 pad = ImGui::GetStyle().FramePadding;
      const float left = ImGui::GetItemRectMin().x + pad.x;
      const float right = ImGui::GetItemRectMax().x - pad.x;
      const float t = std::clamp(
          (ImGui::GetIO().MousePos.x - left) / std::max(1.0f, right - left),
          0.0f, 0.9999f);
      const size_t k = std::min(values.size() - 1,
                                static_cast<size_t>(t * (values.size() - 1)));
      ImGui::SetTooltip("t = %.2f s\n%s = %.4g", p.times()[k],
                        p.column().c_str(), values[k]);
    }
    bool paused = p.paused();
    if (ImGui::Checkbox("pause", &paused)) p.set_paused(paused);
    ImGui::SameLine();
    if (ImGui::SmallButton("PNG")) {
      try {
        // Beside the recordings, named in full: a student looks for it
        // in a file manager.
        const std::filesystem::path folder =
            record_dir_.empty() ? "." : record_dir_;
        std::filesystem::create_directories(folder);
        const std::string png =
            std::filesystem::absolute(folder / (p.column() + ".png")).string();
        ExportPlotPng(p, png);
        png_note_ = {&p, "wrote " + png};
      } catch (const std::exception& e) {
        png_note_ = {&p, e.what()};
      }
    }
    // Away from PNG: a slip of the mouse should not lose the plot.
    ImGui::SameLine(width * 0.95f - ImGui::CalcTextSize("remove").x -
                    2 * ImGui::GetStyle().FramePadding.x);
    const bool remove = ImGui::SmallButton("remove");
    // What the PNG button did, under its plot (at the top of the panel it
    // moved every button down a line).
    if (png_note_.first == &p) {
      ImGui::PushTextWrapPos(width * 0.95f);
      ImGui::TextDisabled("%s", png_note_.second.c_str());
      ImGui::PopTextWrapPos();
    }
    ImGui::PopID();
    if (remove && png_note_.first == &p) png_note_ = {};
    if (remove) {
      session_->RemovePlot(i);
      break;
    }
  }
}

RunOptions LivePanel::FormRun() const {
  RunOptions o;
  o.lcm_url = url_;
  o.prefix = prefix_;
  o.clock = kClocks[clock_];
  o.rate = rate_;
  o.speed = speed_;
  return o;
}

void LivePanel::EndReplay() {
  if (replay_) ++replay_revision_;
  replay_.reset();
  watching_.clear();
}

void LivePanel::WatchBest() {
  const auto best = optimise_.Best();
  if (!best) {
    message_ = "no generation finished yet";
    message_is_note_ = false;
    return;
  }
  Play(*best);
}

void LivePanel::Play(const GenerationRow& row) {
  try {
    BestReplay best = MakeBestReplay(optimise_.options(), row);
    const LiveRobot* robot = session_->robot(best.robot);
    watching_ = fmt::format("playing generation {}'s best ({:.4g}){}",
                            best.generation + 1, best.fitness,
                            best.body ? ", its body and gait" : "");
    const std::vector<double> p = best.gait.parameters.ToVector();
    for (int i = 0; i < 7; ++i) parameters_[i] = static_cast<float>(p[i]);
    if (!best.body && !replay_ && robot != nullptr && runner_.running()) {
      // The design runs: the gait alone changes, the robot goes on.
      Send([&](StudioOutbox* out) {
        session_->SetGaitParameters(best.robot, p, WallClock::now(), out);
      });
      return;
    }
    // A new body (or nothing running): the run restarts with the best's
    // scenario and gait, while the optimisation goes on.
    const RunOptions o = WriteBestReplay(
        best, optimise_.options().out_dir + "/watch", FormRun());
    runner_.Start(o);
    Connect(url_, prefix_);
    if (best.body) {
      replay_ = std::move(best);
      ++replay_revision_;
    } else {
      EndReplay();
    }
    message_.clear();
  } catch (const std::exception& e) {
    message_ = e.what();
    message_is_note_ = false;
  }
}

void LivePanel::DrawOptimise(const LiveDesign& design, float width) {
  static const char* const kAlgorithms[] = {"ga", "sa", "pso", "cmaes",
                                            "random"};
  ImGui::SetNextItemWidth(-60);
  ImGui::InputText("genome", &genome_path_);
  if (Button("Load genome")) {
    try {
      genome_ = ReadGenomeFile(GenomePathFor(genome_path_, design.path));
      message_.clear();
    } catch (const std::exception& e) {
      message_ = e.what();
      message_is_note_ = false;
    }
  }
  if (!genome_.genes.empty() &&
      ImGui::BeginTable("genes", 5,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    for (const char* h : {"gene", "on", "lower", "upper", "start"}) {
      ImGui::TableSetupColumn(h);
    }
    ImGui::TableHeadersRow();
    for (GeneSpec& g : genome_.genes) {
      ImGui::PushID(g.name.c_str());
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(g.name.c_str());
      ImGui::TableNextColumn();
      ImGui::Checkbox("##on", &g.enabled);
      for (double* v : {&g.lower, &g.upper, &g.start}) {
        ImGui::TableNextColumn();
        ImGui::SetNextItemWidth(-1);
        ImGui::PushID(v);
        ImGui::InputDouble("##v", v, 0, 0, "%.3g");
        ImGui::PopID();
      }
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  ImGui::SetNextItemWidth(90);
  ImGui::Combo("algorithm", &algorithm_, kAlgorithms,
               IM_ARRAYSIZE(kAlgorithms));
  ImGui::SameLine();
  ImGui::Checkbox("farm", &farm_);
  if (farm_) {
    // Two populations taking turns keep a farm's workers busy through
    // each generation's slowest episode (docs/optimizer.md).
    ImGui::SameLine();
    ImGui::SetNextItemWidth(60);
    ImGui::InputInt("islands", &islands_, 0, 0, kNumberFlags);
    Record("islands");
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "Populations taking turns: with 2, workers go on with one while\n"
          "the other's generation ends. Each gets half the generations.");
    }
  }
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("generations", &generations_, 0, 0, kNumberFlags);
  Record("generations");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("population", &population_, 0, 0, kNumberFlags);
  Record("population");
  ImGui::SetNextItemWidth(80);
  ImGui::InputFloat("episode s", &episode_, 0, 0, "%.1f", kNumberFlags);
  Record("episode");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("seed", &seed_);
  ImGui::SetNextItemWidth(-60);
  ImGui::InputText("folder", &opt_dir_);
  auto start = [&](int jump_to) {
    try {
      message_.clear();
      if (design.path.empty() || design.dirty) {
        throw std::invalid_argument("save the design first");
      }
      if (genome_.genes.empty()) {
        genome_ = ReadGenomeFile(GenomePathFor(genome_path_, design.path));
      }
      OptimiseOptions o;
      o.scenario_path = design.path;
      o.out_dir = opt_dir_;
      o.genome = genome_;
      if (!design.robots.empty()) o.genome.robot = design.robots.front();
      o.algorithm = kAlgorithms[algorithm_];
      o.generations = generations_;
      o.population = population_;
      o.seed = static_cast<unsigned>(std::max(0, seed_));
      o.episode_s = episode_;
      o.farm = farm_;
      o.islands = farm_ ? islands_ : 1;
      o.lcm_url = url_;
      if (jump_to > 0) {
        optimise_.Jump(jump_to, o);
      } else {
        optimise_.Start(o);
      }
    } catch (const std::exception& e) {
      message_ = e.what();
      message_is_note_ = false;
    }
  };
  const OptimiseProgress& p = optimise_.progress();
  if (!p.running) {
    if (Button("Start optimisation")) start(-1);
  } else if (Button("Stop optimisation")) {
    optimise_.Stop();
  }
  ImGui::SameLine();
  if (Button("Watch best")) WatchBest();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("##jump", &jump_to_);
  ImGui::SameLine();
  if (Button("Jump to generation")) start(std::max(1, jump_to_));
  if (!watching_.empty()) ImGui::TextUnformatted(watching_.c_str());
  if (optimise_.replay_pending()) {
    ImGui::TextDisabled("waiting for generation %d...", jump_to_);
  }
  if (const std::string stall = optimise_.StallWarning(); !stall.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.6f, 0.2f, 1));
    ImGui::TextWrapped("%s", stall.c_str());
    ImGui::PopStyleColor();
  }
  // "...: the checkpoint was made with other settings: population=8 (this
  // run: 6) (fingerprint ...); use the same, ...": the settings that
  // differ, in the panel's words; the whole line is in the console.
  const std::string kOther = "made with other settings: ";
  const size_t other = p.failure.find(kOther);
  const bool other_settings = p.finished && other != std::string::npos;
  if (other_settings) {
    std::string differ = p.failure.substr(other + kOther.size());
    differ = differ.substr(0, differ.find(" (fingerprint"));
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.35f, 1));
    ImGui::TextWrapped(
        "Not started: the folder '%s' holds a run made with other settings "
        "(%s).",
        optimise_.options().out_dir.c_str(), differ.c_str());
    ImGui::PopStyleColor();
    ImGui::TextWrapped(
        "Start a new run in a new folder, or set those settings back to "
        "continue the old one.");
    if (Button("Start in a new folder")) {
      // "optimise" -> "optimise-2", "optimise-3", ...: the first free.
      const std::string base = opt_dir_;
      for (int k = 2; std::filesystem::exists(opt_dir_); ++k) {
        opt_dir_ = base + "-" + std::to_string(k);
      }
      start(-1);
    }
  } else if (p.finished && p.exit_code != 0 && !p.failure.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.35f, 1));
    ImGui::TextWrapped("failed: %s", p.failure.c_str());
    ImGui::PopStyleColor();
  }
  // With other settings the rows on show are the old run's, not progress.
  if (!other_settings &&
      (p.running || p.finished || p.stopped || !p.rows.empty())) {
    const GenerationRow* last = p.rows.empty() ? nullptr : &p.rows.back();
    if (p.running) {
      // Wrapped: the panel is narrower than the whole line.
      ImGui::TextWrapped(
          "generation %zu of %d, best so far %.4g, %.2f evals/s, %d "
          "worker%s, ETA %s",
          p.rows.size(), p.generations, last ? last->best_so_far : 0.0,
          p.evals_per_s, p.workers, p.workers == 1 ? "" : "s", p.eta.c_str());
    } else {
      ImGui::TextWrapped(
          "%s after generation %zu of %d, best so far %.4g%s",
          p.stopped ? "stopped" : (p.exit_code == 0 ? "finished" : "failed"),
          p.rows.size(), p.generations, last ? last->best_so_far : 0.0,
          p.stopped ? " (Start continues from there)" : "");
      // mrsim-opt writes the best so far on a stop too.
      std::error_code ec;
      const std::filesystem::path best =
          std::filesystem::path(optimise_.options().out_dir) / "best_gait.xml";
      if (!p.rows.empty() && std::filesystem::exists(best, ec)) {
        ImGui::TextWrapped(
            "best gait: %s",
            std::filesystem::absolute(best, ec).string().c_str());
      }
    }
    // Best so far (it only rises) and each generation's mean, each with
    // its range written on it: the curves have no axes.
    const auto curve = [&](const char* label, auto value) {
      std::vector<float> v;
      for (const GenerationRow& r : p.rows) {
        v.push_back(static_cast<float>(value(r)));
      }
      char range[64] = "";
      if (!v.empty()) {
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        std::snprintf(range, sizeof(range), "%.4g .. %.4g", *lo, *hi);
      }
      ImGui::PlotLines(label, v.data(), static_cast<int>(v.size()), 0, range,
                       FLT_MAX, FLT_MAX, ImVec2(width * 0.62f, 50));
    };
    curve("best so far", [](const GenerationRow& r) { return r.best_so_far; });
    curve("mean", [](const GenerationRow& r) { return r.mean; });
  }
}

void LivePanel::DrawConsole(float height) {
  // Long lines scroll sideways rather than being cut off.
  ImGui::BeginChild("console", ImVec2(0, height), true,
                    ImGuiWindowFlags_HorizontalScrollbar);
  for (const std::string& line : runner_.console()) {
    ImGui::TextUnformatted(line.c_str());
  }
  for (const std::string& line : optimise_.console()) {
    ImGui::TextUnformatted(line.c_str());
  }
  if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) {
    ImGui::SetScrollHereY(1.0f);
  }
  ImGui::EndChild();
}

void LivePanel::Draw(float x, float y, float w, float h,
                     const LiveDesign& design) {
  ImGui::SetNextWindowPos(ImVec2(x, y));
  ImGui::SetNextWindowSize(ImVec2(w, h));
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
  if (Header("Simulator", true)) {
    DrawControls();
  }
  if (Header("Steering", true)) {
    DrawSteering();
  }
  if (Header("Recording", false)) DrawRecording();
  if (Header("Plots", false)) DrawPlots(w);
  if (Header("Optimise", false)) DrawOptimise(design, w);
  if (Header("Console", false)) DrawConsole(240);
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
  }
  if (robot != nullptr && robot->gait) {
    ImGui::Text("gait   %s (%s)", robot->gait->gait.c_str(),
                robot->gait->motion.c_str());
  }
  ImGui::End();
}

}  // namespace mrsim::studio
