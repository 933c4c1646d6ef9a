// The Run panel's Plots section: pick a channel and column, live curves,
// PNG export.
// Part of LivePanel (live_panel.h), one file per section.
#include "lcmtypes/runtime/channels.h"
#include "studio/live/plot_export.h"
#include "studio/ui/run/live_panel.h"
#include "studio/ui/run/live_panel_common.h"

namespace mrsim::studio {

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
      if (RecordedButton(layout_, "Add plot")) {
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

}  // namespace mrsim::studio
