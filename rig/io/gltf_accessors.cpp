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

// Where an accessor's elements are, checked: the view and its buffer exist, and `count` elements of
// `element_bytes`, `stride` bytes apart from the accessor's offset, fit in the view and the buffer (in 64
// bits, so no count overflows the test).
struct ElementBytes {
  const unsigned char* first;
  std::size_t stride;  // the view's byteStride, or packed (always, for indices: glTF forbids them one)
};
ElementBytes elementBytes(const tinygltf::Model& model, const tinygltf::Accessor& a, std::size_t element_bytes,
                          bool strided, const std::string& where, const char* runs_past) {
  if (a.bufferView < 0 || a.bufferView >= static_cast<int>(model.bufferViews.size()))
    throw InputError(where + ": bufferView " + std::to_string(a.bufferView) + ": no such buffer view (the file has " +
                     std::to_string(model.bufferViews.size()) + ")");
  const tinygltf::BufferView& v = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (v.buffer < 0 || v.buffer >= static_cast<int>(model.buffers.size()))
    throw InputError(where + ": bufferView " + std::to_string(a.bufferView) + ".buffer " + std::to_string(v.buffer) +
                     ": no such buffer (the file has " + std::to_string(model.buffers.size()) + ")");
  const tinygltf::Buffer& b = model.buffers[static_cast<std::size_t>(v.buffer)];
  const std::size_t stride = strided && v.byteStride ? v.byteStride : element_bytes;
  const unsigned long long count = a.count, base = static_cast<unsigned long long>(v.byteOffset) + a.byteOffset;
  // Element i's last byte is base + stride * i + element_bytes - 1; a count beyond any buffer is refused
  // before the product can overflow.
  const unsigned long long limit = b.data.size();
  if (count > 0 && (count - 1 > limit || base + stride * (count - 1) + element_bytes > limit ||
                    (v.byteLength > 0 && a.byteOffset + stride * (count - 1) + element_bytes > v.byteLength)))
    throw InputError(where + ": " + runs_past);
  return {b.data.data() + base, stride};
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
  const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
  if (csize <= 0) throw InputError(where + ": unknown component type");
  if (a.bufferView < 0) {
    // No view: zeros (glTF 2.0, 3.6.2.1), as many as the accessor says, if that is a real count.
    if (a.count > (std::size_t(1) << 28)) throw InputError(where + ": accessor count " + std::to_string(a.count) + " without a buffer view");
    return std::vector<float>(a.count * components, 0.0f);
  }
  const auto [first, stride] =
      elementBytes(model, a, static_cast<std::size_t>(csize) * components, true, where, "accessor runs past its buffer");
  std::vector<float> out(a.count * components, 0.0f);
  for (std::size_t i = 0; i < a.count; ++i)
    for (int k = 0; k < components; ++k) {
      const unsigned char* p = first + stride * i + static_cast<std::size_t>(csize) * k;
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
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw InputError(where + ": accessor " + std::to_string(index) + ": no such accessor (the file has " +
                     std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
  if (a.sparse.isSparse) throw InputError(where + ": sparse accessors are not supported");
  if (a.type != TINYGLTF_TYPE_SCALAR) throw InputError(where + ": expected scalar indices, one a vertex");
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw InputError(where + ": expected indices of unsigned bytes, shorts or ints (componentType 5121, 5123 or 5125), got " +
                     std::to_string(a.componentType));
  if (a.bufferView < 0) throw InputError(where + ": expected indices in a buffer view, got none");
  const std::size_t csize = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(a.componentType));
  const unsigned char* first = elementBytes(model, a, csize, false, where, "indices run past the buffer").first;
  std::vector<std::uint32_t> out(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* p = first + i * csize;
    if (csize == 1) out[i] = *p;
    else if (csize == 2) { std::uint16_t u; std::memcpy(&u, p, 2); out[i] = u; }
    else { std::memcpy(&out[i], p, 4); }
  }
  return out;
}

}  // namespace stirrup::rig
