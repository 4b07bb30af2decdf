#include "rig/io/gltf_bake.h"

#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "rig/io/gltf_character.h"
#include "rig/io/gltf_writer.h"

namespace stirrup::rig {

std::vector<glm::mat4> worldToLocal(const Skeleton& s, const std::vector<glm::mat4>& world) {
  if (world.size() != s.size()) throw std::invalid_argument("worldToLocal: expected one matrix per joint");
  std::vector<glm::mat4> local(s.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    const int p = s.joints[j].parent;
    local[j] = p < 0 ? world[j] : glm::mat4(glm::inverse(glm::dmat4(world[p])) * glm::dmat4(world[j]));
  }
  return local;
}

namespace {

// Translation and rotation tracks of a sequence of rigid transforms; quaternions kept in one
// hemisphere from key to key so LINEAR interpolation takes the short way.
struct Tracks {
  std::vector<float> t, r;
  // `unit` scales the translation (centimetres to metres for the camera nodes).
  void push(const glm::dmat4& m, double unit = 1.0) {
    t.insert(t.end(), {float(m[3][0] * unit), float(m[3][1] * unit), float(m[3][2] * unit)});
    glm::dmat3 rot(m);
    for (int k = 0; k < 3; ++k) rot[k] = glm::normalize(rot[k]);
    glm::quat q = glm::normalize(glm::quat(glm::quat_cast(rot)));
    if (r.size() >= 4) {
      const glm::quat prev(r[r.size() - 1], r[r.size() - 4], r[r.size() - 3], r[r.size() - 2]);
      if (glm::dot(prev, q) < 0.0f) q = -q;
    }
    r.insert(r.end(), {q.x, q.y, q.z, q.w});
  }
  bool moves() const {
    for (std::size_t i = 3; i < t.size(); ++i)
      if (t[i] != t[i % 3]) return true;
    for (std::size_t i = 4; i < r.size(); ++i)
      if (r[i] != r[i % 4]) return true;
    return false;
  }
};

void setRest(tinygltf::Node& n, const Tracks& tr) {
  n.translation = {tr.t[0], tr.t[1], tr.t[2]};
  n.rotation = {tr.r[0], tr.r[1], tr.r[2], tr.r[3]};
}

}  // namespace

tinygltf::Value seatExtras(const SeatReport& seat) {
  if (!seat.seated_by_rig && !seat.fitted_to_horse && seat.added_points.empty()) return tinygltf::Value();
  tinygltf::Value::Object o;
  o["seated_by_rig"] = tinygltf::Value(seat.seated_by_rig);
  if (seat.fitted_to_horse) o["fitted_to_horse"] = tinygltf::Value(true);
  const auto number = [&](const char* key, float v) { o[key] = tinygltf::Value(double(v)); };
  if (seat.seated_by_rig || seat.fitted_to_horse) {
    number("stirrup_holes_up", seat.stirrup_holes_up);
    number("tread_below_seat_cm", seat.tread_below_seat_cm);
    number("leather_change_cm", seat.leather_change_cm);
    number("stature_cm", seat.stature_cm);
    number("leg_cm", seat.leg_cm);
    number("seat_depth_cm", seat.seat_depth_cm);
    number("knee_turn_out_deg", seat.knee_turn_out_deg);
    number("tread_out_cm", seat.tread_out_cm);
    number("hand_shortfall_cm", seat.hand_shortfall_cm);
    number("spine_bend_gain", seat.spine_bend_gain);
    number("balance_com_height_cm", seat.balance_com_height_cm);
  }
  const auto list = [&](const char* key, const std::vector<std::string>& items) {
    tinygltf::Value::Array a;
    for (const std::string& t : items) a.emplace_back(t);
    o[key] = tinygltf::Value(a);
  };
  list("added_points", seat.added_points);
  list("notes", seat.notes);
  return tinygltf::Value(o);
}

namespace {

// A pair's two characters: a root per character, in metres, as its skin's skeleton (one armature per
// character in a DCC). A crowd pair's name goes before its roots', meshes' and skins' names.
struct PairNodes {
  GltfCharacterNodes horse, rider;
  int horse_root = -1, rider_root = -1;
};

PairNodes appendPair(tinygltf::Model& model, std::vector<unsigned char>& bin, const BakedPair& pair) {
  PairNodes p;
  const std::string named = pair.name.empty() ? "" : pair.name + "_";
  for (int which = 0; which < 2; ++which) {
    const Character& c = which == 0 ? *pair.horse : *pair.rider;
    const std::string role = which == 0 ? "horse:" : "rider:";
    // The horse's tack a mesh node a part beside its body's (rig/io/gltf_tack.h), fitting its armature.
    GltfCharacterNodes n = appendCharacterGltf(model, bin, c, role, which == 0);
    for (const int node : n.tack_nodes) model.nodes[std::size_t(node)].extras.Get<tinygltf::Value::Object>()["stirrup_fits"] = tinygltf::Value(named + "horse");
    if (!named.empty()) {
      // Each armature is its own and named after its pair; its joints keep their skeleton's own names,
      // so one script drives every pair's bones.
      model.skins[std::size_t(n.skin)].name.insert(0, named);
      std::vector<int> mesh_nodes = n.tack_nodes;
      mesh_nodes.insert(mesh_nodes.begin(), n.mesh_node);
      for (const int node : mesh_nodes) {
        model.nodes[std::size_t(node)].name.insert(0, named);
        tinygltf::Mesh& mesh = model.meshes[std::size_t(model.nodes[std::size_t(node)].mesh)];
        mesh.name.insert(0, named);
        for (const tinygltf::Primitive& prim : mesh.primitives)
          if (prim.material >= 0) model.materials[std::size_t(prim.material)].name.insert(0, named);
      }
    }
    (which == 0 ? p.horse : p.rider) = n;
  }
  for (int which = 0; which < 2; ++which) {
    const Character& c = which == 0 ? *pair.horse : *pair.rider;
    const GltfCharacterNodes& n = which == 0 ? p.horse : p.rider;
    const int root = addCentimetreRoot(model, named + (which == 0 ? "horse" : "rider"));
    for (std::size_t j = 0; j < c.skeleton.size(); ++j)
      if (c.skeleton.joints[j].parent < 0) model.nodes[std::size_t(root)].children.push_back(n.joint_nodes[j]);
    model.skins[std::size_t(n.skin)].skeleton = root;
    (which == 0 ? p.horse_root : p.rider_root) = root;
  }
  if (!pair.name.empty())
    if (const tinygltf::Value seat = seatExtras(pair.seat); seat.IsObject()) {
      tinygltf::Value::Object extras;
      extras["stirrup_seat"] = seat;
      model.nodes[std::size_t(p.rider_root)].extras = tinygltf::Value(extras);
    }
  return p;
}

// The shot's ground mesh under a root of its own (in metres); returns the root's node.
int appendGround(tinygltf::Model& model, std::vector<unsigned char>& bin, const BakedShot& shot) {
  // Smooth normals: each vertex the area-weighted sum of its triangles' (facing up).
  std::vector<glm::vec3> normals(shot.ground_vertices.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < shot.ground_indices.size(); t += 3) {
    const std::uint32_t a = shot.ground_indices[t], b = shot.ground_indices[t + 1], c = shot.ground_indices[t + 2];
    glm::vec3 n = glm::cross(shot.ground_vertices[b] - shot.ground_vertices[a], shot.ground_vertices[c] - shot.ground_vertices[a]);
    if (n.y < 0.0f) n = -n;
    normals[a] += n, normals[b] += n, normals[c] += n;
  }
  std::vector<float> pos, nor;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const glm::vec3 n = glm::length(normals[i]) > 0.0f ? glm::normalize(normals[i]) : glm::vec3(0, 1, 0);
    pos.insert(pos.end(), {shot.ground_vertices[i].x, shot.ground_vertices[i].y, shot.ground_vertices[i].z});
    nor.insert(nor.end(), {n.x, n.y, n.z});
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = appendFloatAccessor(model, bin, pos, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["NORMAL"] = appendFloatAccessor(model, bin, nor, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.indices = appendIndexAccessor(model, bin, shot.ground_indices);
  tinygltf::Mesh mesh;
  mesh.name = "ground";
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "ground_mesh";
  node.mesh = static_cast<int>(model.meshes.size()) - 1;
  model.nodes.push_back(node);
  const int ground_root = addCentimetreRoot(model, "ground");
  model.nodes[std::size_t(ground_root)].children.push_back(static_cast<int>(model.nodes.size()) - 2);
  return ground_root;
}

// The frames each hoof of the pair slides on purpose, by their seconds ({"lb": [2.0, 2.0417, ...]}), or
// null when none does.
tinygltf::Value hoofSlidingExtras(const BakedPair& pair, const std::vector<float>& seconds) {
  static constexpr std::array<const char*, 4> kHooves = {"lf", "rf", "lb", "rb"};
  tinygltf::Value::Object o;
  for (std::size_t leg = 0; leg < 4; ++leg) {
    tinygltf::Value::Array times;
    for (std::size_t f = 0; f < pair.hoof_sliding.size(); ++f)
      if (pair.hoof_sliding[f][leg]) times.emplace_back(double(seconds[f]));
    if (!times.empty()) o[kHooves[leg]] = tinygltf::Value(times);
  }
  return o.empty() ? tinygltf::Value() : tinygltf::Value(o);
}

// A baked camera as a glTF camera on a node of its own (its motion keyed by the caller); returns the node.
int appendCamera(tinygltf::Model& model, const BakedCamera& bc) {
  const double aspect = double(bc.width) / double(bc.height);
  tinygltf::Camera cam;
  cam.name = bc.name;
  // stirrup's film: half height ortho_height / 2 (or tan(fov / 2)), half width that times the aspect,
  // which is glTF's ymag / xmag (in metres) and yfov / aspectRatio.
  if (bc.orthographic) {
    cam.type = "orthographic";
    cam.orthographic.ymag = bc.ortho_height_cm * 0.5 * 0.01;
    cam.orthographic.xmag = cam.orthographic.ymag * aspect;
    cam.orthographic.znear = 0.01;
    cam.orthographic.zfar = 1000.0;
  } else {
    cam.type = "perspective";
    cam.perspective.yfov = bc.fov_deg * 3.14159265358979323846 / 180.0;
    cam.perspective.aspectRatio = aspect;
    cam.perspective.znear = 0.01;
    cam.perspective.zfar = 1000.0;
  }
  tinygltf::Value::Object extras;
  extras["width"] = tinygltf::Value(bc.width);
  extras["height"] = tinygltf::Value(bc.height);
  if (!bc.view.empty()) extras["stirrup_view"] = tinygltf::Value(bc.view);
  if (bc.hold_frame > 0) extras["hold_frame"] = tinygltf::Value(bc.hold_frame);
  cam.extras = tinygltf::Value(extras);
  model.cameras.push_back(cam);
  tinygltf::Node node;
  node.name = "camera:" + bc.name;
  node.camera = static_cast<int>(model.cameras.size()) - 1;
  node.extras = tinygltf::Value(extras);  // also on the node: importers keep node extras more often
  model.nodes.push_back(node);
  return static_cast<int>(model.nodes.size()) - 1;
}

}  // namespace

std::vector<unsigned char> bakedShotGlb(const BakedShot& shot) {
  const std::size_t frames = shot.seconds.size();
  if (shot.pairs.empty()) throw std::invalid_argument("bakedShotGlb: expected a pair at least");
  for (const BakedPair& pair : shot.pairs) {
    if (!pair.horse || !pair.rider) throw std::invalid_argument("bakedShotGlb: a pair without its characters");
    if (frames == 0 || pair.poses.size() != frames) throw std::invalid_argument("bakedShotGlb: expected one pose per frame");
  }
  for (std::size_t i = 1; i < frames; ++i)
    if (!(shot.seconds[i] > shot.seconds[i - 1])) throw std::invalid_argument("bakedShotGlb: times must increase");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "stirrup bake";
  std::vector<unsigned char> bin;
  std::vector<PairNodes> pair_nodes;
  for (const BakedPair& pair : shot.pairs) {
    if (!pair.hoof_sliding.empty() && pair.hoof_sliding.size() != frames)
      throw std::invalid_argument("bakedShotGlb: expected the hooves' sliding at every frame or none");
    pair_nodes.push_back(appendPair(model, bin, pair));
    if (const tinygltf::Value sliding = hoofSlidingExtras(pair, shot.seconds); sliding.IsObject()) {
      tinygltf::Value::Object extras;
      extras["stirrup_hoof_sliding"] = sliding;
      model.nodes[std::size_t(pair_nodes.back().horse_root)].extras = tinygltf::Value(extras);
    }
  }
  const int ground_root = shot.ground_indices.empty() ? -1 : appendGround(model, bin, shot);

  tinygltf::Animation anim;
  anim.name = shot.name;
  const int input = appendFloatAccessor(model, bin, shot.seconds, 1, true);
  const auto animate = [&](int node, const Tracks& tr) {
    setRest(model.nodes[node], tr);  // the first frame is the node's own transform
    if (!tr.moves() || frames < 2) return;
    appendLinearChannel(model, bin, anim, input, node, "translation", tr.t, 3);
    appendLinearChannel(model, bin, anim, input, node, "rotation", tr.r, 4);
  };
  for (std::size_t i = 0; i < shot.pairs.size(); ++i) {
    for (int which = 0; which < 2; ++which) {
      const Character& c = which == 0 ? *shot.pairs[i].horse : *shot.pairs[i].rider;
      const GltfCharacterNodes& n = which == 0 ? pair_nodes[i].horse : pair_nodes[i].rider;
      std::vector<Tracks> tracks(c.skeleton.size());
      for (const MountedPose& p : shot.pairs[i].poses) {
        const std::vector<glm::mat4> local = worldToLocal(c.skeleton, which == 0 ? p.horse : p.rider);
        for (std::size_t j = 0; j < local.size(); ++j) tracks[j].push(glm::dmat4(local[j]));
      }
      for (std::size_t j = 0; j < tracks.size(); ++j) animate(n.joint_nodes[j], tracks[j]);
    }
  }
  std::vector<int> camera_nodes;
  for (const BakedCamera& bc : shot.cameras) {
    if (bc.world.size() != frames) throw std::invalid_argument("bakedShotGlb: expected one camera transform per frame");
    if (bc.width <= 0 || bc.height <= 0) throw std::invalid_argument("bakedShotGlb: expected a positive image size");
    const int ni = appendCamera(model, bc);
    camera_nodes.push_back(ni);
    Tracks tr;
    for (const glm::dmat4& w : bc.world) tr.push(w, 0.01);
    animate(ni, tr);
  }
  if (!anim.channels.empty()) model.animations.push_back(anim);
  tinygltf::Scene scene;
  scene.name = shot.name;
  for (const PairNodes& p : pair_nodes) scene.nodes.insert(scene.nodes.end(), {p.horse_root, p.rider_root});
  for (const PairNodes& p : pair_nodes) {
    scene.nodes.push_back(p.horse.mesh_node);
    scene.nodes.insert(scene.nodes.end(), p.horse.tack_nodes.begin(), p.horse.tack_nodes.end());
    scene.nodes.push_back(p.rider.mesh_node);
  }
  scene.nodes.insert(scene.nodes.end(), camera_nodes.begin(), camera_nodes.end());
  if (ground_root >= 0) scene.nodes.push_back(ground_root);
  tinygltf::Value::Object extras;
  extras["fps"] = tinygltf::Value(shot.fps);
  extras["frame_time"] = tinygltf::Value(std::string("seconds = (frame - 1) / fps: frame 1 at t = 0"));
  if (shot.pairs.size() == 1 && shot.pairs[0].name.empty())
    if (const tinygltf::Value seat = seatExtras(shot.pairs[0].seat); seat.IsObject()) extras["stirrup_seat"] = seat;
  scene.extras = tinygltf::Value(extras);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return glbBytes(model, std::move(bin));
}

}  // namespace stirrup::rig
