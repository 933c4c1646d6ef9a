#include "studio/ui/studio_context.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <vector>

#include "common/data_dir.h"
#include "launcher/program_locator.h"
#include "sim_core/scenario/embed_assets.h"
#include "sim_core/scenario/scenario_validate.h"
#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

StudioContext::StudioContext(Design design_in, const AppOptions& options_in)
    : design(std::move(design_in)),
      options(options_in),
      preview(std::make_unique<Preview>(options_in.width, options_in.height)),
      camera_feed(std::make_unique<CameraFeed>()),
      layout(options_in.layout_dump),
      live(std::make_unique<LivePanel>(ProgramSearchPath(""), &layout)),
      recent(options_in.recent_store) {
  Note(design.note());
  if (options.full_view) ToggleFullView();
  show_template = options.open_template;
  embed_on_save = !NamesAssetFiles(design.scenario());
  live->LoadRunSettings(design.scenario().run);
  live->LoadOptimisation(design.scenario().optimization);
  if (!design.path().empty() && std::filesystem::exists(design.path())) {
    recent.Add(design.path());
  }
}

StudioContext::~StudioContext() = default;

bool StudioContext::Button(const char* label, float width) {
  return RecordedButton(&layout, label, width);
}

void StudioContext::Record(const std::string& name) {
  RecordItem(&layout, name);
}

void StudioContext::Try(const std::function<void()>& edit) {
  try {
    edit();
    message.clear();
  } catch (const ScenarioError& e) {
    // The design's own words, without the XML path of the part: the
    // inspector already shows which part is selected.
    Refuse(e.message().empty() ? e.what() : e.message());
  } catch (const std::exception& e) {
    Refuse(e.what());
  }
}

void StudioContext::Try(const std::string& action,
                        const std::function<void()>& edit) {
  Try(edit);
  if (message_is_error && !message.empty()) {
    refused_action = action;
    refused_why = message;
  }
}

void StudioContext::Note(const std::string& text) {
  message = text;
  message_is_error = false;
}

void StudioContext::Refuse(const std::string& text) {
  message = text;
  message_is_error = true;
}

void StudioContext::Guard(Pending action) {
  pending = action;
  if (design.dirty() && action != Pending::kTemplate) {
    ask_unsaved = true;
  } else {
    RunPending();
  }
}

void StudioContext::RunPending() {
  const Pending action = pending;
  pending = Pending::kNone;
  switch (action) {
    case Pending::kNew:
      design = Design();
      built_revision = -1;
      message.clear();
      break;
    case Pending::kOpen:
      browse_for = BrowseFor::kOpen;
      browser.Open("Open scenario", OpenFolder(), ".xml", false);
      break;
    case Pending::kTemplate:
      show_template = true;
      break;
    case Pending::kQuit:
      quit = true;
      break;
    case Pending::kNone:
      break;
  }
}

void StudioContext::RequestClose() {
  const std::vector<std::string> busy = live->InProgress();
  if (busy.empty()) {
    Guard(Pending::kQuit);
    return;
  }
  std::string words;
  for (size_t i = 0; i < busy.size(); ++i) {
    words += (i == 0 ? "" : i + 1 == busy.size() ? " and " : ", ") + busy[i];
  }
  words[0] = static_cast<char>(std::toupper(words[0]));
  const bool one = busy.size() == 1;
  ask_busy_quit = words + (one ? " is" : " are") +
                  " going on. Quitting stops " + (one ? "it." : "them.");
  const auto has = [&](const char* what) {
    return std::find(busy.begin(), busy.end(), what) != busy.end();
  };
  if (has("a recording")) ask_busy_quit += " The recorded files are kept.";
  if (has("an optimisation")) {
    ask_busy_quit +=
        " The optimisation continues from its last generation when started "
        "again.";
  }
}

void StudioContext::OpenFile(const std::string& path) {
  try {
    design = Design::Open(path);
    embed_on_save = !NamesAssetFiles(design.scenario());
    live->LoadRunSettings(design.scenario().run);
    live->LoadOptimisation(design.scenario().optimization);
    built_revision = -1;
    recent.Add(path);
    Note(design.note());
    preview->Reframe();
  } catch (const std::exception& e) {
    Refuse(e.what());
  }
}

std::string StudioContext::StartFolder() const {
  if (!design.path().empty()) {
    return std::filesystem::path(design.path()).parent_path().string();
  }
  std::error_code ec;
  return std::filesystem::is_directory("scenarios", ec) ? "scenarios" : ".";
}

std::string StudioContext::OpenFolder() const {
  const std::string start = StartFolder();
  if (start != ".") return start;
  const std::string installed = FindDataFile("scenarios");
  return installed.empty() ? start : installed;
}

void StudioContext::StoreRunSettings() {
  design.SetRunSettings(live->FormRunSettings());
  design.SetOptimizationSettings(live->FormOptimisation());
}

void StudioContext::BrowseSaveAs() {
  browse_for = BrowseFor::kSaveAs;
  browser.Open("Save scenario as", StartFolder(), ".xml", true);
}

void StudioContext::SaveFile() {
  if (design.path().empty()) {
    BrowseSaveAs();
    return;
  }
  try {
    StoreRunSettings();
    design.Save(embed_on_save);
    recent.Add(design.path());
    Note("saved " + design.path());
  } catch (const std::exception& e) {
    Refuse(e.what());
  }
}

void StudioContext::ToggleVideo() {
  if (video.recording()) {
    const std::optional<RecordedVideo> done = video.Stop();
    if (done) {
      Note("video " + done->path + " (" + DescribeVideo(*done) + ")");
    } else {
      Note("no video: the 3-D view was not drawn while recording");
    }
    return;
  }
  const std::string stem =
      design.path().empty()
          ? std::string("untitled")
          : std::filesystem::path(design.path()).stem().string();
  const std::string folder =
      design.path().empty()
          ? std::string(".")
          : std::filesystem::path(design.path()).parent_path().string();
  Try("record a video", [&] { video.Start(NextVideoPath(folder, stem)); });
  if (video.recording()) {
    Note("recording " + video.path() + " (Ctrl+R or Stop video to finish)");
  }
}

void StudioContext::ToggleFullView() {
  const bool show = !panels.show_left && !panels.show_right;
  panels.show_left = show;
  panels.show_right = show;
}

}  // namespace mrsim::studio
