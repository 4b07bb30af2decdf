#include "rig/io/gltf_writer.h"

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <tiny_gltf.h>

#include "rig/io/gltf_extras.h"

namespace stirrup::rig {
namespace {

int accessorType(int components) {
  switch (components) {
    case 1: return TINYGLTF_TYPE_SCALAR;
    case 2: return TINYGLTF_TYPE_VEC2;
    case 3: return TINYGLTF_TYPE_VEC3;
    case 4: return TINYGLTF_TYPE_VEC4;
    case 16: return TINYGLTF_TYPE_MAT4;
    default: throw std::invalid_argument("glTF: unsupported component count");
  }
}

int appendAccessor(tinygltf::Model& model, tinygltf::Accessor a) {
  model.accessors.push_back(std::move(a));
  return static_cast<int>(model.accessors.size()) - 1;
}

// `model` serialised by tinygltf with `bin` as buffer 0.
std::string serialised(tinygltf::Model& model, std::vector<unsigned char> bin, bool binary) {
  while (bin.size() % 4) bin.push_back(0);
  tinygltf::Buffer buffer;
  buffer.data = std::move(bin);
  model.buffers = {buffer};
  tinygltf::TinyGLTF gltf;
  std::ostringstream os;
  if (!gltf.WriteGltfSceneToStream(&model, os, !binary, binary)) throw std::runtime_error("glTF: cannot serialise the model");
  return os.str();
}

}  // namespace

int appendBytes(tinygltf::Model& model, std::vector<unsigned char>& bin, const void* data, std::size_t size,
                int target) {
  while (bin.size() % 4) bin.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin.size();
  view.byteLength = size;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  bin.insert(bin.end(), p, p + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

int appendFloatAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const std::vector<float>& values,
                        int components, bool minmax, int target) {
  tinygltf::Accessor a;
  a.bufferView = appendBytes(model, bin, values.data(), values.size() * sizeof(float), target);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = values.size() / components;
  a.type = accessorType(components);
  if (minmax) {
    a.minValues.assign(components, std::numeric_limits<double>::infinity());
    a.maxValues.assign(components, -std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < values.size(); ++i) {
      const int k = static_cast<int>(i % components);
      a.minValues[k] = std::min<double>(a.minValues[k], values[i]);
      a.maxValues[k] = std::max<double>(a.maxValues[k], values[i]);
    }
  }
  return appendAccessor(model, std::move(a));
}

int appendIndexAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const std::vector<std::uint32_t>& indices) {
  return appendIntegerAccessor(model, bin, indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, 1,
                               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
}

int appendIntegerAccessor(tinygltf::Model& model, std::vector<unsigned char>& bin, const void* data, std::size_t count,
                          std::size_t bytes_per_value, int component_type, int type, int components, int target) {
  tinygltf::Accessor a;
  a.bufferView = appendBytes(model, bin, data, count * bytes_per_value, target);
  a.componentType = component_type;
  a.count = count / components;
  a.type = type;
  return appendAccessor(model, std::move(a));
}

void appendLinearChannel(tinygltf::Model& model, std::vector<unsigned char>& bin, tinygltf::Animation& anim, int input,
                         int node, const char* path, const std::vector<float>& values, int components) {
  tinygltf::AnimationSampler s;
  s.input = input;
  s.output = appendFloatAccessor(model, bin, values, components, false);
  s.interpolation = "LINEAR";
  anim.samplers.push_back(s);
  tinygltf::AnimationChannel ch;
  ch.sampler = static_cast<int>(anim.samplers.size()) - 1;
  ch.target_node = node;
  ch.target_path = path;
  anim.channels.push_back(ch);
}

int addCentimetreRoot(tinygltf::Model& model, const std::string& name) {
  tinygltf::Node n;
  n.name = name;
  n.scale = {0.01, 0.01, 0.01};
  model.nodes.push_back(n);
  return static_cast<int>(model.nodes.size()) - 1;
}

std::vector<unsigned char> glbBytes(tinygltf::Model& model, std::vector<unsigned char> bin) {
  const std::string s = serialised(model, std::move(bin), true);
  // Empty lists in extras as [] (tinygltf writes them as null).
  return withExactExtras(model, std::vector<unsigned char>(s.begin(), s.end()));
}

std::vector<unsigned char> gltfTextBytes(tinygltf::Model& model, std::vector<unsigned char> bin) {
  const std::string s = serialised(model, std::move(bin), false);
  return std::vector<unsigned char>(s.begin(), s.end());
}

}  // namespace stirrup::rig
