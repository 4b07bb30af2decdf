#include "rig/characters/horse_tack.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <span>
#include <vector>

#include "rig/error.h"
#include "rig/horse_body.h"
#include "rig/characters/implicit_body.h"
#include "rig/characters/joint_placement.h"
#include "rig/characters/tube.h"

namespace stirrup::rig {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The joint that moves a triangle (or a vertex: a = b = c) most: the largest summed weight.
int dominantJoint(const SkinnedMesh& m, std::initializer_list<std::uint32_t> vertices) {
  std::map<int, float> sum;
  for (std::uint32_t v : vertices)
    for (int k = 0; k < kMaxInfluences; ++k)
      if (m.weights[v][k] > 0.0f) sum[m.joints[v][k]] += m.weights[v][k];
  int best = -1;
  float most = -1.0f;
  for (const auto& [j, w] : sum)
    if (w > most) most = w, best = j;
  return best;
}

// The role's name for a rig point, or, where the file has a joint of that name, one it has not.
std::string freeName(const Skeleton& s, std::string name) {
  while (s.find(name) >= 0) name = "rig_" + name;
  return name;
}

int addRigPoint(Skeleton& s, const std::string& role, int parent, glm::vec3 at) {
  const int j = addJointAt(s, freeName(s, role), parent, at);
  s.joints[j].rig_point = true;
  return j;
}

// Where the mesh's triangles that `keep` accepts (by their dominant joint) cross the plane x = `x`: the
// ends of the segments the plane cuts from them. Measured on triangles, not vertices, so a mesh of
// few, long triangles (a game model's) is measured as well as a dense one.
template <class Keep>
std::vector<glm::vec3> sectionAt(const SkinnedMesh& m, float x, Keep&& keep) {
  std::vector<glm::vec3> out;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t i[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
    const glm::vec3 p[3] = {m.positions[i[0]], m.positions[i[1]], m.positions[i[2]]};
    const float lo = std::min({p[0].x, p[1].x, p[2].x}), hi = std::max({p[0].x, p[1].x, p[2].x});
    if (x < lo || x > hi || !keep(dominantJoint(m, {i[0], i[1], i[2]}))) continue;
    for (int e = 0; e < 3; ++e) {
      const glm::vec3 a = p[e], b = p[(e + 1) % 3];
      if ((a.x - x) * (b.x - x) > 0.0f || a.x == b.x) continue;
      out.push_back(a + (b - a) * ((x - a.x) / (b.x - a.x)));
    }
  }
  return out;
}

void appendMesh(SkinnedMesh& to, const SkinnedMesh& from) {
  const auto base = static_cast<std::uint32_t>(to.positions.size());
  to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
  to.normals.insert(to.normals.end(), from.normals.begin(), from.normals.end());
  to.colors.insert(to.colors.end(), from.colors.begin(), from.colors.end());
  to.joints.insert(to.joints.end(), from.joints.begin(), from.joints.end());
  to.weights.insert(to.weights.end(), from.weights.begin(), from.weights.end());
  for (std::uint32_t i : from.indices) to.indices.push_back(base + i);
  // The tack is untextured: its own colours.
  if (to.textured()) {
    to.uvs.resize(to.positions.size(), glm::vec2(0.0f));
    to.triangle_textures.resize(to.triangleCount(), -1);
  }
}

// A shell around the barrel (inflated by `offset`) cut to a box, as the generator's pad, flaps and girth.
ImplicitPrimitive barrelShell(glm::vec3 centre, glm::vec3 radii, float offset, glm::vec3 clip_min, glm::vec3 clip_max,
                              int joint, glm::vec3 color) {
  ImplicitPrimitive s = ellipsoid(centre, radii + offset, joint, color, 0.3f);
  s.clip_min = clip_min;
  s.clip_max = clip_max;
  s.clip_round = 2.0f;
  return s;
}

}  // namespace

HorseTackReport addHorseTack(Character& horse, const std::string& file, const HorseTackParams& p) {
  HorseTackReport rep;
  std::string present, missing;
  for (const char* role : kHorseTackRoles) {
    std::string& list = horse.roles.count(role) ? present : missing;
    list += (list.empty() ? "" : ", ") + std::string(role);
  }
  if (missing.empty()) return rep;
  if (!present.empty())
    throw InputError(file + ": roles." + missing.substr(0, missing.find(',')) + ": missing (the horse's " + present +
                     " mapped: expected all five tack roles, saddle, lStirrup, rStirrup, lRein and rRein, or none, and "
                     "the rig adds its own tack)");
  rep.added = true;
  Skeleton& s = horse.skeleton;
  const SkinnedMesh& m = horse.mesh;
  const int root = horse.role("root"), neck1 = horse.role("neck1"), head = horse.role("head");
  const HorseBody body = horseBody(horse);

  // The body's chain: the root and the joints from it to neck1.
  std::vector<int> back = s.pathFrom(root, neck1);
  back.insert(back.begin(), root);
  const auto onBack = [&](int j) { return std::find(back.begin(), back.end(), j) != back.end(); };

  // The withers: the role, or the tops of the fore legs (the first joint of each off the body's chain).
  if (const auto it = horse.roles.find("withers"); it != horse.roles.end()) {
    rep.withers = s.restPosition(it->second);
  } else {
    for (const char* leg : {"lfUpper", "rfUpper"}) {
      int j = horse.role(leg);
      while (s.joints[j].parent >= 0 && !onBack(s.joints[j].parent)) j = s.joints[j].parent;
      rep.withers += 0.5f * s.restPosition(j);
    }
  }
  const glm::vec3 hips = s.restPosition(root);
  const float span = std::abs(rep.withers.x - hips.x);
  const float mid_z = hips.z;  // the root lies on the midline
  const float seat_x = rep.withers.x + p.seat_back_fraction * (hips.x - rep.withers.x);

  // The top of the back: the highest surface a vertical line through the midline meets there.
  float top = -kInf;
  int top_joint = -1;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t ia = m.indices[t], ib = m.indices[t + 1], ic = m.indices[t + 2];
    const glm::vec3 a = m.positions[ia], b = m.positions[ib], c = m.positions[ic];
    const float d = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
    if (std::abs(d) < 1e-9f) continue;
    const float wa = ((b.x - seat_x) * (c.z - mid_z) - (c.x - seat_x) * (b.z - mid_z)) / d;
    const float wb = ((seat_x - a.x) * (c.z - a.z) - (c.x - a.x) * (mid_z - a.z)) / d;
    const float wc = 1.0f - wa - wb;
    if (wa < -1e-6f || wb < -1e-6f || wc < -1e-6f) continue;
    const float y = wa * a.y + wb * b.y + wc * c.y;
    if (y > top) top = y, top_joint = dominantJoint(m, {ia, ib, ic});
  }
  const auto named = [&](const char* role) { return std::string(role) + " \"" + s.joints[horse.role(role)].name + "\""; };
  const std::string where = " at x = " + std::to_string(static_cast<int>(std::lround(seat_x))) +
                            " cm, a saddle's place behind the withers (check roles " + named("root") + ", " + named("neck1") +
                            ", " + named("lfUpper") + " and " + named("rfUpper") + ", or map the tack roles to joints of the horse's own)";
  if (top == -kInf) throw InputError(file + ": no back to put a saddle on: the mesh has no surface over the midline" + where);
  int back_joint = top_joint;
  while (back_joint >= 0 && !onBack(back_joint)) back_joint = s.joints[back_joint].parent;
  if (back_joint < 0) back_joint = body.back_turn >= 0 ? body.back_turn : root;
  rep.back_joint = back_joint;
  rep.back_top_y = top;

  // The barrel there: the section of the body's skin (its chain's joints: the legs and neck left out).
  float bottom = kInf, half_width = 0.0f;
  for (const glm::vec3& q : sectionAt(m, seat_x, onBack)) {
    if (q.y > top + 1.0f) continue;
    bottom = std::min(bottom, q.y);
    half_width = std::max(half_width, std::abs(q.z - mid_z));
  }
  if (bottom == kInf || !(top - bottom > 1.0f) || !(half_width > 1.0f))
    throw InputError(file + ": no barrel under the saddle: no surface of the body's joints" + where);
  rep.barrel_bottom_y = bottom;
  rep.barrel_half_width = half_width;
  const glm::vec3 seat{seat_x, top + p.seat_above_back_cm, mid_z};
  rep.seat = seat;
  const glm::vec3 barrel_centre{seat_x, 0.5f * (top + bottom), mid_z};
  const glm::vec3 barrel_radii{p.barrel_length_fraction * span, 0.5f * (top - bottom), half_width};

  // Rig points.
  const int saddle = addRigPoint(s, "saddle", back_joint, seat);
  const float tread_z = half_width + p.tread_out_of_barrel_cm;
  const glm::vec3 l_tread{seat.x + p.mount.stirrup.x, seat.y + p.mount.stirrup.y, mid_z - tread_z};
  const glm::vec3 r_tread{l_tread.x, l_tread.y, mid_z + tread_z};
  const int l_stirrup = addRigPoint(s, "lStirrup", saddle, l_tread);
  const int r_stirrup = addRigPoint(s, "rStirrup", saddle, r_tread);
  const glm::vec3 l_hand = seat + p.mount.rein_grip;
  const glm::vec3 r_hand = seat + mirrorZ(p.mount.rein_grip, -1.0f);
  const int l_rein = addRigPoint(s, "lRein", saddle, l_hand);
  const int r_rein = addRigPoint(s, "rRein", saddle, r_hand);
  horse.roles["saddle"] = saddle;
  horse.roles["lStirrup"] = l_stirrup;
  horse.roles["rStirrup"] = r_stirrup;
  horse.roles["lRein"] = l_rein;
  horse.roles["rRein"] = r_rein;

  // The saddle: pad, flaps and girth shaped to the barrel, the seat with pommel and cantle: the
  // generator's shapes and sizes (a saddle's flaps are cut to the rider's thigh, not to the horse).
  ImplicitBody shapes;
  const float far = half_width + 100.0f;
  shapes.add(barrelShell(barrel_centre, barrel_radii, 1.8f, {seat.x - 28.0f, seat.y - 44.0f, mid_z - far},
                         {seat.x + 28.0f, seat.y + 50.0f, mid_z + far}, saddle, p.pad));
  shapes.add(barrelShell(barrel_centre, barrel_radii, 3.2f, {seat.x - 16.0f, seat.y - 38.0f, mid_z - far},
                         {seat.x + 22.0f, seat.y + 50.0f, mid_z + far}, saddle, p.leather));
  shapes.add(barrelShell(barrel_centre, barrel_radii, 1.0f, {seat.x + 16.0f, bottom - 10.0f, mid_z - far},
                         {seat.x + 21.0f, seat.y - 36.0f, mid_z + far}, saddle, p.leather));
  shapes.add(ellipsoid(seat + glm::vec3(-2.0f, -6.0f, 0.0f), {24.0f, 6.0f, 14.0f}, saddle, p.leather, 2.0f));
  shapes.add(ellipsoid(seat + glm::vec3(22.0f, 1.0f, 0.0f), {7.0f, 7.0f, 10.0f}, saddle, p.leather, 3.0f));
  shapes.add(ellipsoid(seat + glm::vec3(-22.0f, 3.0f, 0.0f), {5.5f, 8.0f, 13.0f}, saddle, p.leather, 3.0f, {1.0f, 0.5f, 0.0f}));
  PolygonizeParams poly;
  poly.cell = p.cell;
  poly.skin_falloff = 3.0f;
  SkinnedMesh tack = polygonize(shapes, poly);

  auto tube = [&](std::initializer_list<TubePoint> pts, float radius, glm::vec3 color, float sag = 0.0f) {
    TubeParams tp;
    tp.radius = radius;
    tp.color = color;
    tp.sag = sag;
    tp.sides = radius < 0.9f ? 6 : 8;
    appendTube(tack, std::span<const TubePoint>(pts.begin(), pts.size()), tp);
  };
  // Leathers from under the skirt down to the irons; the irons round the treads.
  for (float side : {-1.0f, 1.0f}) {
    const int js = side < 0 ? l_stirrup : r_stirrup;
    const glm::vec3 tread = side < 0 ? l_tread : r_tread;
    const glm::vec3 up = tread + glm::vec3(0.0f, 12.0f, 0.0f);
    const glm::vec3 a = tread + glm::vec3(0.0f, 0.0f, -5.5f), b = tread + glm::vec3(0.0f, 0.0f, 5.5f);
    tube({{{seat.x, seat.y - 28.0f, mid_z + (half_width + 4.2f) * side}, saddle}, {up, js}}, p.strap_radius, p.leather);
    tube({{up, js}, {a + glm::vec3(0.0f, 2.0f, 0.0f), js}, {a, js}, {b, js}, {b + glm::vec3(0.0f, 2.0f, 0.0f), js}, {up, js}},
         0.7f, p.metal);
  }

  // The head: its skin (the head joint and the joints below it), its front (the muzzle) and the mouth's corners.
  std::vector<char> in_head(s.size(), 0);
  in_head[head] = 1;
  for (std::size_t j = 0; j < s.size(); ++j)
    if (s.joints[j].parent >= 0 && in_head[s.joints[j].parent]) in_head[j] = 1;
  std::vector<std::uint32_t> head_vertices;
  for (std::uint32_t v = 0; v < m.positions.size(); ++v)
    if (const int j = dominantJoint(m, {v}); j >= 0 && in_head[j]) head_vertices.push_back(v);
  if (head_vertices.empty())
    throw InputError(file + ": no mesh on the head (joint \"" + s.joints[head].name +
                     "\", roles.head) to put a bit in (expected the head's skin bound to it or the joints below it)");
  float x_min = kInf, x_max = -kInf;
  for (std::uint32_t v : head_vertices) x_min = std::min(x_min, m.positions[v].x), x_max = std::max(x_max, m.positions[v].x);
  const float head_length = x_max - x_min;
  const auto headSection = [&](float x) { return sectionAt(m, x, [&](int j) { return j >= 0 && in_head[j] != 0; }); };
  // The bit lies in the corners of the mouth: back from the muzzle's front by 30% of the head's length
  // (the generator's bit, 17 cm behind the front of its 55 cm head), in the lower third of the head's
  // height there, against the sides of the head's section at that height.
  const float bit_x = x_max - 0.3f * head_length;
  const std::vector<glm::vec3> at_bit = headSection(bit_x);
  float y_lo = kInf, y_hi = -kInf;
  for (const glm::vec3& q : at_bit) y_lo = std::min(y_lo, q.y), y_hi = std::max(y_hi, q.y);
  if (at_bit.empty()) y_lo = y_hi = s.restPosition(head).y;
  const float bit_y = y_lo + 0.3f * (y_hi - y_lo);
  float mouth_half = 0.0f;
  for (const glm::vec3& q : at_bit)
    if (std::abs(q.y - bit_y) <= 0.25f * (y_hi - y_lo)) mouth_half = std::max(mouth_half, std::abs(q.z - mid_z));
  if (mouth_half == 0.0f) mouth_half = 0.1f * head_length;
  const glm::vec3 bit_l{bit_x, bit_y, mid_z - (mouth_half + 0.5f)}, bit_r = {bit_x, bit_y, mid_z + mouth_half + 0.5f};
  rep.bit = bit_l;
  tube({{bit_l + glm::vec3(0.0f, 0.0f, -1.0f), head}, {bit_r + glm::vec3(0.0f, 0.0f, 1.0f), head}}, 0.6f, p.metal);
  // A headstall: the cheek pieces from the bit up over the crown behind the ears' line (at the head joint, the poll).
  const glm::vec3 poll = s.restPosition(head);
  float crown_y = poll.y, crown_half = 0.0f;
  for (const glm::vec3& q : headSection(poll.x)) crown_y = std::max(crown_y, q.y), crown_half = std::max(crown_half, std::abs(q.z - mid_z));
  if (crown_half == 0.0f) crown_half = mouth_half;
  const float hz = crown_half + 0.3f;
  tube({{glm::vec3(poll.x, bit_y, mid_z - hz), head}, {glm::vec3(poll.x, crown_y + 0.3f, mid_z - 0.6f * hz), head},
        {glm::vec3(poll.x, crown_y + 0.3f, mid_z + 0.6f * hz), head}, {glm::vec3(poll.x, bit_y, mid_z + hz), head}},
       p.strap_radius, p.leather);
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 bit = side < 0 ? bit_l : bit_r;
    tube({{glm::vec3(poll.x, bit_y, mid_z + hz * side), head}, {bit + glm::vec3(0.0f, 1.0f, 0.0f), head}}, p.strap_radius, p.leather);
  }
  // Reins: from the bit along the sides of the neck's middle, in its upper half (40% of its depth down
  // from the crest: on the generated horse 5 cm above the generator's rein line), to the hand ends.
  const glm::vec3 neck_middle = 0.5f * (s.restPosition(neck1) + poll);
  int neck_joint = body.neck.front();
  for (int j : body.neck)
    if (glm::length(s.restPosition(j) - neck_middle) < glm::length(s.restPosition(neck_joint) - neck_middle)) neck_joint = j;
  const glm::vec3 nj = s.restPosition(neck_joint);
  const float rein_x = nj.x + 4.0f;
  const std::vector<glm::vec3> neck_section = sectionAt(m, rein_x, [&](int j) {
    return j >= 0 && (onBack(j) || std::find(body.neck.begin(), body.neck.end(), j) != body.neck.end());
  });
  float neck_lo = kInf, neck_hi = -kInf;
  for (const glm::vec3& q : neck_section) neck_lo = std::min(neck_lo, q.y), neck_hi = std::max(neck_hi, q.y);
  const float rein_y = neck_section.empty() ? nj.y : neck_hi - 0.4f * (neck_hi - neck_lo);
  float neck_half = 0.0f;
  for (const glm::vec3& q : neck_section)
    if (q.y >= 0.5f * (neck_lo + neck_hi)) neck_half = std::max(neck_half, std::abs(q.z - mid_z));
  if (neck_half == 0.0f) neck_half = 0.5f * half_width;
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 bit = side < 0 ? bit_l : bit_r;
    const glm::vec3 mid{rein_x, rein_y, mid_z + (neck_half + 2.0f) * side};
    tube({{bit, head}, {mid, neck_joint}, {side < 0 ? l_hand : r_hand, side < 0 ? l_rein : r_rein}}, p.rein_radius, p.leather, 3.0f);
  }
  groupTrianglesByColor(tack);
  appendMesh(horse.mesh, tack);
  return rep;
}

}  // namespace stirrup::rig
