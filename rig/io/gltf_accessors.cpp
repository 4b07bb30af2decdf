#include "rig/io/gltf_accessors.h"

#include <algorithm>
#include <cstring>

#include <tiny_gltf.h>

#include "rig/error.h"

namespace stirrup::rig {

namespace {

// tinygltf's image callback: keeps the encoded bytes, then decodes them with tinygltf's own stb_image
// loader (to RGBA, 8 or 16 bits a channel). A failure is kept, not returned.
bool keepAndDecodeImage(tinygltf::Image* image, const int index, std::string* /*err*/, std::string* warn, int width,
                        int height, const unsigned char* bytes, int size, void* user) {
  auto& images = *static_cast<GltfImageBytes*>(user);
  const std::size_t i = static_cast<std::size_t>(index);
  if (images.encoded.size() <= i) {
    images.encoded.resize(i + 1);
    images.errors.resize(i + 1);
  }
  images.encoded[i].assign(bytes, bytes + size);
  std::string error;
  if (!tinygltf::LoadImageData(image, index, &error, warn, width, height, bytes, size, nullptr)) {
    std::replace(error.begin(), error.end(), '\n', ' ');
    while (!error.empty() && error.back() == ' ') error.pop_back();
    images.errors[i] = error.empty() ? "cannot decode it" : error;
    image->image.clear();
  }
  return true;
}

}  // namespace

tinygltf::Model readGltfFile(const std::filesystem::path& file, const std::string& where, GltfImageBytes* images) {
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  if (images) loader.SetImageLoader(&keepAndDecodeImage, images);
  std::string err, warn;
  const bool ok = file.extension() == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                                             : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
  if (!ok) {
    std::replace(err.begin(), err.end(), '\n', ' ');
    throw InputError(where + ": not a readable glTF file (" + err + ")");
  }
  return model;
}

std::vector<float> readAccessor(const tinygltf::Model& model, int index, int components, const std::string& where) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size())) throw InputError(where + ": no such accessor");
  const tinygltf::Accessor& a = model.accessors[index];
  if (a.sparse.isSparse) throw InputError(where + ": sparse accessors are not supported");
  if (tinygltf::GetNumComponentsInType(a.type) != components)
    throw InputError(where + ": expected " + std::to_string(components) + " components per element");
  std::vector<float> out(a.count * components, 0.0f);
  if (a.bufferView < 0) return out;
  const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
  const tinygltf::Buffer& b = model.buffers.at(v.buffer);
  const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
  if (csize <= 0) throw InputError(where + ": unknown component type");
  const std::size_t stride = v.byteStride ? v.byteStride : static_cast<std::size_t>(csize * components);
  const std::size_t base = v.byteOffset + a.byteOffset;
  if (a.count > 0 && base + stride * (a.count - 1) + csize * components > b.data.size())
    throw InputError(where + ": accessor runs past its buffer");
  for (std::size_t i = 0; i < a.count; ++i)
    for (int k = 0; k < components; ++k) {
      const unsigned char* p = b.data.data() + base + stride * i + static_cast<std::size_t>(csize) * k;
      float value = 0.0f;
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&value, p, 4); break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = *p; if (a.normalized) value /= 255.0f; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          std::uint16_t u;
          std::memcpy(&u, p, 2);
          value = u;
          if (a.normalized) value /= 65535.0f;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
          std::uint32_t u;
          std::memcpy(&u, p, 4);
          value = static_cast<float>(u);
          break;
        }
        default: throw InputError(where + ": unsupported component type");
      }
      out[i * components + k] = value;
    }
  return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& where) {
  const tinygltf::Accessor& a = model.accessors.at(index);
  const tinygltf::BufferView& v = model.bufferViews.at(a.bufferView);
  const tinygltf::Buffer& b = model.buffers.at(v.buffer);
  const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
  const std::size_t base = v.byteOffset + a.byteOffset;
  if (base + a.count * static_cast<std::size_t>(csize) > b.data.size()) throw InputError(where + ": indices run past the buffer");
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = b.data.data() + base + i * csize;
    if (csize == 1) out[i] = *p;
    else if (csize == 2) { std::uint16_t u; std::memcpy(&u, p, 2); out[i] = u; }
    else { std::memcpy(&out[i], p, 4); }
  }
  return out;
}

}  // namespace stirrup::rig
