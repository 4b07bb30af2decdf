#include "rig/mapping/skeleton_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <utility>

#include <glm/geometric.hpp>

#include "rig/error.h"

namespace stirrup::rig {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double sq(double x) { return x * x; }

// Which joints the rules count (JointCount), and for each joint the counted joints of its subtree.
struct Liveness {
  std::vector<char> live;
  std::vector<std::vector<int>> sub;   // live joints at or below each joint
  std::vector<std::vector<int>> tree;  // every joint at or below each joint (weights can differ between
                                       // a limb and its mirror image where a coarse mesh barely reaches a
                                       // finger tip; the joints cannot)
  std::vector<int> height;             // bones down to its deepest live joint (0: none below)
};

// A rider's joints count when weighted or above a weighted joint; a horse's all but end markers (an
// unweighted leaf under a weighted joint).
bool counted(const MappingSkeleton& s, JointCount count, const std::vector<char>& live_children, int j) {
  if (count == JointCount::Weighted) return s.weighted[j] != 0 || live_children[j] != 0;
  const bool end_marker = s.children[j].empty() && !s.weighted[j] && s.parent[j] >= 0 && s.weighted[s.parent[j]];
  return !end_marker;
}

Liveness liveness(const MappingSkeleton& s, JointCount count) {
  const int n = s.size();
  Liveness l;
  l.live.assign(n, 0);
  l.sub.assign(n, {});
  l.height.assign(n, 0);
  l.tree.assign(n, {});
  std::vector<int> order(n);
  for (int j = 0; j < n; ++j) order[j] = j;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return s.depth[a] > s.depth[b]; });
  std::vector<char> live_children(n, 0);
  for (int j : order) {
    for (int c : s.children[j])
      if (l.live[c]) {
        live_children[j] = 1;
        l.height[j] = std::max(l.height[j], l.height[c] + 1);
      }
    const bool live = counted(s, count, live_children, j);
    l.live[j] = live;
    l.tree[j].push_back(j);
    for (int c : s.children[j]) l.tree[j].insert(l.tree[j].end(), l.tree[c].begin(), l.tree[c].end());
    if (!live) continue;
    l.sub[j].push_back(j);
    for (int c : s.children[j])
      if (l.live[c]) l.sub[j].insert(l.sub[j].end(), l.sub[c].begin(), l.sub[c].end());
  }
  return l;
}

// The largest extent of the live joints' bounding box: the skeleton's size.
double skeletonSize(const MappingSkeleton& s, const Liveness& l) {
  glm::dvec3 lo(kInf), hi(-kInf);
  for (int j = 0; j < s.size(); ++j)
    if (l.live[j]) lo = glm::min(lo, s.position[j]), hi = glm::max(hi, s.position[j]);
  const glm::dvec3 e = hi - lo;
  return std::max({e.x, e.y, e.z, 0.0});
}

int lowestCommonAncestor(const MappingSkeleton& s, int a, int b) {
  while (a >= 0 && b >= 0 && a != b) {
    if (s.depth[a] >= s.depth[b])
      a = s.parent[a];
    else
      b = s.parent[b];
  }
  return a == b ? a : -1;
}

double farthest(const MappingSkeleton& s, const Liveness& l, int j, const glm::dvec3& from) {
  double d = 0.0;
  for (int k : l.sub[j]) d = std::max(d, glm::length(s.position[k] - from));
  return d;
}

// How far a limb's joints reach from its root, weighted or not (the same on both sides of a mirror pair).
double reachOf(const MappingSkeleton& s, const Liveness& l, int root) {
  double d = 0.0;
  for (int k : l.tree[root]) d = std::max(d, glm::length(s.position[k] - s.position[root]));
  return d;
}

struct Mirror {
  glm::dvec3 middle, normal;
  glm::dvec3 reflect(const glm::dvec3& p) const { return p - 2.0 * glm::dot(p - middle, normal) * normal; }
};

Mirror mirrorOf(const MappingSkeleton& s, int a, int b) {
  const glm::dvec3 d = s.position[a] - s.position[b];
  return {0.5 * (s.position[a] + s.position[b]), glm::normalize(d)};
}

int nearestIn(const MappingSkeleton& s, const std::vector<int>& joints, const glm::dvec3& p, double* distance = nullptr) {
  int best = -1;
  double bd = kInf;
  for (int k : joints)
    if (const double d = glm::length(s.position[k] - p); d < bd) bd = d, best = k;
  if (distance) *distance = bd;
  return best;
}

bool mirrorPair(const MappingSkeleton& s, const Liveness& l, int a, int b, double size) {
  if (!l.live[a] || !l.live[b] || s.contains(a, b) || s.contains(b, a)) return false;
  const std::vector<int>&sa = l.tree[a], &sb = l.tree[b];
  if (sa.size() != sb.size() || l.sub[a].size() < 2 || l.sub[b].size() < 2) return false;
  const double tol = kMirrorTolerance * size;
  if (glm::length(s.position[a] - s.position[b]) < kMinPairSeparation * size) return false;
  const double ra = reachOf(s, l, a), rb = reachOf(s, l, b);
  if (ra < kMinLimbReach * size || std::abs(ra - rb) > tol) return false;
  const Mirror m = mirrorOf(s, a, b);
  const int branch = lowestCommonAncestor(s, a, b);
  if (branch < 0 || std::abs(glm::dot(s.position[branch] - m.middle, m.normal)) > tol) return false;
  // Every joint's reflection lands on a joint of the other side, a different one for each.
  double d = 0.0;
  std::set<int> hit;
  for (int x : sa) {
    const int y = nearestIn(s, sb, m.reflect(s.position[x]), &d);
    if (d > tol || !hit.insert(y).second) return false;
  }
  return true;
}

// The chain on the other side: each joint's mirror image in the partner's subtree.
std::vector<int> mirroredChain(const MappingSkeleton& s, const Liveness& l, const std::vector<int>& chain, int a, int b) {
  const Mirror m = mirrorOf(s, a, b);
  std::vector<int> out;
  for (int j : chain) out.push_back(nearestIn(s, l.tree[b], m.reflect(s.position[j])));
  return out;
}

std::vector<int> chainFrom(const MappingSkeleton& s, const Liveness& l, int root) {
  std::vector<int> chain;
  if (root < 0 || !l.live[root]) return chain;
  chain.push_back(root);
  for (int j = root;;) {
    int best = -1;
    double bd = -1.0;
    for (int c : s.children[j])
      if (l.live[c])
        if (const double d = farthest(s, l, c, s.position[root]); d > bd) bd = d, best = c;
    if (best < 0) break;
    chain.push_back(best);
    j = best;
  }
  return chain;
}

std::string quoted(const MappingSkeleton& s, int j) { return "\"" + s.names[j] + "\""; }

struct HeightFrame {
  glm::dvec3 up;
  double ground = 0.0, height = 0.0;  // the mesh's lowest point and extent along up
  double of(const glm::dvec3& p) const { return glm::dot(p, up) - ground; }
};

HeightFrame heightFrame(const MappingSkeleton& s, const glm::dvec3& up) {
  HeightFrame f;
  f.up = up;
  double lo = kInf, hi = -kInf;
  for (const glm::dvec3& v : s.vertices) lo = std::min(lo, glm::dot(v, up)), hi = std::max(hi, glm::dot(v, up));
  for (const glm::dvec3& p : s.position) lo = std::min(lo, glm::dot(p, up)), hi = std::max(hi, glm::dot(p, up));
  f.ground = lo;
  f.height = hi - lo;
  return f;
}

glm::dvec3 directionOr(const glm::dvec3& v, const glm::dvec3& fallback) {
  const double n = glm::length(v);
  return n > 0.0 && std::isfinite(n) ? v / n : fallback;
}

// The file's axis nearest `v` when within kAxisSnapDeg of it, else `v` (a unit vector).
glm::dvec3 nearAxis(const glm::dvec3& v) {
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(v[i]) > std::abs(v[k])) k = i;
  if (std::abs(v[k]) < std::cos(kAxisSnapDeg * std::numbers::pi / 180.0)) return v;
  glm::dvec3 axis(0.0);
  axis[k] = v[k] > 0.0 ? 1.0 : -1.0;
  return axis;
}

// Two-bone limb: the proximal and middle joints (indices into `chain`, both before `end`) whose bone
// lengths and spacing across the body fit the proportions best; `rest_cost` adds a cost per end.
struct LimbFit {
  int top = -1, middle = -1, end = -1;
  double cost = kInf;
};

LimbFit fitLimb(const MappingSkeleton& s, const std::vector<int>& chain, const std::vector<int>& partner, double H,
                double upper, double lower, double spacing, int end_from, int end_to,
                const std::vector<double>& end_cost) {
  LimbFit best;
  for (int w = end_from; w <= end_to; ++w)
    for (int e = 1; e < w; ++e)
      for (int t = 0; t < e; ++t) {
        const double U = glm::length(s.position[chain[e]] - s.position[chain[t]]);
        const double F = glm::length(s.position[chain[w]] - s.position[chain[e]]);
        const double sep = glm::length(s.position[chain[t]] - s.position[partner[t]]);
        if (!(U > 0.0 && F > 0.0 && sep > 0.0 && H > 0.0)) continue;
        const double cost = sq(std::log((U / F) / (upper / lower))) + sq(std::log((U + F) / ((upper + lower) * H))) +
                            sq(std::log(sep / (spacing * H))) + end_cost[static_cast<std::size_t>(w)];
        if (cost < best.cost) best = {t, e, w, cost};
      }
  return best;
}

void assign(TopologyRoles& t, const std::string& role, int joint, const std::string& why) {
  if (joint < 0) return;
  t.roles[role] = joint;
  t.why[role] = why;
}

// The chain up from `from` along the file's own joints (none hung by proximity) on the midline, never
// into `excluded`'s subtrees: at each joint the child that rises most (`min_rise`: the least rise per unit
// of bone accepted, negative to allow a chain that runs forward and a little down).
std::vector<int> midlineChain(const MappingSkeleton& s, const Liveness& l, int from, const Mirror& midline, double size,
                              const glm::dvec3& up, double min_rise, const std::vector<int>& excluded) {
  std::vector<int> out;
  for (int j = from;;) {
    int best = -1;
    double best_rise = -kInf;
    for (int c : s.children[j]) {
      if (!l.live[c] || s.hung[c]) continue;
      bool skip = false;
      for (int x : excluded) skip = skip || s.contains(c, x);
      if (skip) continue;
      if (std::abs(glm::dot(s.position[c] - midline.middle, midline.normal)) > kMirrorTolerance * size) continue;
      const glm::dvec3 d = s.position[c] - s.position[j];
      const double len = glm::length(d);
      if (!(len > 0.0)) continue;
      const double rise = glm::dot(d, up) / len;
      if (rise < min_rise) continue;
      if (rise > best_rise) best_rise = rise, best = c;
    }
    if (best < 0) return out;
    out.push_back(best);
    j = best;
  }
}

std::vector<LimbPair> mirroredLimbs(const MappingSkeleton& s, const Liveness& l, double size) {
  const int n = s.size();
  std::set<std::pair<int, int>> valid;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if (l.tree[a].size() == l.tree[b].size() && mirrorPair(s, l, a, b, size)) valid.insert({a, b});
  std::vector<LimbPair> pairs;
  for (const auto& [a, b] : valid) {
    const int pa = s.parent[a], pb = s.parent[b];
    if (pa >= 0 && pb >= 0 && pa != pb && valid.count({std::min(pa, pb), std::max(pa, pb)})) continue;  // part of a bigger limb
    pairs.push_back({a, b, lowestCommonAncestor(s, a, b), 0.5 * (reachOf(s, l, a) + reachOf(s, l, b))});
  }
  std::stable_sort(pairs.begin(), pairs.end(), [](const LimbPair& x, const LimbPair& y) { return x.reach > y.reach; });
  return pairs;
}

std::string countText(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::vector<LimbPair> mirroredLimbs(const MappingSkeleton& s, JointCount count) {
  const Liveness l = liveness(s, count);
  return mirroredLimbs(s, l, skeletonSize(s, l));
}

std::vector<int> limbChain(const MappingSkeleton& s, int root) { return chainFrom(s, liveness(s, JointCount::Weighted), root); }

int upperChestJoint(const MappingSkeleton& s, const std::map<std::string, int>& roles) {
  const auto at = [&](const char* r) {
    const auto it = roles.find(r);
    return it == roles.end() ? -1 : it->second;
  };
  const int pelvis = at("pelvis"), neck = at("neck"), ls = at("lShoulder"), rs = at("rShoulder");
  if (pelvis < 0 || neck < 0 || ls < 0 || rs < 0) return -1;
  const std::vector<int> spine = s.pathDown(pelvis, neck);  // excludes the pelvis, ends at the neck
  const auto meet = [&](int j) {
    for (; j >= 0; j = s.parent[j]) {
      if (std::find(spine.begin(), spine.end(), j) != spine.end() || j == pelvis) return j;
      if (s.hung[j]) return -1;
    }
    return -1;
  };
  const int a = meet(ls), b = meet(rs);
  if (a < 0 || a != b || a == pelvis || a == neck) return -1;
  return a;
}

namespace {

// A biped's arms: the wrist where two fingers branch (else by arm lengths), shoulder and elbow by
// Winter's lengths and spacing, and the grip, a palm joint the fingers hang from.
void riderArmRoles(const MappingSkeleton& s, const Liveness& l, const LimbPair& arms, double H, const std::string& cannot,
                   const std::string& fix, TopologyRoles& t) {
  const std::vector<int> chain = chainFrom(s, l, arms.a);
  const std::vector<int> other = mirroredChain(s, l, chain, arms.a, arms.b);
  int wrist = -1;
  for (std::size_t i = 2; i < chain.size() && wrist < 0; ++i) {
    int fingers = 0;
    for (int c : s.children[chain[i]]) fingers += l.live[c] && l.height[c] >= 1;
    if (fingers >= 2) wrist = static_cast<int>(i);
  }
  const int last = static_cast<int>(chain.size()) - 1;
  if (last < 2)
    throw InputError(cannot + "the arms from " + quoted(s, arms.a) + " have " + countText(chain.size(), "joint", "joints") +
                     " (expected a shoulder, an elbow and a wrist)" + fix);
  std::vector<double> hand_cost(chain.size(), 0.0);
  for (int w = 0; w <= last; ++w) {
    const double rest = glm::length(s.position[chain[last]] - s.position[chain[w]]);
    if (rest > kHandLength * H) hand_cost[w] = sq(std::log(rest / (kHandLength * H)));
  }
  const LimbFit fit = wrist >= 0 ? fitLimb(s, chain, other, H, kUpperArmLength, kForearmLength, kShoulderSpacing, wrist, wrist, hand_cost)
                                 : fitLimb(s, chain, other, H, kUpperArmLength, kForearmLength, kShoulderSpacing, 2, last, hand_cost);
  if (fit.end < 0)
    throw InputError(cannot + "the arms from " + quoted(s, arms.a) + " have no bones of length" + fix);
  const std::string why = "topology: arm lengths and spacing (Winter 2009)";
  assign(t, "lShoulder", chain[fit.top], why);
  assign(t, "rShoulder", other[fit.top], why);
  assign(t, "lElbow", chain[fit.middle], why);
  assign(t, "rElbow", other[fit.middle], why);
  const std::string wrist_why = wrist >= 0 ? "topology: where the fingers branch" : "topology: arm lengths (no fingers)";
  assign(t, "lWrist", chain[fit.end], wrist_why);
  assign(t, "rWrist", other[fit.end], wrist_why);
  // The grip: a joint in the palm the fingers hang from, one joint deeper than the fingers beside it
  // and running on along the forearm (not the thumb, off to the side), the middle one of several
  // (metacarpals); or, without fingers, the hand's one joint past the wrist.
  const int w = chain[fit.end];
  const glm::dvec3 hand_dir = directionOr(s.position[w] - s.position[chain[fit.middle]], {0, 0, 0});
  const auto bonesBelow = [&](int j) {
    int deepest = 0;
    std::vector<std::pair<int, int>> todo = {{j, 0}};
    while (!todo.empty()) {
      const auto [k, d] = todo.back();
      todo.pop_back();
      deepest = std::max(deepest, d);
      for (int c : s.children[k]) todo.push_back({c, d + 1});
    }
    return deepest;
  };
  std::vector<int> fingers;
  int shortest = std::numeric_limits<int>::max();
  for (int c : s.children[w])
    if (const int below = bonesBelow(c); below >= 1) fingers.push_back(c), shortest = std::min(shortest, below);
  std::vector<int> palms;
  if (fingers.size() >= 2)
    for (int c : fingers)
      if (bonesBelow(c) > shortest && glm::dot(directionOr(s.position[c] - s.position[w], {0, 0, 0}), hand_dir) > std::cos(kPalmAngleDeg * std::numbers::pi / 180.0))
        palms.push_back(c);
  int grip = -1;
  std::string grip_why;
  if (!palms.empty()) {
    glm::dvec3 mid(0.0);
    for (int c : palms) mid += s.position[c] / static_cast<double>(palms.size());
    grip = nearestIn(s, palms, mid);
    grip_why = "topology: the palm joint a finger hangs from";
  } else {
    std::vector<int> live_children;
    for (int c : s.children[w])
      if (l.live[c]) live_children.push_back(c);
    if (live_children.size() == 1 && l.height[live_children[0]] == 0) {
      grip = live_children[0];
      grip_why = "topology: the hand's one joint past the wrist";
    }
  }
  if (grip >= 0) {
    const Mirror m = mirrorOf(s, arms.a, arms.b);
    assign(t, "lHand", grip, grip_why);
    assign(t, "rHand", nearestIn(s, l.tree[arms.b], m.reflect(s.position[grip])), grip_why);
  }
}

// A biped's legs: the ankle the leg's first joint near the ground, hip and knee by Winter's lengths
// and spacing, the ball the joint below the ankle.
void riderLegRoles(const MappingSkeleton& s, const Liveness& l, const LimbPair& legs, const HeightFrame& hf, const std::string& cannot,
                   const std::string& fix, TopologyRoles& t) {
  const double H = hf.height;
  const std::vector<int> chain = chainFrom(s, l, legs.a);
  const std::vector<int> other = mirroredChain(s, l, chain, legs.a, legs.b);
  int ankle = -1;
  for (std::size_t i = 2; i < chain.size() && ankle < 0; ++i)
    if (hf.of(s.position[chain[i]]) < kAnkleBand * H) ankle = static_cast<int>(i);
  if (ankle < 0) {
    ankle = static_cast<int>(chain.size()) - 1;
    t.warnings.push_back("no leg joint near the ground: took the legs' last joints " + quoted(s, chain[ankle]) + " as the ankles");
  }
  if (ankle < 2)
    throw InputError(cannot + "the legs from " + quoted(s, legs.a) + " have " + countText(chain.size(), "joint", "joints") +
                     " (expected a hip, a knee and an ankle)" + fix);
  const LimbFit fit = fitLimb(s, chain, other, H, kThighLength, kShinLength, kHipSpacing, ankle, ankle,
                              std::vector<double>(chain.size(), 0.0));
  const std::string why = "topology: leg lengths and spacing (Winter 2009)";
  assign(t, "lHip", chain[fit.top], why);
  assign(t, "rHip", other[fit.top], why);
  assign(t, "lKnee", chain[fit.middle], why);
  assign(t, "rKnee", other[fit.middle], why);
  assign(t, "lAnkle", chain[ankle], "topology: the leg's first joint near the ground");
  assign(t, "rAnkle", other[ankle], "topology: the leg's first joint near the ground");
  if (ankle + 1 < static_cast<int>(chain.size())) {
    assign(t, "lBall", chain[ankle + 1], "topology: the joint below the ankle");
    assign(t, "rBall", other[ankle + 1], "topology: the joint below the ankle");
  }
}

// A biped's neck and head: the head the top of the midline chain above where the arms branch, the neck
// the joint above that branch (or, arms hung by proximity, the spine's first joint above the shoulders).
void riderSpineRoles(const MappingSkeleton& s, const Liveness& l, const LimbPair& legs, const LimbPair& arms, double size,
                     const glm::dvec3& up0, const HeightFrame& hf, const std::string& cannot, const std::string& fix,
                     TopologyRoles& t) {
  const int pelvis = legs.branch, branch = arms.branch;
  const Mirror midline = mirrorOf(s, legs.a, legs.b);
  const std::vector<int> to_branch = s.pathDown(pelvis, branch);
  const std::vector<int> above = midlineChain(s, l, branch, midline, size, up0, 0.0, {arms.a, arms.b});
  if (above.empty())
    throw InputError(cannot + "no joint rises on the midline above " + quoted(s, branch) +
                     ", where the arms branch (expected the neck and head)" + fix);
  const int head = above.back();
  bool arms_hung = false;
  for (int root : {arms.a, arms.b})
    for (int j : s.pathDown(branch, root)) arms_hung = arms_hung || s.hung[j];
  int neck = -1;
  std::string neck_why;
  if (!arms_hung) {
    neck = above.size() > 1 ? above.front() : branch;
    neck_why = above.size() > 1 ? "topology: the joint above where the arms branch" : "topology: where the arms branch (no joint between it and the head)";
    if (above.size() == 1) t.warnings.push_back("no neck joint between the shoulders and the head: the neck is " + quoted(s, branch));
  } else {
    // The arms were hung from the body by proximity, so where they branch says little: the neck is the
    // first joint of the chain level with the shoulders or above.
    const double shoulders = 0.5 * (hf.of(s.position[t.roles.at("lShoulder")]) + hf.of(s.position[t.roles.at("rShoulder")]));
    std::vector<int> chain = to_branch;
    chain.insert(chain.end(), above.begin(), above.end());
    for (int j : chain)
      if (hf.of(s.position[j]) >= shoulders) {
        neck = j;
        break;
      }
    if (neck == head || neck < 0) neck = s.parent[head];
    neck_why = "topology: the spine's first joint above the shoulders";
  }
  if (neck < 0 || s.pathDown(pelvis, neck).size() < 2)
    throw InputError(cannot + "no spine joint between the pelvis " + quoted(s, pelvis) + " and the neck" +
                     (neck >= 0 ? " " + quoted(s, neck) : std::string()) + fix);
  assign(t, "neck", neck, neck_why);
  assign(t, "head", head, "topology: the top of the spine's chain");
}

}  // namespace

TopologyRoles riderByTopology(const MappingSkeleton& s) {
  const Liveness l = liveness(s, JointCount::Weighted);
  const double size = skeletonSize(s, l);
  const std::string cannot = s.file + ": cannot map as a rider by topology: ";
  const std::string fix = " (write a mapping file: docs/characters.md, \"Mapping by itself\")";
  const std::vector<LimbPair> pairs = mirroredLimbs(s, l, size);
  if (pairs.size() < 2)
    throw InputError(cannot + "found " + countText(pairs.size(), "mirror-image limb pair", "mirror-image limb pairs") + " among " +
                     std::to_string(s.size()) + " joints (expected two: arms and legs)" + fix);
  TopologyRoles t;
  if (pairs.size() > 2)
    t.warnings.push_back(std::to_string(pairs.size()) + " mirror-image limb pairs: took the two longest as arms and legs");
  // Legs point away from where the other pair branches; arms sideways or toward it.
  std::array<double, 2> away{};
  std::array<glm::dvec3, 2> ends{};
  for (int i = 0; i < 2; ++i) {
    const LimbPair& p = pairs[i];
    const LimbPair& q = pairs[1 - i];
    const glm::dvec3 ea = s.position[chainFrom(s, l, p.a).back()], eb = s.position[chainFrom(s, l, p.b).back()];
    const glm::dvec3 toward = directionOr(s.position[q.branch] - s.position[p.branch], {0, 0, 0});
    ends[i] = 0.5 * (ea + eb);
    away[i] = 0.5 * (glm::dot(directionOr(ea - s.position[p.branch], {0, 0, 0}), toward) +
                     glm::dot(directionOr(eb - s.position[p.branch], {0, 0, 0}), toward));
  }
  if (pairs[0].branch == pairs[1].branch)
    throw InputError(cannot + "both limb pairs branch from joint " + quoted(s, pairs[0].branch) +
                     " (expected the legs at the pelvis and the arms higher up the spine)" + fix);
  const int li = away[0] <= away[1] ? 0 : 1;
  const LimbPair& legs = pairs[li];
  const LimbPair& arms = pairs[1 - li];
  if (!(away[li] < kLegsAway && away[1 - li] > away[li] + kArmsAwayMargin))
    throw InputError(cannot + "cannot tell the legs from the arms: neither limb pair (from " + quoted(s, pairs[0].branch) + " and " +
                     quoted(s, pairs[1].branch) + ") hangs away from the other (a four-legged character? try --as horse)" + fix);
  const int pelvis = legs.branch, branch = arms.branch;
  if (!s.above(pelvis, branch))
    throw InputError(cannot + "the arms branch from " + quoted(s, branch) + ", which is not below the pelvis " + quoted(s, pelvis) +
                     " in the hierarchy (expected the spine to run up from the pelvis)" + fix);
  const glm::dvec3 up0 = nearAxis(directionOr(s.position[branch] - ends[li], {0, 1, 0}));
  const HeightFrame hf = heightFrame(s, up0);
  const double H = hf.height;

  assign(t, "pelvis", pelvis, "topology: where the legs branch");
  riderLegRoles(s, l, legs, hf, cannot, fix, t);
  riderArmRoles(s, l, arms, H, cannot, fix, t);
  riderSpineRoles(s, l, legs, arms, size, up0, hf, cannot, fix, t);
  return t;
}

namespace {

// ---- Horse.

const std::string kMapFix = " (write a mapping file: docs/characters.md, \"Mapping by itself\")";

// `p` reflected through `m` lands on `q`, each at least half the pair separation off the mirror
// plane: a mirror-image pair beside the midline (ears, eyes), not two joints on it (a mane's).
bool mirrorImages(const Mirror& m, const glm::dvec3& p, const glm::dvec3& q, double size) {
  const double off = 0.5 * kMinPairSeparation * size;
  return glm::length(m.reflect(p) - q) <= kMirrorTolerance * size && std::abs(glm::dot(p - m.middle, m.normal)) >= off &&
         std::abs(glm::dot(q - m.middle, m.normal)) >= off;
}

// A walk out of one end of the trunk (horseEndWalk).
struct EndWalk {
  std::vector<int> up_steps;  // joints reached going up the hierarchy: the back beyond the branch
  std::vector<int> chain;     // then down it: the neck and head, or the tail
  double top = -kInf;         // the highest joint of the chain (-inf: none)
};

// From `branch` (where `legs` leave the trunk) away from `other` (the other pair's branch), never into
// the pair's legs: at each joint the neighbour whose joints reach farthest along `away`, compared over
// every joint each neighbour holds (weighted or not). The head walk goes down the hierarchy only,
// through the file's own joints (Rigify's loose face and mane bones were hung by proximity: none of
// the neck), and stops at a joint a mirror-image pair branches from (the head: ears, eyes); the tail
// walk may go up first (Rigify's tail hangs from spine.001, the parent of the joint the thighs' pelvis
// bones hang from) and takes hung roots (a deform-bones-only export leaves the tail a root).
EndWalk horseEndWalk(const MappingSkeleton& s, const Liveness& l, const LimbPair& legs, int other, const glm::dvec3& away,
                     const Mirror& midline, double size, const HeightFrame& hf, bool head_walk) {
  EndWalk w;
  const glm::dvec3 from = s.position[legs.branch];
  // The joints on `n`'s side of `cur` (its subtree, or for the parent everything outside cur's).
  const auto holds = [&](int cur, int n, int x) { return n == s.parent[cur] ? !s.contains(cur, x) : s.contains(n, x); };
  int cur = legs.branch, prev = -1;
  bool down = false;
  for (;;) {
    if (head_walk && cur != legs.branch) {
      const std::vector<int>& kids = s.children[cur];
      bool pair = false;
      for (std::size_t i = 0; i < kids.size() && !pair; ++i)
        for (std::size_t k = i + 1; k < kids.size() && !pair; ++k)
          pair = mirrorImages(midline, s.position[kids[i]], s.position[kids[k]], size);
      if (pair) break;
    }
    std::vector<int> next = s.children[cur];
    if (!head_walk && !down && s.parent[cur] >= 0) next.push_back(s.parent[cur]);
    int best = -1;
    double reach = -kInf;
    for (int n : next) {
      if (n == prev || !l.live[n] || (head_walk && s.hung[n])) continue;
      if (holds(cur, n, other) || holds(cur, n, legs.a) || holds(cur, n, legs.b)) continue;
      for (int k = 0; k < s.size(); ++k)
        if (holds(cur, n, k))
          if (const double r = glm::dot(s.position[k] - from, away); r > reach) reach = r, best = n;
    }
    if (best < 0) break;
    if (best == s.parent[cur]) {
      w.up_steps.push_back(best);
    } else {
      down = true;
      w.chain.push_back(best);
      w.top = std::max(w.top, hf.of(s.position[best]));
    }
    prev = cur;
    cur = best;
  }
  return w;
}

// The joints from `a` to `b` along the tree, both included.
std::vector<int> treePath(const MappingSkeleton& s, int a, int b) {
  const int top = lowestCommonAncestor(s, a, b);
  std::vector<int> path;
  for (int j = a; j != top; j = s.parent[j]) path.push_back(j);
  path.push_back(top);
  const std::vector<int> down = s.pathDown(top, b);
  path.insert(path.end(), down.begin(), down.end());
  return path;
}

// A leg's chain with a split bone's further segments left out (kSplitBoneDeg): which of its joints are
// joints of the limb.
std::vector<char> limbJoints(const MappingSkeleton& s, const std::vector<int>& chain) {
  std::vector<char> keep(chain.size(), 1);
  for (std::size_t i = 1; i + 1 < chain.size(); ++i) {
    const glm::dvec3 in = s.position[chain[i]] - s.position[chain[i - 1]], out = s.position[chain[i + 1]] - s.position[chain[i]];
    const double a = glm::length(in), b = glm::length(out);
    if (!(a > 0.0 && b > 0.0)) continue;
    const double turn = std::acos(std::clamp(glm::dot(in, out) / (a * b), -1.0, 1.0)) * 180.0 / std::numbers::pi;
    if (turn <= kSplitBoneDeg && std::abs(a - b) <= kSplitLengthTolerance * std::max(a, b)) keep[i] = 0;
  }
  return keep;
}

// With fewer than two pairs of legs: the leg that has no mirror image, when one pair was found and a
// limb of the rest reaches the ground beside it (a horse with three legs), else what was found.
[[noreturn]] void throwNotFourLegs(const MappingSkeleton& s, const Liveness& l, const std::vector<LimbPair>& pairs,
                                   const std::string& cannot) {
  if (pairs.size() == 1) {
    const LimbPair& p = pairs[0];
    const std::vector<int> ca = chainFrom(s, l, p.a), cb = chainFrom(s, l, p.b);
    const glm::dvec3 feet = 0.5 * (s.position[ca.back()] + s.position[cb.back()]);
    const HeightFrame rough = heightFrame(s, nearAxis(directionOr(s.position[p.branch] - feet, {0, 1, 0})));
    for (int foot = 0; foot < s.size(); ++foot) {
      if (!l.live[foot] || l.height[foot] != 0 || s.contains(p.a, foot) || s.contains(p.b, foot)) continue;
      if (rough.of(s.position[foot]) > kFootBand * rough.height) continue;
      int top = foot;
      while (s.parent[top] >= 0 && !s.contains(s.parent[top], p.branch)) top = s.parent[top];
      throw InputError(cannot + "the leg from " + quoted(s, top) + " down to " + quoted(s, foot) +
                       " has no mirror image on the other side (found one pair of legs, from " + quoted(s, p.a) + " and " +
                       quoted(s, p.b) + "; expected two pairs: a horse with four legs, each the mirror image of its partner)" + kMapFix);
    }
  }
  throw InputError(cannot + "found " + countText(pairs.size(), "mirror-image limb pair", "mirror-image limb pairs") + " among " +
                   std::to_string(s.size()) + " joints (expected two pairs of legs)" + kMapFix);
}

// The legs' chains (each pair's first leg from its root down, the second its mirror image) checked to
// reach the ground, and the height frame: up square to the ground the four feet stand on, toward the
// trunk.
struct HorseLegs {
  std::array<std::array<std::vector<int>, 2>, 2> chains;
  glm::dvec3 up;
  HeightFrame hf;
};

HorseLegs horseLegChains(const MappingSkeleton& s, const Liveness& l, const std::vector<LimbPair>& pairs, const std::string& cannot) {
  HorseLegs g;
  glm::dvec3 feet(0.0);
  for (int i = 0; i < 2; ++i) {
    g.chains[i][0] = chainFrom(s, l, pairs[i].a);
    g.chains[i][1] = mirroredChain(s, l, g.chains[i][0], pairs[i].a, pairs[i].b);
    feet += 0.25 * (s.position[g.chains[i][0].back()] + s.position[g.chains[i][1].back()]);
  }
  // Four legs reaching the ground: every limb ends low, measured from the feet toward the trunk.
  const glm::dvec3 trunk = 0.5 * (s.position[pairs[0].branch] + s.position[pairs[1].branch]) - feet;
  const HeightFrame rough = heightFrame(s, nearAxis(directionOr(trunk, {0, 1, 0})));
  for (int i = 0; i < 2; ++i)
    for (const std::vector<int>& c : g.chains[i])
      if (rough.of(s.position[c.back()]) > kFootBand * rough.height)
        throw InputError(cannot + "the limb from " + quoted(s, c.front()) + " ends at " + quoted(s, c.back()) + ", " +
                         std::to_string(static_cast<int>(std::lround(100.0 * rough.of(s.position[c.back()]) / rough.height))) +
                         "% of the height above the ground (expected four legs reaching the ground; a two-legged character? try --as rider)" + kMapFix);
  const auto foot = [&](int i, int side) { return s.position[g.chains[i][side].back()]; };
  const glm::dvec3 along = 0.5 * (foot(0, 0) + foot(0, 1)) - 0.5 * (foot(1, 0) + foot(1, 1));
  glm::dvec3 ground_normal = glm::cross(along, foot(0, 0) - foot(0, 1));
  if (glm::dot(ground_normal, trunk) < 0.0) ground_normal = -ground_normal;
  g.up = nearAxis(directionOr(ground_normal, directionOr(trunk, {0, 1, 0})));
  g.hf = heightFrame(s, g.up);
  return g;
}

// The body, neck, head and tail by shape: the two ends' walks, the fore pair's end the one whose walk
// rises higher, the neck from the front walk's first joint ahead of the fore legs' pivots (each pair's
// in `fore_pivots`, taken as fore legs). `fore` gets the index of the fore pair; the hind roots are
// left to the caller.
HorseChains horseChainsByShape(const MappingSkeleton& s, const Liveness& l, const std::vector<LimbPair>& pairs,
                               const std::array<std::array<int, 2>, 2>& fore_pivots, const HeightFrame& hf, double size,
                               const std::string& cannot, int& fore) {
  const Mirror midline = mirrorOf(s, pairs[0].a, pairs[0].b);
  std::array<glm::dvec3, 2> away;
  std::array<EndWalk, 2> head_walk;
  for (int i = 0; i < 2; ++i) {
    away[i] = directionOr(s.position[pairs[i].branch] - s.position[pairs[1 - i].branch], {0, 0, 0});
    head_walk[i] = horseEndWalk(s, l, pairs[i], pairs[1 - i].branch, away[i], midline, size, hf, true);
  }
  if (head_walk[0].chain.empty() && head_walk[1].chain.empty())
    throw InputError(cannot + "no neck leaves either end of the trunk (" + quoted(s, pairs[0].branch) + ", " +
                     quoted(s, pairs[1].branch) + "), so its front is unknown" + kMapFix);
  fore = head_walk[1].chain.empty() || (!head_walk[0].chain.empty() && head_walk[0].top >= head_walk[1].top) ? 0 : 1;
  const LimbPair& f = pairs[fore];
  const LimbPair& h = pairs[1 - fore];
  const EndWalk rear = horseEndWalk(s, l, h, f.branch, away[1 - fore], midline, size, hf, false);
  HorseChains c;
  c.fore_roots = fore_pivots[fore];
  c.body.assign(rear.up_steps.rbegin(), rear.up_steps.rend());
  const std::vector<int> back = treePath(s, h.branch, f.branch);
  c.body.insert(c.body.end(), back.begin(), back.end());
  c.tail = rear.chain;
  // The neck starts ahead of the fore legs' roots: the withers' joints behind them are the body's.
  const std::vector<int>& front = head_walk[fore].chain;
  const glm::dvec3 shoulders = 0.5 * (s.position[c.fore_roots[0]] + s.position[c.fore_roots[1]]);
  std::size_t first = 0;
  while (first + 2 < front.size() && !(glm::dot(s.position[front[first]] - shoulders, away[fore]) > 0.0)) ++first;
  c.body.insert(c.body.end(), front.begin(), front.begin() + static_cast<std::ptrdiff_t>(first));
  c.neck.assign(front.begin() + static_cast<std::ptrdiff_t>(first), front.end() - 1);
  c.head = front.back();
  return c;
}

// A leg's joints from its root down, a split bone's further segments left out (limbJoints), and the
// mirror image's the same.
std::array<std::vector<int>, 2> limbChains(const MappingSkeleton& s, const std::array<std::vector<int>, 2>& chains) {
  const std::vector<char> keep = limbJoints(s, chains[0]);
  std::array<std::vector<int>, 2> out;
  for (int side = 0; side < 2; ++side)
    for (std::size_t i = 0; i < chains[side].size(); ++i)
      if (keep[i]) out[side].push_back(chains[side][i]);
  return out;
}

// Where a leg swings: the hind leg's hip joint, the fifth joint up (the parent of the stifle's femur);
// the fore leg's scapula, the sixth (its child carries the humerus), or, on a leg of five, its root
// (the humerus's head: Rigify's scapula was a loose joint of its own). Its root when the leg is
// shorter (no pivot role then; the root is still where it leaves the body).
int legPivot(const std::vector<int>& c, bool fore, bool* found = nullptr) {
  const int n = static_cast<int>(c.size()), up = fore && n >= 6 ? 6 : 5;
  if (found) *found = n >= 5;
  return n >= up ? c[static_cast<std::size_t>(n - up)] : c.front();
}

// Each leg counted from the ground up, a split bone's further segments passed over.
void horseLegRoles(const MappingSkeleton& s, const std::array<std::vector<int>, 2>& chains, const LimbPair& pair, bool fore,
                   TopologyRoles& t) {
  const std::array<std::vector<int>, 2> legs = limbChains(s, chains);
  const std::string split = legs[0].size() < chains[0].size() ? " (a split bone's segments passed over)" : "";
  for (int side = 0; side < 2; ++side) {
    const std::vector<int>& c = legs[side];
    const std::string leg = std::string(side == 0 ? "l" : "r") + (fore ? "f" : "b");
    const int n = static_cast<int>(c.size());
    if (n < 3) {
      t.warnings.push_back("the leg from " + quoted(s, c.front()) + " has " + countText(c.size(), "joint", "joints") +
                           " (expected at least three): not mapped");
      continue;
    }
    assign(t, leg + "Hoof", c[n - 1], "topology: the leg's lowest joint");
    if (n >= 4) {
      assign(t, leg + "Fetlock", c[n - 2], "topology: the leg's second joint from the ground" + split);
      assign(t, leg + "Middle", c[n - 3], "topology: the leg's third joint from the ground" + split);
      assign(t, leg + "Upper", c[n - 4], "topology: the leg's fourth joint from the ground" + split);
    } else {
      assign(t, leg + "Fetlock", c[n - 1], "topology: the leg's lowest joint (three joints: shared with the hoof)");
      assign(t, leg + "Middle", c[n - 2], "topology: the leg's second joint from the ground");
      assign(t, leg + "Upper", c[n - 3], "topology: the leg's third joint from the ground");
    }
    bool pivot = false;
    const int p = legPivot(c, fore, &pivot);
    if (pivot)
      assign(t, leg + "Pivot", p, !fore ? "topology: the hip joint, where the limb swings"
                                  : n >= 6 ? "topology: the scapula's pivot, where the limb swings"
                                           : "topology: the leg's root, where the limb swings (no scapula on its chain)");
  }
  if (legs[0].size() == 3)
    t.warnings.push_back("the legs from " + quoted(s, pair.a) + " have three joints: each shares its lowest joint between Fetlock and Hoof");
}

// The body's joint the legs from `roots` hang from: their parent in the file when both hang from one
// joint of the body, else the body's joint whose bone passes nearest the roots' middle (a bone runs
// from each body joint to the next, the last to the neck).
int legsHangFrom(const MappingSkeleton& s, const HorseChains& c, const std::array<int, 2>& roots, bool& by_hierarchy) {
  const auto onBody = [&](int j) { return std::find(c.body.begin(), c.body.end(), j) != c.body.end(); };
  const int pa = s.parent[roots[0]], pb = s.parent[roots[1]];
  by_hierarchy = pa >= 0 && pa == pb && !s.hung[roots[0]] && !s.hung[roots[1]] && onBody(pa);
  if (by_hierarchy) return pa;
  const glm::dvec3 p = 0.5 * (s.position[roots[0]] + s.position[roots[1]]);
  int best = -1;
  double bd = kInf;
  const int beyond = !c.neck.empty() ? c.neck.front() : c.head;
  for (std::size_t k = 0; k < c.body.size(); ++k) {
    const glm::dvec3 a = s.position[c.body[k]];
    if (const double d = glm::length(p - a); d < bd) bd = d, best = c.body[k];
    const int next = k + 1 < c.body.size() ? c.body[k + 1] : beyond;
    if (next < 0) continue;
    const glm::dvec3 bone = s.position[next] - a;
    const double len2 = glm::dot(bone, bone), u = len2 > 0.0 ? glm::dot(p - a, bone) / len2 : -1.0;
    if (u > 0.0 && u < 1.0)
      if (const double d = glm::length(p - (a + u * bone)); d < bd) bd = d, best = c.body[k];
  }
  return best;
}

}  // namespace

void horseTrunkRoles(const MappingSkeleton& s, const HorseChains& c, const std::string& how, std::map<std::string, int>& roles,
                     std::map<std::string, std::string>& why) {
  const auto set = [&](const std::string& role, int j, const std::string& reason) {
    if (j < 0) return;
    roles[role] = j;
    why[role] = how + ": " + reason;
  };
  const auto index = [&](int j) { return static_cast<int>(std::find(c.body.begin(), c.body.end(), j) - c.body.begin()); };
  int root = -1, chest = -1;
  if (!c.body.empty() && c.hind_roots[0] >= 0 && c.hind_roots[1] >= 0) {
    bool direct = false;
    root = legsHangFrom(s, c, c.hind_roots, direct);
    set("root", root, direct ? "where the hind legs hang (the end away from the head)"
                             : "the back's joint nearest the hip joints (the hind legs hang from a side bone or were loose)");
  }
  if (!c.body.empty() && c.fore_roots[0] >= 0 && c.fore_roots[1] >= 0) {
    bool direct = false;
    chest = legsHangFrom(s, c, c.fore_roots, direct);
    set("chest", chest, direct ? "where the fore legs hang" : "the back's joint nearest the fore legs' roots (they were loose)");
  }
  if (root >= 0 && chest >= 0 && index(chest) - index(root) >= 2)
    set("backMid", c.body[static_cast<std::size_t>((index(root) + index(chest)) / 2)], "the middle joint of the back");
  if (!c.neck.empty()) {
    set("neck1", c.neck.front(), "the neck's first joint");
    set("neck2", c.neck[c.neck.size() / 2], c.neck.size() > 1 ? "the neck's middle joint" : "the neck's one joint (shared with neck1)");
  }
  set("head", c.head, "the end of the chain leaving the front of the trunk");
  if (const std::size_t n = c.tail.size(); n > 0) {
    const std::array<std::size_t, 3> at = n >= 3 ? std::array<std::size_t, 3>{0, (n + 1) / 3, (2 * n + 1) / 3}
                                                 : std::array<std::size_t, 3>{0, std::min<std::size_t>(1, n - 1), n - 1};
    for (int k = 0; k < 3; ++k)
      set("tail" + std::to_string(k + 1), c.tail[at[k]],
          n >= 3 ? "along the chain leaving the back of the trunk" : "the tail's chain (shorter than three joints: shared)");
  }
}

TopologyRoles horseByTopology(const MappingSkeleton& s) {
  const Liveness l = liveness(s, JointCount::Skeleton);
  const double size = skeletonSize(s, l);
  const std::string cannot = s.file + ": cannot map as a horse by topology: ";
  const std::vector<LimbPair> pairs = mirroredLimbs(s, l, size);
  if (pairs.size() < 2) throwNotFourLegs(s, l, pairs, cannot);
  TopologyRoles t;
  if (pairs.size() > 2)
    t.warnings.push_back(std::to_string(pairs.size()) + " mirror-image limb pairs: took the two longest as the legs");
  if (pairs[0].branch == pairs[1].branch)
    throw InputError(cannot + "both pairs of legs branch from joint " + quoted(s, pairs[0].branch) +
                     " (expected the hind legs at the hips and the fore legs at the chest)" + kMapFix);
  const HorseLegs legs = horseLegChains(s, l, pairs, cannot);
  // Each pair's pivots (the hip joints, the scapulae): taken as fore and as hind, the trunk's end
  // decides which.
  std::array<std::array<std::array<int, 2>, 2>, 2> pivots;  // [as fore][pair][side]
  for (int as_fore = 0; as_fore < 2; ++as_fore)
    for (int i = 0; i < 2; ++i) {
      const std::array<std::vector<int>, 2> c = limbChains(s, legs.chains[i]);
      pivots[as_fore][i] = {legPivot(c[0], as_fore == 1), legPivot(c[1], as_fore == 1)};
    }
  int fore = 0;
  HorseChains c = horseChainsByShape(s, l, pairs, {pivots[1][0], pivots[1][1]}, legs.hf, size, cannot, fore);
  c.hind_roots = pivots[0][1 - fore];
  horseTrunkRoles(s, c, "topology", t.roles, t.why);
  horseLegRoles(s, legs.chains[fore], pairs[fore], true, t);
  horseLegRoles(s, legs.chains[1 - fore], pairs[1 - fore], false, t);
  return t;
}

}  // namespace stirrup::rig
