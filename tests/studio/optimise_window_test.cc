// The Run panel's Optimise section in the real mrsim-studio under its own
// Xvfb, clicked and typed with real events (xdotool): the built-in gene
// sets, the task picker, the robust episodes and mode and the folded
// reality gap reach both the design file (Save) and the mrsim-opt command
// line that Start optimisation runs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>

#include "optimizer/search/genome.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/studio/studio_test_util.h"

namespace mrsim::testing {
namespace {

namespace fs = std::filesystem;

bool HaveX() {
  return fs::exists("/usr/bin/Xvfb") && fs::exists("/usr/bin/xdotool");
}

struct Box {
  int x = 0, y = 0, w = 0, h = 0;
};

bool ParseBox(const std::string& text, Box* box) {
  std::istringstream in(text);
  return static_cast<bool>(in >> box->x >> box->y >> box->w >> box->h);
}

// "<count> <name> <name> ...", as the layout's "optimise genes" line.
std::string GeneLine(const GenomeSpec& genome) {
  std::string line = std::to_string(genome.size());
  for (const GeneSpec& g : genome.genes) line += " " + g.name;
  return line;
}

std::vector<std::string> Words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

class StudioOptimiseWindow : public ::testing::Test {
 protected:
  // The studio on a copy of the case study, started from its directory
  // (the section's folder "optimise" is relative to it), with its own
  // display, settings and LCM port (mrsim-opt's progress), Run panel open.
  void Start(const std::string& name, int port) {
    dir_ = TempDir(name);
    file_ = dir_ + "/design.xml";
    fs::copy_file(SourcePath("scenarios/case_study.xml"), file_);
    layout_ = dir_ + "/layout.txt";
    xvfb_ = std::make_unique<XvfbDisplay>(dir_);
    ASSERT_TRUE(xvfb_->ok()) << "Xvfb did not start, see " << dir_;
    setenv("XDG_CONFIG_HOME", dir_.c_str(), 1);
    setenv("LCM_DEFAULT_URL", TestLcmUrl(port).c_str(), 1);
    studio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{"/bin/sh", "-c",
                                 "cd '" + dir_ + "' && exec '" +
                                     BinaryPath("studio/mrsim-studio") +
                                     "' --layout-dump layout.txt design.xml"},
        dir_ + "/studio.log");
    ASSERT_TRUE(WaitForLayout(layout_, "revision", "0")) << studio_->Output();
    ASSERT_TRUE(Xdotool({"mousemove", "640", "400"}));
    ASSERT_TRUE(Xdotool({"key", "F5"}));
    ASSERT_NO_FATAL_FAILURE(Click("header Optimise"));
  }

  // Waits until `widget` is drawn, then scrolls the Run panel (the wheel
  // over it) until the widget is inside it, below its title bar.
  void Show(const std::string& widget) {
    ASSERT_TRUE(WaitUntil(
        [&] { return ReadLayout(layout_).count("widget " + widget) > 0; }, 90))
        << widget << " never drawn";
    for (int turn = 0; turn < 60; ++turn) {
      auto l = ReadLayout(layout_);
      Box panel, box;
      ASSERT_TRUE(ParseBox(l["panel right"], &panel)) << l["panel right"];
      ASSERT_TRUE(ParseBox(l["widget " + widget], &box)) << widget;
      const int top = panel.y + 30, bottom = panel.y + panel.h - 8;
      if (box.y >= top && box.y + box.h <= bottom) return;
      const std::string xs = std::to_string(panel.x + panel.w - 30),
                        ys = std::to_string(panel.y + panel.h / 2);
      ASSERT_TRUE(Xdotool({"mousemove", xs, ys}));
      ASSERT_TRUE(WaitForLayout(layout_, "mouse", xs + " " + ys));
      ASSERT_TRUE(Xdotool({"click", box.y < top ? "4" : "5"}));
      // Seen moved before the next turn (at the end it cannot move).
      WaitUntil(
          [&] {
            Box now;
            return ParseBox(ReadLayout(layout_)["widget " + widget], &now) &&
                   now.y != box.y;
          },
          5);
    }
    FAIL() << widget << " never scrolled into the Run panel";
  }

  // Where to click `widget`: its centre, or `left` pixels into it (a
  // number field's box is left of its label, both in its rectangle).
  bool Target(const std::string& widget, int left, int* x, int* y) {
    Box box;
    if (!ParseBox(ReadLayout(layout_)["widget " + widget], &box)) return false;
    *x = left >= 0 ? box.x + left : box.x + box.w / 2;
    *y = box.y + box.h / 2;
    return true;
  }

  // Clicks `widget` once a frame drawn with the pointer on it still has it
  // there: a popup's first frame lays its rows out before placing them.
  void ClickShown(const std::string& widget, int left = -1) {
    for (int turn = 0; turn < 20; ++turn) {
      int x = 0, y = 0, now_x = 0, now_y = 0;
      ASSERT_TRUE(WaitUntil([&] { return Target(widget, left, &x, &y); }, 90))
          << widget << " never shown";
      const std::string xs = std::to_string(x), ys = std::to_string(y);
      ASSERT_TRUE(Xdotool({"mousemove", xs, ys}));
      ASSERT_TRUE(WaitForLayout(layout_, "mouse", xs + " " + ys));
      if (Target(widget, left, &now_x, &now_y) && now_x == x && now_y == y) {
        ASSERT_TRUE(Xdotool({"click", "1"})) << widget;
        return;
      }
    }
    FAIL() << widget << " never stayed in place";
  }

  void Click(const std::string& widget) {
    ASSERT_NO_FATAL_FAILURE(Show(widget));
    ASSERT_NO_FATAL_FAILURE(ClickShown(widget));
  }

  // A click selects a number field's text whole; typed characters go to
  // it once the window says it is the active one.
  void TypeInto(const std::string& widget, const std::string& text) {
    ASSERT_NO_FATAL_FAILURE(Show(widget));
    ASSERT_NO_FATAL_FAILURE(ClickShown(widget, 15));
    ASSERT_TRUE(WaitForLayout(layout_, "active", widget))
        << ReadLayout(layout_)["active"];
    ASSERT_TRUE(Xdotool({"type", text}));
  }

  bool WaitForState(const std::string& key,
                    const std::function<bool(const std::string&)>& ok) {
    return WaitUntil([&] { return ok(ReadLayout(layout_)[key]); }, 90);
  }

  std::string dir_, file_, layout_;
  std::unique_ptr<XvfbDisplay> xvfb_;
  std::unique_ptr<ChildProcess> studio_;
};

// The student clicks "sine genes", then "cpg genes", picks the task
// "slope", sets 2 robust episodes scored by the worst, and in the folded
// "reality gap" a friction variation of 0.25: Save writes each into the
// design's <optimization>, and Start optimisation runs mrsim-opt with the
// same (--task, --robust, --robust-mode, --robust-gap, the cpg genome).
TEST_F(StudioOptimiseWindow, GenesTaskRobustAndGapReachTheFileAndTheRun) {
  if (!HaveX()) GTEST_SKIP() << "Xvfb or xdotool missing (install_deps.sh)";
  ASSERT_NO_FATAL_FAILURE(Start("studio_optimise_form", 7957));
  const GenomeSpec sine = BuiltInGenome("sine"), cpg = BuiltInGenome("cpg");
  ASSERT_NE(GeneLine(sine), GeneLine(cpg));

  ASSERT_NO_FATAL_FAILURE(Click("sine genes"));
  ASSERT_TRUE(WaitForLayout(layout_, "optimise genes", GeneLine(sine)))
      << ReadLayout(layout_)["optimise genes"];
  ASSERT_NO_FATAL_FAILURE(Click("cpg genes"));
  ASSERT_TRUE(WaitForLayout(layout_, "optimise genes", GeneLine(cpg)))
      << ReadLayout(layout_)["optimise genes"];

  ASSERT_NO_FATAL_FAILURE(Click("task"));
  ASSERT_NO_FATAL_FAILURE(ClickShown("task slope"));
  ASSERT_TRUE(WaitForLayout(layout_, "optimise task", "slope"))
      << ReadLayout(layout_)["optimise task"];

  ASSERT_NO_FATAL_FAILURE(Click("header Fitness and algorithm settings"));
  ASSERT_NO_FATAL_FAILURE(TypeInto("robust episodes", "2"));
  ASSERT_TRUE(WaitForState("optimise robust", [](const std::string& s) {
    return s.rfind("2 mean ", 0) == 0;
  })) << ReadLayout(layout_)["optimise robust"];
  ASSERT_NO_FATAL_FAILURE(Click("robust worst"));
  ASSERT_TRUE(WaitForState("optimise robust", [](const std::string& s) {
    return s.rfind("2 worst ", 0) == 0;
  })) << ReadLayout(layout_)["optimise robust"];
  ASSERT_NO_FATAL_FAILURE(Click("header reality gap"));
  ASSERT_NO_FATAL_FAILURE(TypeInto("friction variation", "0.25"));
  ASSERT_TRUE(WaitForState("optimise robust", [](const std::string& s) {
    return s.find(" friction_range=0.25 ") != std::string::npos;
  })) << ReadLayout(layout_)["optimise robust"];

  // Save (the Design panel's button) writes the form into the file.
  ASSERT_NO_FATAL_FAILURE(ClickShown("Save"));
  ASSERT_TRUE(WaitForState("message", [](const std::string& s) {
    return s.rfind("saved ", 0) == 0;
  })) << ReadLayout(layout_)["message"];
  const Scenario saved = ReadScenarioFile(file_);
  ASSERT_TRUE(saved.optimization.has_value());
  const OptimizationSettings& o = *saved.optimization;
  EXPECT_EQ(GeneLine(ReadGenomeString(o.genome, "saved")), GeneLine(cpg));
  EXPECT_EQ(o.task, "slope");
  EXPECT_EQ(o.robust, 2);
  EXPECT_EQ(o.robust_mode, "worst");
  EXPECT_DOUBLE_EQ(o.gap_friction_range, 0.25);

  // Start optimisation runs what the form holds.
  ASSERT_NO_FATAL_FAILURE(Click("Start optimisation"));
  ASSERT_TRUE(WaitForState("optimise command", [](const std::string& s) {
    return !s.empty();
  })) << ReadLayout(layout_)["live message"];
  const std::string command = ReadLayout(layout_)["optimise command"];
  for (const char* part : {"--task slope ", " --robust 2 --robust-mode worst ",
                           " --robust-gap friction_range=0.25 "}) {
    EXPECT_NE(command.find(part), std::string::npos) << part << "\n" << command;
  }
  const std::vector<std::string> args = Words(command);
  const auto genome = std::find(args.begin(), args.end(), "--genome");
  ASSERT_TRUE(genome != args.end() && genome + 1 != args.end()) << command;
  EXPECT_EQ(GeneLine(ReadGenomeFile((fs::path(dir_) / *(genome + 1)).string())),
            GeneLine(cpg));

  // The run is not needed to its end: stopped, it keeps its checkpoint.
  if (ReadLayout(layout_)["optimise"].find("running") != std::string::npos) {
    ASSERT_NO_FATAL_FAILURE(Click("Stop optimisation"));
    ASSERT_TRUE(WaitForState("optimise", [](const std::string& s) {
      return s.find("running") == std::string::npos;
    })) << ReadLayout(layout_)["optimise"];
  }
  studio_->Stop();
}

}  // namespace
}  // namespace mrsim::testing
