#include "rig/motion/gait_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rig/error.h"

namespace stirrup::rig {

double phaseDistance(double a, double b) {
  const double d = std::abs(a - b) - std::floor(std::abs(a - b));
  return std::min(d, 1.0 - d);
}

double phaseDistance(double a, const Range& r) {
  const double lo = r.lo - std::floor(r.lo), width = r.hi - r.lo;
  const double from_lo = a - lo - std::floor(a - lo);  // 0..1 past lo, going forward
  if (from_lo <= width + 1e-12) return 0.0;
  return std::min(from_lo - width, 1.0 - from_lo);
}

std::array<double, 2> gallopOneSuspensionForePhases(double stride_hz) {
  // gait-reference (Witte 2006): hind stance 143 ms at 2.0 Hz (9 m/s) -> 94 ms at 2.4 Hz (17 m/s).
  const double u = std::clamp((stride_hz - 2.0) / 0.4, 0.0, 1.0);
  const double hind_duty = (0.143 - 0.049 * u) * stride_hz;
  const double lf = 0.10 + hind_duty;  // the right hind (table .10) lifts off: the latest one-suspension touchdown
  return {lf, lf + 0.10};              // the table's fore pair lag
}

std::optional<GaitReference> gaitReference(const std::string& gait) {
  // Every number from docs/gait-reference.md; ≈ ranges are its engineering estimates.
  GaitReference r;
  r.gait = gait;
  const auto phases = [&](double lf, double rf, double lb, double rb) {
    r.touchdown_phase = {Range{lf, lf}, Range{rf, rf}, Range{lb, lb}, Range{rb, rb}};
  };
  if (gait == "walk") {
    phases(0.25, 0.75, 0.0, 0.5);
    r.stride_hz = Range{1.0 / 1.1, 1.0};          // stride ≈ 1.0–1.1 s
    r.stride_length_cm = Range{160, 190};         // ≈ 1.6–1.9 m
    r.speed_cm_s = Range{180, 190};               // 1.8–1.9 m/s
    r.duty_fore = r.duty_hind = Range{0.60, 0.70};
    r.suspensions_per_stride = 0;
    r.pitch_range_deg = Range{0, 20};             // head, neck, trunk within ≈ 20° (Dunbar 2008)
    return r;
  }
  if (gait == "trot") {
    phases(0.5, 0.0, 0.0, 0.5);                   // the hind of a pair lands ≈ 30 ms first: inside ±.05
    r.stride_hz = Range{1.0 / 0.808, 1.0 / 0.780};  // 794 ± 14 ms (Holmström)
    r.stride_length_cm = Range{260, 300};
    r.speed_cm_s = Range{350, 370};               // 3.6 ± 0.1 m/s (Gómez Álvarez 2009)
    r.duty_fore = r.duty_hind = Range{0.35, 0.45};
    r.suspensions_per_stride = 2;
    r.suspension_ms = Range{40, 90};
    r.pivot_ty_peak_to_peak_cm = Range{5, 7};     // withers ≈ 7 cm (Buchner 2000)
    r.pivot_cycles_per_stride = 2;
    r.pitch_range_deg = Range{2, 4};
    return r;
  }
  if (gait == "canter") {
    r.touchdown_phase = {Range{0.25, 0.30}, Range{0.50, 0.55}, Range{0.0, 0.0}, Range{0.25, 0.30}};
    r.stride_hz = Range{1.0 / 0.65, 1.0 / 0.55};  // stride ≈ 0.55–0.65 s
    r.stride_length_cm = Range{300, 400};
    r.speed_cm_s = Range{500, 700};
    r.suspensions_per_stride = 1;
    r.pivot_cycles_per_stride = 1;                // Viry 2013
    r.pitch_range_deg = Range{5, 10};
    return r;
  }
  if (gait == "gallop") {
    phases(0.50, 0.60, 0.0, 0.10);                // Muybridge via Rotenberg
    r.one_suspension_fore_phases = true;          // see gallopOneSuspensionForePhases
    r.stride_hz = Range{2.0, 2.4};                // Witte 2006, 9 -> 17 m/s
    r.stride_length_cm = Range{450, 710};
    r.speed_cm_s = Range{900, 1700};
    r.duty_fore = Range{0.18, 0.26};
    r.duty_hind = Range{0.094 * 2.4, 0.143 * 2.0};  // hind stance 143 -> 94 ms at those strides
    r.suspensions_per_stride = 1;
    r.pivot_cycles_per_stride = 1;
    r.pitch_range_deg = Range{5, 10};
    return r;
  }
  r.periodic = false;
  if (gait == "rear") {
    r.rear_pitch_deg = Range{40, 70};             // ≈ 40–70° trunk pitch held 0.5–2 s (Kuhnel 5.4)
    r.rear_held_s = Range{0.5, 2.0};
    return r;
  }
  if (gait == "buck") {
    r.croup_pitch_deg = Range{-35, -20};          // croup-up pitch ≈ −20 to −35° (Kuhnel 5.6)
    r.all_four_leave_ground = true;               // "all four legs leave the ground"
    return r;
  }
  if (gait == "jump") {
    r.takeoff_pitch_deg = Range{21.4 - 2.5, 21.4 + 2.5};  // Colborne 1995, at the leading hind's lift-off
    return r;
  }
  if (gait == "stop") {
    r.slide_cm = Range{0, 1000};                  // slides up to ≈ 10 m (Kuhnel 5.5)
    r.fore_steps_during_slide = 2;                // "the forelegs keep stepping"
    return r;
  }
  return std::nullopt;
}

namespace {

constexpr double kAtLeast = std::numeric_limits<double>::infinity();

Verdict verdict(std::string key, double value, Range range, bool ok, std::string note = {}) {
  return Verdict{std::move(key), value, range, ok, std::move(note)};
}

Verdict inRange(std::string key, double value, Range range, double slack = 0.0, std::string note = {}) {
  const bool ok = Range{range.lo - slack, range.hi + slack}.contains(value);
  return verdict(std::move(key), value, range, ok, std::move(note));
}

}  // namespace

std::vector<Verdict> clipVerdicts(const ClipInfo& c, const GaitReference& ref) {
  std::vector<Verdict> out;
  if (ref.periodic) {
    if (c.strides > 0) {
      for (int h = 0; h < 4; ++h) {
        Range r = ref.touchdown_phase[h];
        std::string note;
        if (ref.one_suspension_fore_phases && h < 2) {
          const double table = r.lo, derived = gallopOneSuspensionForePhases(c.stride_hz)[h];
          const double away = phaseDistance(c.hooves[h].touchdown_phase, table);
          r = Range{derived, derived};
          note = "one-suspension phase (right hind .10 + Witte's hind stance at this stride; docs/horse-clips.md "
                 "\"Gallop phases\"); the table's " + printfNumber("%.2f", table) + " is " + printfNumber("%.2f", away) + " away: " +
                 (away <= kTouchdownTolerance ? "ok" : "OUTSIDE");
        }
        const bool ok = phaseDistance(c.hooves[h].touchdown_phase, r) <= kTouchdownTolerance + 1e-9;
        out.push_back(verdict(std::string(kHoofNames[h]) + ".touchdown_phase", c.hooves[h].touchdown_phase, r, ok, note));
      }
        // Within the 1 kHz measurement's resolution of the range counts as inside: a stance is measured up
      // to one sample short at each end (duty ± two samples per stride), a stride up to one sample off
      // over all the strides.
      const double duty_slack = 2.0 * c.stride_hz / c.sample_hz;
      for (int h = 0; h < 4; ++h)
        if (const auto& duty = h < 2 ? ref.duty_fore : ref.duty_hind)
          out.push_back(inRange(std::string(kHoofNames[h]) + ".duty_factor", c.hooves[h].duty_factor, *duty, duty_slack));
    }
    const double hz_slack = c.strides > 0 ? c.stride_hz * c.stride_hz / (c.sample_hz * c.strides) : 0.0;
    if (ref.stride_hz) out.push_back(inRange("stride_hz", c.stride_hz, *ref.stride_hz, hz_slack));
    if (ref.stride_length_cm) out.push_back(inRange("stride_length_cm", c.stride_length_cm, *ref.stride_length_cm));
    if (ref.speed_cm_s) out.push_back(inRange("speed_cm_s", c.speed_cm_s, *ref.speed_cm_s));
    const double n = ref.suspensions_per_stride;
    out.push_back(verdict("suspensions_per_stride", c.suspensions_per_stride, Range{n, n},
                          c.strides > 0 && std::abs(c.suspensions_per_stride - n) <= kPerStrideTolerance));
    if (ref.suspension_ms) out.push_back(inRange("suspension_ms", c.suspension_ms, *ref.suspension_ms));
    if (ref.pivot_ty_peak_to_peak_cm)
      out.push_back(inRange("rear_pivot_ty_peak_to_peak_cm", c.pivot_ty_peak_to_peak_cm, *ref.pivot_ty_peak_to_peak_cm));
    if (ref.pivot_cycles_per_stride > 0) {
      const double k = ref.pivot_cycles_per_stride;
      out.push_back(verdict("rear_pivot_cycles_per_stride", c.pivot_ty_cycles_per_stride, Range{k, k},
                            c.strides > 0 && std::abs(c.pivot_ty_cycles_per_stride - k) <= kPerStrideTolerance));
    }
    if (ref.pitch_range_deg) out.push_back(inRange("pitch_range_deg", c.pitch_max_deg - c.pitch_min_deg, *ref.pitch_range_deg));
    return out;
  }
  if (ref.rear_pitch_deg) out.push_back(inRange("rear.peak_pitch_deg", c.pitch_highest_deg, *ref.rear_pitch_deg));
  if (ref.rear_held_s) out.push_back(inRange("rear.held_s", c.pitch_held_s, *ref.rear_held_s));
  if (ref.croup_pitch_deg) out.push_back(inRange("buck.croup_pitch_deg", c.pitch_lowest_deg, *ref.croup_pitch_deg));
  if (ref.all_four_leave_ground) {
    // Every buck (every croup-up) has its airborne phase: at least one in all, and no fewer than bucks.
    const double need = std::max(1, c.croup_ups);
    out.push_back(verdict("buck.airborne_phases", c.airborne_phases, Range{need, kAtLeast}, c.airborne_phases >= need,
                          std::to_string(c.croup_ups) + " croup-ups"));
  }
  if (ref.takeoff_pitch_deg) {
    if (c.airborne_phases > 0)
      out.push_back(inRange("jump.takeoff_pitch_deg", c.liftoff_pitch_deg, *ref.takeoff_pitch_deg, 0.0,
                            "at the last lift-off before the longest airborne phase"));
    else
      out.push_back(verdict("jump.takeoff_pitch_deg", 0.0, *ref.takeoff_pitch_deg, false, "no airborne phase: no take-off"));
  }
  if (ref.slide_cm) {
    const double slide = c.slide_hoof >= 0 ? c.hooves[c.slide_hoof].stance_slide_cm : 0.0;
    out.push_back(inRange("stop.slide_cm", slide, *ref.slide_cm, 0.0,
                          c.slide_hoof >= 0 ? std::string(kHoofNames[c.slide_hoof]) : std::string("no hoof slides")));
  }
  if (ref.fore_steps_during_slide > 0) {
    const double need = ref.fore_steps_during_slide;
    out.push_back(verdict("stop.fore_steps_during_slide", c.fore_touchdowns_during_slide, Range{need, kAtLeast},
                          c.slide_hoof >= 0 && c.fore_touchdowns_during_slide >= need));
  }
  return out;
}

}  // namespace stirrup::rig
