#include "rig/io/gltf_humanoid.h"

#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "rig/io/gltf_writer.h"

namespace stirrup::rig {
namespace {

constexpr double kMetresPerCm = 0.01;

std::vector<unsigned char> base64Decode(const std::string& text) {
  std::vector<unsigned char> out;
  unsigned value = 0;
  int bits = 0;
  for (char ch : text) {
    int d;
    if (ch >= 'A' && ch <= 'Z') d = ch - 'A';
    else if (ch >= 'a' && ch <= 'z') d = ch - 'a' + 26;
    else if (ch >= '0' && ch <= '9') d = ch - '0' + 52;
    else if (ch == '+') d = 62;
    else if (ch == '/') d = 63;
    else break;  // '=' padding ends the data
    value = (value << 6) | static_cast<unsigned>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((value >> bits) & 0xFF));
    }
  }
  return out;
}

// PNG bytes of an sRGB image, by tinygltf's own image writer (stb_image_write): it hands them back as
// a data URI, which is decoded here so the PNG can sit in a buffer view as exporters put it.
std::vector<unsigned char> pngBytes(const RgbImage& img) {
  tinygltf::Image image;
  image.width = img.width;
  image.height = img.height;
  image.component = 3;
  image.bits = 8;
  image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image.image = img.rgb;
  const std::string base, name = "texture.png";
  std::string uri;
  if (!tinygltf::WriteImageData(&base, &name, &image, true, &uri, nullptr))
    throw std::runtime_error("glTF: cannot encode the humanoid's texture as PNG");
  const std::string header = "data:image/png;base64,";
  if (uri.rfind(header, 0) != 0) throw std::runtime_error("glTF: unexpected image data URI");
  return base64Decode(uri.substr(header.size()));
}

// A joint's world transform as written: rotation and translation (metres) of its rest frame.
struct RestFrame {
  glm::dmat3 rotation{1.0};
  glm::dvec3 position{0.0};
};

}  // namespace

std::string vrmHumanBoneName(const HumanoidJointLabel& l, int spine_joints) {
  const std::string s = l.side > 0 ? "left" : "right";
  switch (l.bone) {
    case HumanoidBone::Pelvis: return "hips";
    case HumanoidBone::Spine:
      if (l.index == 0) return "spine";
      if (l.index == 1) return "chest";
      if (l.index == spine_joints - 1) return "upperChest";
      return "";
    case HumanoidBone::Neck: return l.index == 0 ? "neck" : "";
    case HumanoidBone::Head: return "head";
    case HumanoidBone::Clavicle: return s + "Shoulder";
    case HumanoidBone::UpperArm: return l.index == 0 ? s + "UpperArm" : "";
    case HumanoidBone::Forearm: return l.index == 0 ? s + "LowerArm" : "";
    case HumanoidBone::Hand: return s + "Hand";
    case HumanoidBone::Thumb: {
      static const char* const kThumb[] = {"ThumbMetacarpal", "ThumbProximal", "ThumbDistal"};
      return l.index < 3 ? s + kThumb[l.index] : "";
    }
    case HumanoidBone::Index: {
      static const char* const kIndex[] = {"IndexProximal", "IndexIntermediate", "IndexDistal"};
      return l.index < 3 ? s + kIndex[l.index] : "";
    }
    case HumanoidBone::UpperLeg: return l.index == 0 ? s + "UpperLeg" : "";
    case HumanoidBone::LowerLeg: return l.index == 0 ? s + "LowerLeg" : "";
    case HumanoidBone::Foot: return s + "Foot";
    case HumanoidBone::Toe: return s + "Toes";
    default: return "";
  }
}

namespace {

// Joints: local TRS from the rest frames; the world frames are then recomposed from exactly the numbers
// written (floats), and the inverse bind matrices are their inverses, so a reader that multiplies the
// file's own transforms out gets identity at rest. Returns the frames as written.
std::vector<RestFrame> appendJoints(tinygltf::Model& model, const StandingHumanoid& h) {
  const Skeleton& s = h.character.skeleton;
  const std::size_t nj = s.size();
  const int first_joint = static_cast<int>(model.nodes.size());
  std::vector<RestFrame> written(nj);
  for (std::size_t j = 0; j < nj; ++j) {
    const int parent = s.joints[j].parent;
    const RestFrame want{glm::dmat3(h.rest_axes[j]), glm::dvec3(s.restPosition(static_cast<int>(j))) * kMetresPerCm};
    const RestFrame up = parent < 0 ? RestFrame{} : written[parent];
    const glm::dmat3 local_r = glm::transpose(up.rotation) * want.rotation;
    const glm::dvec3 local_t = glm::transpose(up.rotation) * (want.position - up.position);
    glm::dquat q = glm::normalize(glm::quat_cast(local_r));
    if (q.w < 0.0) q = -q;
    tinygltf::Node n;
    n.name = s.joints[j].name;
    const glm::vec3 tf(local_t);
    const glm::quat qf(static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y), static_cast<float>(q.z));
    if (tf != glm::vec3(0.0f)) n.translation = {tf.x, tf.y, tf.z};
    if (qf != glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) n.rotation = {qf.x, qf.y, qf.z, qf.w};
    model.nodes.push_back(n);
    // What a reader recomposes: the float values, in double.
    const glm::dquat qd(qf.w, qf.x, qf.y, qf.z);
    RestFrame w;
    w.rotation = up.rotation * glm::mat3_cast(glm::normalize(qd));
    w.position = up.position + up.rotation * glm::dvec3(tf);
    written[j] = w;
  }
  for (std::size_t j = 0; j < nj; ++j)
    if (s.joints[j].parent >= 0) model.nodes[first_joint + s.joints[j].parent].children.push_back(first_joint + static_cast<int>(j));
  return written;
}

// One primitive of the mesh (part 0 the body, 1 the hair) with its own vertices, as exporters split per
// material, and its material.
tinygltf::Primitive appendPart(tinygltf::Model& model, std::vector<unsigned char>& bin, const StandingHumanoid& h, int part) {
  const SkinnedMesh& m = h.character.mesh;
  const bool byte_joints = h.character.skeleton.size() <= 256;
  const std::size_t begin = part == 0 ? 0 : h.hair_first_index, end = part == 0 ? h.hair_first_index : m.indices.size();
  std::map<std::uint32_t, std::uint32_t> remap;
  std::vector<std::uint32_t> order, indices;
  for (std::size_t i = begin; i < end; ++i) {
    const auto [it, fresh] = remap.emplace(m.indices[i], static_cast<std::uint32_t>(order.size()));
    if (fresh) order.push_back(m.indices[i]);
    indices.push_back(it->second);
  }
  std::vector<float> pos, nor, uv, wts;
  std::vector<std::uint8_t> j8;
  std::vector<std::uint16_t> j16;
  for (std::uint32_t v : order) {
    for (int c = 0; c < 3; ++c) {
      pos.push_back(static_cast<float>(m.positions[v][c] * kMetresPerCm));
      nor.push_back(m.normals[v][c]);
    }
    uv.push_back(h.uvs[v].x);
    uv.push_back(h.uvs[v].y);
    for (int c = 0; c < 4; ++c) {
      const float w = m.weights[v][c];
      const std::uint16_t joint = w > 0.0f ? m.joints[v][c] : 0;
      wts.push_back(w);
      if (byte_joints) j8.push_back(static_cast<std::uint8_t>(joint));
      else j16.push_back(joint);
    }
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = appendFloatAccessor(model, bin, pos, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["NORMAL"] = appendFloatAccessor(model, bin, nor, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
  {
    tinygltf::Accessor a;
    a.bufferView = appendBytes(model, bin, uv.data(), uv.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = order.size();
    a.type = TINYGLTF_TYPE_VEC2;
    model.accessors.push_back(a);
    prim.attributes["TEXCOORD_0"] = static_cast<int>(model.accessors.size()) - 1;
  }
  prim.attributes["JOINTS_0"] =
      byte_joints ? appendIntegerAccessor(model, bin, j8, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER)
                  : appendIntegerAccessor(model, bin, j16, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, 4, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["WEIGHTS_0"] = appendFloatAccessor(model, bin, wts, 4, false, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (order.size() < 65536) {
    std::vector<std::uint16_t> i16(indices.begin(), indices.end());
    prim.indices = appendIntegerAccessor(model, bin, i16, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 1,
                                         TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  } else {
    prim.indices = appendIndexAccessor(model, bin, indices);
  }
  tinygltf::Material mat;
  mat.name = part == 0 ? "Body" : "Hair";
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
  mat.pbrMetallicRoughness.baseColorTexture.index = 0;
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = part == 0 ? 0.8 : 0.6;
  model.materials.push_back(mat);
  prim.material = static_cast<int>(model.materials.size()) - 1;
  return prim;
}

// The texture: PNG in a buffer view.
void appendTexture(tinygltf::Model& model, std::vector<unsigned char>& bin, const StandingHumanoid& h) {
  const std::vector<unsigned char> png = pngBytes(h.texture);
  tinygltf::Image image;
  image.name = "Body_BaseColor";
  image.mimeType = "image/png";
  image.bufferView = appendBytes(model, bin, png.data(), png.size(), 0);
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.sampler = 0;
  texture.source = 0;
  model.textures.push_back(texture);
}

// The skin over the joints from `first_joint`, its inverse bind matrices those of the frames written.
void appendSkin(tinygltf::Model& model, std::vector<unsigned char>& bin, const StandingHumanoid& h, int first_joint,
                const std::vector<RestFrame>& written) {
  const std::size_t nj = written.size();
  tinygltf::Skin skin;
  skin.name = h.params.names == HumanoidNames::Rigify ? "rig" : "Armature";
  for (std::size_t j = 0; j < nj; ++j) skin.joints.push_back(first_joint + static_cast<int>(j));
  std::vector<float> ibm;
  for (std::size_t j = 0; j < nj; ++j) {
    glm::dmat4 inv(glm::transpose(written[j].rotation));
    inv[3] = glm::dvec4(-(glm::transpose(written[j].rotation) * written[j].position), 1.0);
    const glm::mat4 f(inv);
    ibm.insert(ibm.end(), glm::value_ptr(f), glm::value_ptr(f) + 16);
    for (int r = 0; r < 3; ++r) ibm[ibm.size() - 16 + r * 4 + 3] = 0.0f;  // exact affine bottom row
    ibm.back() = 1.0f;
  }
  skin.inverseBindMatrices = appendFloatAccessor(model, bin, ibm, 16, false);
  model.skins.push_back(skin);

}

// VRM 1.0's humanoid table (VRMC_vrm) naming the joints from `first_joint`.
void addVrmExtension(tinygltf::Model& model, const StandingHumanoid& h, int first_joint) {
  const std::size_t nj = h.labels.size();
  tinygltf::Value::Object bones;
  for (std::size_t j = 0; j < nj; ++j) {
    const std::string bone = vrmHumanBoneName(h.labels[j], h.params.spine_joints);
    if (bone.empty()) continue;
    tinygltf::Value::Object node;
    node["node"] = tinygltf::Value(first_joint + static_cast<int>(j));
    bones[bone] = tinygltf::Value(node);
  }
  tinygltf::Value::Object humanoid;
  humanoid["humanBones"] = tinygltf::Value(bones);
  tinygltf::Value::Object meta;
  meta["name"] = tinygltf::Value(std::string("stirrup test humanoid"));
  meta["version"] = tinygltf::Value(std::string("1"));
  meta["authors"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(std::string("stirrup"))});
  meta["licenseUrl"] = tinygltf::Value(std::string("https://vrm.dev/licenses/1.0/"));
  tinygltf::Value::Object vrm;
  vrm["specVersion"] = tinygltf::Value(std::string("1.0"));
  vrm["meta"] = tinygltf::Value(meta);
  vrm["humanoid"] = tinygltf::Value(humanoid);
  model.extensions["VRMC_vrm"] = tinygltf::Value(vrm);
  model.extensionsUsed.push_back("VRMC_vrm");
}

}  // namespace

std::vector<unsigned char> humanoidGlb(const StandingHumanoid& h) {
  const Skeleton& s = h.character.skeleton;
  const SkinnedMesh& m = h.character.mesh;
  const StandingHumanoidParams& p = h.params;
  const std::size_t nj = s.size();
  if (h.labels.size() != nj || h.rest_axes.size() != nj || h.uvs.size() != m.vertexCount())
    throw std::invalid_argument("humanoidGlb: labels, rest axes or texture coordinates do not match the character");

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "stirrup character make humanoid (" + std::string(humanoidNamesName(p.names)) + " names)";
  std::vector<unsigned char> bin;

  const int first_joint = static_cast<int>(model.nodes.size());
  const std::vector<RestFrame> written = appendJoints(model, h);
  std::vector<int> roots;
  for (std::size_t j = 0; j < nj; ++j)
    if (s.joints[j].parent < 0) roots.push_back(first_joint + static_cast<int>(j));

  // Mesh: a body and a hair primitive, each with its own vertices (as exporters split per material).
  tinygltf::Mesh mesh;
  mesh.name = "Body";
  for (int part = 0; part < 2; ++part) {
    const std::size_t begin = part == 0 ? 0 : h.hair_first_index, end = part == 0 ? h.hair_first_index : m.indices.size();
    if (begin == end) continue;
    mesh.primitives.push_back(appendPart(model, bin, h, part));
  }
  model.meshes.push_back(mesh);

  appendTexture(model, bin, h);
  appendSkin(model, bin, h, first_joint, written);
  tinygltf::Node body;
  body.name = "Body";
  body.mesh = 0;
  body.skin = 0;
  model.nodes.push_back(body);
  const int body_node = static_cast<int>(model.nodes.size()) - 1;

  tinygltf::Scene scene;
  scene.name = "Scene";
  // The skeleton root: the one root joint, or the armature node above several (detached limbs).
  if (roots.size() == 1 && p.ground_root) {
    scene.nodes = roots;
    model.skins[0].skeleton = roots.front();
  } else {
    tinygltf::Node armature;  // Blender writes the armature object as a plain node above its bones
    armature.name = p.names == HumanoidNames::Rigify ? "rig" : "Armature";
    armature.children = roots;
    model.nodes.push_back(armature);
    scene.nodes = {static_cast<int>(model.nodes.size()) - 1};
    model.skins[0].skeleton = roots.size() == 1 ? roots.front() : scene.nodes.front();
  }
  scene.nodes.push_back(body_node);
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  if (p.names == HumanoidNames::Vrm) addVrmExtension(model, h, first_joint);
  return glbBytes(model, std::move(bin));
}

}  // namespace stirrup::rig
