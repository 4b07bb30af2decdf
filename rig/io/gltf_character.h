// Characters as skinned glTF 2.0 (docs/characters.md). Offline jobs: writing a built character, and
// importing one (ours or a user's) into a rig::Character the posing jobs can drive.
//
// Writing (through rig/io/gltf_writer.h): under a node "stirrup_cm" scaling centimetres to glTF's metres, the joints as nodes (named by their role where they have one), one skinned mesh with
// smooth normals (a horse's tack parts in "_TACK_PART", rig/io/gltf_tack.h), triangles grouped into one primitive per base colour (one material each), at most
// four joints per vertex, inverse bind matrices; the exact per-vertex colour in `_COLOR` and the role
// table in the skinned mesh node's extras ("stirrup_roles": role -> index into skin.joints, and
// "stirrup_role_joints": role -> the joint's name, which survives a tool listing the joints in another
// order), so a file written here loads back without a mapping file. Bytes are reproducible: the same character gives the same
// file.
//
// Reading: one skin's joints (the first, unless told) and every mesh primitive bound to it. Joints are re-based to
// translation-only rest transforms at their bind positions (the posing jobs work in world terms),
// which leaves the bind-pose mesh unchanged.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rig/character.h"
#include "rig/mapping/character_mapping.h"

namespace tinygltf {
class Model;
}

namespace stirrup::rig {

// Where a character landed in a model being written.
struct GltfCharacterNodes {
  std::vector<int> joint_nodes;  // one node per skeleton joint, in skeleton order
  int mesh_node = -1;
  int skin = -1;
  std::vector<int> tack_nodes;  // split_tack: the tack's parts' mesh nodes (rig/io/gltf_tack.h), in kTackParts order
};

// Appends `character` to `model`: nodes, mesh, materials, skin. Binary data goes to `bin` (which
// becomes buffer 0 when the model is written); the caller adds the returned root nodes to a scene.
// `prefix` is prepended to the mesh's, skin's and materials' names (for two characters in one file), never
// to a joint's: joints keep their skeleton's own names (a file's, or a generated character's roles), each
// character being an armature of its own. A horse's tack (SkinnedMesh::tack_parts) goes, with
// `split_tack`, to a mesh node a part beside the body's (named by the part, not prefixed: the caller
// names them for a crowd's pair), else into the one mesh with its parts as the "_TACK_PART" attribute
// (rig/io/gltf_tack.h).
GltfCharacterNodes appendCharacterGltf(tinygltf::Model& model, std::vector<unsigned char>& bin,
                                       const Character& character, const std::string& prefix = "", bool split_tack = false);

// The .glb bytes of one character.
std::vector<unsigned char> characterGlb(const Character& character);
void writeCharacterGlb(const Character& character, const std::filesystem::path& file);

struct AutoMapping;
struct HorseTackReport;
struct GltfImageBytes;

// One skin of a glTF file already read (readGltfFile, its images kept): the character to load.
struct GltfSkinSource {
  const tinygltf::Model* model = nullptr;
  const GltfImageBytes* images = nullptr;
  std::string file;  // for messages
  int skin = 0;      // index into model.skins
};

// Loads a skinned glTF (.glb or .gltf) as a character of `kind`. With `mapping` null, the role table
// the file carries (written by writeCharacterGlb) is used, or, in a file without one, the mapping the
// file gets by itself (rig/mapping/auto_mapping.h), kept in `auto_mapped` when given. Errors are one-line
// InputErrors naming the file (and, for a role, the role and the joint, and what to change): a role
// missing, a joint not in the file, a mapped role off its chain (rig/mapping/character_mapping.h
// roleChainProblem). A horse that names no tack gets the rig's (rig/characters/horse_tack.h); one that
// names it in part, or whose mesh has no back or head for it, is an error too.
// `tack`, when given, receives what the rig did about a horse's tack (rig/characters/horse_tack.h).
Character loadCharacterGltf(const std::filesystem::path& file, CharacterKind kind,
                            const CharacterMapping* mapping = nullptr, AutoMapping* auto_mapped = nullptr,
                            HorseTackReport* tack = nullptr);

// The same, from skin `source.skin` of a file already read (a baked shot holds a skin a character).
Character loadCharacterGltf(const GltfSkinSource& source, CharacterKind kind, const CharacterMapping* mapping = nullptr,
                            AutoMapping* auto_mapped = nullptr, HorseTackReport* tack = nullptr);

// The role table stirrup writes on a skinned mesh node (extras.stirrup_roles, by the joints' names in
// extras.stirrup_role_joints where the file has them) for skin `skin`: role -> index into its joints,
// the required roles of `kind` and the optional ones it names; nullopt when the file has no table for
// the skin. A role missing or pointing at no joint is a one-line InputError naming `file` and the role.
// `by_joint_name`, when given, is set when the table named the joints (a file stirrup wrote before
// stirrup_role_joints, or one from a tool that dropped it, has indices only). With `names_alone` a table
// naming the joints only (extras.stirrup_role_joints without stirrup_roles: the Blender add-on's shot,
// its horse's tack joints among them) is read too; it says nothing of the file's units and axes, so only
// a reader that knows the file's world takes it (rig/io/gltf_shot.h).
std::optional<std::map<std::string, int>> gltfRoleTable(const tinygltf::Model& model, const std::string& file, int skin,
                                                        CharacterKind kind, bool* by_joint_name = nullptr, bool names_alone = false);

// What a scene's "characters" entry names: "default" (the built-in generator), or a glTF file with
// an optional mapping file (empty: the file's own role table, or the mapping it gets by itself, whose
// choices are summed up on stderr, once a file).
Character resolveCharacter(CharacterKind kind, const std::string& file, const std::string& mapping_file);

}  // namespace stirrup::rig
