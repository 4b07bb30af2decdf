// glTF 2.0 writing, the one home of every writer's plumbing: the binary buffer and its views, float,
// index and integer accessors, linear animation channels, the centimetre root, and a model's file bytes
// (.glb, or .gltf text with the buffer embedded). Reading has its home beside it (rig/io/gltf_accessors.h).
//
// A model is written as tinygltf::Model plus one byte vector `bin` that becomes buffer 0: every append
// adds a 4-byte-aligned buffer view of buffer 0 (glTF 2.0, 3.6.2.4: accessor offsets aligned to their
// component size), so the writers need not track offsets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
struct Animation;
}  // namespace tinygltf

namespace stirrup::rig {

// Appends `size` bytes to `bin` (4-byte aligned) as a new buffer view of buffer 0 with `target` (0 for
// none); returns the view's index.
int appendBytes(tinygltf::Model& model, std::vector<unsigned char>& bin, const void* data, std::size_t size, int target);

// Appends float data (`components` per element: 1, 2, 3, 4 or 16) as a tightly packed buffer view and
// an accessor, with each component's min and max when `minmax` (glTF requires them on POSITION and on
// animation inputs); returns the accessor.
int appendFloatAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const std::vector<float>& values,
                        int components, bool minmax, int target = 0);

// Appends 32-bit indices as a SCALAR element-array accessor; returns its index.
int appendIndexAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const std::vector<std::uint32_t>& indices);

// Appends integers of a narrower type (`component_type`, e.g. TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE for
// JOINTS_0) as an accessor of `type` with `components` per element; returns its index.
int appendIntegerAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const void* data, std::size_t count,
                          std::size_t bytes_per_value, int component_type, int type, int components, int target);
template <class T>
int appendIntegerAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const std::vector<T>& values,
                          int component_type, int type, int components, int target) {
  return appendIntegerAccessor(model, bin, values.data(), values.size(), sizeof(T), component_type, type, components, target);
}

// Appends to `anim` a LINEAR sampler from the accessor `input` (the key times) to `values` (3 floats a
// key for "translation" and "scale", 4 for "rotation"), and the channel driving `path` of `node`.
void appendLinearChannel(tinygltf::Model& model, std::vector<unsigned char>& bin, tinygltf::Animation& anim, int input,
                         int node, const char* path, const std::vector<float>& values, int components);

// Adds a node `name` (scale 0.01): stirrup works in centimetres, glTF in metres, so joints hang
// under it. Returns the node.
int addCentimetreRoot(tinygltf::Model& model, const std::string& name = "stirrup_cm");

// Serialises a model whose binary data is `bin` as .glb bytes, extras exactly (rig/io/gltf_extras.h).
std::vector<unsigned char> glbBytes(tinygltf::Model& model, std::vector<unsigned char> bin);

// The same model as .gltf text (indented JSON), the buffer embedded as a base64 data URI.
std::vector<unsigned char> gltfTextBytes(tinygltf::Model& model, std::vector<unsigned char> bin);

}  // namespace stirrup::rig
