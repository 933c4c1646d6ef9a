// Benchmarks of mrsim-studio, off-screen through EGL like --screenshot
// (software GL without a GPU), in one run:
//   BENCH studio_fps                 full UI, scenarios/snake11.xml, 1280x800
//                                    (target >= 30)
//   BENCH studio_render_only_fps     baseline: the same frames without the
//                                    ImGui panels (3-D preview alone)
//   BENCH studio_rebuild_ms_50       a module added to (or removed from) a
//                                    50-module robot until the new preview
//                                    is drawn (median, target <= 100)
//   BENCH studio_rebuild_ms_50_field the same for a field edit (a frame's
//                                    mass): the model is compiled again too
//   BENCH studio_frame_ms_50         baseline: a frame of that robot with no
//                                    edit
#include <GL/gl.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <vector>

#include "studio/app/headless_studio.h"
#include "studio/design/design.h"
#include "studio/ui/studio_app.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kWidth = 1280;
constexpr int kHeight = 800;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main() {
  using namespace mrsim::studio;
  AppOptions options;
  options.width = kWidth;
  options.height = kHeight;
  options.recent_store = "-";
  {
    StudioApp app(Design::Open("scenarios/snake11.xml"), options);
    HeadlessStudio studio(&app, kWidth, kHeight);
    for (int i = 0; i < 5; ++i) studio.Frame();
    int frames = 0;
    const auto start = Clock::now();
    while (Seconds(start) < 4.0) {
      studio.Frame();
      ++frames;
    }
    const double fps = frames / Seconds(start);
    // Baseline: the 3-D preview alone, same context and model.
    frames = 0;
    const auto start3d = Clock::now();
    while (Seconds(start3d) < 4.0) {
      app.preview().Render({0, 0, kWidth, kHeight}, true,
                           app.design().selection());
      glFinish();
      ++frames;
    }
    const double fps3d = frames / Seconds(start3d);
    std::printf("BENCH studio_fps %.1f frames/s\n", fps);
    std::printf("BENCH studio_render_only_fps %.1f frames/s\n", fps3d);
    std::printf("BENCH studio_fps_ratio %.3f x\n", fps / fps3d);
  }
  // The 50-module robot: a frame with no edit (baseline), then edits each
  // followed by the frame that shows them. Structural edits (a module added
  // at the tail, then removed again) compile a new model every time; field
  // edits (the selected module's mass) too, as every edit does.
  TemplateOptions big;
  big.chain.modules = 50;
  big.chain.pattern = mrsim::ChainPattern::kPitchYaw;
  Design design;
  design.ApplyTemplate(big);
  StudioApp app(std::move(design), options);
  HeadlessStudio studio(&app, kWidth, kHeight);
  for (int i = 0; i < 3; ++i) studio.Frame();
  if (!app.build_error().empty()) {
    std::fprintf(stderr,
                 "bench_studio: the 50-module preview does not build: %s\n",
                 app.build_error().c_str());
    std::printf("BENCH studio_rebuild_ms_50 nan ms\n");
    return 1;
  }
  auto timed = [&](const std::function<void()>& edit) {
    const auto start = Clock::now();
    edit();
    studio.Frame();  // rebuilds the model and draws it
    return 1000 * Seconds(start);
  };
  std::vector<double> frame_ms, structural_ms, field_ms;
  for (int k = 0; k < 11; ++k) {
    frame_ms.push_back(timed([] {}));
    structural_ms.push_back(timed([&] {
      app.design().Select({SelectionKind::kModule, 0, 49});
      app.design().AddPart(NextPart::kYawModule, Where::kTail);
    }));
    structural_ms.push_back(timed([&] { app.design().RemoveSelected(); }));
    field_ms.push_back(timed([&] {
      app.design().SetField(
          {{SelectionKind::kModule, 0, k}, "frames[0]", "mass"},
          std::to_string(0.03 + 0.001 * k));
    }));
  }
  if (!app.build_error().empty()) {
    std::fprintf(stderr, "bench_studio: an edit did not build: %s\n",
                 app.build_error().c_str());
    return 1;
  }
  std::printf("BENCH studio_rebuild_ms_50 %.1f ms\n", Median(structural_ms));
  std::printf("BENCH studio_rebuild_ms_50_field %.1f ms\n", Median(field_ms));
  std::printf("BENCH studio_frame_ms_50 %.1f ms\n", Median(frame_ms));
  return 0;
}
