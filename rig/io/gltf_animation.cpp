#include "rig/io/gltf_animation.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_nodes.h"

namespace stirrup::rig {

glm::dmat4 GltfTrs::toMatrix() const {
  if (matrix) return *matrix;
  return glm::translate(glm::dmat4(1.0), t) * glm::dmat4(glm::mat3_cast(r)) * glm::scale(glm::dmat4(1.0), s);
}

glm::dquat gltfRotationOf(const glm::dmat4& m) {
  glm::dmat3 r(m);
  for (int i = 0; i < 3; ++i) r[i] = glm::normalize(r[i]);
  return glm::normalize(glm::quat_cast(r));
}

namespace {

int animationIndex(const tinygltf::Model& model, const std::string& file, const std::string& name) {
  if (model.animations.empty()) throw InputError(file + ": the file has no animation");
  if (name.empty()) return 0;
  std::string known;
  for (std::size_t i = 0; i < model.animations.size(); ++i) {
    if (model.animations[i].name == name) return static_cast<int>(i);
    known += (known.empty() ? "" : ", ") + ("\"" + model.animations[i].name + "\"");
  }
  throw InputError(file + ": no animation named \"" + name + "\" (the file has " + known + ")");
}

GltfTrs restOf(const tinygltf::Node& n) {
  GltfTrs x;
  if (n.matrix.size() == 16) {
    x.matrix = gltfNodeLocal(n);
    return x;
  }
  if (n.translation.size() == 3) x.t = {n.translation[0], n.translation[1], n.translation[2]};
  if (n.rotation.size() == 4) x.r = glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
  if (n.scale.size() == 3) x.s = {n.scale[0], n.scale[1], n.scale[2]};
  return x;
}

}  // namespace

GltfAnimation::GltfAnimation(const tinygltf::Model& model, const std::string& file, const std::string& animation) {
  index_ = animationIndex(model, file, animation);
  name_ = model.animations[static_cast<std::size_t>(index_)].name;
  setUp(model, file);
  addTracks(model, file, index_);
}

GltfAnimation GltfAnimation::together(const tinygltf::Model& model, const std::string& file) {
  GltfAnimation a;
  a.setUp(model, file);
  for (std::size_t i = 0; i < model.animations.size(); ++i) {
    const tinygltf::Animation& anim = model.animations[i];
    const std::string name = anim.name.empty() ? "animations[" + std::to_string(i) + "]" : anim.name;
    bool other_take = false;
    for (const tinygltf::AnimationChannel& ch : anim.channels)
      other_take = other_take || (ch.target_node >= 0 && ch.target_node < a.nodeCount() && a.animates(ch.target_node) &&
                                  ch.target_path != "weights");
    if (other_take) {
      a.left_out_.push_back(name);
      continue;
    }
    if (a.played_.empty()) a.index_ = static_cast<int>(i);
    a.addTracks(model, file, static_cast<int>(i));
    a.played_.push_back(name);
    a.name_ += (a.name_.empty() ? "" : " + ") + name;
  }
  return a;
}

void GltfAnimation::setUp(const tinygltf::Model& model, const std::string& file) {
  parent_ = gltfNodeParents(model, file);
  for (const tinygltf::Node& n : model.nodes) rest_.push_back(restOf(n));
  // Parents before children: by depth, stable.
  std::vector<int> depth(rest_.size(), 0);
  for (std::size_t i = 0; i < rest_.size(); ++i)
    for (int p = parent_[i]; p >= 0; p = parent_[static_cast<std::size_t>(p)]) ++depth[i];
  order_.resize(rest_.size());
  for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return depth[std::size_t(a)] < depth[std::size_t(b)]; });
  drive_.assign(rest_.size(), {});
}

void GltfAnimation::addTracks(const tinygltf::Model& model, const std::string& file, int index) {
  const tinygltf::Animation& anim = model.animations[static_cast<std::size_t>(index)];
  const std::string where_animation = file + ": animation \"" + anim.name + "\"";
  for (std::size_t c = 0; c < anim.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = anim.channels[c];
    const std::string at_channel = where_animation + ": channels[" + std::to_string(c) + "]";
    if (ch.target_path == "weights") continue;  // morph targets: not a transform
    if (ch.target_node < 0) continue;           // a channel for an extension's target
    if (ch.target_node >= static_cast<int>(rest_.size()))
      throw InputError(at_channel + ".target.node: expected a node index 0.." + std::to_string(rest_.size() - 1) + ", got " +
                       std::to_string(ch.target_node));
    if (ch.target_path != "translation" && ch.target_path != "rotation" && ch.target_path != "scale")
      throw InputError(at_channel + ".target.path: expected translation, rotation, scale or weights, got \"" + ch.target_path + "\"");
    if (ch.sampler < 0 || ch.sampler >= static_cast<int>(anim.samplers.size()))
      throw InputError(at_channel + ".sampler: expected a sampler index 0.." + std::to_string(int(anim.samplers.size()) - 1) + ", got " +
                       std::to_string(ch.sampler));
    const tinygltf::AnimationSampler& s = anim.samplers[static_cast<std::size_t>(ch.sampler)];
    const std::string where = where_animation + ": sampler " + std::to_string(ch.sampler);
    if (s.interpolation != "LINEAR" && s.interpolation != "STEP" && s.interpolation != "CUBICSPLINE")
      throw InputError(where + ": interpolation: expected LINEAR, STEP or CUBICSPLINE, got \"" + s.interpolation + "\"");
    Track tr;
    tr.components = ch.target_path == "rotation" ? 4 : 3;
    tr.step = s.interpolation == "STEP";
    tr.cubic = s.interpolation == "CUBICSPLINE";
    tr.times = readAccessor(model, s.input, 1, where + ": input");
    tr.values = readAccessor(model, s.output, tr.components, where + ": output");
    if (tr.times.empty()) continue;
    const std::size_t keys = tr.times.size() * (tr.cubic ? 3 : 1);
    if (tr.values.size() != keys * static_cast<std::size_t>(tr.components))
      throw InputError(where + ": output: expected " + std::to_string(keys) + " elements for " + std::to_string(tr.times.size()) +
                       " keys, got " + std::to_string(tr.values.size() / static_cast<std::size_t>(tr.components)));
    for (std::size_t k = 0; k < tr.times.size(); ++k)
      if (!std::isfinite(tr.times[k]) || (k > 0 && !(tr.times[k] > tr.times[k - 1])))
        throw InputError(where + ": input: key times must increase (key " + std::to_string(k) + ")");
    for (const float v : tr.values)
      if (!std::isfinite(v)) throw InputError(where + ": output: expected finite numbers");
    duration_ = std::max(duration_, double(tr.times.back()));
    start_ = tracks_.empty() ? double(tr.times.front()) : std::min(start_, double(tr.times.front()));
    tracks_.push_back(std::move(tr));
    const int k = static_cast<int>(tracks_.size()) - 1;
    Drive& d = drive_[static_cast<std::size_t>(ch.target_node)];
    (ch.target_path == "translation" ? d.translation : ch.target_path == "rotation" ? d.rotation : d.scale) = k;
  }
}

bool GltfAnimation::animates(int node) const {
  const Drive& d = drive_.at(static_cast<std::size_t>(node));
  return d.translation >= 0 || d.rotation >= 0 || d.scale >= 0;
}

std::vector<double> GltfAnimation::evaluate(const Track& tr, double t) const {
  const int c = tr.components;
  std::vector<double> out(static_cast<std::size_t>(c));
  const auto& ts = tr.times;
  const std::size_t i1 = static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), float(t)) - ts.begin());
  // Element k's value: CUBICSPLINE keys store (in-tangent, value, out-tangent).
  const std::size_t vs = tr.cubic ? 3 : 1, vo = tr.cubic ? 1 : 0;
  const auto value = [&](std::size_t k, int j) { return double(tr.values[((k * vs) + vo) * std::size_t(c) + std::size_t(j)]); };
  if (i1 == 0 || i1 >= ts.size() || tr.step) {
    const std::size_t k = i1 == 0 ? 0 : i1 - 1;
    for (int j = 0; j < c; ++j) out[std::size_t(j)] = value(k, j);
    return out;
  }
  const std::size_t i0 = i1 - 1;
  const double td = std::max(1e-12, double(ts[i1] - ts[i0]));
  const double u = (t - ts[i0]) / td;
  if (tr.cubic) {
    // glTF 2.0 Appendix C: cubic Hermite with tangents scaled by the key interval.
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int j = 0; j < c; ++j) {
      const double out_tangent = tr.values[(i0 * 3 + 2) * std::size_t(c) + std::size_t(j)];
      const double in_tangent = tr.values[(i1 * 3) * std::size_t(c) + std::size_t(j)];
      out[std::size_t(j)] = h00 * value(i0, j) + h10 * td * out_tangent + h01 * value(i1, j) + h11 * td * in_tangent;
    }
    if (c == 4) {
      const double n = std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
      if (n > 0.0)
        for (double& x : out) x /= n;
    }
    return out;
  }
  if (c == 4) {
    const glm::dquat a(value(i0, 3), value(i0, 0), value(i0, 1), value(i0, 2));
    const glm::dquat b(value(i1, 3), value(i1, 0), value(i1, 1), value(i1, 2));
    const glm::dquat q = glm::slerp(a, b, u);
    return {q.x, q.y, q.z, q.w};
  }
  for (int j = 0; j < c; ++j) out[std::size_t(j)] = value(i0, j) * (1 - u) + value(i1, j) * u;
  return out;
}

GltfTrs GltfAnimation::localTrs(int node, std::optional<double> t) const {
  GltfTrs x = rest_.at(static_cast<std::size_t>(node));
  if (!t || x.matrix) return x;
  const Drive& d = drive_[static_cast<std::size_t>(node)];
  if (d.translation >= 0) {
    const auto v = evaluate(tracks_[static_cast<std::size_t>(d.translation)], *t);
    x.t = {v[0], v[1], v[2]};
  }
  if (d.rotation >= 0) {
    const auto v = evaluate(tracks_[static_cast<std::size_t>(d.rotation)], *t);
    const glm::dquat q(v[3], v[0], v[1], v[2]);
    // A zero quaternion (an all-zero key) is no rotation at all: keep the rest rather than divide by 0.
    if (glm::length(q) > 0.0) x.r = glm::normalize(q);
  }
  if (d.scale >= 0) {
    const auto v = evaluate(tracks_[static_cast<std::size_t>(d.scale)], *t);
    x.s = {v[0], v[1], v[2]};
  }
  return x;
}

glm::dmat4 GltfAnimation::world(int node, std::optional<double> t) const {
  glm::dmat4 m = local(node, t);
  for (int p = parent_.at(static_cast<std::size_t>(node)); p >= 0; p = parent_[static_cast<std::size_t>(p)]) m = local(p, t) * m;
  return m;
}

std::vector<glm::dmat4> GltfAnimation::worlds(std::optional<double> t) const {
  std::vector<glm::dmat4> w(rest_.size());
  for (const int n : order_) {
    const int p = parent_[static_cast<std::size_t>(n)];
    w[static_cast<std::size_t>(n)] = p < 0 ? local(n, t) : w[static_cast<std::size_t>(p)] * local(n, t);
  }
  return w;
}

}  // namespace stirrup::rig
