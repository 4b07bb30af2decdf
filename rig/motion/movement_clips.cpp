#include "rig/motion/movement_clips.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rig/error.h"
#include "rig/motion/noise.h"

namespace stirrup::rig {
namespace {

constexpr double kGravityCm = 981.0;
constexpr double kNever = std::numeric_limits<double>::infinity();
constexpr int kLF = 0, kRF = 1, kLH = 2, kRH = 3;
using HC = HorseChannel;

Keys& key(Movement& m, HorseChannel c) { return m.channel_keys[static_cast<std::size_t>(c)]; }

// Seeded ±amount jitter for one named quantity of a scripted movement.
double jitter(const Variation& v, int what, int index = 0) { return 1.0 + 0.1 * v.amount * hashSigned(v.seed, what, index); }

GaitTimeline oneGait(const GaitParams& g, double duration_s, const Variation& v) {
  GaitTimeline tl;
  tl.segments.push_back({g, duration_s});
  tl.variation = v.amount;
  tl.seed = v.seed;
  return tl;
}

Footfall planted(double down, double up, double x, SwingShape swing = {}) {
  Footfall f;
  f.down_s = down;
  f.up_s = up;
  f.x_cm = x;
  f.swing = swing;
  return f;
}

void append(HoofSchedule& s, const HoofSchedule& more) { s.insert(s.end(), more.begin(), more.end()); }

// Scripted footfalls continue from the gait: the last gait swing carries the gait's lift.
void setLastSwing(HoofSchedule& s, const SwingShape& w) {
  if (!s.empty()) s.back().swing = w;
}

// The timeline of `gaits` in turn, each segment_s long, blended over blend_s, varied by `v`.
GaitTimeline gaitTimeline(const std::vector<GaitParams>& gaits, double segment_s, double blend_s, Variation v) {
  if (gaits.empty()) throw InputError("gait sequence: no gaits");
  GaitTimeline tl;
  for (const GaitParams& g : gaits) tl.segments.push_back({g, segment_s});
  tl.blend_s = blend_s;
  tl.variation = v.amount;
  tl.seed = v.seed;
  return tl;
}

}  // namespace

Movement makeSteadyGait(const GaitParams& gait, double duration_s, Variation v) {
  return makeGaitSequence({gait}, duration_s, 1.0, v);
}

Movement makeGaitSequence(const std::vector<GaitParams>& gaits, double segment_s, double blend_s, Variation v) {
  GaitTimeline tl = gaitTimeline(gaits, segment_s, blend_s, v);
  if (!(segment_s > blend_s)) throw InputError("gait sequence: each gait must last longer than the blend");
  Movement m;
  m.name = gaits.size() == 1 ? gaits.front().name : "sequence";
  m.duration_s = applyGaitTimeline(tl, m);
  for (int h = 0; h < 4; ++h) m.hooves[h] = scanFootfalls(m, tl, h, -2.0, m.duration_s + 2.0, kNever);
  return m;
}

namespace {

// The sliding stop from whatever gait state `m` holds, starting at t_s.
void appendStop(Movement& m, const GaitTimeline& tl, double t_s, const StopParams& p, const Variation& v) {
  const double v0 = m.speed_cm_s.at(t_s);
  const double t_e = t_s + p.slide_s;
  m.duration_s = t_e + p.settle_s;
  // Speed falls linearly to zero over the slide.
  m.speed_cm_s.add(t_s, v0);
  m.speed_cm_s.add(t_e, 0.0);
  // The trunk oscillation fades as the hind legs lock.
  m.oscillation_gain.add(t_s - 0.25, 1.0).add(t_s + 0.2, 0.0);

  // Hind hooves: the last gait footfalls lift by t_s - 0.12, then both land under the body and slide.
  const int lead_hind = p.lead == Lead::Right ? kRH : kLH, trail_hind = lead_hind == kRH ? kLH : kRH;
  const double under = p.hind_under_cm * jitter(v, 1);
  for (int h : {trail_hind, lead_hind}) {
    const double down = t_s + (h == lead_hind ? 0.04 : 0.0);
    m.hooves[h] = scanFootfalls(m, tl, h, -2.0, down, down - 0.12);
    Footfall slide;
    slide.down_s = down;
    slide.up_s = t_e + 0.3 + (h == lead_hind ? 0.3 : 0.0);
    slide.slides = true;
    slide.slide_tx_cm = under;
    slide.swing.lift_cm = 8.0;
    m.hooves[h].push_back(slide);
    // Square up: step back to the rest place once stopped.
    m.hooves[h].push_back(planted(slide.up_s + 0.3, kNever, m.travelCm(t_e)));
  }
  // Fore hooves keep stepping, planted ahead of the body to brake; each stance lasts until the body
  // has passed about 90 cm over it, so the braking steps shorten as the horse slows.
  const int lead_fore = p.lead == Lead::Right ? kRF : kLF, trail_fore = lead_fore == kRF ? kLF : kRF;
  const double fore_start = t_s + 0.12;
  for (int h : {trail_fore, lead_fore}) {
    double down = fore_start + (h == lead_fore ? 0.16 : 0.0);
    m.hooves[h] = scanFootfalls(m, tl, h, -2.0, down, down - 0.1);
    SwingShape swing;
    swing.lift_cm = p.fore_lift_cm * jitter(v, 2, h);
    setLastSwing(m.hooves[h], swing);
    while (down < t_e - 0.2) {
      const double x0 = m.travelCm(down);
      double up = down + 0.05;
      while (up < down + 0.3 && m.travelCm(up) - x0 < 90.0) up += 0.005;
      m.hooves[h].push_back(planted(down, up, x0 + 45.0, swing));
      down = up + 0.14;
    }
    // The last step lands just ahead of the rest place and stays.
    m.hooves[h].push_back(planted(std::max(down, t_e - 0.1), kNever, m.travelCm(t_e) + (h == lead_fore ? 12.0 : 8.0)));
  }

  // Trunk: croup lowered, front up, back rounded, weight shifted back, head up; then stand.
  const double pitch = p.pitch_deg * jitter(v, 3), drop = p.croup_drop_cm * jitter(v, 4);
  key(m, HC::rearPivotRz).add(t_s - 0.1, 0.0).add(t_s + 0.4, pitch).add(t_e, pitch).add(t_e + 0.7, 0.0);
  key(m, HC::rearPivotTy).add(t_s - 0.1, 0.0).add(t_s + 0.5, -drop).add(t_e, -drop).add(t_e + 0.8, 0.0);
  key(m, HC::rearPivotTx).add(t_s - 0.1, 0.0).add(t_s + 0.5, -10.0).add(t_e, -10.0).add(t_e + 0.8, 0.0);
  key(m, HC::backMidRz).add(t_s - 0.1, 0.0).add(t_s + 0.5, 6.0).add(t_e, 6.0).add(t_e + 0.8, 0.0);
  m.neck_rz.add(t_s - 0.1, 0.0).add(t_s + 0.5, 10.0).add(t_e, 10.0).add(t_e + 0.8, 0.0);
  m.tail_rz.add(t_s - 0.1, 0.0).add(t_s + 0.5, 12.0).add(t_e, 12.0).add(t_e + 0.8, 0.0);
}

}  // namespace

Movement makeStop(const StopParams& p, Variation v) {
  GaitParams gallop = gallopParams(p.entry_speed_cm_s, p.lead);
  return makeGaitSequenceToStop({gallop}, p.entry_s, 0.5, p, v);
}

Movement makeGaitSequenceToStop(const std::vector<GaitParams>& gaits, double segment_s, double blend_s,
                                const StopParams& p, Variation v) {
  GaitTimeline tl = gaitTimeline(gaits, segment_s, blend_s, v);
  Movement m;
  m.name = gaits.size() == 1 ? "stop" : "sequence";
  const double t_s = applyGaitTimeline(tl, m);
  appendStop(m, tl, t_s, p, v);
  return m;
}

JumpTimes jumpTimes(const JumpParams& p) {
  JumpTimes t;
  const double stride_s = 1.0 / canterParams(p.lead).stride_hz;
  // The centre of gravity rises enough for the tucked hooves to clear the fence.
  // The centre of gravity rises enough for every folded hoof to clear the fence with the clearance.
  t.apex_cm = std::max(20.0, p.fence_height_cm + p.clearance_cm - std::min(p.fore_tuck_cm, p.hind_tuck_cm));
  t.takeoff_s = p.approach_strides * stride_s + 0.45;
  t.landing_s = t.takeoff_s + std::sqrt(8.0 * t.apex_cm / kGravityCm);  // ballistic: apex = g T^2 / 8
  return t;
}

Movement makeJump(const JumpParams& p, Variation v) {
  if (p.fence_height_cm < 0.0 || p.fence_height_cm > 200.0) throw InputError("jump: fence_height_cm must be 0..200");
  if (p.approach_strides < 1) throw InputError("jump: approach_strides must be >= 1");
  GaitParams canter = canterParams(p.lead);
  canter.speed_cm_s = p.approach_speed_cm_s;
  const JumpTimes jt = jumpTimes(p);
  const double t_off = jt.takeoff_s, t_land = jt.landing_s;
  const double stride_s = 1.0 / canter.stride_hz;
  Movement m;
  m.name = "jump";
  m.duration_s = t_land + 0.6 + std::max(0, p.recovery_strides) * stride_s;
  const GaitTimeline tl = oneGait(canter, m.duration_s + 2.0, v);
  applyGaitTimeline(tl, m);
  m.flight_start_s = t_off;
  m.flight_end_s = t_land;
  m.flight_apex_cm = jt.apex_cm;
  Obstacle fence;
  fence.travel_cm = m.travelCm(0.5 * (t_off + t_land));
  fence.height_cm = p.fence_height_cm;
  m.obstacles.push_back(fence);

  const bool right = p.lead == Lead::Right;
  const int lead_fore = right ? kRF : kLF, trail_fore = right ? kLF : kRF;
  const int lead_hind = right ? kRH : kLH, trail_hind = right ? kLH : kRH;
  // Take-off: the forelegs plant and leave first (raising the forehand), then the hind legs come
  // under the body and push off together; the leading hind leaves last.
  // Folded legs are held through the middle of the flight (plateau), hooves up and under the body.
  SwingShape fore_tuck{p.fore_tuck_cm * jitter(v, 5), 0.5, -15.0, true};
  SwingShape hind_tuck{p.hind_tuck_cm * jitter(v, 6), 0.5, 10.0, true};
  const std::array<std::array<double, 2>, 4> takeoff = {{
      {t_off - 0.44, t_off - 0.30},  // trailing fore
      {t_off - 0.40, t_off - 0.26},  // leading fore
      {t_off - 0.18, t_off - 0.03},  // trailing hind
      {t_off - 0.16, t_off},         // leading hind
  }};
  // Landing: the trailing fore first, the leading fore, then the hind legs.
  const std::array<std::array<double, 2>, 4> landing = {{
      {t_land, t_land + 0.20},
      {t_land + 0.07, t_land + 0.27},
      {t_land + 0.30, t_land + 0.48},
      {t_land + 0.34, t_land + 0.52},
  }};
  const std::array<int, 4> order = {trail_fore, lead_fore, trail_hind, lead_hind};
  for (int i = 0; i < 4; ++i) {
    const int h = order[i];
    const bool fore = i < 2;
    const auto [d0, u0] = takeoff[i];
    const auto [d1, u1] = landing[i];
    m.hooves[h] = scanFootfalls(m, tl, h, -2.0, d0, d0 - 0.12);
    // Take-off stance: fores planted a little ahead, hinds under the body (tx from +40 to about -56,
    // gait-reference: leading hind ≈ 1.1 m behind the centre of gravity at lift-off).
    const double ahead = fore ? 30.0 : 40.0;
    m.hooves[h].push_back(planted(d0, u0, m.travelCm(d0) + ahead, fore ? fore_tuck : hind_tuck));
    SwingShape after;
    after.lift_cm = canter.hoof_lift_cm * (fore ? canter.fore_lift_scale : 1.0);
    m.hooves[h].push_back(planted(d1, u1, m.travelCm(d1) + 45.0, after));
    append(m.hooves[h], scanFootfalls(m, tl, h, u1 + 0.2, m.duration_s + 2.0, kNever));
  }

  // Trunk: gait oscillation fades for the jump and returns in the recovery.
  m.oscillation_gain.add(t_off - 0.7, 1.0).add(t_off - 0.4, 0.0).add(t_land + 0.3, 0.0).add(t_land + 0.8, 1.0);
  const double up = p.takeoff_pitch_deg * jitter(v, 7), down = p.landing_pitch_deg * jitter(v, 8);
  key(m, HC::rearPivotRz)
      .add(t_off - 0.7, 0.0).add(t_off - 0.42, -4.0).add(t_off, up).add(t_land, down)
      .add(t_land + 0.35, -3.0).add(t_land + 0.8, 0.0);
  key(m, HC::rearPivotTy)
      .add(t_off - 0.6, 0.0).add(t_off - 0.12, -10.0).add(t_off, 0.0).add(t_land, 0.0)
      .add(t_land + 0.25, -8.0).add(t_land + 0.7, 0.0);
  // Bascule: the back rounds over the fence, the neck reaches forward and down, then lifts to land.
  key(m, HC::backMidRz).add(t_off - 0.2, 0.0).add(0.5 * (t_off + t_land), 7.0).add(t_land + 0.3, 0.0);
  m.neck_rz.add(t_off - 0.3, 0.0).add(0.5 * (t_off + t_land), -12.0).add(t_land, 8.0).add(t_land + 0.6, 0.0);
  m.head_rz.add(t_off - 0.3, 0.0).add(0.5 * (t_off + t_land), 6.0).add(t_land + 0.6, 0.0);
  m.tail_rz.add(t_off - 0.2, 0.0).add(t_off + 0.1, 15.0).add(t_land + 0.4, 0.0);
  return m;
}

RearTimes rearTimes(const RearParams& p) {
  const double t_r0 = 1.0;
  return {t_r0 + p.rise_s, t_r0 + p.rise_s + p.hold_s};
}

Movement makeRear(const RearParams& p, Variation v) {
  if (p.angle_deg < 10.0 || p.angle_deg > 80.0) throw InputError("rear: angle_deg must be 10..80");
  if (p.hold_s < 0.0 || p.rise_s < 0.2 || p.descend_s < 0.2) throw InputError("rear: rise_s, descend_s >= 0.2 and hold_s >= 0");
  if (p.paw_strokes < 0 || p.paw_strokes > 8) throw InputError("rear: paw_strokes must be 0..8");
  if (p.paw_cm < 0.0 || p.paw_cm > 40.0) throw InputError("rear: paw_cm must be 0..40");
  const double t_r0 = 1.0, t_r1 = t_r0 + p.rise_s, t_h1 = t_r1 + p.hold_s, t_d1 = t_h1 + p.descend_s;
  Movement m;
  m.name = "rear";
  m.duration_s = t_d1 + 1.6;
  const double angle = p.angle_deg * jitter(v, 9);
  const double theta = angle * std::numbers::pi / 180.0;
  // Hind hooves step under the body, carry the whole weight, then step back to rest.
  for (int h : {kLH, kRH}) {
    const double off = h == kLH ? 0.0 : 0.18;
    SwingShape step{8.0, 0.0, 0.0, false};
    m.hooves[h].push_back(planted(-1.0, 0.4 + off, 0.0, step));
    m.hooves[h].push_back(planted(0.72 + off, t_d1 + 0.3 + off, p.hind_under_cm, step));
    m.hooves[h].push_back(planted(t_d1 + 0.62 + off, kNever, 0.0, step));
  }
  // Forelegs: leave as the forehand rises, held up and folded (the shoulders swing up and back about
  // the hips), land as it comes down.
  for (int h : {kLF, kRF}) {
    const double off = h == kLF ? 0.0 : 0.06;
    const double up = t_r0 + 0.05 + off, down = t_d1 - 0.08 + off;
    SwingShape raised;
    raised.lift_cm = p.shoulder_cm * std::sin(theta) + 30.0 * jitter(v, 10, h);
    raised.reach_cm = -p.shoulder_cm * (1.0 - std::cos(theta)) - 25.0;
    // Rise and fall of the hoof take as long as the trunk's rise and descent.
    raised.plateau = std::clamp(1.0 - (p.rise_s + p.descend_s) / (down - up), 0.0, 0.9);
    // Pawing the air, the legs half a stroke apart (one strikes out as the other pulls back).
    raised.paw_strokes = p.paw_strokes;
    raised.paw_cm = p.paw_cm * jitter(v, 14, h);
    raised.paw_phase = h == kLF ? 0.0 : 0.5;
    m.hooves[h].push_back(planted(-1.0, up, 0.0, raised));
    m.hooves[h].push_back(planted(down, kNever, 4.0));
  }
  // A little balancing sway while up (seeded), the hips lowered as the hocks bend under the weight.
  const double sway = 3.0 * v.amount * hashSigned(v.seed, 11);
  key(m, HC::rearPivotRz).add(t_r0, 0.0).add(t_r1, angle).add(0.5 * (t_r1 + t_h1), angle + sway).add(t_h1, angle).add(t_d1, 0.0);
  key(m, HC::rearPivotTy).add(t_r0, 0.0).add(t_r1, -12.0).add(t_h1, -12.0).add(t_d1, 0.0);
  key(m, HC::rearPivotTx).add(t_r0, 0.0).add(t_r1, -6.0).add(t_h1, -6.0).add(t_d1, 0.0);
  // The head leans back to bring weight over the hind legs (Kuhnel 5.4); the tail drops.
  m.neck_rz.add(t_r0, 0.0).add(t_r1, 15.0).add(t_h1, 15.0).add(t_d1, 0.0);
  m.head_rz.add(t_r0, 0.0).add(t_r1, 10.0).add(t_h1, 10.0).add(t_d1, 0.0);
  m.tail_rz.add(t_r0, 0.0).add(t_r1, -20.0).add(t_h1, -20.0).add(t_d1, 0.0);
  return m;
}

namespace {
constexpr double kBuckLead_s = 0.3;       // standing still before the first buck
constexpr double kBuckForeUp_s = 0.42;    // the forehand's flight, from the start of a buck
constexpr double kRightLag_s = 0.03;      // the right fore follows the left (the right hind: 0.02)
}  // namespace

BuckTimes buckTimes(const BuckParams& p, int buck) {
  BuckTimes t;
  t.start_s = kBuckLead_s + buck * p.period_s;
  t.fore_land_s = t.start_s + kBuckForeUp_s;
  t.hind_off_s = t.fore_land_s - p.leap_s;
  t.hind_land_s = t.hind_off_s + p.kick_s;
  // The croup keeps rising after the forelegs plant and peaks in the second half of the kick.
  t.croup_peak_s = std::max(t.fore_land_s + 0.06, t.hind_off_s + 0.75 * p.kick_s);
  return t;
}

Movement makeBuck(const BuckParams& p, Variation v) {
  if (p.bucks < 1 || p.bucks > 50) throw InputError("buck: bucks must be 1..50");
  if (p.kick_s < 0.15 || p.kick_s > 0.6 * p.period_s) throw InputError("buck: kick_s must be 0.15..0.6 x period_s");
  if (p.leap_s < 0.05 || p.leap_s > 0.3) throw InputError("buck: leap_s must be 0.05..0.3");
  if (p.kick_s < p.leap_s + 0.1) throw InputError("buck: kick_s must be at least leap_s + 0.1 (the hind legs land after the forelegs)");
  if (buckTimes(p, 0).hind_land_s + 0.05 > buckTimes(p, 1).start_s)
    throw InputError("buck: period_s must leave the hind legs time to land before the next buck (longer period_s or shorter kick_s)");
  Movement m;
  m.name = "buck";
  const double P = p.period_s;
  const double t0 = kBuckLead_s;
  m.duration_s = t0 + p.bucks * P + 0.8;
  for (auto& s : m.hooves) s.push_back(planted(-1.0, t0, 0.0));
  for (auto& k : {HC::rearPivotRz, HC::rearPivotTy, HC::rearPivotRx, HC::rearPivotRy, HC::backMidRz})
    key(m, k).add(t0, 0.0);
  m.neck_rz.add(t0, 0.0);
  m.head_rz.add(t0, 0.0);
  for (int b = 0; b < p.bucks; ++b) {
    const BuckTimes bt = buckTimes(p, b);
    const double s = bt.start_s;
    const double amp = jitter(v, 12, b);
    // Side action: the twist changes side from buck to buck, its size seeded.
    const double side = (b % 2 == 0 ? 1.0 : -1.0) * p.twist_deg * jitter(v, 13, b);
    // Forehand rises (hinds planted) ...
    for (int h : {kLF, kRF}) {
      const double off = h == kLF ? 0.0 : kRightLag_s;
      m.hooves[h].back().up_s = s + off;
      m.hooves[h].back().swing = {35.0 * amp, 0.2, -10.0, false};
      m.hooves[h].push_back(planted(bt.fore_land_s + off, s + P + off, 0.0));
    }
    // ... the hind legs push off before it lands (all four in the air), then kick back and land.
    for (int h : {kLH, kRH}) {
      const double off = h == kLH ? 0.0 : 0.02;
      m.hooves[h].back().up_s = bt.hind_off_s + off;
      m.hooves[h].back().swing = {p.kick_lift_cm * amp, 0.3, -40.0, false};
      m.hooves[h].push_back(planted(bt.hind_land_s + off, s + P + 0.5, 0.0));
    }
    const double peak = bt.croup_peak_s;
    // Level at the top of the leap, then croup up while the forelegs carry the weight.
    key(m, HC::rearPivotRz).add(s + 0.22, p.front_rise_deg * amp).add(bt.fore_land_s, 0.0)
        .add(peak, p.croup_deg * amp).add(s + P, 0.0);
    key(m, HC::rearPivotTy).add(s + 0.22, 8.0).add(bt.fore_land_s - 0.5 * p.leap_s, 16.0 * amp)
        .add(peak, 14.0 * amp).add(s + P, 0.0);
    key(m, HC::rearPivotRx).add(peak, side).add(s + P, 0.0);
    key(m, HC::rearPivotRy).add(peak, 0.8 * side).add(s + P, 0.0);
    // Back arched like an angry cat, head down between the legs (Thayer via Kuhnel 5.6).
    key(m, HC::backMidRz).add(peak, 10.0).add(s + P, 0.0);
    m.neck_rz.add(s + 0.22, 8.0).add(peak, -25.0).add(s + P, 0.0);
    m.head_rz.add(peak, -10.0).add(s + P, 0.0);
  }
  for (auto& s : m.hooves) s.back().up_s = kNever;
  return m;
}

}  // namespace stirrup::rig
