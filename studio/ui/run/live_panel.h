// The studio's Run panel (Dear ImGui): run the design or attach to a
// simulation, simulator controls, steering buttons and arrow keys, gait
// parameters, recording, live plots, a camera's picture and the children's
// console. A thin face over studio/live (LiveSession, LiveLink,
// LiveRunner): every button is one LCM message or one process a script
// could send or start. One file per section: live_panel.cc (connection, keys,
// overlay, the panel's frame) and live_<section>_section.cc (Run, Simulator,
// Steering, Camera, Locks, Recording, Plots, Optimise, Console), sharing
// live_panel_common.h.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "gait_controller/gait.h"
#include "gait_controller/gait_parameters.h"
#include "optimizer/episode/episode.h"
#include "optimizer/search/algorithm.h"
#include "optimizer/search/algorithm_registry.h"
#include "studio/live/best_replay.h"
#include "studio/live/live_link.h"
#include "studio/live/live_runner.h"
#include "studio/live/live_session.h"
#include "studio/live/optimise_session.h"
#include "studio/ui/run/controller_panel.h"
#include "studio/ui/widgets/layout_recorder.h"
#include "studio/ui/widgets/task_picker.h"

namespace mrsim::studio {

class CameraFeed;

// What the panel needs to know of the design.
struct LiveDesign {
  std::string path;  // saved file, "" before the first save
  bool dirty = false;
  std::vector<std::string> robots;
  // Parts overlapping at the start, one line per pair ("robot 'snake'
  // module 0 frame 0 / scene object 'ball': 12.0 mm"): Run refuses them
  // unless the user allows it, as mrsim-sim does.
  std::vector<std::string> overlaps;
  // Saves the design as Save does; returns its path once saved, "" when
  // it is not (Save As asks where first, or saving failed).
  std::function<std::string()> save;
  // The shown robots' camera pictures (the Camera section); null: none.
  CameraFeed* camera = nullptr;
};

class LivePanel {
 public:
  // `search_path`: where mrsim-sim, mrsim-gait and mrsim-log are looked up.
  LivePanel(std::vector<std::string> search_path, LayoutRecorder* layout);
  ~LivePanel();

  // Takes what arrived (LCM, children's output); once per frame.
  void Poll();
  void Draw(float x, float y, float w, float h, const LiveDesign& design);
  // Sim time, real-time factor, speed and gait of the followed robot, in a
  // corner of the 3-D view at (x, y); nothing when not connected.
  void DrawOverlay(float x, float y);
  // Arrow keys steer the followed robot while something runs; returns
  // whether the key was used.
  bool OnKey(int glfw_key);
  bool connected() const { return link_ != nullptr; }
  // As the Attach button: hear the simulation at `url` with `prefix`.
  // Throws std::runtime_error when LCM cannot open the URL.
  void Attach(const std::string& url, const std::string& prefix) {
    url_ = url;
    prefix_ = prefix;
    Connect(url, prefix);
  }
  LiveSession& mutable_session() { return *session_; }
  // The Run form (clock, rate, speed, controller and its script or gait)
  // as the run settings Save writes into the design.
  RunSettings FormRunSettings() const;
  // Fills the Run form from an opened design's saved run settings; none
  // (a file from before they were saved): the defaults.
  void LoadRunSettings(const std::optional<RunSettings>& run);
  // The Optimise form as Save writes it into the design (<optimization>);
  // none while a design without one has the form as it opened.
  std::optional<OptimizationSettings> FormOptimisation() const;
  // Fills the Optimise form from an opened design's saved setup; none: the
  // form as it was (a note says when the setup cannot be shown).
  void LoadOptimisation(const std::optional<OptimizationSettings>& saved);
  // Something live is shown (a simulation heard, processes or an
  // optimisation running): the window redraws at a steady rate.
  bool animating() const {
    return link_ != nullptr || runner_.running() ||
           optimise_.progress().running;
  }
  // What quitting would cut off, in words ("a run", "a recording", "an
  // optimisation"); empty when nothing is going on.
  std::vector<std::string> InProgress() const {
    std::vector<std::string> busy;
    if (runner_.running()) busy.push_back("a run");
    if (runner_.recording()) busy.push_back("a recording");
    if (optimise_.progress().running) busy.push_back("an optimisation");
    return busy;
  }
  const LiveSession& session() const { return *session_; }
  // The scenario the live run plays: the best of an optimisation with body
  // genes, or the design as it was saved when Run started (edits made
  // while it runs wait for the next Run); null when nothing runs. Its
  // revision changes whenever it does.
  const Scenario* live_scenario() const {
    if (replay_) return &replay_->scenario;
    return running_ ? &*running_ : nullptr;
  }
  int live_scenario_revision() const { return replay_revision_; }
  // The robot steered by keys and buttons ("" when none is heard).
  const std::string& followed() const { return followed_; }
  // The Camera section was open in the last Draw: its picture is wanted.
  bool camera_shown() const { return camera_shown_; }
  // Whether the 3-D view's camera moves with the running robots.
  bool camera_follows() const { return camera_follows_; }

 private:
  void Connect(const std::string& url, const std::string& prefix);
  void Disconnect();
  void Send(const std::function<void(StudioOutbox*)>& request);
  void DrawRun(const LiveDesign& design);
  // Beside Run: why it is refused (parts overlapping at the start) and the
  // box that allows it.
  void DrawOverlapRefusal(const LiveDesign& design, bool refused);
  void DrawControls();
  void DrawSteering();
  void DrawRecording();
  // Locks of the followed robot: state, break force, Detach / Attach.
  void DrawLocks();
  void DrawPlots(float width);
  void DrawConsole(float height);
  // The chosen camera's picture and the chooser (live_camera_section.cc).
  void DrawCamera(CameraFeed* feed, float width);
  void DrawOptimise(const LiveDesign& design, float width);
  // Fitness, base gait and the chosen algorithm's own settings.
  void DrawOptimiseSettings();
  // Its "reality gap" header: the robust episodes' gap, field by field.
  void DrawRealityGap();
  // What the genes drive (the gait, the design's Lua script, a network)
  // and, for a script, its declared params; returns whether the gait's
  // genome is the one to edit.
  bool DrawGenesDrive();
  // The gait's genome: its file and the table of its genes.
  void DrawGenome(const LiveDesign& design);
  void WatchBest();
  // Plays an optimisation's individual live: its gait sent to the running
  // design, or (body genes, or nothing running) a run of its scenario.
  void Play(const GenerationRow& row);
  void EndReplay();
  // The run settings of the form (clock, rate, speed, URL, prefix).
  RunOptions FormRun() const;
  // The Optimise form's settings (not the design, folder or farm).
  OptimiseOptions FormOptimiseOptions() const;
  // Whether the followed robot can be steered, in the words the panel
  // shows: the session's view, told who drives the robot when this window
  // started the run.
  Steering FollowedSteering() const;

  LayoutRecorder* layout_;
  LiveRunner runner_;
  ControllerPanel controller_;  // who drives the robots on Run
  OptimiseSession optimise_;
  TaskPicker task_picker_;
  GenomeSpec genome_;
  std::string genome_path_ = "scenarios/forward_gait.genome.xml";
  // What the genes drive: 0 the gait (genome_), 1 the design's Lua script
  // (its declared params), 2 a neural network of mlp_hidden_ ("8", "8,8").
  int genes_drive_ = 0;
  std::string mlp_hidden_ = "8";
  // The Lua script's declared params as genes, made again only when the
  // script changes (running its top level every frame would cost a frame).
  std::string lua_genes_source_;
  GenomeSpec lua_genes_;
  std::string lua_genes_error_;
  std::string opt_dir_ = "optimise";
  // The last PNG export's outcome, shown under the plot it is for.
  std::pair<const PlotSeries*, std::string> png_note_;
  int algorithm_ = AlgorithmIndex(AlgorithmKind::kCmaes);
  // The form's fitness, base gait and algorithm settings (each algorithm's
  // own from the registry, AlgorithmInfo::settings).
  FitnessSettings fitness_;
  RobustSettings robust_;
  std::string base_gait_ = "forward";
  AlgorithmSettings algorithm_settings_;
  int generations_ = 10;
  int population_ = 8;
  int seed_ = 1;
  double episode_ = 5;
  // Whether the opened design had an optimisation setup, and the form's
  // as it opened: a design without one gets one only once it is changed.
  bool had_optimisation_ = false;
  OptimizationSettings opened_optimisation_;
  bool farm_ = false;
  int islands_ = 1;
  int jump_to_ = 1;
  std::optional<BestReplay> replay_;  // what runs, when not the design
  int replay_revision_ = 0;
  std::optional<Scenario> running_;  // what Run started
  // Who drives the robots of the run this window started (none when
  // attached to someone else's simulation).
  std::optional<ControllerKind> run_controller_;
  std::string watching_;  // "playing generation 3's best ..."
  std::unique_ptr<LiveSession> session_;
  std::unique_ptr<LiveLink> link_;
  StudioOutbox outbox_;
  std::string followed_;
  // Per robot, the locks detached from this window (a released lock not
  // among them broke).
  std::map<std::string, std::set<std::string>> detached_locks_;
  std::string message_;
  bool message_is_note_ = false;  // "wrote ...": not an error
  bool allow_overlap_ = false;    // Run with parts overlapping at the start
  // Form state.
  std::string url_ = "udpm://239.255.76.67:7667?ttl=0";
  std::string prefix_ = "MRSIM";
  int clock_ = 0;  // into ClockModes().entries(): realtime
  // Doubles, as the design saves them: a saved 33.3 Hz stays 33.3.
  double rate_ = 100;
  double speed_ = 1;
  bool camera_follows_ = true;
  bool camera_shown_ = false;  // the Camera section was open
  int step_periods_ = 10;
  float strength_ = 1;
  float parameters_[GaitParameters::kVectorSize] = {1, 0, 2.5f, 0, 4, 0, 0};
  // The gait the parameters above were last tuned to (or the design's
  // saved one): Save keeps it in the design (<run><tunedGait>) and Run
  // starts the robots with it; none until the user tunes or opens one.
  std::optional<Gait> tuned_gait_;
  std::string checkpoint_ = "studio.checkpoint";
  std::string gait_file_ = "studio.gait.xml";
  std::string record_dir_ = "recordings";
  int plot_channel_ = -1;      // -1: the followed robot's state channel
  std::string column_filter_;  // typed in the column list
  int plot_column_ = -1;       // -1: a force sensor, else com.x
};

}  // namespace mrsim::studio
