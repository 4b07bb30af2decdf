#include "rig/io/gltf_character.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <cstdio>
#include <optional>
#include <sstream>
#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "rig/characters/horse_character.h"
#include "rig/characters/horse_tack.h"
#include "rig/characters/rider_character.h"
#include "rig/error.h"
#include "rig/io/atomic_file.h"
#include "rig/io/character_mapping_json.h"
#include "rig/io/gltf_accessors.h"
#include "rig/io/gltf_extras.h"
#include "rig/io/gltf_mapping.h"
#include "rig/io/gltf_nodes.h"
#include "rig/io/gltf_tack.h"
#include "rig/io/gltf_writer.h"
#include "rig/io/gltf_texture.h"
#include "rig/mapping/auto_mapping.h"
#include "rig/mapping/mapping_skeleton.h"

namespace stirrup::rig {

namespace {

// A joint index as a file gives it (a float read from any component type), for an error: whole numbers
// as integers, anything else as it is.
std::string jointIndexText(float j) {
  if (std::isfinite(j) && j == std::floor(j) && std::abs(j) < 1e9f) return std::to_string(static_cast<long long>(j));
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(j));
  return text;
}

// The name a joint's node gets. A character read from a file keeps its file's names, whatever roles a
// joint plays (two roles on one joint never rename it). A generated character's joints are written
// under their roles (the first, with "upperChest" and the like preferred over the chain's "spineN"),
// as the shipped files have them.
std::vector<std::string> jointNodeNames(const Character& c) {
  std::vector<std::string> names(c.skeleton.size());
  for (std::size_t j = 0; j < c.skeleton.size(); ++j) names[j] = c.skeleton.joints[j].name;
  if (!c.source.file.empty()) return names;
  std::vector<bool> named(c.skeleton.size(), false);
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& [role, j] : c.roles) {
      const bool chain = role.rfind("spine", 0) == 0;
      if (named[j] || chain != (pass == 1)) continue;
      names[j] = role;
      named[j] = true;
    }
  return names;
}

}  // namespace


namespace {

// Writes a character's mesh piece by piece (rig/io/gltf_tack.h GltfMeshPiece): its vertices' attributes,
// then its triangles as one primitive per run of one base colour (a triangle's colour is its first
// vertex's) and texture, in the order the runs first appear, a material per colour and texture.
struct MeshPieceWriter {
  tinygltf::Model& model;
  std::vector<unsigned char>& bin;
  const Character& c;
  const std::string& prefix;
  std::vector<int> textures;  // the mesh's textures in the file, written with the first textured piece

  // The accessors of the piece's vertices (with "_TACK_PART" where `tack_attribute`): a primitive's
  // attributes, shared by the piece's primitives.
  tinygltf::Primitive attributes(const GltfMeshPiece& piece, bool tack_attribute) {
    const SkinnedMesh& m = c.mesh;
    const std::size_t nv = piece.vertices.empty() ? m.vertexCount() : piece.vertices.size();
    const auto vertex = [&](std::size_t i) { return piece.vertices.empty() ? i : std::size_t(piece.vertices[i]); };
    std::vector<float> pos(nv * 3), nor(nv * 3), col(nv * 3), wts(nv * 4);
    std::vector<std::uint16_t> jts(nv * 4);
    for (std::size_t i = 0; i < nv; ++i) {
      const std::size_t v = vertex(i);
      for (int k = 0; k < 3; ++k) {
        pos[i * 3 + k] = m.positions[v][k];
        nor[i * 3 + k] = m.normals[v][k];
        col[i * 3 + k] = m.colors[v][k];
      }
      for (int k = 0; k < 4; ++k) {
        wts[i * 4 + k] = m.weights[v][k];
        jts[i * 4 + k] = m.weights[v][k] > 0.0f ? m.joints[v][k] : 0;
      }
    }
    tinygltf::Primitive proto;
    proto.mode = TINYGLTF_MODE_TRIANGLES;
    proto.attributes["POSITION"] = appendFloatAccessor(model, bin, pos, 3, true, TINYGLTF_TARGET_ARRAY_BUFFER);
    proto.attributes["NORMAL"] = appendFloatAccessor(model, bin, nor, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    proto.attributes["_COLOR"] = appendFloatAccessor(model, bin, col, 3, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    proto.attributes["WEIGHTS_0"] = appendFloatAccessor(model, bin, wts, 4, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    // A textured character: its texture coordinates and its textures (each image as the file held it).
    // The tack is untextured: a part's mesh has none.
    const bool textured = m.textured() && (piece.part == TackPart::None ||
                                           std::any_of(piece.triangles.begin(), piece.triangles.end(),
                                                       [&](std::uint32_t t) { return m.triangleTexture(t) >= 0; }));
    if (textured) {
      std::vector<float> uv(nv * 2);
      for (std::size_t i = 0; i < nv; ++i) uv[i * 2] = m.uvs[vertex(i)].x, uv[i * 2 + 1] = m.uvs[vertex(i)].y;
      proto.attributes["TEXCOORD_0"] = appendFloatAccessor(model, bin, uv, 2, false, TINYGLTF_TARGET_ARRAY_BUFFER);
      for (std::size_t i = textures.size(); i < m.textures.size(); ++i) {
        const std::string name = m.textures[i]->name.empty() ? c.name + "_texture_" + std::to_string(i) : m.textures[i]->name;
        textures.push_back(appendGltfTexture(model, bin, *m.textures[i], prefix + name));
      }
    }
    tinygltf::Accessor a;
    a.bufferView = appendBytes(model, bin, jts.data(), jts.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    a.count = nv;
    a.type = TINYGLTF_TYPE_VEC4;
    model.accessors.push_back(a);
    proto.attributes["JOINTS_0"] = static_cast<int>(model.accessors.size()) - 1;
    if (tack_attribute) {
      std::vector<float> parts(nv);
      for (std::size_t i = 0; i < nv; ++i) parts[i] = float(m.tackPart(vertex(i)));
      proto.attributes["_TACK_PART"] = appendFloatAccessor(model, bin, parts, 1, false, TINYGLTF_TARGET_ARRAY_BUFFER);
    }
    return proto;
  }

  // The piece's mesh, named `name`, its k-th material `material_name(k)`; returns the mesh.
  int mesh(const GltfMeshPiece& piece, const tinygltf::Primitive& proto, const std::string& name,
           const std::function<std::string(std::size_t)>& material_name) {
    const SkinnedMesh& m = c.mesh;
    std::vector<std::uint32_t> index_of;  // the mesh's vertex -> the piece's (empty: the same)
    if (!piece.vertices.empty()) {
      index_of.assign(m.vertexCount(), 0);
      for (std::size_t i = 0; i < piece.vertices.size(); ++i) index_of[piece.vertices[i]] = std::uint32_t(i);
    }
    tinygltf::Mesh mesh;
    mesh.name = name;
    const std::size_t nt = piece.triangles.size();
    const auto colour = [&](std::size_t i) { return m.colors[m.indices[std::size_t(piece.triangles[i]) * 3]]; };
    const auto texture = [&](std::size_t i) { return m.triangleTexture(piece.triangles[i]); };
    std::map<std::tuple<float, float, float, int>, int> materials;
    for (std::size_t t = 0; t < nt;) {
      const glm::vec3 color = colour(t);
      std::size_t end = t + 1;
      while (end < nt && colour(end) == color && texture(end) == texture(t)) ++end;
      const auto key = std::make_tuple(color.x, color.y, color.z, texture(t));
      auto it = materials.find(key);
      if (it == materials.end()) {
        tinygltf::Material mat;
        mat.name = material_name(materials.size());
        mat.pbrMetallicRoughness.baseColorFactor = {color.x, color.y, color.z, 1.0};
        mat.pbrMetallicRoughness.metallicFactor = 0.0;
        mat.pbrMetallicRoughness.roughnessFactor = 0.7;
        if (texture(t) >= 0) mat.pbrMetallicRoughness.baseColorTexture.index = textures.at(static_cast<std::size_t>(texture(t)));
        model.materials.push_back(mat);
        it = materials.emplace(key, static_cast<int>(model.materials.size()) - 1).first;
      }
      std::vector<std::uint32_t> indices;
      indices.reserve((end - t) * 3);
      for (std::size_t i = t; i < end; ++i)
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t v = m.indices[std::size_t(piece.triangles[i]) * 3 + std::size_t(k)];
          indices.push_back(index_of.empty() ? v : index_of[v]);
        }
      tinygltf::Primitive prim = proto;
      prim.material = it->second;
      prim.indices = appendIndexAccessor(model, bin, indices);
      mesh.primitives.push_back(prim);
      t = end;
    }
    model.meshes.push_back(mesh);
    return static_cast<int>(model.meshes.size()) - 1;
  }
};

}  // namespace

GltfCharacterNodes appendCharacterGltf(tinygltf::Model& model, std::vector<unsigned char>& bin,
                                       const Character& c, const std::string& prefix, bool split_tack) {
  const Skeleton& s = c.skeleton;
  const SkinnedMesh& m = c.mesh;
  GltfCharacterNodes out;
  const std::vector<std::string> names = jointNodeNames(c);
  const int first = static_cast<int>(model.nodes.size());
  for (std::size_t j = 0; j < s.size(); ++j) {
    tinygltf::Node n;
    // Joints keep their skeleton's own names, whatever the scene called the character (docs/round-trip.md,
    // "Names"): each character is an armature of its own, and a script finds a bone by one name.
    n.name = names[j];
    const glm::mat4& l = s.joints[j].rest_local;
    const glm::vec3 t(l[3]);
    const glm::quat q = glm::normalize(glm::quat_cast(glm::mat3(l)));
    if (t != glm::vec3(0.0f)) n.translation = {t.x, t.y, t.z};
    if (q != glm::quat(1.0f, 0.0f, 0.0f, 0.0f)) n.rotation = {q.x, q.y, q.z, q.w};
    model.nodes.push_back(n);
    out.joint_nodes.push_back(first + static_cast<int>(j));
  }
  for (std::size_t j = 0; j < s.size(); ++j)
    if (s.joints[j].parent >= 0) model.nodes[first + s.joints[j].parent].children.push_back(first + static_cast<int>(j));

  // The body's mesh (and with `split_tack` one mesh a part of the tack, rig/io/gltf_tack.h).
  const std::vector<GltfMeshPiece> pieces = gltfMeshPieces(m, split_tack);
  MeshPieceWriter writer{model, bin, c, prefix, {}};
  const tinygltf::Primitive body = writer.attributes(pieces[0], !split_tack && m.hasTack());
  const int body_mesh = writer.mesh(pieces[0], body, prefix + c.name, [&](std::size_t k) { return prefix + c.name + "_" + std::to_string(k); });

  tinygltf::Skin skin;
  skin.name = prefix + c.name;
  skin.joints = out.joint_nodes;
  std::vector<float> ibm;
  for (std::size_t j = 0; j < s.size(); ++j) {
    const glm::mat4 bind = s.skinBind(static_cast<int>(j));
    ibm.insert(ibm.end(), glm::value_ptr(bind), glm::value_ptr(bind) + 16);
  }
  skin.inverseBindMatrices = appendFloatAccessor(model, bin, ibm, 16, false);
  tinygltf::Value::Object roles, role_joints;
  for (const auto& [role, j] : c.roles) {
    roles[role] = tinygltf::Value(j);
    role_joints[role] = tinygltf::Value(names[std::size_t(j)]);
  }
  tinygltf::Value::Object extras;
  extras["stirrup_roles"] = tinygltf::Value(roles);
  extras["stirrup_role_joints"] = tinygltf::Value(role_joints);
  extras["stirrup_character"] = tinygltf::Value(c.name);
  for (std::size_t j = 0; j < s.size(); ++j)
    if (s.joints[j].parent < 0) {
      skin.skeleton = first + static_cast<int>(j);
      break;
    }
  model.skins.push_back(skin);
  out.skin = static_cast<int>(model.skins.size()) - 1;

  tinygltf::Node mesh_node;
  mesh_node.name = prefix + c.name + "_mesh";
  mesh_node.mesh = body_mesh;
  mesh_node.skin = out.skin;
  mesh_node.extras = tinygltf::Value(extras);  // (tinygltf 2.7 does not write a skin's extras)
  model.nodes.push_back(mesh_node);
  out.mesh_node = static_cast<int>(model.nodes.size()) - 1;
  for (std::size_t k = 1; k < pieces.size(); ++k) {
    const std::string part(tackPartName(pieces[k].part));
    tinygltf::Node node;
    node.name = part;
    node.mesh = writer.mesh(pieces[k], writer.attributes(pieces[k], false), part, [&](std::size_t n) {
      char suffix[16];
      std::snprintf(suffix, sizeof suffix, ".%03zu", n);
      return n == 0 ? part : part + suffix;  // as Blender numbers a name's copies
    });
    node.skin = out.skin;
    node.extras = tackNodeExtras(pieces[k].part, c.name, c.source.file);
    model.nodes.push_back(node);
    out.tack_nodes.push_back(static_cast<int>(model.nodes.size()) - 1);
  }
  return out;
}

std::vector<unsigned char> characterGlb(const Character& c) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "stirrup character make";
  std::vector<unsigned char> bin;
  const GltfCharacterNodes nodes = appendCharacterGltf(model, bin, c);
  const int cm = addCentimetreRoot(model);
  for (std::size_t j = 0; j < c.skeleton.size(); ++j)
    if (c.skeleton.joints[j].parent < 0) model.nodes[cm].children.push_back(nodes.joint_nodes[j]);
  tinygltf::Scene scene;
  scene.name = c.name;
  scene.nodes = {cm, nodes.mesh_node};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  return glbBytes(model, std::move(bin));
}

void writeCharacterGlb(const Character& c, const std::filesystem::path& file) { writeFileAtomically(file, characterGlb(c)); }

std::optional<std::map<std::string, int>> gltfRoleTable(const tinygltf::Model& model, const std::string& f, int skin, CharacterKind kind,
                                                        bool* by_joint_name, bool names_alone) {
  const tinygltf::Value* by_index = nullptr;
  const tinygltf::Value* by_name = nullptr;
  // A table by joint names alone is another tool's (the Blender add-on writes its mappings' so).
  for (const tinygltf::Node& n : model.nodes)
    if (n.skin == skin && n.extras.IsObject() && (n.extras.Has("stirrup_roles") || (names_alone && n.extras.Has("stirrup_role_joints")))) {
      by_index = n.extras.Has("stirrup_roles") ? &n.extras.Get("stirrup_roles") : nullptr;
      by_name = n.extras.Has("stirrup_role_joints") ? &n.extras.Get("stirrup_role_joints") : nullptr;
    }
  if (!by_index && !by_name) return std::nullopt;
  if (by_index && !by_index->IsObject())
    throw InputError(f + ": the file's role table (extras.stirrup_roles) is not an object (expected role -> joint index)");
  if (!by_index && !by_name->IsObject())
    throw InputError(f + ": the file's role table (extras.stirrup_role_joints) is not an object (expected role -> joint name)");
  const std::vector<std::string> names = gltfJointNames(model, skin);
  const int nj = static_cast<int>(names.size());
  const std::string kind_name(characterKindName(kind));
  // By the joint's name where the table gives it: a tool that keeps extras may list the skin's joints in
  // another order (Blender's exporter lists them depth first), which leaves the indices pointing at others.
  const bool named = by_name && by_name->IsObject();
  if (by_joint_name) *by_joint_name = named;
  const auto jointOf = [&](const std::string& role) -> std::optional<int> {
    if (named) {
      if (!by_name->Has(role)) return std::nullopt;
      const tinygltf::Value& v = by_name->Get(role);
      const auto it = v.IsString() ? std::find(names.begin(), names.end(), v.Get<std::string>()) : names.end();
      if (it == names.end())
        throw InputError(f + ": role " + role + ": the file's role table (extras.stirrup_role_joints) names no joint of skins[" +
                         std::to_string(skin) + "] (expected one of its joints' names)");
      return static_cast<int>(it - names.begin());
    }
    if (!by_index->Has(role)) return std::nullopt;
    const tinygltf::Value& v = by_index->Get(role);
    if (!v.IsInt() || v.Get<int>() < 0 || v.Get<int>() >= nj)
      throw InputError(f + ": role " + role + ": expected a joint index 0.." + std::to_string(nj - 1) + " in the file's role table");
    return v.Get<int>();
  };
  std::map<std::string, int> roles;
  for (const std::string& role : requiredRoles(kind)) {
    const std::optional<int> j = jointOf(role);
    if (!j) throw InputError(f + ": role " + role + ": missing from the file's role table (expected a joint of the " + kind_name + ")");
    roles[role] = *j;
  }
  for (const std::string& role : optionalRoles(kind))
    if (const std::optional<int> j = jointOf(role)) roles[role] = *j;
  return roles;
}

namespace {

// Which joints play the character's roles: role -> index into the skin's joints, and what told.
struct SkinRoles {
  std::map<std::string, int> role_joint;
  std::string where;                     // the mapping file, or the glTF file, for messages
  std::string hint;                      // how to change a role that is off its chain
  std::optional<AutoMapping> automatic;  // the file mapped by itself
  const CharacterMapping* given = nullptr;
  const CharacterMapping* mapping() const { return automatic ? &automatic->mapping : given; }
};

// The roles from the mapping given, else the file's role table, else the mapping the file gets by
// itself (rig/mapping/auto_mapping.h). Each a one-line InputError naming the file and the role.
SkinRoles findSkinRoles(const tinygltf::Model& model, const std::string& f, int skin, CharacterKind kind,
                        const CharacterMapping* mapping, const std::vector<std::string>& joint_names) {
  const std::string kind_name(characterKindName(kind));
  const int nj = static_cast<int>(joint_names.size());
  SkinRoles out;
  out.where = f;
  out.given = mapping;
  std::optional<std::map<std::string, int>> table;
  if (!mapping) table = gltfRoleTable(model, f, skin, kind);
  if (!mapping && !table) {
    // No mapping file and no role table: the file is mapped by itself.
    out.automatic = autoMapCharacter(mappingSkeletonFromGltf(model, f, skin), kind);
    mapping = &out.automatic->mapping;
  }
  out.hint = out.automatic ? "the automatic mapping chose it: map it in a mapping file, stirrup character map " + f + " --as " +
                                 kind_name + " -o MAP.json"
                           : "change it in the mapping file";
  if (!mapping) {
    out.role_joint = *table;
    return out;
  }
  out.where = mapping->file.empty() ? f : mapping->file.string();
  const auto mapRole = [&](const std::string& role, const std::string& joint_name) {
    int found = -1;
    for (int j = 0; j < nj; ++j)
      if (joint_names[j] == joint_name) found = j;
    if (found < 0)
      throw InputError(out.where + ": roles." + role + ": no joint named \"" + joint_name + "\" in " + f + " (change it to one of the file's joints: " +
                       "stirrup character map " + f + " --as " + kind_name + " lists them with the roles they seem to play)");
    out.role_joint[role] = found;
  };
  for (const std::string& role : requiredRoles(kind)) {
    const auto it = mapping->roles.find(role);
    if (it == mapping->roles.end()) {
      if (out.automatic) {
        std::string missing;
        for (const std::string& r : out.automatic->report.not_mapped) missing += (missing.empty() ? "" : ", ") + r;
        throw InputError(f + ": roles." + role + ": not found by the automatic mapping (by " + out.automatic->report.method +
                         "; not mapped: " + missing + "; map them in a mapping file: stirrup character map " + f + " --as " +
                         kind_name + " -o MAP.json, then add them)");
      }
      throw InputError(out.where + ": roles." + role + ": missing (expected the name of the " + kind_name + "'s " + role + " joint in " + f + ")");
    }
    mapRole(role, it->second);
  }
  for (const std::string& role : optionalRoles(kind))
    if (const auto it = mapping->roles.find(role); it != mapping->roles.end()) mapRole(role, it->second);
  return out;
}

// A primitive's vertex attributes as read, checked for one of each a vertex.
struct PrimitiveVertices {
  std::vector<float> pos, nor, jts, wts;  // nor: zeros where the file has no normals
  std::vector<float> col;                 // `_COLOR`, or COLOR_0 times the base colour; empty: `base`
  glm::vec3 base{0.8f};                   // the material's base colour factor
  std::size_t n = 0;                      // vertices
};

PrimitiveVertices readPrimitiveVertices(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                        const tinygltf::Material* material, const std::string& pw) {
  if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != -1) throw InputError(pw + ": expected triangles");
  for (const char* a : {"POSITION", "JOINTS_0", "WEIGHTS_0"})
    if (!prim.attributes.count(a)) throw InputError(pw + ": expected a " + std::string(a) + " attribute");
  PrimitiveVertices out;
  out.pos = readAccessor(model, prim.attributes.at("POSITION"), 3, pw + ".POSITION");
  out.nor = prim.attributes.count("NORMAL") ? readAccessor(model, prim.attributes.at("NORMAL"), 3, pw + ".NORMAL")
                                            : std::vector<float>(out.pos.size(), 0.0f);
  out.jts = readAccessor(model, prim.attributes.at("JOINTS_0"), 4, pw + ".JOINTS_0");
  out.wts = readAccessor(model, prim.attributes.at("WEIGHTS_0"), 4, pw + ".WEIGHTS_0");
  const std::size_t n = out.n = out.pos.size() / 3;
  if (out.nor.size() != n * 3 || out.jts.size() != n * 4 || out.wts.size() != n * 4) throw InputError(pw + ": attribute counts differ");
  if (material) {
    const auto& bc = material->pbrMetallicRoughness.baseColorFactor;
    if (bc.size() >= 3) out.base = glm::vec3(float(bc[0]), float(bc[1]), float(bc[2]));
  }
  if (prim.attributes.count("_COLOR")) {
    out.col = readAccessor(model, prim.attributes.at("_COLOR"), 3, pw + "._COLOR");
    // A fuzzing finding: fewer colours than vertices read past the end.
    if (out.col.size() != n * 3) throw InputError(pw + "._COLOR: expected one colour a vertex");
  } else if (prim.attributes.count("COLOR_0")) {
    const int ca = prim.attributes.at("COLOR_0");
    const int comps = tinygltf::GetNumComponentsInType(gltfElement(model.accessors, ca, pw + ".COLOR_0", "accessor").type);
    if (comps != 3 && comps != 4) throw InputError(pw + ".COLOR_0: expected a VEC3 or VEC4 accessor");
    const std::vector<float> c0 = readAccessor(model, ca, comps, pw + ".COLOR_0");
    if (c0.size() != n * static_cast<std::size_t>(comps)) throw InputError(pw + ".COLOR_0: expected one colour a vertex");
    out.col.resize(n * 3);
    for (std::size_t v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k) out.col[v * 3 + k] = c0[v * comps + k] * out.base[k];
  }
  return out;
}

// Primitives that share their attributes (as written here) share their vertices, when their colours
// come from the same place (`_COLOR`, or the same material's base colour) and their texture
// coordinates too: a block of vertices read without texture coordinates takes the first textured
// primitive's; one read through another set or transform is not shared.
struct VertexBlock {
  std::uint32_t first = 0;
  std::optional<GltfTextureRef> uvs;  // how its texture coordinates were read, if they were
};
using VertexBlocks = std::map<std::pair<std::map<std::string, int>, std::vector<float>>, std::vector<VertexBlock>>;

// A primitive's base colour texture: the texture coordinates it reads (one pair a vertex) and the
// texture's index in m.textures (read once a file texture), or -1 without one.
struct PrimitiveTexture {
  GltfTextureRef ref;
  std::vector<float> uv;
  std::int32_t texture = -1;
};

PrimitiveTexture readPrimitiveTexture(const tinygltf::Model& model, const GltfImageBytes& images, const tinygltf::Primitive& prim,
                                      const tinygltf::Material* material, const std::string& f, const std::string& pw, std::size_t n,
                                      std::map<int, int>& texture_of, SkinnedMesh& m) {
  std::string material_name;  // "materials[3] \"fur\"", for errors
  if (material) {
    const std::string& name = material->name;
    material_name = "materials[" + std::to_string(prim.material) + "]" + (name.empty() ? "" : " \"" + name + "\"");
  }
  const std::string mw = f + ": " + material_name;
  PrimitiveTexture out;
  out.ref = baseColorTextureOf(model, prim.material, mw);
  if (out.ref.texture < 0) return out;
  const std::string set = "TEXCOORD_" + std::to_string(out.ref.tex_coord);
  if (!prim.attributes.count(set))
    throw InputError(pw + ": expected a " + set + " attribute (the base colour texture of " + material_name + " reads it)");
  out.uv = readAccessor(model, prim.attributes.at(set), 2, pw + "." + set);
  if (out.uv.size() != n * 2) throw InputError(pw + "." + set + ": expected one texture coordinate a vertex");
  auto [it, added] = texture_of.emplace(out.ref.texture, static_cast<int>(m.textures.size()));
  if (added) m.textures.push_back(readGltfTexture(model, images, out.ref.texture, mw + ".baseColorTexture"));
  out.texture = it->second;
  return out;
}

// How a primitive's vertices go into the rig: to rig space (`toRig`, normals by `rot`), bound to the
// rig's joints (`new_index`: the skin's joint -> the skeleton's).
struct VertexTransfer {
  const std::vector<int>& new_index;
  const std::function<glm::vec3(glm::vec3)>& toRig;
  const glm::mat3& rot;
  int skin = 0;
};

// Appends a primitive's vertices to `m`, each with its tack part and its own-saddle flag.
void appendPrimitiveVertices(const PrimitiveVertices& p, const VertexTransfer& to, const std::vector<TackPart>& parts, bool saddle,
                             const std::string& pw, SkinnedMesh& m, std::vector<char>& own_saddle) {
  const int nj = static_cast<int>(to.new_index.size());
  const std::size_t first_new = m.positions.size();
  own_saddle.resize(m.positions.size() + p.n, saddle ? 1 : 0);
  for (std::size_t v = 0; v < p.n; ++v) {
    m.positions.push_back(to.toRig({p.pos[v * 3], p.pos[v * 3 + 1], p.pos[v * 3 + 2]}));
    glm::vec3 nn = to.rot * glm::vec3(p.nor[v * 3], p.nor[v * 3 + 1], p.nor[v * 3 + 2]);
    if (std::abs(glm::length(nn) - 1.0f) > 1e-3f) nn = glm::length(nn) > 0.0f ? glm::normalize(nn) : glm::vec3(0.0f);
    m.normals.push_back(nn);  // zero: computed from the faces (fillMissingNormals)
    m.colors.push_back(p.col.empty() ? p.base : glm::vec3(p.col[v * 3], p.col[v * 3 + 1], p.col[v * 3 + 2]));
    glm::u16vec4 jv(0);
    glm::vec4 wv(0.0f);
    for (int k = 0; k < 4; ++k) {
      const float j = p.jts[v * 4 + k];  // a float as read: cast only once it is known to be an index
      wv[k] = p.wts[v * 4 + k];
      if (wv[k] > 0.0f) {
        if (!(j >= 0.0f && j < float(nj)))  // a fuzzing finding: 2.8e29 cast to int first
          throw InputError(pw + ".JOINTS_0: joint index " + jointIndexText(j) + " outside skins[" + std::to_string(to.skin) + "]");
        jv[k] = static_cast<std::uint16_t>(to.new_index[static_cast<std::size_t>(j)]);
      }
    }
    const float sum = wv.x + wv.y + wv.z + wv.w;
    if (!(sum > 0.0f)) throw InputError(pw + ".WEIGHTS_0: vertex " + std::to_string(v) + " has no weight");
    m.joints.push_back(jv);
    m.weights.push_back(std::abs(sum - 1.0f) > 1e-4f ? wv / sum : wv);
  }
  if (!m.tack_parts.empty() || std::any_of(parts.begin(), parts.end(), [](TackPart part) { return part != TackPart::None; })) {
    m.tack_parts.resize(first_new, TackPart::None);
    m.tack_parts.insert(m.tack_parts.end(), parts.begin(), parts.end());
  }
}

// Appends a primitive's triangles (its indices, else its vertices in order) on the vertices from
// `first_vertex`, and their texture.
void appendPrimitiveTriangles(const tinygltf::Model& model, const tinygltf::Primitive& prim, std::size_t n, std::uint32_t first_vertex,
                              std::int32_t texture, const std::string& pw, SkinnedMesh& m) {
  const std::size_t first_index = m.indices.size();
  if (prim.indices >= 0) {
    for (std::uint32_t i : readIndices(model, prim.indices, pw + ".indices")) {
      if (i >= n) throw InputError(pw + ".indices: index " + std::to_string(i) + " outside the vertices");
      m.indices.push_back(first_vertex + i);
    }
  } else {
    for (std::uint32_t i = 0; i < n; ++i) m.indices.push_back(first_vertex + i);
  }
  if ((m.indices.size() - first_index) % 3 != 0) throw InputError(pw + ": expected a whole number of triangles (indices a multiple of 3)");
  if (texture >= 0 && m.triangle_textures.empty()) m.triangle_textures.assign(first_index / 3, -1);
  if (!m.textures.empty()) m.triangle_textures.resize(m.indices.size() / 3, texture);
}

// A horse modelled with its own saddle: the vertices of primitives whose node, mesh or material is
// called a saddle (rig/characters/horse_tack.h seats the rider on it instead of adding one).
bool saddleNamed(std::string name) {
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return name.find("saddle") != std::string::npos;
}

// The mesh: every primitive of every node skinned by the skin, its vertices taken to the rig
// (VertexTransfer). `own_saddle` gets a flag a vertex: a horse's own saddle (saddleNamed).
void readSkinMesh(const tinygltf::Model& model, const GltfImageBytes& images, const std::string& f, CharacterKind kind,
                  const VertexTransfer& to, SkinnedMesh& m, std::vector<char>& own_saddle) {
  VertexBlocks blocks;
  std::map<int, int> texture_of;  // the file's texture -> index into m.textures
  for (std::size_t ni = 0; ni < model.nodes.size(); ++ni) {
    const tinygltf::Node& node = model.nodes[ni];
    if (node.mesh < 0 || node.skin != to.skin) continue;
    const tinygltf::Mesh& mesh = gltfElement(model.meshes, node.mesh, f + ": nodes[" + std::to_string(ni) + "].mesh", "mesh");
    // A part of a horse's tack written a node a part (rig/io/gltf_tack.h).
    const TackPart node_part = kind == CharacterKind::Horse ? gltfNodeTackPart(model, node, f + ": nodes[" + std::to_string(ni) + "]") : TackPart::None;
    for (std::size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      const tinygltf::Primitive& prim = mesh.primitives[pi];
      const std::string pw = f + ": meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(pi) + "]";
      const tinygltf::Material* material =
          prim.material >= 0 ? &gltfElement(model.materials, prim.material, pw + ".material", "material") : nullptr;
      const PrimitiveVertices p = readPrimitiveVertices(model, prim, material, pw);
      const std::size_t n = p.n;
      const PrimitiveTexture tex = readPrimitiveTexture(model, images, prim, material, f, pw, n, texture_of, m);
      // Vertices already taken from an earlier primitive with the same attributes are reused.
      std::vector<float> colour_source;  // empty: the colours are `_COLOR`'s, the material's otherwise
      if (!prim.attributes.count("_COLOR")) colour_source = {p.base.x, p.base.y, p.base.z};
      std::vector<VertexBlock>& candidates = blocks[{prim.attributes, colour_source}];
      VertexBlock* block = nullptr;
      for (VertexBlock& b : candidates)
        if (tex.texture < 0 || !b.uvs || b.uvs->sameCoordinates(tex.ref)) {
          block = &b;
          break;
        }
      const bool fresh = block == nullptr;
      if (fresh) block = &candidates.emplace_back(VertexBlock{static_cast<std::uint32_t>(m.positions.size()), std::nullopt});
      const std::uint32_t first_vertex = block->first;
      if (tex.texture >= 0 && !block->uvs) {
        block->uvs = tex.ref;
        m.uvs.resize(m.positions.size() + (fresh ? n : 0), glm::vec2(0.0f));
        for (std::size_t v = 0; v < n; ++v) m.uvs[first_vertex + v] = tex.ref.transform({tex.uv[v * 2], tex.uv[v * 2 + 1]});
      }
      if (fresh) {
        // The tack's parts: each vertex's "_TACK_PART", else the node's part (stirrup's own tack, never the horse's own saddle).
        const std::vector<TackPart> parts = kind == CharacterKind::Horse && prim.attributes.count("_TACK_PART")
                                                ? tackPartsOf(readAccessor(model, prim.attributes.at("_TACK_PART"), 1, pw + "._TACK_PART"), n, pw)
                                                : std::vector<TackPart>(n, node_part);
        const bool saddle = kind == CharacterKind::Horse && node_part == TackPart::None && !prim.attributes.count("_TACK_PART") &&
                            (saddleNamed(node.name) || saddleNamed(mesh.name) || (material && saddleNamed(material->name)));
        appendPrimitiveVertices(p, to, parts, saddle, pw, m, own_saddle);
      }
      appendPrimitiveTriangles(model, prim, n, first_vertex, tex.texture, pw, m);
    }
  }
  if (m.indices.empty()) throw InputError(f + ": no triangles skinned by skins[" + std::to_string(to.skin) + "]");
}

// Each joint's parent joint: the nearest ancestor node that is a joint, then a Rigify rig's deform
// bones as Rigify means them (rigifyDeformParents). -1 for a root.
std::vector<int> skinJointParents(const tinygltf::Model& model, const std::string& f, const tinygltf::Skin& skin,
                                  const std::vector<std::string>& joint_names) {
  const int nj = static_cast<int>(skin.joints.size());
  const std::vector<int> node_parent = gltfNodeParents(model, f);
  std::map<int, int> node_joint;
  for (int j = 0; j < nj; ++j) node_joint[skin.joints[j]] = j;
  std::vector<int> parent(nj, -1);
  for (int j = 0; j < nj; ++j)
    for (int n = node_parent.at(skin.joints[j]); n >= 0; n = node_parent[n])
      if (node_joint.count(n)) {
        parent[j] = node_joint[n];
        break;
      }
  rigifyDeformParents(parent, joint_names);
  return parent;
}

// The joints parents first: as they are when the file lists them so (as written here), else sorted by
// depth, stable.
std::vector<int> parentsFirstOrder(const std::vector<int>& parent) {
  const int nj = static_cast<int>(parent.size());
  std::vector<int> depth(nj, 0), order(nj);
  for (int j = 0; j < nj; ++j)
    for (int p = parent[j]; p >= 0; p = parent[p]) ++depth[j];
  for (int j = 0; j < nj; ++j) order[j] = j;
  bool parents_first = true;
  for (int j = 0; j < nj; ++j) parents_first = parents_first && parent[j] < j;
  if (!parents_first) std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return depth[a] < depth[b]; });
  return order;
}

// Smooth normals (area-weighted face normals) where the file has none (zero normals).
void fillMissingNormals(SkinnedMesh& m) {
  std::vector<glm::vec3> acc(m.positions.size(), glm::vec3(0.0f));
  bool missing = false;
  for (const glm::vec3& n : m.normals) missing = missing || n == glm::vec3(0.0f);
  if (!missing) return;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const std::uint32_t a = m.indices[t], b = m.indices[t + 1], c2 = m.indices[t + 2];
    const glm::vec3 fn = glm::cross(m.positions[b] - m.positions[a], m.positions[c2] - m.positions[a]);
    acc[a] += fn;
    acc[b] += fn;
    acc[c2] += fn;
  }
  for (std::size_t v = 0; v < m.normals.size(); ++v)
    if (m.normals[v] == glm::vec3(0.0f))
      m.normals[v] = glm::length(acc[v]) > 0.0f ? glm::normalize(acc[v]) : glm::vec3(0.0f, 1.0f, 0.0f);
}

Character loadSkinUnchecked(const GltfSkinSource& source, CharacterKind kind, const CharacterMapping* given, AutoMapping* auto_mapped,
                            HorseTackReport* tack) {
  const tinygltf::Model& model = *source.model;
  const std::string& f = source.file;
  const int skin_index = source.skin;
  const std::string kind_name(characterKindName(kind));
  const tinygltf::Skin& skin = checkedSkin(model, f, kind_name, skin_index);
  const int nj = static_cast<int>(skin.joints.size());

  // The joints' names as the character will carry them (unnamed joints: "jointN").
  const std::vector<std::string> joint_names = gltfJointNames(model, skin_index);
  const SkinRoles roles = findSkinRoles(model, f, skin_index, kind, given, joint_names);
  const std::map<std::string, int>& role_joint = roles.role_joint;
  const CharacterMapping* mapping = roles.mapping();
  const std::string& where = roles.where;

  // Axes: file -> stirrup (cm, +X forward, +Y up, +Z right).
  glm::mat4 convert(1.0f);
  glm::vec3 offset(0.0f);
  if (mapping) {
    convert = glm::mat4(mappingToRig(*mapping));
    offset = glm::vec3(convert[3]);
    convert[3] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  }
  const auto toRig = [&](glm::vec3 p) { return glm::vec3(convert * glm::vec4(p, 1.0f)) + offset; };

  // Joint bind positions from the inverse bind matrices (identity when absent).
  const std::vector<glm::mat4> ibm = gltfInverseBinds(model, f, skin_index);
  std::vector<int> parent = skinJointParents(model, f, skin, joint_names);  // hung loose roots get parents below
  // Joint bind positions from the inverse bind matrices (identity when absent), in the file's space.
  std::vector<glm::vec3> file_bind(nj);
  for (int j = 0; j < nj; ++j) file_bind[j] = glm::vec3(glm::inverse(ibm[j])[3]);
  // A horse's legs hang from their pivots where the file lost what held them; a skin of several roots
  // is then one body (Skeleton's hangLooseRoots).
  std::vector<char> root_in_file(nj, 0);
  for (int j = 0; j < nj; ++j) root_in_file[j] = parent[j] < 0;
  const std::vector<int> on_pivots = kind == CharacterKind::Horse ? hangLegsFromPivots(role_joint, parent, root_in_file) : std::vector<int>{};
  const auto core = role_joint.find(kind == CharacterKind::Rider ? "pelvis" : "root");
  std::vector<char> file_root = hangLooseRoots(parent, file_bind, core == role_joint.end() ? -1 : core->second);
  for (int j : on_pivots) file_root[j] = 1;
  // A mapping's roles on their chains (an elbow below its shoulder, ...), in the hierarchy the rig will
  // pose. (A role table is stirrup's own writing, taken as it is.)
  if (mapping)
    if (const std::string problem = roleChainProblem(kind, role_joint, parent, joint_names, roles.hint); !problem.empty())
      throw InputError(where + ": " + problem);
  const std::vector<int> order = parentsFirstOrder(parent);
  std::vector<int> new_index(nj);
  for (int i = 0; i < nj; ++i) new_index[order[i]] = i;

  Character c;
  c.name = kind_name;
  std::vector<glm::vec3> bind_pos(nj);
  for (int j = 0; j < nj; ++j) bind_pos[j] = toRig(glm::vec3(glm::inverse(ibm[j])[3]));
  for (int i = 0; i < nj; ++i) {
    const int j = order[i];
    const std::string& name = joint_names[j];
    const int p = parent[j] < 0 ? -1 : new_index[parent[j]];
    const glm::vec3 pp = p < 0 ? glm::vec3(0.0f) : bind_pos[parent[j]];
    c.skeleton.addJoint(name, p, glm::translate(glm::mat4(1.0f), bind_pos[j] - pp));
    c.skeleton.joints.back().file_root = file_root[j] != 0;
  }
  for (const auto& [role, j] : role_joint) c.roles[role] = new_index[j];

  SkinnedMesh& m = c.mesh;
  const glm::mat3 rot = glm::mat3(convert) / static_cast<float>(mapping ? mapping->scale_cm : 1.0);
  std::vector<char> own_saddle;
  readSkinMesh(model, *source.images, f, kind, VertexTransfer{new_index, toRig, rot, skin_index}, m, own_saddle);
  if (roles.automatic && auto_mapped) *auto_mapped = *roles.automatic;
  c.source.file = f;
  if (mapping) c.source.to_rig = mappingToRig(*mapping);
  if (!m.textures.empty()) m.uvs.resize(m.positions.size(), glm::vec2(0.0f));
  fillMissingNormals(m);
  // A horse that names no tack gets the rig's (rig/characters/horse_tack.h), on its own saddle if it has one.
  if (kind == CharacterKind::Horse) {
    const HorseTackReport report = addHorseTack(c, where, HorseTackParams{}, &own_saddle);
    if (tack) *tack = report;
  }
  return c;
}

}  // namespace

Character loadCharacterGltf(const GltfSkinSource& source, CharacterKind kind, const CharacterMapping* mapping, AutoMapping* auto_mapped,
                            HorseTackReport* tack) {
  try {
    return loadSkinUnchecked(source, kind, mapping, auto_mapped, tack);
  } catch (const std::out_of_range&) {
    // An index the checks above do not cover (a mesh, material or accessor index past its array): the
    // .at() lookups throw, and the user gets one line naming the file (found by fuzzing).
    throw InputError(source.file + ": not a valid glTF file (an index points past the end of its array)");
  }
}

Character loadCharacterGltf(const std::filesystem::path& file, CharacterKind kind, const CharacterMapping* mapping,
                            AutoMapping* auto_mapped, HorseTackReport* tack) {
  const std::string f = file.string();
  if (!std::filesystem::exists(file))
    throw InputError(f + ": no such file (expected a skinned glTF " + std::string(characterKindName(kind)) + ")");
  GltfImageBytes images;
  const tinygltf::Model model = readGltfFile(file, f, &images);
  return loadCharacterGltf(GltfSkinSource{&model, &images, f, 0}, kind, mapping, auto_mapped, tack);
}

Character resolveCharacter(CharacterKind kind, const std::string& file, const std::string& mapping_file) {
  if (file == "default") return kind == CharacterKind::Horse ? buildDefaultHorse() : buildDefaultRider();
  if (mapping_file.empty()) {
    AutoMapping automatic;
    Character c = loadCharacterGltf(file, kind, nullptr, &automatic);
    if (!automatic.report.method.empty()) {
      // Mapped by itself: said once per file and kind (a command may resolve a character twice).
      static std::mutex mutex;
      static std::set<std::pair<std::string, CharacterKind>> told;
      const std::lock_guard<std::mutex> lock(mutex);
      if (told.insert({file, kind}).second) std::fputs(autoMappingSummary(automatic).c_str(), stderr);
    }
    return c;
  }
  const CharacterMapping mapping = loadCharacterMapping(mapping_file, kind);
  return loadCharacterGltf(file, kind, &mapping);
}

}  // namespace stirrup::rig
