#include "rig/io/skeleton_topology.h"

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

// Which joints matter: weighted ones and those above them (end joints and unweighted helpers do not),
// and for each joint the weighted-or-above joints of its subtree.
struct Liveness {
  std::vector<char> live;
  std::vector<std::vector<int>> sub;   // live joints at or below each joint
  std::vector<std::vector<int>> tree;  // every joint at or below each joint (weights can differ between
                                       // a limb and its mirror image where a coarse mesh barely reaches a
                                       // finger tip; the joints cannot)
  std::vector<int> height;             // bones down to its deepest live joint (0: none below)
};

Liveness liveness(const MappingSkeleton& s) {
  const int n = s.size();
  Liveness l;
  l.live.assign(n, 0);
  l.sub.assign(n, {});
  l.height.assign(n, 0);
  l.tree.assign(n, {});
  std::vector<int> order(n);
  for (int j = 0; j < n; ++j) order[j] = j;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return s.depth[a] > s.depth[b]; });
  for (int j : order) {
    bool live = s.weighted[j] != 0;
    for (int c : s.children[j])
      if (l.live[c]) {
        live = true;
        l.height[j] = std::max(l.height[j], l.height[c] + 1);
      }
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

std::string countText(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::vector<LimbPair> mirroredLimbs(const MappingSkeleton& s) {
  const Liveness l = liveness(s);
  const double size = skeletonSize(s, l);
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

std::vector<int> limbChain(const MappingSkeleton& s, int root) { return chainFrom(s, liveness(s), root); }

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

TopologyRoles riderByTopology(const MappingSkeleton& s) {
  const Liveness l = liveness(s);
  const double size = skeletonSize(s, l);
  const std::string cannot = s.file + ": cannot map as a rider by topology: ";
  const std::string fix = " (write a mapping file: docs/characters.md, \"Mapping by itself\")";
  const std::vector<LimbPair> pairs = mirroredLimbs(s);
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
  // Legs.
  {
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
  // Arms.
  {
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
  // Spine, neck and head.
  {
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
  return t;
}

TopologyRoles horseByTopology(const MappingSkeleton& s) {
  const Liveness l = liveness(s);
  const double size = skeletonSize(s, l);
  const std::string cannot = s.file + ": cannot map as a horse by topology: ";
  const std::string fix = " (write a mapping file: docs/characters.md, \"Mapping by itself\")";
  const std::vector<LimbPair> pairs = mirroredLimbs(s);
  if (pairs.size() < 2)
    throw InputError(cannot + "found " + countText(pairs.size(), "mirror-image limb pair", "mirror-image limb pairs") + " among " +
                     std::to_string(s.size()) + " joints (expected two pairs of legs)" + fix);
  TopologyRoles t;
  if (pairs.size() > 2)
    t.warnings.push_back(std::to_string(pairs.size()) + " mirror-image limb pairs: took the two longest as the legs");
  if (pairs[0].branch == pairs[1].branch)
    throw InputError(cannot + "both pairs of legs branch from joint " + quoted(s, pairs[0].branch) +
                     " (expected the hind legs at the hips and the fore legs at the chest)" + fix);
  std::array<std::array<std::vector<int>, 2>, 2> chains;
  glm::dvec3 feet(0.0);
  for (int i = 0; i < 2; ++i) {
    chains[i][0] = chainFrom(s, l, pairs[i].a);
    chains[i][1] = mirroredChain(s, l, chains[i][0], pairs[i].a, pairs[i].b);
    feet += 0.25 * (s.position[chains[i][0].back()] + s.position[chains[i][1].back()]);
  }
  // Four legs reaching the ground: every limb ends low, measured from the feet toward the trunk.
  const glm::dvec3 trunk = 0.5 * (s.position[pairs[0].branch] + s.position[pairs[1].branch]) - feet;
  {
    const HeightFrame rough = heightFrame(s, nearAxis(directionOr(trunk, {0, 1, 0})));
    for (int i = 0; i < 2; ++i)
      for (const std::vector<int>& c : chains[i])
        if (rough.of(s.position[c.back()]) > kFootBand * rough.height)
          throw InputError(cannot + "the limb from " + quoted(s, c.front()) + " ends at " + quoted(s, c.back()) + ", " +
                           std::to_string(static_cast<int>(std::lround(100.0 * rough.of(s.position[c.back()]) / rough.height))) +
                           "% of the height above the ground (expected four legs reaching the ground; a two-legged character? try --as rider)" + fix);
  }
  // Up: square to the ground the four feet stand on (their fore-and-aft and side-to-side lines), toward
  // the trunk.
  const glm::dvec3 along = 0.5 * (s.position[chains[0][0].back()] + s.position[chains[0][1].back()]) -
                           0.5 * (s.position[chains[1][0].back()] + s.position[chains[1][1].back()]);
  const glm::dvec3 across = s.position[chains[0][0].back()] - s.position[chains[0][1].back()];
  glm::dvec3 ground_normal = glm::cross(along, across);
  if (glm::dot(ground_normal, trunk) < 0.0) ground_normal = -ground_normal;
  const glm::dvec3 up0 = nearAxis(directionOr(ground_normal, directionOr(trunk, {0, 1, 0})));
  const HeightFrame hf = heightFrame(s, up0);
  // The chain leaving each end of the trunk other than the legs: neck and head, or tail.
  std::array<int, 2> end_child{-1, -1};
  std::array<double, 2> end_top{-kInf, -kInf};
  for (int i = 0; i < 2; ++i) {
    const int at = pairs[i].branch, other = pairs[1 - i].branch;
    double far = -1.0;
    for (int c : s.children[at]) {
      if (!l.live[c] || s.contains(c, other) || s.contains(c, pairs[i].a) || s.contains(c, pairs[i].b)) continue;
      if (const double d = farthest(s, l, c, s.position[at]); d > far) far = d, end_child[i] = c;
    }
    if (end_child[i] >= 0)
      for (int k : l.sub[end_child[i]]) end_top[i] = std::max(end_top[i], hf.of(s.position[k]));
  }
  if (end_child[0] < 0 && end_child[1] < 0)
    throw InputError(cannot + "no neck or tail leaves either end of the trunk (" + quoted(s, pairs[0].branch) + ", " +
                     quoted(s, pairs[1].branch) + "), so its front is unknown" + fix);
  const int fi = end_child[1] < 0 || (end_child[0] >= 0 && end_top[0] >= end_top[1]) ? 0 : 1;
  const LimbPair& fore = pairs[fi];
  const LimbPair& hind = pairs[1 - fi];
  assign(t, "root", hind.branch, "topology: where the hind legs branch (the end away from the head)");
  assign(t, "chest", fore.branch, "topology: where the fore legs branch");
  // The back between them: the joints on the way from the hips to the chest.
  {
    const int top = lowestCommonAncestor(s, hind.branch, fore.branch);
    std::vector<int> from_hind, from_fore;
    for (int j = hind.branch; j >= 0 && j != top; j = s.parent[j]) from_hind.push_back(j);
    for (int j = fore.branch; j >= 0 && j != top; j = s.parent[j]) from_fore.push_back(j);
    std::vector<int> path = from_hind;
    path.push_back(top);
    path.insert(path.end(), from_fore.rbegin(), from_fore.rend());
    if (path.size() > 2) assign(t, "backMid", path[(path.size() - 1) / 2], "topology: the middle joint of the back");
  }
  // Neck and head.
  const Mirror midline = mirrorOf(s, hind.a, hind.b);
  if (end_child[fi] >= 0) {
    std::vector<int> chain = {end_child[fi]};
    const std::vector<int> more = midlineChain(s, l, end_child[fi], midline, size, up0, kNeckMinRise, {});
    chain.insert(chain.end(), more.begin(), more.end());
    const int head = chain.back();
    assign(t, "head", head, "topology: the end of the chain leaving the front of the trunk");
    chain.pop_back();
    if (!chain.empty()) {
      assign(t, "neck1", chain.front(), "topology: the neck's first joint");
      assign(t, "neck2", chain[chain.size() / 2], chain.size() > 1 ? "topology: the neck's middle joint"
                                                                    : "topology: the neck's one joint (shared with neck1)");
    }
  }
  // Tail.
  if (end_child[1 - fi] >= 0) {
    const std::vector<int> tail = chainFrom(s, l, end_child[1 - fi]);
    const std::size_t n = tail.size();
    const std::array<std::size_t, 3> at = n >= 3 ? std::array<std::size_t, 3>{0, (n + 1) / 3, (2 * n + 1) / 3}
                                                 : std::array<std::size_t, 3>{0, std::min<std::size_t>(1, n - 1), n - 1};
    for (int k = 0; k < 3; ++k)
      assign(t, "tail" + std::to_string(k + 1), tail[at[k]], n >= 3 ? "topology: along the chain leaving the back of the trunk"
                                                                     : "topology: the tail's chain (shorter than three joints: shared)");
  }
  // Legs, counted from the ground up.
  for (const auto& [pair, prefix] : {std::pair<const LimbPair*, const char*>{&fore, "f"}, {&hind, "b"}}) {
    const int pi = pair == &pairs[0] ? 0 : 1;
    for (int side = 0; side < 2; ++side) {
      const std::vector<int>& c = chains[pi][side];
      const std::string leg = std::string(side == 0 ? "l" : "r") + prefix;
      const int n = static_cast<int>(c.size());
      if (n < 3) {
        t.warnings.push_back("the leg from " + quoted(s, c.front()) + " has " + countText(c.size(), "joint", "joints") +
                             " (expected at least three): not mapped");
        continue;
      }
      assign(t, leg + "Hoof", c[n - 1], "topology: the leg's lowest joint");
      if (n >= 4) {
        assign(t, leg + "Fetlock", c[n - 2], "topology: the leg's second joint from the ground");
        assign(t, leg + "Middle", c[n - 3], "topology: the leg's third joint from the ground");
        assign(t, leg + "Upper", c[n - 4], "topology: the leg's fourth joint from the ground");
      } else {
        assign(t, leg + "Fetlock", c[n - 1], "topology: the leg's lowest joint (three joints: shared with the hoof)");
        assign(t, leg + "Middle", c[n - 2], "topology: the leg's second joint from the ground");
        assign(t, leg + "Upper", c[n - 3], "topology: the leg's third joint from the ground");
      }
      if (n >= 5) assign(t, leg + "Pivot", c[0], "topology: the leg's root, where the limb swings");
    }
    if (chains[pi][0].size() == 3)
      t.warnings.push_back("the legs from " + quoted(s, pair->a) + " have three joints: each shares its lowest joint between Fetlock and Hoof");
  }
  return t;
}

}  // namespace stirrup::rig
