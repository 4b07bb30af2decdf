#include "rig/characters/horse_character.h"

#include <cmath>
#include <initializer_list>
#include <span>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "rig/characters/implicit_body.h"
#include "rig/characters/tube.h"
#include "rig/characters/joint_placement.h"

namespace stirrup::rig {
namespace {

// A shell around the barrel (inflated by `offset`) cut to a box: saddle pad, flaps and girth.
ImplicitPrimitive barrelShell(const HorseParams& p, float offset, glm::vec3 clip_min, glm::vec3 clip_max,
                              int joint, glm::vec3 color) {
  ImplicitPrimitive s = ellipsoid(p.barrel_center, p.barrel_radii + offset, joint, color, 0.3f);
  s.clip_min = clip_min;
  s.clip_max = clip_max;
  s.clip_round = 2.0f;
  return s;
}

// The generated horse's trunk, neck, head and tail joints, and its tack's (-1 without tack).
struct HorseJoints {
  int root = -1, back_mid = -1, chest = -1, withers = -1, neck1 = -1, neck2 = -1, head = -1;
  int tail1 = -1, tail2 = -1, tail3 = -1;
  int saddle = -1, l_stirrup = -1, r_stirrup = -1;
  glm::vec3 tail_dir{0.0f}, seat{0.0f};  // the tail's rest direction; the saddle's seat centre
};

HorseJoints addTrunkJoints(const HorseParams& p, Character& c) {
  Skeleton& s = c.skeleton;
  HorseJoints j;
  // Trunk: the root is the rear pivot at the hips; the back bends at backMid.
  j.root = addJointAt(s, "root", -1, p.hips);
  j.back_mid = addJointAt(s, "backMid", j.root, p.back_mid);
  j.chest = addJointAt(s, "chest", j.back_mid, p.chest_joint);
  j.withers = addJointAt(s, "withers", j.chest, {p.withers_x, p.withers_height, 0.0f});
  j.neck1 = addJointAt(s, "neck1", j.chest, p.neck_base);
  j.neck2 = addJointAt(s, "neck2", j.neck1, p.neck_mid);
  j.head = addJointAt(s, "head", j.neck2, p.poll);
  j.tail_dir = glm::normalize(glm::vec3(-0.12f, -1.0f, 0.0f));
  j.tail1 = addJointAt(s, "tail1", j.root, p.tail_root);
  j.tail2 = addJointAt(s, "tail2", j.tail1, p.tail_root + j.tail_dir * (p.tail_length * 0.2f));
  j.tail3 = addJointAt(s, "tail3", j.tail2, p.tail_root + j.tail_dir * (p.tail_length * 0.55f));

  // The saddle sits where the back is lowest behind the withers; its seat centre is the joint.
  const float bx = (p.saddle_x - p.barrel_center.x) / p.barrel_radii.x;
  const float back_top = p.barrel_center.y + p.barrel_radii.y * std::sqrt(std::max(0.0f, 1.0f - bx * bx));
  j.seat = glm::vec3{p.saddle_x, back_top + p.saddle_seat_height, 0.0f};
  j.saddle = p.tack ? addJointAt(s, "saddle", j.back_mid, j.seat) : -1;
  j.l_stirrup = p.tack ? addJointAt(s, "lStirrup", j.saddle, j.seat + p.mount.stirrup) : -1;
  j.r_stirrup = p.tack ? addJointAt(s, "rStirrup", j.saddle, j.seat + mirrorZ(p.mount.stirrup, -1.0f)) : -1;

  c.roles = {{"root", j.root},     {"backMid", j.back_mid}, {"chest", j.chest},       {"withers", j.withers},
             {"neck1", j.neck1},   {"neck2", j.neck2},      {"head", j.head},         {"tail1", j.tail1},
             {"tail2", j.tail2},   {"tail3", j.tail3}};
  if (p.tack) {
    c.roles["saddle"] = j.saddle;
    c.roles["lStirrup"] = j.l_stirrup;
    c.roles["rStirrup"] = j.r_stirrup;
  }

  return j;
}

// The trunk's, neck's, head's and tail's shapes.
void addTrunkShapes(const HorseParams& p, const HorseJoints& j, const Skeleton& s, ImplicitBody& body) {
  body.add(ellipsoid(p.croup_center, p.croup_radii, j.root, p.coat, 6.0f));
  for (float side : {-1.0f, 1.0f})
    body.add(ellipsoid(mirrorZ(p.buttock_center, side), p.buttock_radii, j.root, p.coat, 8.0f));
  body.add(ellipsoid(p.barrel_center, p.barrel_radii, j.back_mid, p.coat, 10.0f));
  body.add(ellipsoid(p.chest_center, p.chest_radii, j.chest, p.coat, 10.0f));
  body.add(ellipsoid({p.withers_x, p.withers_height - 10.0f, 0.0f}, {24.0f, 10.0f, 9.0f}, j.withers, p.coat, 10.0f,
                     {1.0f, -0.25f, 0.0f}));
  // Neck, head, ears, eyes, mane, forelock.
  body.add(taperedCapsule(p.neck_base, p.neck_mid, p.neck_base_radius, p.neck_mid_radius, j.neck1, p.coat, 10.0f));
  body.add(taperedCapsule(p.neck_mid, p.poll + glm::vec3(-2.0f, -6.0f, 0.0f), p.neck_mid_radius, p.throat_radius,
                          j.neck2, p.coat, 6.0f));
  const glm::vec3 head_axis = glm::normalize(p.muzzle - p.poll);
  body.add(ellipsoid(p.poll + glm::vec3(-1.0f, -9.0f, 0.0f), {12.0f, 11.0f, 8.5f}, j.head, p.coat, 4.0f, head_axis));
  body.add(taperedCapsule(p.poll + glm::vec3(2.0f, -3.0f, 0.0f), p.muzzle, p.head_radius, p.muzzle_radius * 0.85f,
                          j.head, p.coat, 4.0f));
  body.add(ellipsoid(p.muzzle + head_axis * 1.0f, glm::vec3(p.muzzle_radius * 1.1f, p.muzzle_radius, p.muzzle_radius * 0.95f),
                     j.head, p.coat * 0.45f, 3.0f, head_axis));
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 ear_base = p.poll + glm::vec3(-1.0f, 7.0f, 4.5f * side);
    body.add(taperedCapsule(ear_base, ear_base + glm::vec3(-1.5f, p.ear_length, 2.0f * side), 2.8f, 0.9f, j.head,
                            p.coat, 1.5f));
    const glm::vec3 eye = p.poll + (p.muzzle - p.poll) * 0.3f + glm::vec3(-1.0f, 3.0f, 8.2f * side);
    body.add(ellipsoid(eye, glm::vec3(2.0f), j.head, p.eye, 0.5f));
  }
  const glm::vec3 crest0{p.withers_x + 4.0f, p.withers_height - 2.0f, 0.0f};
  const glm::vec3 crest1 = p.neck_mid + glm::vec3(-5.0f, p.neck_mid_radius - 0.5f, 0.0f);
  const glm::vec3 crest2 = p.poll + glm::vec3(-7.0f, 6.0f, 0.0f);
  body.add(taperedCapsule(crest0, crest1, p.mane_radius, p.mane_radius * 1.1f, j.neck1, p.points, 1.0f));
  body.add(taperedCapsule(crest1, crest2, p.mane_radius * 1.1f, p.mane_radius * 0.8f, j.neck2, p.points, 1.0f));
  body.add(taperedCapsule(p.poll + glm::vec3(1.0f, 8.0f, 0.0f), p.poll + glm::vec3(8.0f, 0.0f, 0.0f), 2.2f, 1.2f,
                          j.head, p.points, 1.0f));
  // Tail: a dock in the coat colour, then a full black switch.
  const glm::vec3 t2 = s.restPosition(j.tail2), t3 = s.restPosition(j.tail3);
  const glm::vec3 tip = p.tail_root + j.tail_dir * p.tail_length;
  body.add(taperedCapsule(p.tail_root + glm::vec3(4.0f, 2.0f, 0.0f), t2, 6.0f, 4.5f, j.tail1, p.coat, 5.0f));
  body.add(taperedCapsule(t2, t3, 6.0f, 9.0f, j.tail2, p.points, 2.0f));
  body.add(taperedCapsule(t3, tip, 9.0f, 4.0f, j.tail3, p.points, 3.0f));

}

// Leg `leg` (lf, rf, lb, rb): a two-bone IK chain (elbow-knee-fetlock in front, stifle-hock-fetlock
// behind), then the pastern and hoof; its joints, roles and shapes.
void addLeg(const HorseParams& p, const HorseJoints& j, int leg, Character& c, ImplicitBody& body) {
  Skeleton& s = c.skeleton;
  static const char* const names[4] = {"lf", "rf", "lb", "rb"};
  const bool fore = leg < 2;
  const float side = (leg % 2 == 0) ? 1.0f : -1.0f;  // parameters describe the left legs
  const std::string n = names[leg];
  const glm::vec3 top = mirrorZ(fore ? p.fore_shoulder : p.hind_hip, side);
  const glm::vec3 upper = mirrorZ(fore ? p.fore_elbow : p.hind_stifle, side);
  const glm::vec3 middle = mirrorZ(fore ? p.fore_knee : p.hind_hock, side);
  const glm::vec3 fetlock = mirrorZ(fore ? p.fore_fetlock : p.hind_fetlock, side);
  const glm::vec3 hoof = mirrorZ(fore ? p.fore_hoof : p.hind_hoof, side);
  // The fore limb swings from the scapula's pivot, the shoulder joint below it; the hind from the hip.
  const int j_scapula = fore ? addJointAt(s, n + "Scapula", j.chest, mirrorZ(p.fore_scapula, side)) : -1;
  const int j_top = addJointAt(s, n + (fore ? "Shoulder" : "Hip"), fore ? j_scapula : j.root, top);
  const int j_upper = addJointAt(s, n + (fore ? "Elbow" : "Stifle"), j_top, upper);
  const int j_middle = addJointAt(s, n + (fore ? "Knee" : "Hock"), j_upper, middle);
  const int j_fetlock = addJointAt(s, n + "Fetlock", j_middle, fetlock);
  const int j_hoof = addJointAt(s, n + "Hoof", j_fetlock, hoof);
  c.roles[n + "Pivot"] = fore ? j_scapula : j_top;
  c.roles[n + "Upper"] = j_upper;
  c.roles[n + "Middle"] = j_middle;
  c.roles[n + "Fetlock"] = j_fetlock;
  c.roles[n + "Hoof"] = j_hoof;

  if (fore) {
    const glm::vec3 scapula_top{p.withers_x - 2.0f, p.withers_height - 16.0f, top.z * 0.7f};
    body.add(taperedCapsule(scapula_top, top, 9.0f, 11.0f, j_scapula, p.coat, 8.0f));
    body.add(taperedCapsule(top, upper + glm::vec3(2.0f, 4.0f, 0.0f), 11.0f, 9.5f, j_top, p.coat, 8.0f));
    body.add(taperedCapsule(upper, middle, p.forearm_radius, p.knee_radius * 0.85f, j_upper, p.coat, 4.0f));
    body.add(ellipsoid(middle, glm::vec3(p.knee_radius * 1.05f, p.knee_radius * 1.3f, p.knee_radius), j_middle,
                       p.points, 2.0f));
  } else {
    body.add(taperedCapsule(top + glm::vec3(-4.0f, 6.0f, 0.0f), upper, 17.0f, 11.0f, j_top, p.coat, 10.0f));
    // Quarter: fills the junction of croup, thigh, gaskin and hamstring, which otherwise blends into
    // a pit on the side of the thigh.
    body.add(ellipsoid(mirrorZ(p.quarter_center, side), p.quarter_radii, j_top, p.coat, 8.0f));
    body.add(taperedCapsule(upper, middle + glm::vec3(2.0f, 3.0f, 0.0f), p.gaskin_radius, p.hock_radius * 0.9f,
                            j_upper, p.coat, 5.0f));
    // Hamstring: fills the gaskin from the point of the buttock down to the point of the hock.
    body.add(taperedCapsule(glm::vec3(p.buttock_center.x - 4.0f, p.buttock_center.y - 10.0f, top.z * 0.8f),
                            middle + glm::vec3(-2.0f, 4.0f, 0.0f), 11.0f, 4.5f, j_upper, p.coat, 10.0f));
    body.add(ellipsoid(0.55f * upper + 0.45f * middle + glm::vec3(-5.0f, 4.0f, 0.0f), {10.5f, 18.0f, 8.5f}, j_upper,
                       p.coat, 8.0f, middle - upper));
    body.add(ellipsoid(middle + glm::vec3(-1.0f, 0.0f, 0.0f),
                       glm::vec3(p.hock_radius * 1.2f, p.hock_radius * 1.2f, p.hock_radius * 0.9f), j_middle,
                       p.points, 2.0f));
  }
  body.add(taperedCapsule(middle, fetlock, p.cannon_radius, p.cannon_radius * 0.95f, j_middle, p.points, 2.0f));
  body.add(ellipsoid(fetlock + glm::vec3(-0.5f, 0.0f, 0.0f), glm::vec3(p.fetlock_radius * 1.1f, p.fetlock_radius,
                                                                         p.fetlock_radius * 0.9f),
                     j_fetlock, p.points, 2.0f));
  body.add(taperedCapsule(fetlock, hoof + glm::vec3(-0.5f, p.hoof_height, 0.0f), 3.6f, 4.0f, j_fetlock, p.points,
                          2.0f));
  ImplicitPrimitive sole = taperedCapsule(hoof + glm::vec3(-1.0f, p.hoof_height, 0.0f),
                                          hoof + glm::vec3(0.5f, 1.0f, 0.0f), p.hoof_radius * 0.75f,
                                          p.hoof_radius, j_hoof, p.hoof, 1.0f);
  sole.clip_min.y = 0.0f;  // flat on the ground
  body.add(sole);
}

// Saddle pad, flaps and girth (shells around the barrel cut to a box: the "saddle pad") and the saddle's
// seat, pommel and cantle (the "saddle"), crisp against the coat.
void addSaddleShapes(const HorseParams& p, const HorseJoints& j, ImplicitBody& body) {
  const auto part = [&](ImplicitPrimitive prim, TackPart tack) {
    prim.tack_part = tack;
    body.add(prim);
  };
  part(barrelShell(p, 1.8f, {j.seat.x - 28.0f, j.seat.y - 44.0f, -100.0f}, {j.seat.x + 28.0f, 300.0f, 100.0f}, j.saddle, p.pad),
       TackPart::SaddlePad);
  part(barrelShell(p, 3.2f, {j.seat.x - 16.0f, j.seat.y - 38.0f, -100.0f}, {j.seat.x + 22.0f, 300.0f, 100.0f}, j.saddle, p.leather),
       TackPart::SaddlePad);
  part(barrelShell(p, 1.0f, {j.seat.x + 16.0f, -100.0f, -100.0f}, {j.seat.x + 21.0f, j.seat.y - 36.0f, 100.0f}, j.saddle, p.leather),
       TackPart::SaddlePad);
  part(ellipsoid(j.seat + glm::vec3(-2.0f, -6.0f, 0.0f), {24.0f, 6.0f, 14.0f}, j.saddle, p.leather, 2.0f), TackPart::Saddle);
  part(ellipsoid(j.seat + glm::vec3(22.0f, 1.0f, 0.0f), {7.0f, 7.0f, 10.0f}, j.saddle, p.leather, 3.0f), TackPart::Saddle);
  part(ellipsoid(j.seat + glm::vec3(-22.0f, 3.0f, 0.0f), {5.5f, 8.0f, 13.0f}, j.saddle, p.leather, 3.0f, {1.0f, 0.5f, 0.0f}),
       TackPart::Saddle);
}

// Thin tack as tubes on the polygonized mesh: stirrup leathers and irons, bridle, bit and reins (whose
// hand ends are joints of their own).
void addThinTack(const HorseParams& p, const HorseJoints& j, Character& c) {
  Skeleton& s = c.skeleton;
  auto tube = [&](TackPart part, std::initializer_list<TubePoint> pts, float radius, glm::vec3 color, float sag = 0.0f) {
    TubeParams tp;
    tp.radius = radius;
    tp.color = color;
    tp.sag = sag;
    tp.part = part;
    tp.sides = radius < 0.9f ? 6 : 8;
    appendTube(c.mesh, std::span<const TubePoint>(pts.begin(), pts.size()), tp);
  };
  for (float side : {-1.0f, 1.0f}) {
    const int js = side < 0 ? j.l_stirrup : j.r_stirrup;
    const glm::vec3 tread = s.restPosition(js);
    const glm::vec3 top = tread + glm::vec3(0.0f, 12.0f, 0.0f);
    const glm::vec3 a = tread + glm::vec3(0.0f, 0.0f, -5.5f), b = tread + glm::vec3(0.0f, 0.0f, 5.5f);
    tube(stirrupLeather(side), {{{j.seat.x, j.seat.y - 28.0f, (p.barrel_radii.z + 4.2f) * side}, j.saddle}, {top, js}}, p.strap_radius,
         p.leather);
    tube(stirrupIron(side), {{top, js}, {a + glm::vec3(0.0f, 2.0f, 0.0f), js}, {a, js}, {b, js}, {b + glm::vec3(0.0f, 2.0f, 0.0f), js},
          {top, js}},
         0.7f, p.metal);
  }
  const float hz = p.head_radius + 0.3f;
  const glm::vec3 bit_l = p.muzzle + glm::vec3(-7.0f, -2.0f, -(p.muzzle_radius + 0.5f)), bit_r = mirrorZ(bit_l, -1.0f);
  const glm::vec3 crown = p.poll + glm::vec3(-3.0f, 8.5f, 0.0f);
  const glm::vec3 nose = p.poll + (p.muzzle - p.poll) * 0.68f + glm::vec3(1.5f, 6.0f, 0.0f);
  const float nz = p.muzzle_radius + 1.6f;
  tube(TackPart::Bridle, {{crown + glm::vec3(0.0f, -6.0f, -hz), j.head}, {crown + glm::vec3(0.0f, 0.0f, -hz * 0.6f), j.head},
        {crown + glm::vec3(0.0f, 0.0f, hz * 0.6f), j.head}, {crown + glm::vec3(0.0f, -6.0f, hz), j.head}},
       p.strap_radius, p.leather);
  tube(TackPart::Bridle, {{nose + glm::vec3(-2.0f, -10.0f, -nz), j.head}, {nose + glm::vec3(0.0f, 0.0f, -nz), j.head},
        {nose + glm::vec3(0.0f, 1.5f, 0.0f), j.head}, {nose + glm::vec3(0.0f, 0.0f, nz), j.head},
        {nose + glm::vec3(-2.0f, -10.0f, nz), j.head}},
       p.strap_radius, p.leather);
  tube(TackPart::Bit, {{bit_l + glm::vec3(0.0f, 0.0f, -1.0f), j.head}, {bit_r + glm::vec3(0.0f, 0.0f, 1.0f), j.head}}, 0.6f, p.metal);
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 bit = side < 0 ? bit_l : bit_r;
    tube(TackPart::Bridle, {{crown + glm::vec3(0.0f, -6.0f, hz * side), j.head}, {bit + glm::vec3(0.0f, 1.0f, 0.0f), j.head}},
         p.strap_radius, p.leather);
    const glm::vec3 mid = p.neck_mid + glm::vec3(4.0f, 2.0f, (p.neck_mid_radius + 2.0f) * side);
    const glm::vec3 hand = j.seat + mirrorZ(p.mount.rein_grip, -side);
    // The hand end is its own joint, which placeReins moves to the rider's hand every frame.
    const int rein = addJointAt(s, side < 0 ? "lRein" : "rRein", j.saddle, hand);
    c.roles[side < 0 ? "lRein" : "rRein"] = rein;
    tube(TackPart::Reins, {{bit, j.head}, {mid, j.neck2}, {hand, rein}}, p.rein_radius, p.leather, 3.0f);
  }
}

PolygonizeParams horsePolygonizing(const HorseParams& p) {
  PolygonizeParams poly;
  poly.cell = p.cell;
  poly.skin_falloff = 3.0f;
  return poly;
}

}  // namespace

Character buildHorse(const HorseParams& p) {
  Character c;
  c.name = "horse";
  ImplicitBody body;
  const HorseJoints j = addTrunkJoints(p, c);
  addTrunkShapes(p, j, c.skeleton, body);
  for (int leg = 0; leg < 4; ++leg) addLeg(p, j, leg, c, body);
  if (p.tack) addSaddleShapes(p, j, body);
  c.mesh = polygonize(body, horsePolygonizing(p));
  if (p.tack) addThinTack(p, j, c);
  groupTrianglesByColor(c.mesh);
  return c;
}

Character buildDefaultHorse() { return buildHorse(HorseParams{}); }

}  // namespace stirrup::rig
