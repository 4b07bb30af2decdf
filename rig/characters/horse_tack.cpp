#include "rig/characters/horse_tack.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "rig/characters/implicit_body.h"
#include "rig/characters/joint_placement.h"
#include "rig/characters/tube.h"
#include "rig/error.h"
#include "rig/horse_body.h"

namespace stirrup::rig {
namespace {

constexpr float kInfF = std::numeric_limits<float>::infinity();

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
  if (!from.tack_parts.empty()) {
    to.tack_parts.resize(base, TackPart::None);
    to.tack_parts.insert(to.tack_parts.end(), from.tack_parts.begin(), from.tack_parts.end());
  } else {
    to.labelTack(base, TackPart::None);
  }
  // The tack is untextured: its own colours.
  if (to.textured()) {
    to.uvs.resize(to.positions.size(), glm::vec2(0.0f));
    to.triangle_textures.resize(to.triangleCount(), -1);
  }
}

// A shell around the barrel (inflated by `offset`) cut to a box, as the generator's pad, flaps and girth
// (the "saddle pad" part).
ImplicitPrimitive barrelShell(glm::vec3 centre, glm::vec3 radii, float offset, glm::vec3 clip_min, glm::vec3 clip_max,
                              int joint, glm::vec3 color) {
  ImplicitPrimitive s = ellipsoid(centre, radii + offset, joint, color, 0.3f);
  s.tack_part = TackPart::SaddlePad;
  s.clip_min = clip_min;
  s.clip_max = clip_max;
  s.clip_round = 2.0f;
  return s;
}

// Where the seat goes and what carries it: the withers, the seat centre on top of the back (or on the
// horse's own saddle), the back joint the saddle hangs from and the barrel under it.
struct SeatPlace {
  glm::vec3 withers{0.0f}, seat{0.0f};
  float mid_z = 0.0f, span = 0.0f;
  int back_joint = -1;
  float top = 0.0f, bottom = 0.0f, half_width = 0.0f;  // the back's top, the barrel's bottom and half-width
  std::vector<int> back;  // the body's chain: the root and the joints from it to neck1
  bool onBack(int j) const { return std::find(back.begin(), back.end(), j) != back.end(); }
};

// The highest surface a vertical line through (x, z) meets on the mesh, and the joint moving it (-inf: none).
std::pair<float, int> topSurface(const SkinnedMesh& m, float x, float z) {
  float top = -kInfF;
  int top_joint = -1;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t ia = m.indices[t], ib = m.indices[t + 1], ic = m.indices[t + 2];
    const glm::vec3 a = m.positions[ia], b = m.positions[ib], c = m.positions[ic];
    const float d = (b.x - a.x) * (c.z - a.z) - (c.x - a.x) * (b.z - a.z);
    if (std::abs(d) < 1e-9f) continue;
    const float wa = ((b.x - x) * (c.z - z) - (c.x - x) * (b.z - z)) / d;
    const float wb = ((x - a.x) * (c.z - a.z) - (c.x - a.x) * (z - a.z)) / d;
    const float wc = 1.0f - wa - wb;
    if (wa < -1e-6f || wb < -1e-6f || wc < -1e-6f) continue;
    const float y = wa * a.y + wb * b.y + wc * c.y;
    if (y > top) top = y, top_joint = dominantJoint(m, {ia, ib, ic});
  }
  return {top, top_joint};
}

// The seat of a horse's own saddle: along its middle (within kOwnSeatMidlineCm of the midline), the top
// surface in 2 cm slices fore and aft; the seat centre halfway between the pommel and the cantle (the
// highest slice of the front half and of the back half), on the top surface there. A saddle's seat dips
// between them, or (a simple model) rises gently: either way its centre is between them.
constexpr float kOwnSeatMidlineCm = 4.0f;
std::optional<glm::vec3> ownSeat(const SkinnedMesh& m, const std::vector<char>& own, float mid_z) {
  float lo = kInfF, hi = -kInfF;
  for (std::size_t v = 0; v < own.size(); ++v)
    if (own[v]) lo = std::min(lo, m.positions[v].x), hi = std::max(hi, m.positions[v].x);
  if (!(hi - lo > 4.0f)) return std::nullopt;
  const int bins = static_cast<int>(std::ceil((hi - lo) / 2.0f));
  std::vector<float> top(std::size_t(bins), -kInfF);
  for (std::size_t v = 0; v < own.size(); ++v) {
    const glm::vec3& q = m.positions[v];
    if (!own[v] || std::abs(q.z - mid_z) > kOwnSeatMidlineCm) continue;
    const int b = std::min(bins - 1, static_cast<int>((q.x - lo) / 2.0f));
    top[std::size_t(b)] = std::max(top[std::size_t(b)], q.y);
  }
  const auto highest = [&](int from, int to) {
    int best = -1;
    for (int b = from; b < to; ++b)
      if (top[std::size_t(b)] > -kInfF && (best < 0 || top[std::size_t(b)] > top[std::size_t(best)])) best = b;
    return best;
  };
  const int cantle = highest(0, bins / 2), pommel = highest(bins / 2, bins);
  if (cantle < 0 || pommel < 0) return std::nullopt;
  int centre = (cantle + pommel) / 2;
  for (int d = 0; top[std::size_t(centre)] == -kInfF && d < bins; ++d)  // the nearest slice with a surface
    for (int b : {centre - d, centre + d})
      if (b >= 0 && b < bins && top[std::size_t(b)] > -kInfF) {
        centre = b;
        break;
      }
  return glm::vec3(lo + 2.0f * (float(centre) + 0.5f), top[std::size_t(centre)], mid_z);
}

SeatPlace placeSeat(const Character& horse, const std::string& file, const HorseTackParams& p, const std::vector<char>* own_saddle) {
  const Skeleton& s = horse.skeleton;
  const SkinnedMesh& m = horse.mesh;
  const int root = horse.role("root"), neck1 = horse.role("neck1");
  const HorseBody body = horseBody(horse);
  SeatPlace place;
  place.back = s.pathFrom(root, neck1);
  place.back.insert(place.back.begin(), root);
  // The withers: the role, or the tops of the fore legs (the first joint of each off the body's chain).
  if (const auto it = horse.roles.find("withers"); it != horse.roles.end()) {
    place.withers = s.restPosition(it->second);
  } else {
    for (const char* leg : {"lfUpper", "rfUpper"}) {
      int j = horse.role(leg);
      while (s.joints[j].parent >= 0 && !place.onBack(s.joints[j].parent)) j = s.joints[j].parent;
      place.withers += 0.5f * s.restPosition(j);
    }
  }
  const glm::vec3 hips = s.restPosition(root);
  place.span = std::abs(place.withers.x - hips.x);
  place.mid_z = hips.z;  // the root lies on the midline
  const std::optional<glm::vec3> own = own_saddle ? ownSeat(m, *own_saddle, place.mid_z) : std::nullopt;
  const float seat_x = own ? own->x : place.withers.x + p.seat_back_fraction * (hips.x - place.withers.x);
  const auto [top, top_joint] = topSurface(m, seat_x, place.mid_z);
  const auto named = [&](const char* role) { return std::string(role) + " \"" + s.joints[horse.role(role)].name + "\""; };
  const std::string where = " at x = " + std::to_string(static_cast<int>(std::lround(seat_x))) +
                            " cm, a saddle's place behind the withers (check roles " + named("root") + ", " + named("neck1") +
                            ", " + named("lfUpper") + " and " + named("rfUpper") + ", or map the tack roles to joints of the horse's own)";
  if (top == -kInfF) throw InputError(file + ": no back to put a saddle on: the mesh has no surface over the midline" + where);
  int back_joint = top_joint;
  while (back_joint >= 0 && !place.onBack(back_joint)) back_joint = s.joints[back_joint].parent;
  if (back_joint < 0) back_joint = body.back_turn >= 0 ? body.back_turn : root;
  place.back_joint = back_joint;
  place.top = top;
  // The barrel there: the section of the body's skin (its chain's joints: the legs and neck left out).
  float bottom = kInfF, half_width = 0.0f;
  for (const glm::vec3& q : sectionAt(m, seat_x, [&](int j) { return place.onBack(j); })) {
    if (q.y > top + 1.0f) continue;
    bottom = std::min(bottom, q.y);
    half_width = std::max(half_width, std::abs(q.z - place.mid_z));
  }
  if (bottom == kInfF || !(top - bottom > 1.0f) || !(half_width > 1.0f))
    throw InputError(file + ": no barrel under the saddle: no surface of the body's joints" + where);
  place.bottom = bottom;
  place.half_width = half_width;
  // On the horse's own saddle the seat is its seat; on a bare back, the generated saddle's seat height above it.
  place.seat = own ? *own : glm::vec3{seat_x, top + p.seat_above_back_cm, place.mid_z};
  return place;
}

// The generator's saddle: pad, flaps and girth shaped to the barrel, the seat with pommel and cantle
// (a saddle's flaps are cut to the rider's thigh, not to the horse).
SkinnedMesh saddleMesh(const SeatPlace& at, int saddle, const HorseTackParams& p) {
  const glm::vec3 seat = at.seat;
  const float mid_z = at.mid_z;
  const glm::vec3 barrel_centre{seat.x, 0.5f * (at.top + at.bottom), mid_z};
  const glm::vec3 barrel_radii{p.barrel_length_fraction * at.span, 0.5f * (at.top - at.bottom), at.half_width};
  ImplicitBody shapes;
  const float far = at.half_width + 100.0f;
  shapes.add(barrelShell(barrel_centre, barrel_radii, 1.8f, {seat.x - 28.0f, seat.y - 44.0f, mid_z - far},
                         {seat.x + 28.0f, seat.y + 50.0f, mid_z + far}, saddle, p.pad));
  shapes.add(barrelShell(barrel_centre, barrel_radii, 3.2f, {seat.x - 16.0f, seat.y - 38.0f, mid_z - far},
                         {seat.x + 22.0f, seat.y + 50.0f, mid_z + far}, saddle, p.leather));
  shapes.add(barrelShell(barrel_centre, barrel_radii, 1.0f, {seat.x + 16.0f, at.bottom - 10.0f, mid_z - far},
                         {seat.x + 21.0f, seat.y - 36.0f, mid_z + far}, saddle, p.leather));
  for (ImplicitPrimitive seat_part : {ellipsoid(seat + glm::vec3(-2.0f, -6.0f, 0.0f), {24.0f, 6.0f, 14.0f}, saddle, p.leather, 2.0f),
                                      ellipsoid(seat + glm::vec3(22.0f, 1.0f, 0.0f), {7.0f, 7.0f, 10.0f}, saddle, p.leather, 3.0f),
                                      ellipsoid(seat + glm::vec3(-22.0f, 3.0f, 0.0f), {5.5f, 8.0f, 13.0f}, saddle, p.leather, 3.0f, {1.0f, 0.5f, 0.0f})}) {
    seat_part.tack_part = TackPart::Saddle;  // the seat, pommel and cantle
    shapes.add(seat_part);
  }
  PolygonizeParams poly;
  poly.cell = p.cell;
  poly.skin_falloff = 3.0f;
  return polygonize(shapes, poly);
}

void addTube(SkinnedMesh& mesh, TackPart part, std::initializer_list<TubePoint> pts, float radius, glm::vec3 color, float sag = 0.0f) {
  TubeParams tp;
  tp.part = part;
  tp.radius = radius;
  tp.color = color;
  tp.sag = sag;
  tp.sides = radius < 0.9f ? 6 : 8;
  appendTube(mesh, std::span<const TubePoint>(pts.begin(), pts.size()), tp);
}

// The head in its own frame, whichever way its joint points at rest: the poll (the head joint), the
// axis from it to the muzzle (the far end of the head's skin), the jaw's side across it in the midline
// plane (down for a head held level, back toward the throat for one pointing down), and the head's skin.
struct HeadFrame {
  glm::vec3 poll{0.0f}, axis{1.0f, 0.0f, 0.0f}, jaw{0.0f, -1.0f, 0.0f};
  float front = 0.0f, length = 0.0f;  // the muzzle's distance along the axis, and the head's length along it
  std::vector<char> in_head;          // joints of the head (the head joint and those below it)
};

HeadFrame headFrame(const Character& horse, const std::string& file) {
  const Skeleton& s = horse.skeleton;
  const SkinnedMesh& m = horse.mesh;
  const int head = horse.role("head");
  HeadFrame h;
  h.in_head.assign(s.size(), 0);
  h.in_head[std::size_t(head)] = 1;
  for (std::size_t j = 0; j < s.size(); ++j)
    if (s.joints[j].parent >= 0 && h.in_head[std::size_t(s.joints[j].parent)]) h.in_head[j] = 1;
  h.poll = s.restPosition(head);
  std::vector<glm::vec3> skin;
  for (std::uint32_t v = 0; v < m.positions.size(); ++v)
    if (const int j = dominantJoint(m, {v}); j >= 0 && h.in_head[std::size_t(j)]) skin.push_back(m.positions[v]);
  if (skin.empty())
    throw InputError(file + ": no mesh on the head (joint \"" + s.joints[head].name +
                     "\", roles.head) to put a bit in (expected the head's skin bound to it or the joints below it)");
  // The muzzle: the skin farther than 85% of the farthest from the poll, in the midline plane.
  float reach = 0.0f;
  for (const glm::vec3& q : skin) reach = std::max(reach, glm::length(glm::vec2(q.x - h.poll.x, q.y - h.poll.y)));
  glm::vec2 muzzle(0.0f);
  for (const glm::vec3& q : skin)
    if (const glm::vec2 d(q.x - h.poll.x, q.y - h.poll.y); glm::length(d) >= 0.85f * reach) muzzle += d;
  if (glm::length(muzzle) > 1e-3f) {
    const glm::vec2 a = glm::normalize(muzzle);
    h.axis = {a.x, a.y, 0.0f};
    h.jaw = {a.y, -a.x, 0.0f};  // the axis turned a quarter clockwise (+X forward, +Y up): level -> down
  }
  float lo = kInfF, hi = -kInfF;
  for (const glm::vec3& q : skin) lo = std::min(lo, glm::dot(q - h.poll, h.axis)), hi = std::max(hi, glm::dot(q - h.poll, h.axis));
  h.front = hi;
  h.length = hi - lo;
  return h;
}

// Where the head's skin crosses the plane across its axis at `along` from the poll.
std::vector<glm::vec3> headSection(const SkinnedMesh& m, const HeadFrame& h, float along) {
  std::vector<glm::vec3> out;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t i[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
    float d[3];
    for (int e = 0; e < 3; ++e) d[e] = glm::dot(m.positions[i[e]] - h.poll, h.axis) - along;
    if ((d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0)) continue;
    const int j = dominantJoint(m, {i[0], i[1], i[2]});
    if (j < 0 || !h.in_head[std::size_t(j)]) continue;
    for (int e = 0; e < 3; ++e) {
      const int f = (e + 1) % 3;
      if (d[e] * d[f] > 0.0f || d[e] == d[f]) continue;
      out.push_back(m.positions[i[e]] + (m.positions[i[f]] - m.positions[i[e]]) * (d[e] / (d[e] - d[f])));
    }
  }
  return out;
}

// The bit in the corners of the mouth: back from the muzzle's front by kBitBehindMuzzle of the poll-to-
// muzzle length along the head, in the third of the head's depth nearest the jaw there, against the
// sides of the head's section at that depth; a headstall from it over the poll. Returns the bit's left end
// (the right is mirrored about the midline).
//
// The mouth's corners lie at the end of the bars, the toothless gap between the incisors and the cheek
// teeth where the bit rests; the generator's bit sits 10 cm behind the front of its 64 cm poll-to-muzzle
// head, 0.16 of it [E, the generator's anatomy].
constexpr float kBitBehindMuzzle = 0.16f;
glm::vec3 addBridle(SkinnedMesh& tack, const Character& horse, const HeadFrame& h, float mid_z, const HorseTackParams& p,
                    glm::vec3& bit_r) {
  const SkinnedMesh& m = horse.mesh;
  const int head = horse.role("head");
  const float bit_along = h.front * (1.0f - kBitBehindMuzzle);
  const std::vector<glm::vec3> at_bit = headSection(m, h, bit_along);
  float up = kInfF, down = -kInfF;  // across the head: toward the crest (-jaw) and the jaw
  for (const glm::vec3& q : at_bit) up = std::min(up, glm::dot(q - h.poll, h.jaw)), down = std::max(down, glm::dot(q - h.poll, h.jaw));
  if (at_bit.empty()) up = down = 0.0f;
  const float bit_depth = down - 0.3f * (down - up);
  float mouth_half = 0.0f;
  for (const glm::vec3& q : at_bit)
    if (std::abs(glm::dot(q - h.poll, h.jaw) - bit_depth) <= 0.25f * (down - up)) mouth_half = std::max(mouth_half, std::abs(q.z - mid_z));
  if (mouth_half == 0.0f) mouth_half = 0.1f * h.length;
  glm::vec3 centre = h.poll + h.axis * bit_along + h.jaw * bit_depth;
  centre.z = mid_z;
  const glm::vec3 bit_l = centre - glm::vec3(0.0f, 0.0f, mouth_half + 0.5f);
  bit_r = centre + glm::vec3(0.0f, 0.0f, mouth_half + 0.5f);
  addTube(tack, TackPart::Bit, {{bit_l + glm::vec3(0.0f, 0.0f, -1.0f), head}, {bit_r + glm::vec3(0.0f, 0.0f, 1.0f), head}}, 0.6f, p.metal);
  // The headstall: the cheek pieces from the bit up over the crown behind the ears' line (across the
  // head at the poll), at the bit's depth below the crown.
  float crown = 0.0f, crown_half = 0.0f;
  for (const glm::vec3& q : headSection(m, h, 0.0f))
    crown = std::min(crown, glm::dot(q - h.poll, h.jaw)), crown_half = std::max(crown_half, std::abs(q.z - mid_z));
  if (crown_half == 0.0f) crown_half = mouth_half;
  const float hz = crown_half + 0.3f;
  const glm::vec3 cheek = h.poll + h.jaw * bit_depth, top = h.poll + h.jaw * (crown - 0.3f);
  const auto at = [&](glm::vec3 q, float z) { return glm::vec3(q.x, q.y, mid_z + z); };
  addTube(tack, TackPart::Bridle, {{at(cheek, -hz), head}, {at(top, -0.6f * hz), head}, {at(top, 0.6f * hz), head}, {at(cheek, hz), head}}, p.strap_radius,
          p.leather);
  for (float side : {-1.0f, 1.0f})
    addTube(tack, TackPart::Bridle, {{at(cheek, hz * side), head}, {(side < 0 ? bit_l : bit_r) - h.jaw, head}}, p.strap_radius, p.leather);
  return bit_l;
}

// The horse's half-width at (x, y) from the midline: its skin's section there, within `slab` cm up or
// down (-inf: no skin there).
float bodyHalfWidth(const SkinnedMesh& m, float x, float y, float mid_z, float slab) {
  float w = -kInfF;
  for (const glm::vec3& q : sectionAt(m, x, [](int j) { return j >= 0; }))
    if (std::abs(q.y - y) <= slab) w = std::max(w, std::abs(q.z - mid_z));
  return w;
}

// Points along a rein from `from` to `to` (neither included) where the straight line would pass inside
// the horse (a head, neck or shoulders bulkier than a horse's usual build): carried out over the skin with
// kReinClearanceCm to spare, each riding with the joint that moves the skin nearest to it.
constexpr float kReinClearanceCm = 1.5f;
void carryReinOut(const SkinnedMesh& m, glm::vec3 from, glm::vec3 to, float mid_z, float side, float radius, std::vector<TubePoint>& pts) {
  constexpr int kSamples = 8;
  for (int k = 1; k < kSamples; ++k) {
    glm::vec3 q = from + (to - from) * (float(k) / kSamples);
    const float w = bodyHalfWidth(m, q.x, q.y, mid_z, 3.0f);
    const float need = w + radius + kReinClearanceCm;
    if (w == -kInfF || std::abs(q.z - mid_z) >= need) continue;
    q.z = mid_z + need * side;
    int j = -1;
    float best = kInfF;
    for (std::uint32_t v = 0; v < m.positions.size(); ++v)
      if (const float d = glm::length(m.positions[v] - q); d < best) best = d, j = dominantJoint(m, {v});
    pts.push_back({q, j});
  }
}

// The reins: from the bit along the sides of the neck's middle, in its upper half (40% of its depth down
// from the crest: on the generated horse 5 cm above the generator's rein line), to the hand ends, carried
// out over the skin where a straight line would pass inside it (carryReinOut).
void addReins(SkinnedMesh& tack, const Character& horse, const HeadFrame& h, const SeatPlace& at, glm::vec3 bit_l, glm::vec3 bit_r,
              const HorseTackParams& p) {
  const Skeleton& s = horse.skeleton;
  const SkinnedMesh& m = horse.mesh;
  const HorseBody body = horseBody(horse);
  const int head = horse.role("head");
  const glm::vec3 neck_middle = 0.5f * (s.restPosition(horse.role("neck1")) + h.poll);
  int neck_joint = body.neck.front();
  for (int j : body.neck)
    if (glm::length(s.restPosition(j) - neck_middle) < glm::length(s.restPosition(neck_joint) - neck_middle)) neck_joint = j;
  const glm::vec3 nj = s.restPosition(neck_joint);
  const float rein_x = nj.x + 4.0f;
  const std::vector<glm::vec3> neck_section = sectionAt(m, rein_x, [&](int j) {
    return j >= 0 && (at.onBack(j) || std::find(body.neck.begin(), body.neck.end(), j) != body.neck.end());
  });
  float neck_lo = kInfF, neck_hi = -kInfF;
  for (const glm::vec3& q : neck_section) neck_lo = std::min(neck_lo, q.y), neck_hi = std::max(neck_hi, q.y);
  const float rein_y = neck_section.empty() ? nj.y : neck_hi - 0.4f * (neck_hi - neck_lo);
  float neck_half = 0.0f;
  for (const glm::vec3& q : neck_section)
    if (q.y >= 0.5f * (neck_lo + neck_hi)) neck_half = std::max(neck_half, std::abs(q.z - at.mid_z));
  if (neck_half == 0.0f) neck_half = 0.5f * at.half_width;
  for (float side : {-1.0f, 1.0f}) {
    const int hand_joint = horse.role(side < 0 ? "lRein" : "rRein");
    const glm::vec3 hand = s.restPosition(hand_joint), bit = side < 0 ? bit_l : bit_r;
    const glm::vec3 mid{rein_x, rein_y, at.mid_z + (neck_half + 2.0f) * side};
    std::vector<TubePoint> pts = {{bit, head}};
    carryReinOut(m, bit, mid, at.mid_z, side, p.rein_radius, pts);
    pts.push_back({mid, neck_joint});
    carryReinOut(m, mid, hand, at.mid_z, side, p.rein_radius, pts);
    pts.push_back({hand, hand_joint});
    TubeParams tp;
    tp.radius = p.rein_radius;
    tp.color = p.leather;
    tp.sag = pts.size() > 3 ? 0.0f : 3.0f;  // carried over the skin the rein is taut there
    tp.sides = p.rein_radius < 0.9f ? 6 : 8;
    tp.part = TackPart::Reins;
    appendTube(tack, pts, tp);
  }
}

}  // namespace

HorseTackReport addHorseTack(Character& horse, const std::string& file, const HorseTackParams& p, const std::vector<char>* own_saddle) {
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
  const bool own = own_saddle && std::find(own_saddle->begin(), own_saddle->end(), char(1)) != own_saddle->end();
  const SeatPlace at = placeSeat(horse, file, p, own ? own_saddle : nullptr);
  rep.own_saddle = own;
  rep.withers = at.withers;
  rep.back_joint = at.back_joint;
  rep.back_top_y = at.top;
  rep.barrel_bottom_y = at.bottom;
  rep.barrel_half_width = at.half_width;
  rep.seat = at.seat;
  const HeadFrame head = headFrame(horse, file);  // checked before anything is added

  // Rig points.
  Skeleton& s = horse.skeleton;
  const glm::vec3 seat = at.seat;
  const int saddle = addRigPoint(s, "saddle", at.back_joint, seat);
  const float tread_z = at.half_width + p.tread_out_of_barrel_cm;
  const glm::vec3 l_tread{seat.x + p.mount.stirrup.x, seat.y + p.mount.stirrup.y, at.mid_z - tread_z};
  const glm::vec3 r_tread{l_tread.x, l_tread.y, at.mid_z + tread_z};
  const int l_stirrup = addRigPoint(s, "lStirrup", saddle, l_tread);
  const int r_stirrup = addRigPoint(s, "rStirrup", saddle, r_tread);
  const int l_rein = addRigPoint(s, "lRein", saddle, seat + p.mount.rein_grip);
  const int r_rein = addRigPoint(s, "rRein", saddle, seat + mirrorZ(p.mount.rein_grip, -1.0f));
  horse.roles["saddle"] = saddle;
  horse.roles["lStirrup"] = l_stirrup;
  horse.roles["rStirrup"] = r_stirrup;
  horse.roles["lRein"] = l_rein;
  horse.roles["rRein"] = r_rein;

  SkinnedMesh tack = own ? SkinnedMesh{} : saddleMesh(at, saddle, p);
  // Leathers from under the skirt down to the irons; the irons round the treads.
  for (float side : {-1.0f, 1.0f}) {
    const int js = side < 0 ? l_stirrup : r_stirrup;
    const glm::vec3 tread = side < 0 ? l_tread : r_tread;
    const glm::vec3 up = tread + glm::vec3(0.0f, 12.0f, 0.0f);
    const glm::vec3 a = tread + glm::vec3(0.0f, 0.0f, -5.5f), b = tread + glm::vec3(0.0f, 0.0f, 5.5f);
    addTube(tack, stirrupLeather(side), {{{seat.x, seat.y - 28.0f, at.mid_z + (at.half_width + 4.2f) * side}, saddle}, {up, js}}, p.strap_radius, p.leather);
    addTube(tack, stirrupIron(side), {{up, js}, {a + glm::vec3(0.0f, 2.0f, 0.0f), js}, {a, js}, {b, js}, {b + glm::vec3(0.0f, 2.0f, 0.0f), js}, {up, js}},
            0.7f, p.metal);
  }
  glm::vec3 bit_r(0.0f);
  rep.bit = addBridle(tack, horse, head, at.mid_z, p, bit_r);
  addReins(tack, horse, head, at, rep.bit, bit_r, p);
  groupTrianglesByColor(tack);
  appendMesh(horse.mesh, tack);
  return rep;
}

}  // namespace stirrup::rig
