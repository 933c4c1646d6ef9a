// The Run panel's Optimise section: genome, settings, start, stop, jump,
// progress curves, and playing an individual live.
// Part of LivePanel (live_panel.h), one file per section.
#include "gait_controller/gait_presets.h"
#include "optimizer/episode/controller_genes.h"
#include "optimizer/episode/controller_spec.h"
#include "optimizer/episode/task.h"
#include "optimizer/search/algorithm_registry.h"
#include "sim_core/scenario/scenario_schema.h"
#include "studio/live/saved_optimisation.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {
namespace {

// For the window tests (--layout-dump): the genes, task, robust settings
// and gap the form holds, and the command line Start ran.
void RecordForm(LayoutRecorder* layout, const GenomeSpec& genome,
                const std::string& task, const RobustSettings& robust,
                const std::vector<std::string>& command) {
  if (layout == nullptr || !layout->enabled()) return;
  std::string genes;
  for (const GeneSpec& g : genome.genes) genes += " " + g.name;
  layout->State("optimise genes", fmt::format("{}{}", genome.size(), genes));
  layout->State("optimise task", task);
  const RealityGap& g = robust.gap;
  layout->State(
      "optimise robust",
      fmt::format("{} {} sensor_noise={:g} sensor_bias={:g} joint_noise={:g} "
                  "motor_noise={:g} latency={:g} backlash={:g} "
                  "max_accel={:g} friction_range={:g} mass_range={:g} "
                  "gain_range={:g} terrain_range={:g}",
                  robust.episodes, robust.mode, g.sensor_noise, g.sensor_bias,
                  g.joint_noise, g.motor_noise, g.latency, g.backlash,
                  g.max_accel, g.friction_range, g.mass_range, g.gain_range,
                  g.terrain_range));
  std::string line;
  for (const std::string& a : command) line += (line.empty() ? "" : " ") + a;
  layout->State("optimise command", line);
}

}  // namespace

// The robust episodes' reality gap, as the design file's <optimization>
// gap fields: label, unit, help and limits are the schema's rows (so the
// limits are RealityGap::Validate's), each value clamped to them.
void LivePanel::DrawRealityGap() {
  ImGui::Indent(8);
  if (RecordedHeader(layout_, "reality gap", false)) {
    RealityGap& g = robust_.gap;
    const std::pair<const char*, double*> kValues[] = {
        {"gapSensorNoise", &g.sensor_noise},
        {"gapSensorBias", &g.sensor_bias},
        {"gapJointNoise", &g.joint_noise},
        {"gapMotorNoise", &g.motor_noise},
        {"gapLatency", &g.latency},
        {"gapBacklash", &g.backlash},
        {"gapMaxAccel", &g.max_accel},
        {"gapFrictionRange", &g.friction_range},
        {"gapMassRange", &g.mass_range},
        {"gapGainRange", &g.gain_range},
        {"gapTerrainRange", &g.terrain_range}};
    const std::vector<FieldSpec>& specs =
        FieldSpecsOf(PartKind::kOptimizationSettings);
    for (const auto& entry : kValues) {
      const std::string xml = entry.first;
      double* value = entry.second;
      const auto spec =
          std::find_if(specs.begin(), specs.end(),
                       [&](const FieldSpec& f) { return xml == f.info.xml; });
      if (spec == specs.end()) continue;
      const FieldInfo& info = spec->info;
      const std::string label =
          *info.unit ? fmt::format("{} ({})", info.label, info.unit)
                     : std::string(info.label);
      ImGui::SetNextItemWidth(90);
      // A click selects the value whole, as in every number field here.
      if (ImGui::InputDouble(label.c_str(), value, 0, 0, "%.4g",
                             kNumberFlags)) {
        *value = *value >= info.limits.min ? *value : info.limits.min;
        *value = std::min(*value, info.limits.max);
      }
      RecordItem(layout_, label);
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%s\n%s: typical %s, %g..%g (<optimization><%s>)",
                          info.help, info.unit[0] ? info.unit : "no unit",
                          spec->default_text.c_str(), info.limits.min,
                          info.limits.max, info.xml);
      }
    }
  }
  ImGui::Unindent(8);
}

void LivePanel::DrawOptimiseSettings() {
  if (!RecordedHeader(layout_, "Fitness and algorithm settings", false)) {
    return;
  }
  ImGui::Indent(8);
  // Fitness = distance * w_distance + speed * w_speed - energy * w_energy
  //           - drift * w_drift - fell * w_fall (docs/optimizer.md).
  // The words of the one distance-mode table: a new mode shows up here.
  const std::vector<std::string> modes = DistanceModes().Names();
  int mode = static_cast<int>(
      std::find(modes.begin(), modes.end(), ToString(fitness_.distance_mode)) -
      modes.begin());
  ImGui::SetNextItemWidth(110);
  if (ImGui::Combo(
          "distance", &mode,
          +[](void* data, int i, const char** text) {
            *text = static_cast<const std::vector<std::string>*>(data)
                        ->at(i)
                        .c_str();
            return true;
          },
          const_cast<std::vector<std::string>*>(&modes),
          static_cast<int>(modes.size()))) {
    fitness_.distance_mode = ParseDistanceMode(modes.at(mode));
  }
  RecordItem(layout_, "distance mode");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "forward: along +x (the chain's head)\nnet: any horizontal "
        "direction\nup: rise along +z (climbing)");
  }
  struct Weight {
    const char* label;
    double* value;
    const char* help;
  };
  for (const Weight& w :
       {Weight{"w distance", &fitness_.w_distance, "per metre"},
        Weight{"w speed", &fitness_.w_speed, "per m/s"},
        Weight{"w energy", &fitness_.w_energy, "per joule (subtracted)"},
        Weight{"w drift", &fitness_.w_drift,
               "per metre of sideways drift (subtracted)"},
        Weight{"w fall", &fitness_.w_fall, "if it fell (subtracted)"}}) {
    ImGui::SetNextItemWidth(90);
    ImGui::InputDouble(w.label, w.value, 0, 0, "%.4g");
    RecordItem(layout_, w.label);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", w.help);
  }
  // The reality gap (docs/optimizer.md): a gait that works in K perturbed
  // worlds rather than only in the nominal one.
  ImGui::SetNextItemWidth(90);
  if (ImGui::InputInt("robust episodes", &robust_.episodes, 0, 0,
                      kNumberFlags)) {
    robust_.episodes =
        std::clamp(robust_.episodes, 0, RobustSettings::kMaxEpisodes);
  }
  RecordItem(layout_, "robust episodes");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "K > 0: each genome runs K episodes, each in a world of the "
        "reality gap\n(friction, masses, servo gains and noise varied as a "
        "real robot's are),\nand scores their mean or worst (--robust K)");
  }
  ImGui::SameLine();
  bool worst = robust_.mode == "worst";
  if (ImGui::Checkbox("worst of them", &worst)) {
    robust_.mode = worst ? "worst" : "mean";
  }
  RecordItem(layout_, "robust worst");
  DrawRealityGap();
  ImGui::SetNextItemWidth(-90);
  ImGui::InputText("base gait", &base_gait_);
  RecordItem(layout_, "base gait");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "The gait the genes modify: a preset (%s) or a gait "
        "file",
        GaitPresetNames().c_str());
  }
  // The chosen algorithm's own settings, as the registry lists them.
  const AlgorithmInfo& info = Algorithms().at(algorithm_);
  if (info.settings.empty()) {
    ImGui::TextDisabled("%s has no settings of its own", info.title);
  }
  for (const AlgorithmSetting& setting : info.settings) {
    double value = setting.Get(algorithm_settings_);
    ImGui::SetNextItemWidth(90);
    if (ImGui::InputDouble(setting.flag, &value, 0, 0,
                           setting.whole ? "%.0f" : "%.4g")) {
      setting.Set(&algorithm_settings_,
                  std::clamp(value, setting.min, setting.max));
    }
    RecordItem(layout_, std::string("setting ") + setting.flag);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", setting.help);
  }
  ImGui::Unindent(8);
}

bool LivePanel::DrawGenesDrive() {
  const char* const drives[] = {"the gait", "the design's Lua script",
                                "a neural network"};
  ImGui::SetNextItemWidth(-110);
  ImGui::Combo("genes drive", &genes_drive_, drives, IM_ARRAYSIZE(drives));
  RecordItem(layout_, "genes drive");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "What the optimiser tunes (mrsim-opt --controller): the built-in\n"
        "gait's parameters, the params your Lua script declares, or the\n"
        "weights of a small neural network (docs/optimizer.md)");
  }
  if (genes_drive_ == 2) {
    ImGui::SetNextItemWidth(80);
    ImGui::InputText("hidden layer sizes", &mlp_hidden_);
    RecordItem(layout_, "hidden layer sizes");
    ImGui::TextDisabled(
        "the network's weights are the genes (mrsim-nn runs it)");
    return false;
  }
  if (genes_drive_ != 1) return true;
  const std::string& source = controller_.lua_source();
  if (source != lua_genes_source_) {
    lua_genes_source_ = source;
    lua_genes_ = GenomeSpec{};
    lua_genes_error_.clear();
    try {
      ControllerSpec spec;
      spec.kind = ControllerSpec::Kind::kLua;
      spec.source = source;
      spec.name = "the design's script";
      lua_genes_ = ControllerGenome(spec, nullptr);
    } catch (const std::exception& e) {
      lua_genes_error_ = e.what();
    }
  }
  if (!lua_genes_error_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.35f, 0.3f, 1));
    ImGui::TextWrapped("%s", lua_genes_error_.c_str());
    ImGui::PopStyleColor();
    RecordItem(layout_, "lua genes error");
    return false;
  }
  // Read from the script's params table: ranges are edited there.
  ImGui::TextDisabled("genes: the params the script declares");
  if (ImGui::BeginTable("lua genes", 4,
                        ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
    for (const char* h : {"param", "lower", "upper", "start"}) {
      ImGui::TableSetupColumn(h);
    }
    ImGui::TableHeadersRow();
    for (const GeneSpec& g : lua_genes_.genes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(g.name.c_str());
      for (double v : {g.lower, g.upper, g.start}) {
        ImGui::TableNextColumn();
        ImGui::Text("%.4g", v);
      }
    }
    ImGui::EndTable();
  }
  RecordItem(layout_, "lua genes " + std::to_string(lua_genes_.size()));
  return false;
}

void LivePanel::DrawGenome(const LiveDesign& design) {
  ImGui::SetNextItemWidth(-60);
  ImGui::InputText("genome", &genome_path_);
  if (RecordedButton(layout_, "Load genome")) {
    try {
      genome_ = ReadGenomeFile(GenomePathFor(genome_path_, design.path));
      message_.clear();
    } catch (const std::exception& e) {
      message_ = e.what();
      message_is_note_ = false;
    }
  }
  // The built-in gene sets (mrsim-opt --genes): every gait parameter, and
  // those with the CPG's (docs/optimizer.md).
  for (const char* set : {"sine", "cpg"}) {
    ImGui::SameLine();
    const std::string label = std::string(set) + " genes";
    if (RecordedButton(layout_, label.c_str())) {
      genome_ = BuiltInGenome(set);
      message_.clear();
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
}

void LivePanel::DrawOptimise(const LiveDesign& design, float width) {
  // The optimiser's registry: a new algorithm shows up here by itself.
  const std::vector<AlgorithmInfo>& algorithms = Algorithms();
  RecordForm(layout_, genome_, task_picker_.task(), robust_,
             optimise_.command());
  if (DrawGenesDrive()) DrawGenome(design);
  ImGui::SetNextItemWidth(90);
  ImGui::Combo(
      "algorithm", &algorithm_,
      +[](void* data, int i, const char** text) {
        *text =
            static_cast<const std::vector<AlgorithmInfo>*>(data)->at(i).name;
        return true;
      },
      const_cast<std::vector<AlgorithmInfo>*>(&algorithms),
      static_cast<int>(algorithms.size()));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s", algorithms.at(algorithm_).summary);
  ImGui::SameLine();
  ImGui::Checkbox("farm", &farm_);
  if (farm_) {
    // Two populations taking turns keep a farm's workers busy through
    // each generation's slowest episode (docs/optimizer.md).
    ImGui::SameLine();
    ImGui::SetNextItemWidth(60);
    ImGui::InputInt("islands", &islands_, 0, 0, kNumberFlags);
    RecordItem(layout_, "islands");
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip(
          "Populations taking turns: with 2, workers go on with one while\n"
          "the other's generation ends. Each gets half the generations.");
    }
  }
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("generations", &generations_, 0, 0, kNumberFlags);
  RecordItem(layout_, "generations");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("population", &population_, 0, 0, kNumberFlags);
  RecordItem(layout_, "population");
  ImGui::SetNextItemWidth(80);
  ImGui::InputDouble("episode s", &episode_, 0, 0, "%.1f", kNumberFlags);
  RecordItem(layout_, "episode");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("seed", &seed_);
  task_picker_.Draw(layout_);
  ImGui::SetNextItemWidth(-60);
  ImGui::InputText("folder", &opt_dir_);
  DrawOptimiseSettings();
  auto start = [&](int jump_to) {
    try {
      message_.clear();
      const std::string& task = task_picker_.task();
      if (task.empty() && (design.path.empty() || design.dirty)) {
        throw std::invalid_argument("save the design first");
      }
      if (genes_drive_ == 0 && genome_.genes.empty()) {
        genome_ = ReadGenomeFile(GenomePathFor(genome_path_, design.path));
      }
      OptimiseOptions o = FormOptimiseOptions();
      o.scenario_path = design.path;
      o.out_dir = opt_dir_;
      if (!design.robots.empty()) o.genome.robot = design.robots.front();
      if (!task.empty()) {  // the task's world, robot and own gait
        o.genome.robot = kTaskRobot;
        o.base_gait.clear();
      }
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
    if (RecordedButton(layout_, "Start optimisation")) start(-1);
  } else if (RecordedButton(layout_, "Stop optimisation")) {
    optimise_.Stop();
  }
  ImGui::SameLine();
  if (RecordedButton(layout_, "Watch best")) WatchBest();
  ImGui::SetNextItemWidth(80);
  ImGui::InputInt("##jump", &jump_to_);
  ImGui::SameLine();
  if (RecordedButton(layout_, "Jump to generation"))
    start(std::max(1, jump_to_));
  if (!watching_.empty()) ImGui::TextUnformatted(watching_.c_str());
  if (optimise_.replay_pending()) {
    ImGui::TextDisabled("waiting for generation %d...", jump_to_);
  }
  if (!p.failed_note.empty()) {
    // Failed individuals score the worst fitness: the reason tells a
    // student what to change (an overlap, a body the validator refuses).
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.6f, 0.2f, 1));
    ImGui::TextWrapped("%s", p.failed_note.c_str());
    ImGui::PopStyleColor();
    layout_->State("optimise failed note", p.failed_note);
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
    if (RecordedButton(layout_, "Start in a new folder")) {
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
      const OptimiseOptions& run = optimise_.options();
      const std::filesystem::path best = std::filesystem::path(run.out_dir) /
                                         OptimiseSession::BestFileName(run);
      if (!p.rows.empty() && std::filesystem::exists(best, ec)) {
        ImGui::TextWrapped(
            "best %s: %s", run.controller == "gait" ? "gait" : "controller",
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

void LivePanel::WatchBest() {
  const auto best = optimise_.Best();
  if (!best) {
    message_ = "no generation finished yet";
    message_is_note_ = false;
    return;
  }
  if (optimise_.options().controller != "gait") {
    // Its controller is a program of its own (mrsim-lua, mrsim-nn), not
    // gait values to send to the running design: mrsim-opt's replay runs
    // it, once the run has written it (at its end, or on Stop).
    message_ = "the best controller plays with: mrsim launch " +
               optimise_.options().out_dir + "/replay.launch";
    message_is_note_ = true;
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
    for (int i = 0; i < GaitParameters::kVectorSize; ++i) {
      parameters_[i] = static_cast<float>(p[i]);
    }
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
    run_controller_ = o.controller;
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

void LivePanel::EndReplay() {
  if (replay_) ++replay_revision_;
  replay_.reset();
  watching_.clear();
}

OptimiseOptions LivePanel::FormOptimiseOptions() const {
  OptimiseOptions o;
  if (genes_drive_ == 1) {
    o.controller = "lua";
    o.lua_source = controller_.lua_source();
  } else if (genes_drive_ == 2) {
    o.controller = "mlp:" + mlp_hidden_;
  }
  o.genome = genome_;
  o.task = task_picker_.task();
  const AlgorithmInfo& info = Algorithms().at(algorithm_);
  o.algorithm = info.name;
  o.generations = generations_;
  o.population = population_;
  o.seed = static_cast<unsigned>(std::max(0, seed_));
  o.episode_s = episode_;
  o.fitness = fitness_;
  o.robust = robust_;
  o.allow_overlap = allow_overlap_;
  o.base_gait = base_gait_;
  for (const AlgorithmSetting& setting : info.settings) {
    o.algorithm_settings[setting.flag] = setting.Get(algorithm_settings_);
  }
  return o;
}

std::optional<OptimizationSettings> LivePanel::FormOptimisation() const {
  OptimizationSettings s = SavedOptimisation(FormOptimiseOptions());
  if (!had_optimisation_ && s == opened_optimisation_) return std::nullopt;
  return s;
}

void LivePanel::LoadOptimisation(
    const std::optional<OptimizationSettings>& saved) {
  had_optimisation_ = saved.has_value();
  if (saved) {
    try {
      const OptimiseOptions o = OptionsFromSaved(*saved, OptimiseOptions{});
      algorithm_ = AlgorithmIndex(ParseAlgorithm(o.algorithm));
      generations_ = o.generations;
      population_ = o.population;
      seed_ = static_cast<int>(o.seed);
      episode_ = o.episode_s;
      genes_drive_ = o.controller == "lua"                ? 1
                     : o.controller.rfind("mlp:", 0) == 0 ? 2
                                                          : 0;
      if (genes_drive_ == 2) mlp_hidden_ = o.controller.substr(4);
      if (!o.genome.genes.empty()) genome_ = o.genome;
      task_picker_.Pick(o.task);
      base_gait_ = o.base_gait;
      fitness_ = o.fitness;
      robust_ = o.robust;
      allow_overlap_ = o.allow_overlap;
      for (const AlgorithmSetting& setting :
           Algorithms().at(algorithm_).settings) {
        const auto at = o.algorithm_settings.find(setting.flag);
        if (at != o.algorithm_settings.end()) {
          setting.Set(&algorithm_settings_, at->second);
        }
      }
    } catch (const std::exception& e) {
      message_ = std::string("the design's optimisation setup is not used: ") +
                 e.what();
      message_is_note_ = false;
    }
  }
  opened_optimisation_ = SavedOptimisation(FormOptimiseOptions());
}

}  // namespace mrsim::studio
