#include "rig/motion/clip_report.h"

#include <cmath>
#include <cstdio>

#include "rig/error.h"

namespace stirrup::rig {

namespace {

const Verdict* findVerdict(const std::vector<Verdict>& v, const std::string& key) {
  for (const Verdict& x : v)
    if (x.key == key) return &x;
  return nullptr;
}

std::string rangeText(const Range& r, const char* f) {
  if (std::isinf(r.hi)) return "≥ " + printfNumber(f, r.lo);
  if (r.lo == r.hi) return printfNumber(f, r.lo);
  return printfNumber(f, r.lo) + (r.lo < 0.0 || r.hi < 0.0 ? ".." : "–") + printfNumber(f, r.hi);
}

std::string verdictText(const Verdict* v, const char* f) {
  if (!v) return "(no reference)";
  return rangeText(v->range, f) + (v->ok ? "  ok" : "  OUTSIDE");
}

nlohmann::json rangeJson(const Range& r) {
  return nlohmann::json::array({r.lo, std::isinf(r.hi) ? nlohmann::json(nullptr) : nlohmann::json(r.hi)});
}

// A hoof's per-frame slide problem that is the sliding stop's own slide (and nothing else slides).
bool expectedSlide(const ClipInfo& c, const GaitReference* ref, int h) {
  const HoofInfo& hi = c.hooves[h];
  return ref && ref->slide_cm && h >= 2 && hi.stance_slide_cm >= kSlidingStanceCm &&
         hi.max_slide_outside_stance_mm <= c.slide_limit_mm;
}

// The per-hoof table: touchdown, duty, heights and slides, and for a gait the reference's touchdown
// and duty. Sets `starred` when a touchdown was compared with phases other than the table's.
std::string hoofTable(const ClipInfo& c, bool gait, const std::vector<Verdict>& verdicts, bool& starred) {
  std::string s;
  char line[512];
  s += "hoof     touchdown  duty   peak cm  lowest cm  slide mm/frame  stance slide cm   reference touchdown (±" +
       printfNumber("%.2f", kTouchdownTolerance) + " stride), duty\n";
  starred = false;
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi = c.hooves[h];
    std::string r = "-";
    if (gait) {
      const Verdict* td = findVerdict(verdicts, std::string(kHoofNames[h]) + ".touchdown_phase");
      const Verdict* duty = findVerdict(verdicts, std::string(kHoofNames[h]) + ".duty_factor");
      r = td ? rangeText(td->range, "%.2f") + (td->note.empty() ? "" : "*") + (td->ok ? " ok" : " OUTSIDE") : "-";
      starred = starred || (td && !td->note.empty());
      r += ", " + verdictText(duty, "%.2f");
    }
    std::snprintf(line, sizeof line, "%-8s %9.3f  %5.3f  %7.1f  %9.2f  %14.1f  %15.1f   %s\n", kHoofNames[h],
                  hi.touchdown_phase, hi.duty_factor, hi.peak_height_cm, hi.lowest_cm, hi.max_slide_mm, hi.stance_slide_cm,
                  r.c_str());
    s += line;
  }
  return s;
}

// The footnote to a starred table: the gallop's fore pair is judged against one-suspension phases, and
// how far it is from the table's own.
std::string gallopForePairNote(const ClipInfo& c, const GaitReference& ref, const std::vector<Verdict>& verdicts) {
  const Verdict* lf = findVerdict(verdicts, "lfHoof.touchdown_phase");
  const Verdict* rf = findVerdict(verdicts, "rfHoof.touchdown_phase");
  return "  * gallop fore pair compared with the one-suspension phases " + printfNumber("%.3f", lf->range.lo) + "/" +
         printfNumber("%.3f", rf->range.lo) + printfNumber(" at %.2f Hz", c.stride_hz) +
         " (right hind .10 + Witte's hind stance):\n"
         "    the table's .50/.60 with Witte's stance times give two suspensions where gait-reference counts one\n"
         "    (docs/horse-clips.md \"Gallop phases\"). Against the table's phases they are " +
         printfNumber("%.2f", phaseDistance(c.hooves[0].touchdown_phase, ref.touchdown_phase[0])) + "/" +
         printfNumber("%.2f", phaseDistance(c.hooves[1].touchdown_phase, ref.touchdown_phase[1])) + " away: " +
         (phaseDistance(c.hooves[0].touchdown_phase, ref.touchdown_phase[0]) <= kTouchdownTolerance &&
                  phaseDistance(c.hooves[1].touchdown_phase, ref.touchdown_phase[1]) <= kTouchdownTolerance
              ? "ok"
              : "OUTSIDE") +
         "\n";
}

// The footfall order and the stride's numbers, each beside its reference when the clip is a gait.
std::string strideRows(const ClipInfo& c, bool gait, const std::vector<Verdict>& verdicts) {
  std::string s;
  char line[512];
  std::string order;
  for (int h : c.footfall_order) order += std::string(order.empty() ? "" : " ") + kHoofNames[h];
  s += "footfall order: " + (order.empty() ? std::string("(no full stride)") : order) + "\n";
  const auto row = [&](const char* label, const char* vf, double v, const char* key, const char* rf) {
    std::snprintf(line, sizeof line, "%-28s ", label);
    s += line + printfNumber(vf, v) + "   reference " + (gait ? verdictText(findVerdict(verdicts, key), rf) : std::string("-")) + "\n";
  };
  row("stride frequency (Hz)", "%.3f", c.stride_hz, "stride_hz", "%.2f");
  row("stride length (cm)", "%.1f", c.stride_length_cm, "stride_length_cm", "%.0f");
  row("speed (cm/s)", "%.1f", c.speed_cm_s, "speed_cm_s", "%.0f");
  row("suspensions per stride", "%.2f", c.suspensions_per_stride, "suspensions_per_stride", "%.0f");
  row("suspension length (ms)", "%.1f", c.suspension_ms, "suspension_ms", "%.0f");
  row("rear pivot ty p-p (cm)", "%.2f", c.pivot_ty_peak_to_peak_cm, "rear_pivot_ty_peak_to_peak_cm", "%.0f");
  row("rear pivot cycles/stride", "%.2f", c.pivot_ty_cycles_per_stride, "rear_pivot_cycles_per_stride", "%.0f");
  row("pitch range (deg)", "%.2f", c.pitch_max_deg - c.pitch_min_deg, "pitch_range_deg", "%.0f");
  std::snprintf(line, sizeof line, "%-28s %.2f..%.2f\n", "pitch rearPivot.rz (deg)", c.pitch_min_deg, c.pitch_max_deg);
  s += line;
  return s;
}

// The whole window, strides or not: what the scripted movements are judged by (not shown for gaits).
std::string wholeClipRows(const ClipInfo& c) {
  std::string s;
  char line[512];
  std::snprintf(line, sizeof line,
                "whole clip: pitch %.2f..%.2f deg, held at 40–70 deg for %.2f s, %d croup-up%s (pitch below -10 deg)\n",
                c.pitch_lowest_deg, c.pitch_highest_deg, c.pitch_held_s, c.croup_ups, c.croup_ups == 1 ? "" : "s");
  s += line;
  if (c.airborne_phases > 0)
    std::snprintf(line, sizeof line, "airborne phases: %d, longest %.0f ms from %.2f s, pitch %.2f deg as it began\n",
                  c.airborne_phases, c.longest_airborne_ms, c.longest_airborne_from_s, c.liftoff_pitch_deg);
  else
    std::snprintf(line, sizeof line, "airborne phases: none\n");
  s += line;
  if (c.slide_hoof >= 0) {
    const HoofInfo& hi = c.hooves[c.slide_hoof];
    std::snprintf(line, sizeof line, "largest slide while down: %s %.1f cm (%.2f–%.2f s), %d fore touchdowns meanwhile\n",
                  kHoofNames[c.slide_hoof], hi.stance_slide_cm, hi.stance_slide_from_s, hi.stance_slide_to_s,
                  c.fore_touchdowns_during_slide);
  } else {
    std::snprintf(line, sizeof line, "largest slide while down: none (no stance moves %.0f cm)\n", kSlidingStanceCm);
  }
  s += line;
  return s;
}

// A scripted movement's numbers (rear, buck, jump, stop), each beside its reference and its source.
std::string scriptedRows(const std::vector<Verdict>& verdicts) {
  std::string s;
  char line[512];
  const auto scripted = [&](const char* label, const char* vf, const char* key, const char* rf, const char* why) {
    const Verdict* v = findVerdict(verdicts, key);
    if (!v) return;
    std::snprintf(line, sizeof line, "%-28s ", label);
    s += line + printfNumber(vf, v->value) + "   reference " + verdictText(v, rf) + "  (" + why +
         (v->note.empty() ? std::string() : "; " + v->note) + ")\n";
  };
  scripted("rear: peak pitch (deg)", "%.2f", "rear.peak_pitch_deg", "%.0f", "Kuhnel 5.4");
  scripted("rear: held at 40-70 deg (s)", "%.2f", "rear.held_s", "%.1f", "longest continuous stay in the band");
  scripted("buck: croup-up pitch (deg)", "%.2f", "buck.croup_pitch_deg", "%.0f", "Kuhnel 5.6");
  scripted("buck: all four hooves off", "%.0f", "buck.airborne_phases", "%.0f", "airborne phases, one per buck");
  scripted("jump: take-off pitch (deg)", "%.2f", "jump.takeoff_pitch_deg", "%.1f", "21.4 ± 2.5, Colborne 1995");
  scripted("stop: slide (cm)", "%.1f", "stop.slide_cm", "%.0f", "up to ≈ 10 m, Kuhnel 5.5");
  scripted("stop: fore steps in slide", "%.0f", "stop.fore_steps_during_slide", "%.0f", "the forelegs keep stepping");
  return s;
}

// The clip's problems, a sliding stop's own slide told apart as expected.
std::string problemLines(const ClipInfo& c, const GaitReference* ref) {
  std::string s;
  if (c.problems.empty()) s += "no hoof slides or sinks\n";
  for (const std::string& p : c.problems) {
    bool expected = false;
    for (int h = 2; h < 4; ++h)
      expected = expected || (expectedSlide(c, ref, h) && p.rfind(std::string(kHoofNames[h]) + " slides", 0) == 0);
    s += (expected ? "slide (the sliding stop's, expected): " : "problem: ") + p + "\n";
  }
  return s;
}

// The verdict line: all inside the reference, or the keys of those outside it.
std::string verdictLine(const std::vector<Verdict>& verdicts) {
  std::string outside;
  for (const Verdict& v : verdicts)
    if (!v.ok) outside += (outside.empty() ? "" : ", ") + v.key;
  const std::string n = std::to_string(verdicts.size()) + (verdicts.size() == 1 ? " number" : " numbers");
  return outside.empty() ? "verdict: all " + n + " inside the reference\n"
                         : "verdict: OUTSIDE the reference (of " + n + "): " + outside + "\n";
}

}  // namespace

std::string formatClipInfo(const ClipInfo& c, const GaitReference* ref) {
  const std::vector<Verdict> verdicts = ref ? clipVerdicts(c, *ref) : std::vector<Verdict>{};
  std::string s;
  char line[512];
  std::snprintf(line, sizeof line, "clip %s: %.2f s, measured %.2f–%.2f s at 1 kHz, %d strides%s\n", c.name.c_str(),
                c.duration_s, c.start_s, c.end_s, c.strides,
                ref ? (" (reference: " + ref->gait + ", docs/gait-reference.md)").c_str() : " (no gait reference)");
  s += line;
  const bool gait = ref && ref->periodic;
  bool starred = false;
  s += hoofTable(c, gait, verdicts, starred);
  if (starred) s += gallopForePairNote(c, *ref, verdicts);
  s += strideRows(c, gait, verdicts);
  if (!gait) s += wholeClipRows(c);
  if (ref && !ref->periodic) s += scriptedRows(verdicts);
  std::snprintf(line, sizeof line, "%-28s %.0f /s (%s at %.2f s)\n", "fastest channel change", c.max_channel_step,
                c.max_step_channel.c_str(), c.max_step_at_s);
  s += line;
  s += problemLines(c, ref);
  if (ref) s += verdictLine(verdicts);
  return s;
}

nlohmann::json clipInfoJson(const ClipInfo& c, const GaitReference* ref) {
  const std::vector<Verdict> verdicts = ref ? clipVerdicts(c, *ref) : std::vector<Verdict>{};
  nlohmann::json j;
  j["name"] = c.name;
  j["duration_s"] = c.duration_s;
  j["measured_s"] = {c.start_s, c.end_s};
  j["strides"] = c.strides;
  for (int h = 0; h < 4; ++h) {
    const HoofInfo& hi = c.hooves[h];
    nlohmann::json hj = {{"touchdown_phase", hi.touchdown_phase}, {"duty_factor", hi.duty_factor},
                         {"peak_height_cm", hi.peak_height_cm}, {"lowest_cm", hi.lowest_cm},
                         {"max_slide_mm_per_frame", hi.max_slide_mm}, {"touchdowns", hi.touchdowns},
                         {"stance_slide_cm", hi.stance_slide_cm},
                         {"stance_slide_s", {hi.stance_slide_from_s, hi.stance_slide_to_s}},
                         {"max_slide_mm_per_frame_outside_that_stance", hi.max_slide_outside_stance_mm}};
    if (ref && ref->periodic) {
      if (const Verdict* td = findVerdict(verdicts, std::string(kHoofNames[h]) + ".touchdown_phase")) {
        hj["reference_touchdown_phase"] = rangeJson(td->range);
        hj["touchdown_ok"] = td->ok;
        if (!td->note.empty()) {
          // The gallop's fore pair: judged against the one-suspension phase; the table's verdict beside it.
          hj["reference_touchdown_phase_table"] = rangeJson(ref->touchdown_phase[h]);
          hj["touchdown_ok_table"] = phaseDistance(hi.touchdown_phase, ref->touchdown_phase[h]) <= kTouchdownTolerance + 1e-9;
        }
      }
      if (const Verdict* duty = findVerdict(verdicts, std::string(kHoofNames[h]) + ".duty_factor")) {
        hj["reference_duty_factor"] = rangeJson(duty->range);
        hj["duty_ok"] = duty->ok;
      }
    }
    j["hooves"][kHoofNames[h]] = hj;
  }
  j["footfall_order"] = nlohmann::json::array();
  for (int h : c.footfall_order) j["footfall_order"].push_back(kHoofNames[h]);
  j["stride_hz"] = c.stride_hz;
  j["stride_length_cm"] = c.stride_length_cm;
  j["speed_cm_s"] = c.speed_cm_s;
  j["suspensions_per_stride"] = c.suspensions_per_stride;
  j["suspension_ms"] = c.suspension_ms;
  j["rear_pivot_ty_peak_to_peak_cm"] = c.pivot_ty_peak_to_peak_cm;
  j["rear_pivot_cycles_per_stride"] = c.pivot_ty_cycles_per_stride;
  j["pitch_deg"] = {c.pitch_min_deg, c.pitch_max_deg};
  j["whole_clip"] = {{"pitch_deg", {c.pitch_lowest_deg, c.pitch_highest_deg}},
                     {"pitch_held_40_70_s", c.pitch_held_s},
                     {"croup_ups", c.croup_ups},
                     {"airborne_phases", c.airborne_phases},
                     {"longest_airborne_ms", c.longest_airborne_ms},
                     {"longest_airborne_from_s", c.longest_airborne_from_s},
                     {"liftoff_pitch_deg", c.liftoff_pitch_deg},
                     {"slide_hoof", c.slide_hoof >= 0 ? nlohmann::json(kHoofNames[c.slide_hoof]) : nlohmann::json(nullptr)},
                     {"fore_touchdowns_during_slide", c.fore_touchdowns_during_slide}};
  j["fastest_channel"] = {{"channel", c.max_step_channel}, {"per_s", c.max_channel_step}, {"at_s", c.max_step_at_s}};
  j["problems"] = c.problems;
  j["expected_slides"] = nlohmann::json::array();
  for (int h = 2; h < 4; ++h)
    if (expectedSlide(c, ref, h) && c.hooves[h].max_slide_mm > c.slide_limit_mm) j["expected_slides"].push_back(kHoofNames[h]);
  if (ref) {
    nlohmann::json reference = {{"gait", ref->gait}, {"periodic", ref->periodic},
                                {"touchdown_tolerance", kTouchdownTolerance},
                                {"per_stride_tolerance", kPerStrideTolerance},
                                {"source", "docs/gait-reference.md"}};
    nlohmann::json flags = nlohmann::json::object(), details = nlohmann::json::array();
    bool all = true;
    for (const Verdict& v : verdicts) {
      flags[v.key] = v.ok;
      all = all && v.ok;
      reference[v.key] = rangeJson(v.range);
      nlohmann::json d = {{"key", v.key}, {"value", v.value}, {"reference", rangeJson(v.range)}, {"ok", v.ok}};
      if (!v.note.empty()) d["note"] = v.note;
      details.push_back(d);
    }
    // Kept for readers of the earlier format: the counts as whole numbers.
    if (ref->periodic) {
      reference["suspensions_per_stride"] = ref->suspensions_per_stride;
      reference["rear_pivot_cycles_per_stride"] = ref->pivot_cycles_per_stride;
    }
    j["reference"] = reference;
    j["verdicts"] = flags;
    j["verdict_details"] = details;
    j["all_ok"] = all;
  }
  return j;
}

}  // namespace stirrup::rig
