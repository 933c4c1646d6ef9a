// Dragging in mrsim-studio, off-screen through EGL (software GL without a
// GPU), the case study (scenarios/case_study.xml) at 1280x800:
//   BENCH studio_drag_fps           frames per second while the ball is
//                                   dragged with the move handle (target
//                                   >= 30): only poses change, no rebuild
//   BENCH studio_case_study_fps     baseline: the same frames, no drag
//   BENCH studio_drag_fps_ratio     the two
//   BENCH studio_drag_release_ms    the release: one edit, the model
//                                   compiled again, the frame drawn
//   BENCH studio_drag_cpu_ms        CPU time per drag frame (every thread,
//                                   llvmpipe's render thread too): what a
//                                   frame costs, which the machine's load
//                                   changes far less than the frame rate
//   BENCH studio_case_study_cpu_ms  the same without the drag
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>

#include "studio/app/headless_studio.h"
#include "studio/design/design.h"
#include "studio/ui/studio_app.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kWidth = 1280;
constexpr int kHeight = 800;
constexpr double kSeconds = 4.0;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// CPU seconds of the whole process so far (all threads).
double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

}  // namespace

int main() {
  using namespace mrsim::studio;
  AppOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.recent_store = "-";
  StudioApp app(Design::Open("scenarios/case_study.xml"), options);
  if (app.design().scenario().scene_objects.empty()) {
    std::fprintf(stderr, "bench_studio_drag: the case study has no object\n");
    return 1;
  }
  HeadlessStudio studio(&app, kWidth, kHeight);
  app.design().Select({SelectionKind::kSceneObject, 0, 0});
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(-1, -1);
  for (int i = 0; i < 5; ++i) studio.Frame();

  int frames = 0;
  double cpu = CpuSeconds();
  auto start = Clock::now();
  while (Seconds(start) < kSeconds) {
    studio.Frame();
    ++frames;
  }
  const double still_fps = frames / Seconds(start);
  const double still_cpu_ms = 1000 * (CpuSeconds() - cpu) / frames;

  // Press on the move handle, then slide along a circle of 100 px.
  const mjrRect view = app.view();
  double x = 0, y = 0;
  const mrsim::SceneObject& ball = app.design().scenario().scene_objects[0];
  if (!app.preview().ScreenPoint(view, kHeight, ball.position, &x, &y)) {
    std::fprintf(stderr, "bench_studio_drag: the ball is not in view\n");
    return 1;
  }
  const long revision = app.design().revision();
  io.MousePos = ImVec2(static_cast<float>(x), static_cast<float>(y));
  io.MouseDown[0] = true;
  studio.Frame();
  frames = 0;
  cpu = CpuSeconds();
  start = Clock::now();
  while (Seconds(start) < kSeconds) {
    const double a = frames * 0.05;
    io.MousePos = ImVec2(static_cast<float>(x + 100 * std::sin(a)),
                         static_cast<float>(y + 100 * (1 - std::cos(a))));
    studio.Frame();
    ++frames;
  }
  const double drag_fps = frames / Seconds(start);
  const double drag_cpu_ms = 1000 * (CpuSeconds() - cpu) / frames;
  if (app.design().revision() != revision) {
    std::fprintf(stderr, "bench_studio_drag: the drag edited the design\n");
    return 1;
  }
  io.MousePos = ImVec2(static_cast<float>(x + 60), static_cast<float>(y));
  studio.Frame();
  io.MouseDown[0] = false;
  const auto release = Clock::now();
  studio.Frame();  // the edit
  studio.Frame();  // the rebuild drawn
  const double release_ms = 1000 * Seconds(release);
  if (app.design().revision() != revision + 1) {
    std::fprintf(stderr, "bench_studio_drag: the release made no edit\n");
    return 1;
  }
  std::printf("BENCH studio_drag_fps %.1f frames/s\n", drag_fps);
  std::printf("BENCH studio_case_study_fps %.1f frames/s\n", still_fps);
  std::printf("BENCH studio_drag_fps_ratio %.3f x\n", drag_fps / still_fps);
  std::printf("BENCH studio_drag_release_ms %.1f ms\n", release_ms);
  std::printf("BENCH studio_drag_cpu_ms %.1f ms\n", drag_cpu_ms);
  std::printf("BENCH studio_case_study_cpu_ms %.1f ms\n", still_cpu_ms);
  return 0;
}
