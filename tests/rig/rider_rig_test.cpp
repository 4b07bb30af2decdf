// The rider rig against the thesis. Expected values are Appendix B's expressions written out by
// hand with the thesis's literal constants (never by calling the code under test), on both sides of
// every limit. Horse inputs are in cm; the thesis profile divides them by 10, so 40 cm reads as 4.
#include "rig/rider_rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

using H = HorseChannel;
using R = RiderChannel;

constexpr double kTol = 1e-9;

RiderChannels eval(const HorseChannels& h) { return evaluateRider(h, RigProfile::thesis()); }

// A horse with every hoof height and the roll set, used by the foot, knee, hair and cloth tests.
// Hoof heights 30, 20, 10, 40 cm = 3 + 2 + 1 + 4 = 10 thesis units; rearPivot.rx = 8 degrees.
HorseChannels hoovesUp(double scale = 1.0) {
  HorseChannels h;
  h[H::lfHoofTy] = 30 * scale;
  h[H::rfHoofTy] = 20 * scale;
  h[H::lbHoofTy] = 10 * scale;
  h[H::rbHoofTy] = 40 * scale;
  h[H::rearPivotRx] = 8;
  return h;
}

// ---- Equation 1 -------------------------------------------------------------------------------

// Appendix B's first branch, as printed, with thesis units.
double eq1ByHand(double prz, double py, double px, double lfx, double rfx, double lbx, double rbx, double front_y,
                 double hind_y) {
  return prz * ((py + 2) * .07) + ((px - ((lbx + rbx) / 2)) * .25) + ((px - ((lfx + rfx) / 2)) * -.25) +
         (((front_y * ((std::abs(prz) + 5) * .1)) * 0.9) - (hind_y * 0.4)) * .40;
}

HorseChannels eq1Horse(double lf_ty, double rf_ty, double lb_ty, double rb_ty) {
  HorseChannels h;
  h[H::rearPivotRz] = 10;
  h[H::rearPivotTy] = 50;  // 5 units
  h[H::rearPivotTx] = 10;  // 1 unit
  h[H::lfHoofTx] = 40;
  h[H::rfHoofTx] = 20;     // mean 3 units
  h[H::lbHoofTx] = -20;
  h[H::rbHoofTx] = -40;    // mean -3 units
  h[H::lfHoofTy] = lf_ty;
  h[H::rfHoofTy] = rf_ty;
  h[H::lbHoofTy] = lb_ty;
  h[H::rbHoofTy] = rb_ty;
  return h;
}

TEST(RiderRigEq1, BelowBothHoofHeightLimits) {
  // front 3 + 2 = 5 < 18, hind 1 + 2 = 3 < 15:
  // 10*(7*.07) + (1+3)*.25 + (1-3)*-.25 + ((5*1.5)*.9 - 3*.4)*.4 = 4.9 + 1 + 0.5 + 2.22 = 8.62
  const RiderChannels r = eval(eq1Horse(30, 20, 10, 20));
  EXPECT_NEAR(r[R::lowerBackRz], 8.62, kTol);
  EXPECT_NEAR(r[R::lowerBackRz], eq1ByHand(10, 5, 1, 4, 2, -2, -4, 5, 3), kTol);
}

TEST(RiderRigEq1, FrontHoofHeightsClampedAt18) {
  // front 15 + 10 = 25 >= 18: Appendix B substitutes 18 (its +2.5 on lfHoof.tx is decided away).
  // 4.9 + 1 + 0.5 + ((18*1.5)*.9 - 1.2)*.4 = 6.4 + 9.24 = 15.64
  const RiderChannels r = eval(eq1Horse(150, 100, 10, 20));
  EXPECT_NEAR(r[R::lowerBackRz], 15.64, kTol);
  // Just below the limit the unclamped expression still runs: front 17.9.
  EXPECT_NEAR(eval(eq1Horse(90, 89, 10, 20))[R::lowerBackRz], eq1ByHand(10, 5, 1, 4, 2, -2, -4, 17.9, 3), kTol);
}

TEST(RiderRigEq1, HindHoofHeightsClampedAt15) {
  // hind 10 + 10 = 20 >= 15: substitute 15. 6.4 + ((5*1.5)*.9 - 15*.4)*.4 = 6.4 + 0.3 = 6.7
  EXPECT_NEAR(eval(eq1Horse(30, 20, 100, 100))[R::lowerBackRz], 6.7, kTol);
  // hind 14.9 < 15: unclamped.
  EXPECT_NEAR(eval(eq1Horse(30, 20, 70, 79))[R::lowerBackRz], eq1ByHand(10, 5, 1, 4, 2, -2, -4, 5, 14.9), kTol);
}

TEST(RiderRigEq1, BothHoofHeightsClamped) {
  // Appendix B's last branch: 18 and 15. 6.4 + ((18*1.5)*.9 - 15*.4)*.4 = 6.4 + 7.32 = 13.72
  EXPECT_NEAR(eval(eq1Horse(150, 100, 100, 100))[R::lowerBackRz], 13.72, kTol);
}

TEST(RiderRigEq1, AppendixBBranch2OffsetIsAParameter) {
  // With the thesis code's 2.5 on lfHoof.tx restored, branch 2 reads a front mean 1.25 further forward:
  // (1 - (4 + 2.5 + 2)/2) * -.25 = 0.8125 instead of 0.5.
  RigProfile p = RigProfile::thesis();
  p.eq1.front_limited_lf_tx_offset = 2.5;
  EXPECT_NEAR(evaluateRider(eq1Horse(150, 100, 10, 20), p)[R::lowerBackRz], 15.64 + 0.3125, kTol);
  // Branch 4 (both limited) has no offset in Appendix B.
  EXPECT_NEAR(evaluateRider(eq1Horse(150, 100, 100, 100), p)[R::lowerBackRz], 13.72, kTol);
}

// ---- Equations 2-6 ----------------------------------------------------------------------------

TEST(RiderRigEq2to6, LowerBackRollTwistWaistHips) {
  HorseChannels h = eq1Horse(30, 20, 10, 30);  // hind 1 + 3: rb - lb = 2 units
  h[H::rearPivotRx] = 8;
  const RiderChannels r = eval(h);
  const double lower_back = eq1ByHand(10, 5, 1, 4, 2, -2, -4, 5, 4);
  EXPECT_NEAR(r[R::lowerBackRz], lower_back, kTol);
  EXPECT_NEAR(r[R::lowerBackRy], 8 * -1.0, kTol);                   // Eq 2
  EXPECT_NEAR(r[R::lowerBackRx], (8 * -1.0) * .5, kTol);            // Eq 3 (reads lowerBack.ry)
  EXPECT_NEAR(r[R::waistRz], lower_back * 1.7, kTol);               // Eq 4
  EXPECT_NEAR(r[R::hipRz], lower_back * .8, kTol);                  // Eq 5
  EXPECT_NEAR(r[R::hipRy], (8 * .5) + ((3 - 1) * 2), kTol);         // Eq 6 = 8
}

// ---- Equation 7 -------------------------------------------------------------------------------

TEST(RiderRigEq7, LiftBelowTheLimit) {
  HorseChannels h;
  h[H::rearPivotTx] = 5;                           // 0.5
  h[H::lbHoofTx] = -20, h[H::rbHoofTx] = 60;       // |-2 - 6| = 8, mean 2
  h[H::lfHoofTx] = 30, h[H::rfHoofTx] = -10;       // |3 + 1| = 4, mean 1
  h[H::lfHoofTy] = 20;                             // front heights 2
  // (8 + 4 + (0.5 - 2) * -1 + (0.5 - 1) + 2 * 2) * .01 = (12 + 1.5 - 0.5 + 4) * .01 = 0.17
  const RiderChannels r = eval(h);
  EXPECT_NEAR(r[R::cogTy], 0.17, kTol);
  // Eq 9 reads the lift: joints start 0.1 squashed, spine /6, neck and head /7 (Appendix B).
  EXPECT_NEAR(r[R::spineCTy], -.1 + 0.17 / 6, kTol);
  EXPECT_NEAR(r[R::spineDTy], -.1 + 0.17 / 6, kTol);
  EXPECT_NEAR(r[R::spineFTy], -.1 + 0.17 / 6, kTol);
  EXPECT_NEAR(r[R::neckTy], -.1 + 0.17 / 7, kTol);
  EXPECT_NEAR(r[R::headATy], -.1 + 0.17 / 7, kTol);
}

TEST(RiderRigEq7, LiftLimitedTo15) {
  HorseChannels h;
  h[H::lfHoofTy] = 3700, h[H::rfHoofTy] = 3700;  // (740 * 2) * .01 = 14.8 <= 15
  EXPECT_NEAR(eval(h)[R::cogTy], 14.8, kTol);
  h[H::lfHoofTy] = 4000, h[H::rfHoofTy] = 4000;  // (800 * 2) * .01 = 16 > 15: 15
  EXPECT_NEAR(eval(h)[R::cogTy], 15, kTol);
  // The same limit at a scale a real horse reaches, through the parameter.
  RigProfile p = RigProfile::thesis();
  p.eq7.lift_limit = 0.1;
  h[H::lfHoofTy] = 20, h[H::rfHoofTy] = 20;      // (4 * 2) * .01 = 0.08
  EXPECT_NEAR(evaluateRider(h, p)[R::cogTy], 0.08, kTol);
  h[H::lfHoofTy] = 40, h[H::rfHoofTy] = 40;      // 0.16 > 0.1
  EXPECT_NEAR(evaluateRider(h, p)[R::cogTy], 0.1, kTol);
}

// ---- Equation 8 -------------------------------------------------------------------------------

TEST(RiderRigEq8, SeatShiftInsideAndAtTheSaddleLimits) {
  HorseChannels h;
  h[H::rearPivotRz] = 3;  // lowerBack.rz = 3 * (2 * .07) = 0.42
  EXPECT_NEAR(eval(h)[R::cogTx], ((3 * 2) - 3 * (2 * .07)) * 0.1, kTol);  // 0.558
  h[H::rearPivotRz] = 10;  // (20 - 1.4) * .1 = 1.86 > 1
  EXPECT_NEAR(eval(h)[R::cogTx], 1, kTol);
  h[H::rearPivotRz] = -10;  // -1.86 < -1
  EXPECT_NEAR(eval(h)[R::cogTx], -1, kTol);
}

// ---- Equation 10 and 12: the lower-back limits of head and wrists ------------------------------

// Fore hooves X cm ahead: lowerBack.rz = X/10 * .25, lift = (0 - X/10) * .01.
HorseChannels foreReach(double x_cm) {
  HorseChannels h;
  h[H::lfHoofTx] = x_cm;
  h[H::rfHoofTx] = x_cm;
  return h;
}

TEST(RiderRigEq10, HeadInsideTheLimits) {
  const RiderChannels r = eval(foreReach(400));  // lower back 10, lift -0.4
  EXPECT_NEAR(r[R::lowerBackRz], 10, kTol);
  EXPECT_NEAR(r[R::cogTy], -0.4, kTol);
  EXPECT_NEAR(r[R::headRz], (-10 * .9) - (-0.4 * 18) + 5, kTol);  // 3.2
}

TEST(RiderRigEq10, HeadAbove17UsesThe17) {
  const RiderChannels r = eval(foreReach(1000));  // lower back 25, lift -1
  EXPECT_NEAR(r[R::headRz], (-17 * .9) - (-1 * 18) + 5, kTol);  // 7.7
}

TEST(RiderRigEq10, HeadBetweenMinus20AndMinus17FollowsTheLowerBack) {
  const RiderChannels r = eval(foreReach(-720));  // lower back -18, lift 0.72
  EXPECT_NEAR(r[R::lowerBackRz], -18, kTol);
  EXPECT_NEAR(r[R::headRz], (18 * .9) - (0.72 * 18) + 5, kTol);  // 8.24
}

TEST(RiderRigEq10, HeadBelowMinus20UsesThe20) {
  const RiderChannels r = eval(foreReach(-1000));  // lower back -25, lift 1
  EXPECT_NEAR(r[R::headRz], (20 * .9) - (1 * 18) + 5, kTol);  // 5
}

TEST(RiderRigEq11, HeadTurnsWithTheHorseRoll) {
  HorseChannels h;
  h[H::rearPivotRx] = 8;
  EXPECT_NEAR(eval(h)[R::headRy], 8 * .8, kTol);
}

TEST(RiderRigEq12, WristForwardInsideTheLimits) {
  HorseChannels h = foreReach(40);  // front mean 4
  h[H::rearPivotRz] = 10;           // lower back 10 * .14 + 4 * .25 = 2.4
  const RiderChannels r = eval(h);
  EXPECT_NEAR(r[R::lowerBackRz], 2.4, kTol);
  const double expected = (2.4 * .0001) - ((0 - 4) * (std::abs(10.0) * .008));  // 0.32024
  EXPECT_NEAR(r[R::lWristTx], expected, kTol);
  EXPECT_NEAR(r[R::rWristTx], expected, kTol);
}

TEST(RiderRigEq12, WristLowerBackClampedToPlusMinus17) {
  // Lower back 25 and -25, no pitch: the wrists read 17 and -17 (sign-consistent clamp).
  EXPECT_NEAR(eval(foreReach(1000))[R::lWristTx], 17 * .0001, kTol);
  EXPECT_NEAR(eval(foreReach(-1000))[R::rWristTx], -17 * .0001, kTol);
  EXPECT_NEAR(eval(foreReach(400))[R::lWristTx], 10 * .0001, kTol);
}

// ---- Equation 13 ------------------------------------------------------------------------------

TEST(RiderRigEq13, WristUpBelowAndAboveTheHoofHeightLimit) {
  HorseChannels h = hoovesUp();  // sum 10 < 20
  h[H::rearPivotTy] = 100;       // 10 units
  EXPECT_NEAR(eval(h)[R::lWristTy], (10 * 0.03) - (10 * .0005), kTol);  // 0.295
  h = hoovesUp(2.5);             // sum 25 >= 20: substitute 20
  h[H::rearPivotTy] = 100;
  EXPECT_NEAR(eval(h)[R::rWristTy], (20 * 0.03) - (10 * .0005), kTol);  // 0.595
}

// ---- Equations 14 and 15 ----------------------------------------------------------------------

TEST(RiderRigEq14, FootFollowsTheForeHoovesBackward) {
  HorseChannels h = foreReach(-40);  // front mean -4
  h[H::rearPivotRz] = 10;
  h[H::backMidRz] = 5;
  const RiderChannels r = eval(h);
  // lower back = 10 * .14 + (-4) * .25 = 0.4
  EXPECT_NEAR(r[R::lowerBackRz], 0.4, kTol);
  // (-4 - 0) * ((10 * .005) + .08 + (5 * .02)) - (10 * 0.4 * .005) = -0.92 - 0.02 = -0.94
  // Appendix B's backward branch: the reach term is (px - front mean) * -(gain), here <= 0.
  const double foot = ((0 - (-4)) * -((std::abs(10.0) * .005) + .08 + (5 * .02))) - (std::abs(10.0) * 0.4 * .005);
  EXPECT_NEAR(r[R::lFootTx], foot, kTol);
  EXPECT_NEAR(r[R::rFootTx], -0.94, kTol);
  // Eq 15: toe rotation = foot tx * 6 * 2 (toe up as the foot goes forward).
  EXPECT_NEAR(r[R::lFootRz], -0.94 * 6 * 2, kTol);
  EXPECT_NEAR(r[R::rFootRz], -0.94 * 6 * 2, kTol);
}

TEST(RiderRigEq14, ForwardReachIsClampedToZero) {
  HorseChannels h = foreReach(40);  // reach term +0.92 > 0: Appendix B's else branch, 0
  h[H::rearPivotRz] = 10;
  h[H::backMidRz] = 5;
  const RiderChannels r = eval(h);
  // lower back = 1.4 + 1 = 2.4; foot = 0 - (10 * 2.4 * .005) = -0.12
  EXPECT_NEAR(r[R::lFootTx], 0 - (std::abs(10.0) * 2.4 * .005), kTol);
  EXPECT_NEAR(r[R::lFootRz], -0.12 * 12, kTol);
}

// ---- Equations 16, 17, 18, knee lift, hair, cloth ---------------------------------------------

TEST(RiderRigEq16to18, FeetAndKneesBelowTheHoofHeightLimit) {
  const RiderChannels r = eval(hoovesUp());  // hoof heights 10 <= 15, roll 8
  EXPECT_NEAR(r[R::lFootRy], (10 * -1.7) - 1, kTol);  // -18
  EXPECT_NEAR(r[R::rFootRy], (10 * -1.7) - 1, kTol);
  EXPECT_NEAR(r[R::lFootRx], (10 * 0.1) + 1, kTol);   // 2
  EXPECT_NEAR(r[R::rFootRx], (10 * -0.1) + 1, kTol);  // 0
  // Eq 17 without Appendix B's +2 rest position: 10 * -.05 - 8 * .05 = -0.9
  EXPECT_NEAR(r[R::lFootTz], (10 * -0.05) - (8 * .05), kTol);
  EXPECT_NEAR(r[R::rFootTz], -0.9, kTol);
  // Eq 18: knee offset = -foot tz * 1.1 = 0.99
  EXPECT_NEAR(r[R::lKneeTz], -(-0.9) * 1.1, kTol);
  EXPECT_NEAR(r[R::rKneeTz], 0.99, kTol);
  // Appendix B knee lift without its -1 rest height: 10 * 0.03
  EXPECT_NEAR(r[R::lKneeTy], 10 * 0.03, kTol);
  EXPECT_NEAR(r[R::rKneeTy], 0.3, kTol);
}

TEST(RiderRigEq16to18, FeetAndKneesAboveTheHoofHeightLimit) {
  const RiderChannels r = eval(hoovesUp(2.5));  // hoof heights 25 > 15: substitute 15
  EXPECT_NEAR(r[R::lFootRy], (15 * -1.7) - 1, kTol);  // -26.5 on both feet (continuous)
  EXPECT_NEAR(r[R::rFootRy], (15 * -1.7) - 1, kTol);
  EXPECT_NEAR(r[R::lFootRx], (15 * 0.1) + 1, kTol);
  EXPECT_NEAR(r[R::rFootRx], (15 * -0.1) + 1, kTol);
  EXPECT_NEAR(r[R::lFootTz], (15 * -0.05) - (8 * .05), kTol);
  EXPECT_NEAR(r[R::rFootTz], (15 * -0.05) - (8 * .05), kTol);
  EXPECT_NEAR(r[R::rKneeTz], -((15 * -0.05) - (8 * .05)) * 1.1, kTol);
  EXPECT_NEAR(r[R::lKneeTy], 15 * 0.03, kTol);
}

TEST(RiderRigHairCloth, DrivesFromHoofHeightsAndRoll) {
  const RiderChannels r = eval(hoovesUp());  // heights 10, roll 8, rb - lb = 4 - 1
  EXPECT_NEAR(r[R::hairUp], (10 - 2) * 0.7, kTol);                   // 5.6
  EXPECT_NEAR(r[R::hairSide], (10 - 2) * (8 * -1.0) * -.02, kTol);   // reads lowerBack.ry: 1.28
  EXPECT_NEAR(r[R::clothUp], (10 - 2) * 0.7, kTol);
  EXPECT_NEAR(r[R::clothSide], (8 * -.5) + ((4 - 1) * -2), kTol);    // -10
}

TEST(RiderRig, RestPoseGivesTheThesisOffsetsOnly) {
  const RiderChannels r = eval(HorseChannels{});
  EXPECT_EQ(r[R::lowerBackRz], 0);
  EXPECT_EQ(r[R::cogTy], 0);
  EXPECT_EQ(r[R::cogTx], 0);
  EXPECT_NEAR(r[R::headRz], 5, kTol);     // Eq 10: 5 degrees down
  EXPECT_NEAR(r[R::spineCTy], -.1, kTol);  // Eq 9: h1 squash
  EXPECT_NEAR(r[R::lFootRy], -1, kTol);
  EXPECT_NEAR(r[R::rFootRx], 1, kTol);
  EXPECT_EQ(r[R::lKneeTz], 0);
  EXPECT_NEAR(r[R::hairUp], -2 * 0.7, kTol);
}

// ---- Units ------------------------------------------------------------------------------------

TEST(RiderRigUnits, HorseUnitDividesHorseTranslationsOnly) {
  HorseChannels h = foreReach(400);
  RigProfile p = RigProfile::thesis();
  p.horse_unit_cm = 20;  // 400 cm = 20 units: lower back 5 instead of 10
  EXPECT_NEAR(evaluateRider(h, p)[R::lowerBackRz], 5, kTol);
  HorseChannels roll;
  roll[H::rearPivotRx] = 8;  // degrees stay degrees
  EXPECT_NEAR(evaluateRider(roll, p)[R::lowerBackRy], -8, kTol);
}

// ---- Continuity: every limit is a clamp, so no channel jumps as an input sweeps through it ------

// The largest change of any rider channel between neighbouring samples of a fine sweep.
double largestStep(H channel, double from_cm, double to_cm, HorseChannels base, const RigProfile& p,
                   std::string* where = nullptr) {
  constexpr int kSteps = 20000;
  const double step = (to_cm - from_cm) / kSteps;
  base[channel] = from_cm;
  RiderChannels prev = evaluateRider(base, p);
  double largest = 0;
  for (int i = 1; i <= kSteps; ++i) {
    base[channel] = from_cm + i * step;
    const RiderChannels cur = evaluateRider(base, p);
    for (std::size_t c = 0; c < kRiderChannelCount; ++c) {
      const double d = std::abs(cur.value[c] - prev.value[c]);
      if (d > largest && where) *where = std::string(kRiderChannelNames[c]) + " at " + std::to_string(base[channel]);
      largest = std::max(largest, d);
    }
    prev = cur;
  }
  return largest;
}

void expectContinuous(H channel, double from_cm, double to_cm, const HorseChannels& base) {
  std::string where;
  EXPECT_LT(largestStep(channel, from_cm, to_cm, base, RigProfile::thesis(), &where), 0.05)
      << name(channel) << ": " << where;
}

TEST(RiderRigContinuity, AcrossEveryHoofHeightLimit) {
  HorseChannels base = hoovesUp();
  base[H::rearPivotRz] = 12;
  base[H::lfHoofTx] = 30;
  // Front heights through 18 units, hind through 15, all through 15 and 20.
  expectContinuous(H::lfHoofTy, 0, 300, base);
  expectContinuous(H::rbHoofTy, 0, 300, base);
}

TEST(RiderRigContinuity, AcrossTheLowerBackAndSeatLimits) {
  HorseChannels base;
  base[H::rearPivotRz] = 5;
  // Fore reach sweeps the lower back through -20, -17, 17 and the seat shift through +-1.
  expectContinuous(H::lfHoofTx, -2000, 2000, base);
  expectContinuous(H::rearPivotRz, -60, 60, foreReach(40));
}

TEST(RiderRigContinuity, TheSweepWouldCatchAppendixBsBranch2Jump) {
  // Negative control: restoring Appendix B's +2.5 on lfHoof.tx makes the lean jump by 0.3125 degrees
  // where the front hoof heights reach 18, and the sweep sees it.
  RigProfile p = RigProfile::thesis();
  p.eq1.front_limited_lf_tx_offset = 2.5;
  EXPECT_GT(largestStep(H::lfHoofTy, 0, 300, hoovesUp(), p), 0.3);
}

// ---- What the thesis says the rider does ------------------------------------------------------

TEST(RiderRigBehaviour, FrontHoovesLiftedLeansForward) {
  HorseChannels h;
  h[H::lfHoofTy] = 40;
  h[H::rfHoofTy] = 35;
  EXPECT_GT(eval(h)[R::lowerBackRz], 0);
  h[H::rearPivotRz] = -15;  // either way the body pitches, lifted forefeet lean her forward
  h[H::rearPivotTy] = -10;
  EXPECT_GT(eval(h)[R::lowerBackRz], eval(HorseChannels{})[R::lowerBackRz]);
}

TEST(RiderRigBehaviour, PairsDrawnInLeanBackSpreadOutLeanForward) {
  HorseChannels in;
  in[H::lfHoofTx] = in[H::rfHoofTx] = -40;  // fore hooves back toward the middle
  in[H::lbHoofTx] = in[H::rbHoofTx] = 40;   // hind hooves forward toward the middle
  EXPECT_LT(eval(in)[R::lowerBackRz], 0);
  HorseChannels out;
  out[H::lfHoofTx] = out[H::rfHoofTx] = 40;
  out[H::lbHoofTx] = out[H::rbHoofTx] = -40;
  EXPECT_GT(eval(out)[R::lowerBackRz], 0);
  // Fore forward but hind more forward: slightly back (section 8.1).
  HorseChannels both;
  both[H::lfHoofTx] = both[H::rfHoofTx] = 20;
  both[H::lbHoofTx] = both[H::rbHoofTx] = 50;
  EXPECT_LT(eval(both)[R::lowerBackRz], 0);
}

TEST(RiderRigBehaviour, HorseRollsRightRiderLeansLeft) {
  HorseChannels h;
  h[H::rearPivotRx] = 6;
  const RiderChannels r = eval(h);
  EXPECT_LT(r[R::lowerBackRy], 0);
  EXPECT_GT(r[R::hipRy], 0);   // pelvis rolls with the horse (Eq 6)
  EXPECT_GT(r[R::headRy], 0);  // head turns with the horse (Eq 11)
}

// A trot: diagonal pairs (lf + rb, rf + lb) swing in antiphase, 2.8 m of spread at the extremes, each
// hoof rising smoothly off the ground (sin squared) to 12 cm at mid-swing.
HorseChannels trotFrame(double phase) {
  const double reach = 70 * std::cos(phase);
  const double s = std::sin(phase);
  const double lift = s > 0 ? 12 * s * s : 0.0;
  const double lift_other = s < 0 ? 12 * s * s : 0.0;
  HorseChannels h;
  h[H::lfHoofTx] = reach, h[H::rbHoofTx] = -reach;
  h[H::rfHoofTx] = -reach, h[H::lbHoofTx] = reach;
  h[H::lfHoofTy] = lift, h[H::rbHoofTy] = lift;
  h[H::rfHoofTy] = lift_other, h[H::lbHoofTy] = lift_other;
  return h;
}

TEST(RiderRigBehaviour, TrotLiftIsHighestWhenThePairsAreSpreadWidest) {
  double best_lift = -1e9, best_spread = 0, widest = 0;
  for (int i = 0; i < 360; ++i) {
    const HorseChannels h = trotFrame(i * std::numbers::pi / 180);
    const double spread = std::abs(h[H::lfHoofTx] - h[H::rfHoofTx]) + std::abs(h[H::lbHoofTx] - h[H::rbHoofTx]);
    widest = std::max(widest, spread);
    const double lift = eval(h)[R::cogTy];
    if (lift > best_lift) best_lift = lift, best_spread = spread;
  }
  EXPECT_NEAR(best_spread, widest, 1e-6);
  // ... and lowest as the pairs pass each other (phase 90 degrees: no spread).
  EXPECT_LT(eval(trotFrame(std::numbers::pi / 2))[R::cogTy], best_lift / 4);
  // With 1 unit = 10 cm, a 2.8 m trot stride lifts the seat about 0.28 units (2.8 cm).
  EXPECT_NEAR(best_lift, (70 * 2 / 10.0 * 2) * .01, 1e-9);
}

TEST(RiderRigBehaviour, RearingWithForelegsUpLeansForwardAndLifts) {
  HorseChannels h;
  h[H::rearPivotRz] = 35;
  h[H::rearPivotTy] = 30;
  h[H::lfHoofTy] = 60;
  h[H::rfHoofTy] = 55;
  h[H::lfHoofTx] = -15;  // forelegs tucked back under the chest
  h[H::rfHoofTx] = -15;
  h[H::lbHoofTx] = h[H::rbHoofTx] = 20;  // hind hooves under the body carrying the weight
  const RiderChannels r = eval(h);
  EXPECT_GT(r[R::lowerBackRz], 0);
  EXPECT_GT(r[R::cogTy], 0);
  EXPECT_LT(r[R::lFootTx], 0);  // section 5.4: feet shift slightly backward
}

TEST(RiderRigBehaviour, StopHindHoovesFurtherUnderThanForeReachLeansBack) {
  HorseChannels h;
  h[H::lbHoofTx] = h[H::rbHoofTx] = 60;  // hind hooves drawn 60 cm under the body
  h[H::lfHoofTx] = h[H::rfHoofTx] = 40;  // fore hooves braced 40 cm forward
  const RiderChannels r = eval(h);
  EXPECT_LT(r[R::lowerBackRz], 0);
  EXPECT_GT(r[R::cogTx], 0);  // seat slides forward as she leans back (Eq 8)
}

}  // namespace
}  // namespace stirrup::rig
