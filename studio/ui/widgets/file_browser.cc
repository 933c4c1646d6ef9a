#include "studio/ui/widgets/file_browser.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <filesystem>

#include "studio/ui/widgets/widgets.h"

namespace mrsim::studio {

namespace fs = std::filesystem;

void FileBrowser::Open(const std::string& title, const std::string& dir,
                       const std::string& extension, bool save,
                       const std::string& name) {
  title_ = title;
  std::error_code ec;
  // A folder that is gone (or never was, like ./scenarios outside the
  // source tree) opens its nearest existing parent instead of an error.
  fs::path start = fs::absolute(dir.empty() ? "." : dir, ec).lexically_normal();
  while (!fs::is_directory(start, ec) && start.has_relative_path()) {
    start = start.parent_path();
  }
  dir_ = start.string();
  extension_ = extension;
  save_ = save;
  name_ = name;
  error_.clear();
  open_ = true;
  opening_ = true;
  frames_shown_ = 0;
  List();
}

void FileBrowser::List() {
  error_.clear();
  dirs_.clear();
  files_.clear();
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir_, ec)) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    if (e.is_directory(ec)) {
      dirs_.push_back(name);
    } else if (("|" + extension_ + "|")
                   .find("|" + e.path().extension().string() + "|") !=
               std::string::npos) {
      files_.push_back(name);
    }
  }
  std::sort(dirs_.begin(), dirs_.end());
  std::sort(files_.begin(), files_.end());
  if (ec) error_ = "cannot list " + dir_ + ": " + ec.message();
}

bool FileBrowser::Draw(std::string* chosen, LayoutRecorder* layout) {
  if (!open_) return false;
  if (opening_) {
    ImGui::OpenPopup(title_.c_str());
    opening_ = false;
  }
  bool done = false;
  const ImVec2 size(560, 440);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(
      ImVec2((display.x - size.x) / 2, (display.y - size.y) / 2));
  ImGui::SetNextWindowSize(size);
  if (ImGui::BeginPopupModal(
          title_.c_str(), nullptr,
          ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize)) {
    // ImGui hides a popup on its first frame (it measures it) and finds
    // the window under the mouse from the frame before: a click reaches
    // the dialog only from its third frame on. Its widgets go to the
    // layout dump from the second, so a test that clicks them by name
    // never clicks before the dialog can take it.
    frames_shown_ = std::min(frames_shown_ + 1, 2);
    LayoutRecorder* shown = frames_shown_ >= 2 ? layout : nullptr;
    if (layout != nullptr) {
      layout->State("file dialog", shown ? "ready" : "opening");
      layout->State("file folder", dir_);
      layout->State("file typed", name_);
    }
    ImGui::TextWrapped("%s", dir_.c_str());
    ImGui::BeginChild("entries", ImVec2(0, size.y - 140), true);
    if (ImGui::Selectable("[..]")) {
      dir_ = fs::path(dir_).parent_path().string();
      List();
    }
    for (const std::string& d : dirs_) {
      if (ImGui::Selectable(("[" + d + "]").c_str())) {
        dir_ = (fs::path(dir_) / d).string();
        List();
        break;
      }
    }
    for (const std::string& f : files_) {
      if (ImGui::Selectable(f.c_str(), f == name_,
                            ImGuiSelectableFlags_AllowDoubleClick)) {
        name_ = f;
        if (ImGui::IsMouseDoubleClicked(0)) done = true;
      }
      RecordItem(shown, "entry " + f);
    }
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-1);
    if (ImGui::InputText("##name", &name_,
                         ImGuiInputTextFlags_EnterReturnsTrue)) {
      done = true;
    }
    RecordItem(shown, "file name");
    if (!error_.empty()) {
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", error_.c_str());
    }
    if (ImGui::Button(save_ ? "Save" : "Open", ImVec2(100, 0))) done = true;
    RecordItem(shown, "file ok");
    ImGui::SameLine();
    if (ImGui::Button("Cancel", ImVec2(100, 0))) {
      open_ = false;
      ImGui::CloseCurrentPopup();
    }
    if (done) {
      error_.clear();
      std::string name = name_;
      if (save_ && !name.empty() && fs::path(name).extension().empty()) {
        name += extension_;
      }
      const fs::path path =
          fs::path(name).is_absolute() ? fs::path(name) : fs::path(dir_) / name;
      std::error_code ec;
      if (name.empty()) {
        error_ = "type or pick a file name";
        done = false;
      } else if (!save_ && !fs::is_regular_file(path, ec)) {
        error_ = path.string() + ": no such file";
        done = false;
      } else {
        *chosen = path.lexically_normal().string();
        open_ = false;
        ImGui::CloseCurrentPopup();
      }
    }
    ImGui::EndPopup();
  }
  return done;
}

}  // namespace mrsim::studio
