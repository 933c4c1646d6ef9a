// A small modal file browser for Dear ImGui (it has none): folders and
// files with the wanted extension, a name field, OK/Cancel.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace mrsim::studio {

class LayoutRecorder;

class FileBrowser {
 public:
  // Opens the dialog in `dir`. save: the name may be a new file.
  // `extension` may list several, ".stl|.obj".
  // `name` fills the name field.
  void Open(const std::string& title, const std::string& dir,
            const std::string& extension, bool save,
            const std::string& name = "");
  bool is_open() const { return open_; }
  // Draws it when open; returns true once with the chosen path.
  bool Draw(std::string* chosen, LayoutRecorder* layout);

 private:
  void List();

  bool open_ = false;
  bool opening_ = false;
  int frames_shown_ = 0;  // frames drawn since it opened, up to 2
  bool save_ = false;
  std::string title_;
  std::string dir_;
  std::string extension_;
  std::string name_;
  std::string error_;
  std::vector<std::string> dirs_;
  std::vector<std::string> files_;
};

}  // namespace mrsim::studio
