#include "render/review/channel_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace stirrup::render {
namespace {

using namespace plot_palette;

std::string format(double v) {
  char buf[32];
  if (std::abs(v) < 1e-9) v = 0.0;
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::vector<double> niceTicks(double lo, double hi, int approx_count) {
  if (!(hi > lo)) hi = lo + 1.0;
  const double raw = (hi - lo) / std::max(1, approx_count);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step) ticks.push_back(t);
  return ticks;
}

ChannelPlot movementPlot(const std::string& title, const std::vector<rig::BakedFrame>& frames,
                         double rider_unit_cm) {
  using H = rig::HorseChannel;
  using R = rig::RiderChannel;
  ChannelPlot plot;
  plot.title = title;
  PlotPanel hooves{"Hoof heights", "cm",
                   {{"lfHoof.ty  left fore", kBlue, {}},
                    {"rfHoof.ty  right fore", kSky, {}},
                    {"lbHoof.ty  left hind", kVermilion, {}},
                    {"rbHoof.ty  right hind", kOrange, {}}}};
  PlotPanel pivotHeight{"Rear pivot height", "cm", {{"rearPivot.ty  height", kGreen, {}}}};
  PlotPanel pivot{"Rear pivot pitch and mid-back", "degrees",
                  {{"rearPivot.rz  pitch", kGreen, {}}, {"backMid.rz  mid-back", kPurple, {}}}};
  PlotPanel rider{"Rider", "degrees / cm",
                  {{"lowerBack.rz  lower-back rotation (deg)", kBlue, {}},
                   {"cog.ty  lift (cm)", kVermilion, {}},
                   {"head.rz  head pitch (deg)", kPurple, {}}}};
  for (const rig::BakedFrame& b : frames) {
    plot.frames.push_back(b.frame);
    plot.seconds.push_back(b.seconds);
    hooves.series[0].values.push_back(b.horse.controls[H::lfHoofTy]);
    hooves.series[1].values.push_back(b.horse.controls[H::rfHoofTy]);
    hooves.series[2].values.push_back(b.horse.controls[H::lbHoofTy]);
    hooves.series[3].values.push_back(b.horse.controls[H::rbHoofTy]);
    pivotHeight.series[0].values.push_back(b.horse.controls[H::rearPivotTy]);
    pivot.series[0].values.push_back(b.horse.controls[H::rearPivotRz]);
    pivot.series[1].values.push_back(b.horse.controls[H::backMidRz]);
    rider.series[0].values.push_back(b.rider[R::lowerBackRz]);
    rider.series[1].values.push_back(b.rider[R::cogTy] * rider_unit_cm);
    rider.series[2].values.push_back(b.rider[R::headRz]);
  }
  plot.panels = {hooves, pivotHeight, pivot, rider};
  return plot;
}

std::vector<PlotPanel> pathPanels(const rig::PathClip& clip, const std::vector<rig::BakedFrame>& frames,
                                  double clip_offset_s) {
  PlotPanel speed{"Speed and gait", "m/s, gait",
                  {{"speed (m/s)", kBlue, {}}, {"gait  1-4 walk-gallop, - left lead", kVermilion, {}}}};
  PlotPanel turn{"Turn and slope", "degrees",
                 {{"rearPivot.rx  roll (+ right)", kGreen, {}},
                  {"ground pitch (+ uphill)", kOrange, {}},
                  {"lowerBack.ry  rider (+ right)", kPurple, {}}}};
  for (const rig::BakedFrame& b : frames) {
    const double t = b.seconds + clip_offset_s;  // the path clip's own time
    speed.series[0].values.push_back(clip.speedAt(t) / 100.0);
    // The section the frame is in: the last that starts at or before it.
    const rig::PathClip::Section* in = &clip.sections().front();
    for (const rig::PathClip::Section& s : clip.sections())
      if (s.start_s <= t) in = &s;
    const double gait = 1.0 + static_cast<double>(in->gait);
    const bool leads = in->gait == rig::PathGait::Canter || in->gait == rig::PathGait::Gallop;
    speed.series[1].values.push_back(leads && in->lead == rig::Lead::Left ? -gait : gait);
    turn.series[0].values.push_back(b.horse.controls[rig::HorseChannel::rearPivotRx]);
    turn.series[1].values.push_back(b.horse.ground_pitch_deg);
    turn.series[2].values.push_back(b.rider[rig::RiderChannel::lowerBackRy]);
  }
  return {speed, turn};
}

void writeChannelPlot(const ChannelPlot& plot, const std::filesystem::path& file, int width) {
  if (plot.seconds.size() < 2) throw std::invalid_argument(file.string() + ": a plot needs at least two frames");
  const int titleH = 84, panelH = 210, gap = 46, left = 78, legendW = 300, right = 24, bottom = 58;
  const int n = static_cast<int>(plot.panels.size());
  const int height = titleH + n * panelH + (n - 1) * gap + bottom;
  Canvas c(width, height, kBackground);
  const int x0 = left, x1 = width - legendW - right;
  const double t0 = plot.seconds.front(), t1 = plot.seconds.back();
  auto X = [&](double t) { return x0 + (x1 - x0) * (t - t0) / (t1 - t0); };

  c.text(x0, 34, plot.title, 22, kInk, TextAlign::Left, FontStyle::SansBold);
  c.text(x1, 34, "frames " + std::to_string(plot.frames.front()) + "-" + std::to_string(plot.frames.back()),
         14, kMuted, TextAlign::Right);
  const std::vector<double> tticks = niceTicks(t0, t1, 10);

  for (int i = 0; i < n; ++i) {
    const PlotPanel& p = plot.panels[i];
    const int top = titleH + i * (panelH + gap), bot = top + panelH;
    double lo = 1e300, hi = -1e300;
    for (const ChannelSeries& s : p.series)
      for (double v : s.values) lo = std::min(lo, v), hi = std::max(hi, v);
    if (hi - lo < 1e-6) lo -= 1.0, hi += 1.0;
    const double pad = 0.08 * (hi - lo);
    lo -= pad, hi += pad;
    const std::vector<double> vticks = niceTicks(lo, hi, 5);
    auto Y = [&](double v) { return bot - (bot - top) * (v - lo) / (hi - lo); };

    c.fill(x0, top, x1, bot, kPanel);
    for (double t : tticks) c.line({X(t), double(top)}, {X(t), double(bot)}, 1.0, kGrid);
    for (double v : vticks) {
      c.line({double(x0), Y(v)}, {double(x1), Y(v)}, 1.0, std::abs(v) < 1e-9 ? kZero : kGrid);
      c.text(x0 - 8, int(Y(v)) + 5, format(v), 13, kMuted, TextAlign::Right);
    }
    c.text(x0, top - 9, p.title + "  (" + p.unit + ")", 16, kInk, TextAlign::Left, FontStyle::SansBold);
    for (const ChannelSeries& s : p.series) {
      std::vector<glm::dvec2> points;
      for (std::size_t k = 0; k < s.values.size(); ++k) points.emplace_back(X(plot.seconds[k]), Y(s.values[k]));
      c.polyline(points, 2.2, s.colour);
    }
    // Frame of the panel.
    c.line({double(x0), double(top)}, {double(x1), double(top)}, 1.0, kFrameLine);
    c.line({double(x0), double(bot)}, {double(x1), double(bot)}, 1.0, kFrameLine);
    c.line({double(x0), double(top)}, {double(x0), double(bot)}, 1.0, kFrameLine);
    c.line({double(x1), double(top)}, {double(x1), double(bot)}, 1.0, kFrameLine);
    // Time tick labels under every panel (seconds).
    for (double t : tticks) c.text(int(X(t)), bot + 16, format(t), 12, kMuted, TextAlign::Center);
    // Legend beside the panel.
    int ly = top + 18;
    for (const ChannelSeries& s : p.series) {
      c.line({double(x1 + 18), ly - 5.0}, {double(x1 + 44), ly - 5.0}, 3.0, s.colour);
      c.text(x1 + 52, ly, s.label, 13, kInk);
      ly += 22;
    }
  }
  c.text((x0 + x1) / 2, height - 14, "time (seconds; frame 1 = 0 s)", 15, kInk, TextAlign::Center);
  if (!file.parent_path().empty()) std::filesystem::create_directories(file.parent_path());
  c.write(file);
}

}  // namespace stirrup::render
