#include "cli/check_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "render/review/index_page.h"
#include "render/review/plot_canvas.h"
#include "render/shot.h"
#include "render/tracer/image.h"
#include "rig/bake.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "scene/preset.h"

namespace stirrup::cli {
namespace {

namespace fs = std::filesystem;

// Writes `text` to `file` whole or not at all (a temporary name, then a rename).
void writeWhole(const fs::path& file, const std::string& text) { rig::writeFileAtomically(file, text); }

// The value a rule measures at a frame (for the HTML page's plot), -1 where there is none.
double measureOf(const rig::FrameMeasures& m, const rig::FrameMeasures* prev, const std::string& rule, const std::string& where) {
  static const std::map<std::string, int> kLeg = {{"lf", 0}, {"rf", 1}, {"lb", 2}, {"rb", 3}};
  const int leg = kLeg.count(where) ? kLeg.at(where) : -1;
  const int side = where == "left" ? 0 : where == "right" ? 1 : -1;
  if (rule == "hoof-slide" && leg >= 0) {
    if (!prev || !prev->down[std::size_t(leg)] || !m.down[std::size_t(leg)]) return 0;
    return rig::soleSlide(prev->contact[std::size_t(leg)], m.contact[std::size_t(leg)]);
  }
  if (rule == "over-reach" && leg >= 0) return std::max(0.0f, m.reach_short_cm[std::size_t(leg)]);
  if (rule == "hoof-in-ground" && leg >= 0) return m.below_ground_cm[std::size_t(leg)];
  if (rule == "rider-in-horse") return m.rider_depth_cm;
  if (rule == "hand-off-rein" && side >= 0) return m.hand_off_cm[std::size_t(side)];
  if (rule == "foot-off-stirrup" && side >= 0) return m.foot_off_cm[std::size_t(side)];
  if (rule == "trunk-balance") return m.trunk_lean_deg;
  return -1;
}

// A small line plot, drawn as SVG on the plot canvas (render/review/plot_canvas.h): series over frames,
// with horizontal guide lines.
struct Series {
  std::string name, colour;
  std::vector<std::pair<int, double>> points;
};
std::string svgPlot(const std::vector<Series>& series, const std::vector<std::pair<std::string, double>>& guides, int mark_frame) {
  constexpr double W = 360, H = 150, L = 40, R = 8, T = 8, B = 22;
  constexpr int kFontSize = 10;
  int f0 = mark_frame, f1 = mark_frame;
  double lo = 0, hi = 0;
  for (const Series& s : series)
    for (const auto& [f, v] : s.points) f0 = std::min(f0, f), f1 = std::max(f1, f), lo = std::min(lo, v), hi = std::max(hi, v);
  for (const auto& g : guides) lo = std::min(lo, g.second), hi = std::max(hi, g.second);
  if (hi - lo < 1e-6) hi = lo + 1;
  if (f1 == f0) f1 = f0 + 1;
  const auto X = [&](double f) { return L + (f - f0) / double(f1 - f0) * (W - L - R); };
  const auto Y = [&](double v) { return T + (hi - v) / (hi - lo) * (H - T - B); };
  const render::Color ink = render::hexColor("#000"), limit = render::hexColor("#c00");
  render::SvgCanvas s(int(W), int(H), kFontSize);
  s.rect({L, T}, {W - R, H - B}, render::hexColor("#fafafa"), render::hexColor("#ccc"));
  for (const auto& [name, v] : guides) {
    s.dashedLine({L, Y(v)}, {W - R, Y(v)}, 1.0, limit, 3);
    s.text({W - R - 2, Y(v) - 2}, name, kFontSize, limit, render::TextAlign::Right);
  }
  s.line({X(mark_frame), T}, {X(mark_frame), H - B}, 1.0, render::hexColor("#888"));
  int row = 0;
  for (const Series& se : series) {
    std::vector<glm::dvec2> pts;
    for (const auto& [f, v] : se.points) pts.emplace_back(X(f), Y(v));
    s.polyline(pts, 1.5, render::hexColor(se.colour));
    s.text({L + 4, T + 11 + 11 * row++}, se.name, kFontSize, render::hexColor(se.colour));
  }
  s.text({L, H - 6}, std::to_string(f0), kFontSize, ink);
  s.text({W - R, H - 6}, std::to_string(f1), kFontSize, ink, render::TextAlign::Right);
  s.text({4, Y(hi) + 8}, rig::printfNumber("%.3g", hi), kFontSize, ink);
  s.text({4, Y(lo)}, rig::printfNumber("%.3g", lo), kFontSize, ink);
  return s.markup();
}

// The channels plotted beside a rule's measure.
std::vector<std::string> plotChannels(const std::string& rule, const std::string& where) {
  if (rule == "hoof-slide" || rule == "over-reach" || rule == "hoof-in-ground") return {where + "Hoof.tx", where + "Hoof.ty"};
  if (rule == "hand-off-rein") return {where == "left" ? "lWrist.tx" : "rWrist.tx", "rearPivot.rz"};
  if (rule == "foot-off-stirrup") return {where == "left" ? "lFoot.tx" : "rFoot.tx", where == "left" ? "lFoot.tz" : "rFoot.tz"};
  if (rule == "trunk-balance" || rule == "rider-in-horse") return {"rearPivot.rz", "lowerBack.rz"};
  return {"rearPivot.rz"};
}

double channelValue(const rig::BakedFrame& b, const std::string& name) {
  if (const auto h = rig::horseChannelFromName(name)) return b.horse.controls[*h];
  if (const auto r = rig::riderChannelFromName(name)) return b.rider[*r];
  return 0;
}

constexpr int kMaxRuns = 24;        // thumbnails rendered at most (the rest are listed)
constexpr int kPlotHalfFrames = 24;  // a second either side at 24 fps

// A run of flagged frames: consecutive frames of one pair, one rule and place, and its worst finding.
struct FlaggedRun {
  CheckedPair* pair;
  const rig::CheckFinding* worst;
  int first, last, count;
};

// The runs of every pair's failures and warnings, failures first, then in order of their first frame.
std::vector<FlaggedRun> flaggedRuns(std::vector<CheckedPair>& pairs) {
  std::vector<FlaggedRun> runs;
  for (CheckedPair& p : pairs) {
    std::vector<FlaggedRun> mine;
    for (const rig::CheckFinding& f : p.findings) {
      if (f.severity == rig::CheckSeverity::Note) continue;
      bool joined = false;
      for (FlaggedRun& r : mine)
        if (r.worst->rule == f.rule && r.worst->where == f.where && f.frame > 0 && f.frame <= r.last + 1) {
          r.last = std::max(r.last, f.frame);
          ++r.count;
          if (f.value > r.worst->value) r.worst = &f;
          joined = true;
          break;
        }
      if (!joined) mine.push_back({&p, &f, f.frame, f.frame, 1});
    }
    runs.insert(runs.end(), mine.begin(), mine.end());
  }
  std::stable_sort(runs.begin(), runs.end(), [](const FlaggedRun& a, const FlaggedRun& b) {
    return int(a.worst->severity) != int(b.worst->severity) ? int(a.worst->severity) > int(b.worst->severity) : a.first < b.first;
  });
  return runs;
}

// The thumbnails of the runs' worst frames, at most kMaxRuns of them, each pair's shots made once a view.
// Hoof and limit findings are seen from the side (the whole horse and its hooves), the rider's close up.
class RunThumbnails {
 public:
  RunThumbnails(const CheckInput& in, const fs::path& dir) : dir_(dir), thumb_(in.scene) {
    thumb_.width = 320;
    thumb_.height = 180;
    scene::applyPreset(thumb_, scene::findPreset("draft"));
  }

  // The <img> of the run's worst frame, rendered into the page's folder; "" past kMaxRuns or when
  // there is nothing to render from (a baked shot has no scene, nor a clip whose channels drive the measure).
  std::string imageHtml(const FlaggedRun& r) {
    const rig::CheckFinding& f = *r.worst;
    CheckedPair& p = *r.pair;
    if (!(f.frame > 0 && rendered_ < kMaxRuns && p.clip)) return "";
    const bool rider_rule = f.rule == "rider-in-horse" || f.rule == "hand-off-rein" || f.rule == "foot-off-stirrup" || f.rule == "trunk-balance";
    const std::string view = rider_rule ? "close" : "side";
    auto it = shots_.find({p.index, view});
    if (it == shots_.end()) {
      scene::CameraSpec cam;
      cam.name = view;
      cam.view = view;
      cam.follow_pair = p.name.empty() ? -1 : p.index;
      it = shots_.emplace(std::make_pair(p.index, view), std::make_unique<render::Shot>(thumb_, p.profile, cam, 0)).first;
    }
    const std::string png = "frame_" + (p.name.empty() ? "" : std::to_string(p.index) + "_") + std::to_string(f.frame) + ".png";
    render::writePng(it->second->renderFrame(f.frame), dir_ / png);
    ++rendered_;
    return "<img src=\"" + png + "\" width=\"320\" height=\"180\" alt=\"frame " + std::to_string(f.frame) + "\">";
  }

 private:
  fs::path dir_;
  scene::SceneSpec thumb_;
  int rendered_ = 0;
  std::map<std::pair<int, std::string>, std::unique_ptr<render::Shot>> shots_;  // by pair index and view
};

// The run's measure plotted a second either side of its worst frame against the limit, and beside it
// the channels that drive it (when the pair has a clip to bake them from).
std::string runPlots(const FlaggedRun& r) {
  const rig::CheckFinding& f = *r.worst;
  const CheckedPair& p = *r.pair;
  Series measure{f.rule + (f.where.empty() ? "" : " " + f.where), "#000", {}};
  const std::vector<std::string> names = plotChannels(f.rule, f.where);
  std::vector<Series> channels;
  const char* colours[] = {"#1f77b4", "#2ca02c"};
  for (std::size_t k = 0; k < names.size() && k < 2 && p.clip; ++k) channels.push_back({names[k], colours[k], {}});
  for (std::size_t i = 0; i < p.measures.size(); ++i) {
    const rig::FrameMeasures& m = p.measures[i];
    if (std::abs(m.frame - f.frame) > kPlotHalfFrames) continue;
    const rig::FrameMeasures* prev = i > 0 && p.measures[i - 1].frame == m.frame - 1 ? &p.measures[i - 1] : nullptr;
    measure.points.emplace_back(m.frame, measureOf(m, prev, f.rule, f.where));
    if (!p.clip) continue;
    const rig::BakedFrame b = rig::bakeFrame(*p.clip, p.profile, m.frame, m.time_s);
    for (std::size_t k = 0; k < channels.size(); ++k) channels[k].points.emplace_back(m.frame, channelValue(b, names[k]));
  }
  return svgPlot({measure}, {{"limit", f.bound}}, f.frame) + (p.clip ? svgPlot(channels, {}, f.frame) : "");
}

// One run's section of the page: its heading and worst finding, the thumbnail and the plots.
std::string runSection(const FlaggedRun& r, RunThumbnails& thumbnails) {
  const rig::CheckFinding& f = *r.worst;
  const CheckedPair& p = *r.pair;
  std::string body;
  body += "<section class=\"" + std::string(rig::checkSeverityName(f.severity)) + "\"><h2>" +
          render::htmlEscape((p.name.empty() ? "" : p.name + ": ") + f.rule + (f.where.empty() ? "" : " (" + f.where + ")")) + ", frame" +
          (r.first == r.last ? " " + std::to_string(r.first) : "s " + std::to_string(r.first) + "-" + std::to_string(r.last)) + "</h2>";
  body += "<p>" + render::htmlEscape(std::string(rig::checkSeverityName(f.severity)) + " at frame " + std::to_string(f.frame) + ": " + f.text) + "</p>";
  body += thumbnails.imageHtml(r);
  if (f.frame > 0) body += runPlots(r);
  body += "</section>\n";
  return body;
}

// The whole page around the runs' sections: the title, what was checked and counted, what was not measured.
std::string checkPageHtml(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
                          std::size_t runs, const std::string& body) {
  std::string unmeasured;
  for (const CheckedPair& p : pairs)
    for (const std::string& u : p.unmeasured) unmeasured += "<li>" + render::htmlEscape((p.name.empty() ? "" : p.name + ": ") + u) + "</li>";
  const std::string title = "stirrup check: " + in.source;
  return "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + render::htmlEscape(title) +
         "</title><style>body{font-family:sans-serif;margin:2em}section{border-top:1px solid #ccc;padding:.5em 0}"
         "section.failure h2{color:#b00}section.warning h2{color:#a60}h2{font-size:1.1em}img,svg{vertical-align:top;margin-right:1em}"
         "</style></head><body>\n<h1>" + render::htmlEscape(title) + "</h1>\n<p>" + render::htmlEscape(in.described) + ".</p>\n" +
         (in.shot ? "<p>No thumbnails or channel plots: they need the scene the shot was baked from.</p>\n" : "") +
         "<p>" + std::to_string(frames.size()) + " frames, " +
         std::to_string(pairs.size()) + (pairs.size() == 1 ? " pair" : " pairs") + ": " + std::to_string(counts.failures) +
         " failures, " + std::to_string(counts.warnings) + " warnings, " + std::to_string(counts.notes) + " notes; " +
         std::to_string(runs) + " runs of flagged frames" +
         (int(runs) > kMaxRuns ? " (thumbnails of the first " + std::to_string(kMaxRuns) + ")" : "") + ".</p>\n" +
         (unmeasured.empty() ? "" : "<p>Not measured:</p><ul>" + unmeasured + "</ul>\n") +
         (runs == 0 ? "<p>Nothing flagged.</p>\n" : body) + "</body></html>\n";
}

}  // namespace

// JUnit XML: one test suite a pair, one test case a rule. A rule with failures fails its case; one with
// only warnings passes and lists them in system-out (exit status 1 is the gate for warnings); a rule the
// pair cannot be measured by is skipped with the reason.
std::string junitXml(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames) {
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"stirrup check\">\n";
  for (const CheckedPair& p : pairs) {
    const std::string suite = in.name + (p.name.empty() ? "" : "." + p.name);
    int failures = 0, skipped = 0;
    std::string cases;
    for (const char* rule : kRules) {
      std::string failed, warned, skip;
      for (const std::string& u : p.unmeasured)
        if (u.rfind(std::string(rule) + ":", 0) == 0) skip += (skip.empty() ? "" : "; ") + u;
      int n_fail = 0;
      std::string first_failure;
      for (const rig::CheckFinding& f : p.findings) {
        if (f.rule != rule || f.severity == rig::CheckSeverity::Note) continue;
        const std::string line = (f.frame > 0 ? "frame " + std::to_string(f.frame) + ": " : "") + f.text + "\n";
        if (f.severity == rig::CheckSeverity::Failure) {
          if (first_failure.empty()) first_failure = line.substr(0, line.size() - 1);
          failed += line, ++n_fail;
        } else {
          warned += "warning: " + line;
        }
      }
      cases += "    <testcase classname=\"" + render::htmlEscape(suite) + "\" name=\"" + rule + "\">\n";
      if (n_fail) {
        ++failures;
        cases += "      <failure type=\"" + std::string(rule) + "\" message=\"" + render::htmlEscape(std::to_string(n_fail) + " failing: " + first_failure) +
                 "\">" + render::htmlEscape(failed) + "</failure>\n";
      } else if (!skip.empty()) {
        ++skipped;
        cases += "      <skipped message=\"" + render::htmlEscape(skip) + "\"/>\n";
      }
      if (!warned.empty()) cases += "      <system-out>" + render::htmlEscape(warned) + "</system-out>\n";
      cases += "    </testcase>\n";
    }
    x += "  <testsuite name=\"" + render::htmlEscape(suite) + "\" tests=\"" + std::to_string(kRules.size()) + "\" failures=\"" +
         std::to_string(failures) + "\" errors=\"0\" skipped=\"" + std::to_string(skipped) + "\">\n";
    x += "    <properties><property name=\"file\" value=\"" + render::htmlEscape(in.source) + "\"/><property name=\"frames\" value=\"" +
         std::to_string(frames.size()) + "\"/></properties>\n";
    x += cases + "  </testsuite>\n";
  }
  return x + "</testsuites>\n";
}

// The HTML page: each run of flagged frames (consecutive frames of one pair, one rule and place) with
// a thumbnail of its worst frame and the measure and channels plotted around it.
void writeHtml(const CheckInput& in, std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const fs::path& dir,
               const Counts& counts) {
  fs::create_directories(dir);
  const std::vector<FlaggedRun> runs = flaggedRuns(pairs);
  std::string body;
  RunThumbnails thumbnails(in, dir);
  for (const FlaggedRun& r : runs) body += runSection(r, thumbnails);
  writeWhole(dir / "index.html", checkPageHtml(in, pairs, frames, counts, runs.size(), body));
}

void printJson(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
               std::map<std::string, Counts>& by_rule, const nlohmann::json& gait_json) {
  static const char* const kKinds[] = {"scene", "clip", "shot"};
  nlohmann::json j = {{"input", in.source}, {"read_as", kKinds[int(in.kind)]}, {"described", in.described}, {"ground", in.ground}, {"frames", frames.size()},
                      {"pairs", pairs.size()}, {"status", counts.status()}, {"failures", counts.failures}, {"warnings", counts.warnings},
                      {"notes", counts.notes}};
  nlohmann::json rules = nlohmann::json::object();
  for (const char* rule : kRules) rules[rule] = {{"failures", by_rule[rule].failures}, {"warnings", by_rule[rule].warnings}, {"notes", by_rule[rule].notes}};
  j["rules"] = rules;
  nlohmann::json unmeasured = nlohmann::json::array(), list = nlohmann::json::array(), names = nlohmann::json::array();
  for (const CheckedPair& p : pairs) {
    names.push_back({{"pair", p.index}, {"name", p.name}});
    for (const std::string& u : p.unmeasured) unmeasured.push_back({{"pair", p.index}, {"rule", u.substr(0, u.find(':'))}, {"reason", u}});
    for (const rig::CheckFinding& f : p.findings) {
      nlohmann::json e = {{"pair", f.pair}, {"severity", rig::checkSeverityName(f.severity)}, {"rule", f.rule}, {"where", f.where},
                          {"value", f.value}, {"bound", f.bound}, {"text", f.text}};
      if (f.frame > 0) e["frame"] = f.frame, e["time_s"] = f.time_s;
      else e["frame"] = nullptr;
      list.push_back(e);
    }
  }
  j["pair_names"] = names;
  j["unmeasured"] = unmeasured;
  nlohmann::json paths = nlohmann::json::array();
  for (const scene::SceneSpec::PathLimits& l : in.scene.limits) {
    if (in.kind == CheckInput::Kind::Shot) break;  // --scene's paths are not the shot's
    nlohmann::json breaches = nlohmann::json::array();
    for (const rig::LimitBreach& b : l.check->breaches())
      breaches.push_back({{"limit", rig::horseLimitName(b.limit)}, {"field", b.field}, {"segment", b.segment},
                          {"from_s", b.time_s}, {"value", b.value}, {"bound", b.bound}, {"error", l.check->errorText(b)}});
    paths.push_back({{"path", l.check->clipField()}, {"breaches", breaches}});
  }
  j["paths"] = paths;
  if (!gait_json.is_null()) j["gait"] = gait_json;
  j["findings"] = list;
  std::printf("%s\n", j.dump(2).c_str());
}

void printText(const CheckInput& in, const std::vector<CheckedPair>& pairs, const std::vector<int>& frames, const Counts& counts,
               std::map<std::string, Counts>& by_rule) {
  std::printf("%s: %s\n", in.source.c_str(), in.described.c_str());
  for (const CheckedPair& p : pairs) {
    for (const std::string& u : p.unmeasured)
      std::printf("%s: %snot measured: %s\n", in.source.c_str(), p.name.empty() ? "" : (p.name + ": ").c_str(), u.c_str());
    for (const rig::CheckFinding& f : p.findings) {
      const std::string where = f.frame > 0 ? "frame " + std::to_string(f.frame) + " (" + rig::printfNumber("%.3f", f.time_s) + " s)" : "the clip";
      std::printf("%s: %s%s: %s: %s: %s\n", in.source.c_str(), where.c_str(), p.name.empty() ? "" : (", " + p.name).c_str(),
                  rig::checkSeverityName(f.severity), f.rule.c_str(), f.text.c_str());
    }
  }
  std::string per_rule;
  for (const char* rule : kRules)
    if (by_rule[rule].failures + by_rule[rule].warnings > 0)
      per_rule += std::string(per_rule.empty() ? " (" : ", ") + rule + " " + std::to_string(by_rule[rule].failures + by_rule[rule].warnings);
  if (!per_rule.empty()) per_rule += ")";
  std::printf("%s: %zu frames, %zu %s: %d failures, %d warnings, %d notes%s\n", in.source.c_str(), frames.size(), pairs.size(),
              pairs.size() == 1 ? "pair" : "pairs", counts.failures, counts.warnings, counts.notes, per_rule.c_str());
}

}  // namespace stirrup::cli
