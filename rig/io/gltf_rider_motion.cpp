#include "rig/io/gltf_rider_motion.h"

#include <cstring>
#include <map>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "rig/error.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_bake.h"
#include "rig/io/gltf_nodes.h"
#include "rig/io/gltf_writer.h"
#include "rig/mapping/character_mapping.h"

namespace stirrup::rig {
namespace {

// The rider's skeleton as it stands in the file it came from, joint for joint with the Character.
struct FileRig {
  std::vector<std::string> names;
  std::vector<glm::dmat4> bind;    // joint world at bind, file space (inverse of the inverse bind matrix)
  std::vector<glm::dmat4> rest;    // joint world at rest, file space (the nodes' own transforms)
  glm::dmat4 root_parent{1.0};     // rest world of the node the root joint hangs from
  glm::dmat4 to_rig{1.0};          // file space -> stirrup space (cm, +X forward, +Y up)
};

FileRig builtInRig(const Character& rider) {
  // Metres, stirrup's axes: the skeleton's own binds, which are its rest.
  FileRig r;
  r.to_rig = glm::scale(glm::dmat4(1.0), glm::dvec3(100.0));
  const glm::dmat4 from_rig = glm::inverse(r.to_rig);
  for (const Joint& j : rider.skeleton.joints) {
    r.names.push_back(j.name);
    r.bind.push_back(from_rig * glm::inverse(glm::dmat4(j.inverse_bind)));
  }
  r.rest = r.bind;
  return r;
}

FileRig userRig(const Character& rider) {
  FileRig r;
  const std::string& file = rider.source.file;
  r.to_rig = rider.source.to_rig;
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = file.ends_with(".glb") ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                                         : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!ok || model.skins.empty()) throw InputError(file + ": not a readable skinned glTF file");
  const tinygltf::Skin& skin = model.skins[0];
  const std::vector<int> parent = gltfNodeParents(model, file);
  const auto worldOf = [&](int n) {
    glm::dmat4 m = gltfNodeLocal(model.nodes[n]);
    for (int p = parent[n]; p >= 0; p = parent[p]) m = gltfNodeLocal(model.nodes[p]) * m;
    return m;
  };
  std::vector<float> ibm;
  if (skin.inverseBindMatrices >= 0) ibm = readAccessor(model, skin.inverseBindMatrices, 16, file + ": skins[0].inverseBindMatrices");
  // The loader names a joint after its node, or "jointN" (N its index in the skin) when the name is
  // empty or taken. Points the rig added are not in the file: they keep an identity entry.
  for (const Joint& j : rider.skeleton.joints) {
    r.names.push_back(j.name);
    if (j.rig_point) {
      r.rest.emplace_back(1.0);
      r.bind.emplace_back(1.0);
      continue;
    }
    int found = -1;
    for (std::size_t k = 0; k < skin.joints.size() && found < 0; ++k)
      if (model.nodes.at(skin.joints[k]).name == j.name) found = static_cast<int>(k);
    if (found < 0 && j.name.starts_with("joint")) found = std::stoi(j.name.substr(5));
    if (found < 0 || found >= static_cast<int>(skin.joints.size()))
      throw std::logic_error("riderMotionGlb: joint " + j.name + " is not in " + file);
    const int node = skin.joints[found];
    r.names.back() = model.nodes[node].name.empty() ? j.name : model.nodes[node].name;
    r.rest.push_back(worldOf(node));
    r.bind.push_back(ibm.size() < std::size_t(16 * (found + 1)) ? glm::dmat4(1.0)
                                                  : glm::inverse(glm::dmat4(glm::make_mat4(ibm.data() + 16 * found))));
    if (j.parent < 0 && parent[node] >= 0) r.root_parent = worldOf(parent[node]);  // every root hangs from it
  }
  return r;
}

// Translation and rotation of a rigid local transform (its scale kept apart).
void decompose(const glm::dmat4& m, glm::dvec3& t, glm::dquat& q, glm::dvec3& s) {
  t = glm::dvec3(m[3]);
  glm::dmat3 rot(m);
  for (int k = 0; k < 3; ++k) s[k] = glm::length(rot[k]), rot[k] /= s[k];
  q = glm::normalize(glm::quat_cast(rot));
}

// The scene's extras: the frame rate and how frames map to seconds, the rig's forward and up in the
// file's axes, and the seat (rig/characters/seating.h).
tinygltf::Value sceneExtras(const RiderMotion& motion, const glm::dmat4& from_rig) {
  tinygltf::Value::Object extras;
  extras["fps"] = tinygltf::Value(motion.fps);
  extras["frame_time"] = tinygltf::Value(std::string("seconds = (frame - 1) / fps: frame 1 at t = 0"));
  const auto fileDirection = [&](const glm::dvec3& rig) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(from_rig * glm::dvec4(rig, 0.0)));
    return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(d.x), tinygltf::Value(d.y), tinygltf::Value(d.z)});
  };
  extras["stirrup_forward"] = fileDirection({1.0, 0.0, 0.0});
  extras["stirrup_up"] = fileDirection({0.0, 1.0, 0.0});
  if (const tinygltf::Value seat = seatExtras(motion.seat); seat.IsObject()) extras["stirrup_seat"] = seat;
  return tinygltf::Value(extras);
}

}  // namespace

std::vector<unsigned char> riderMotionGlb(const Character& rider, const RiderMotion& motion) {
  const std::size_t frames = motion.seconds.size();
  if (frames == 0 || motion.world.size() != frames) throw std::invalid_argument("riderMotionGlb: expected one pose per frame");
  const FileRig f = rider.source.file.empty() ? builtInRig(rider) : userRig(rider);
  const Skeleton& s = rider.skeleton;
  // The joints written, and each one's node: the rig's own points are left out (they are leaves).
  std::vector<int> node_of(s.size(), -1);
  std::vector<std::size_t> written;
  for (std::size_t j = 0; j < s.size(); ++j)
    if (!s.joints[j].rig_point) {
      node_of[j] = 1 + static_cast<int>(written.size());
      written.push_back(j);
    }
  const glm::dmat4 from_rig = glm::inverse(f.to_rig);

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "stirrup bake --rider-only";
  std::vector<unsigned char> bin;
  tinygltf::Node holder;  // the root joint's parent in the user's file, at rest
  holder.name = "rider";
  if (f.root_parent != glm::dmat4(1.0))
    holder.matrix = std::vector<double>(glm::value_ptr(f.root_parent), glm::value_ptr(f.root_parent) + 16);
  model.nodes.push_back(holder);
  // A joint's parent in the file: a root the loader hung from the body is a root again.
  const auto fileParent = [&](std::size_t j) { return s.joints[j].file_root ? -1 : s.joints[j].parent; };
  const auto localAtRest = [&](std::size_t j) {
    const int p = fileParent(j);
    return glm::inverse(p < 0 ? f.root_parent : f.rest[p]) * f.rest[j];
  };
  for (const std::size_t j : written) {
    tinygltf::Node n;
    n.name = f.names[j];
    glm::dvec3 t, sc;
    glm::dquat q;
    decompose(localAtRest(j), t, q, sc);
    n.translation = {t.x, t.y, t.z};
    n.rotation = {q.x, q.y, q.z, q.w};
    if (glm::length(sc - glm::dvec3(1.0)) > 1e-6) n.scale = {sc.x, sc.y, sc.z};
    model.nodes.push_back(n);
    const int p = fileParent(j);
    model.nodes[p < 0 ? 0 : node_of[p]].children.push_back(node_of[j]);
  }
  tinygltf::Skin skin;
  skin.name = "rider";
  skin.skeleton = 0;
  std::vector<float> ibm;
  for (const std::size_t j : written) {
    skin.joints.push_back(node_of[j]);
    const glm::mat4 m(glm::inverse(f.bind[j]));
    ibm.insert(ibm.end(), glm::value_ptr(m), glm::value_ptr(m) + 16);
  }
  skin.inverseBindMatrices = appendFloatAccessor(model, bin, ibm, 16, false);
  model.skins.push_back(skin);

  // The user's joint world that skins the user's mesh as stirrup's joint skins its copy:
  //   skin matrix in stirrup space  S = W * inverse_bind * bind_offset, in file space  to_rig^-1 S to_rig,
  //   and the joint world is that times the joint's bind.
  std::vector<std::vector<float>> tr(s.size()), rot(s.size());
  std::vector<glm::dmat4> posed(s.size());
  for (std::size_t k = 0; k < frames; ++k) {
    if (motion.world[k].size() != s.size()) throw std::invalid_argument("riderMotionGlb: expected one matrix per joint");
    for (const std::size_t j : written) {
      const glm::dmat4 skin_rig = glm::dmat4(motion.world[k][j]) * glm::dmat4(s.skinBind(static_cast<int>(j)));
      posed[j] = from_rig * skin_rig * f.to_rig * f.bind[j];
      const int p = fileParent(j);
      glm::dvec3 t, sc;
      glm::dquat q;
      decompose(glm::inverse(p < 0 ? f.root_parent : posed[p]) * posed[j], t, q, sc);
      if (rot[j].size() >= 4) {
        const std::vector<float>& r = rot[j];
        const glm::dquat prev(r[r.size() - 1], r[r.size() - 4], r[r.size() - 3], r[r.size() - 2]);
        if (glm::dot(prev, q) < 0.0) q = -q;  // the short way between keys
      }
      tr[j].insert(tr[j].end(), {float(t.x), float(t.y), float(t.z)});
      rot[j].insert(rot[j].end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
    }
  }
  tinygltf::Animation anim;
  anim.name = motion.name;
  const int input = appendFloatAccessor(model, bin, motion.seconds, 1, true);
  for (const std::size_t j : written) {
    appendLinearChannel(model, bin, anim, input, node_of[j], "translation", tr[j], 3);
    appendLinearChannel(model, bin, anim, input, node_of[j], "rotation", rot[j], 4);
  }
  model.animations.push_back(anim);
  tinygltf::Scene scene;
  scene.name = motion.name;
  scene.nodes = {0};
  scene.extras = sceneExtras(motion, from_rig);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return glbBytes(model, std::move(bin));
}

}  // namespace stirrup::rig
