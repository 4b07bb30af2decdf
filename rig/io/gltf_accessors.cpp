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

namespace {

// One component at p as a float: float data as it is, integers as their value or, normalised, mapped
// to [0, 1] (unsigned) or [-1, 1] (signed) as glTF 2.0 section 3.11 says.
float componentValue(const unsigned char* p, int component_type, bool normalized, const std::string& where) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: { float x; std::memcpy(&x, p, 4); return x; }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(*p) / 255.0f : float(*p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float x = float(static_cast<std::int8_t>(*p));
      return normalized ? std::max(x / 127.0f, -1.0f) : x;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t u;
      std::memcpy(&u, p, 2);
      return normalized ? float(u) / 65535.0f : float(u);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t q;
      std::memcpy(&q, p, 2);
      return normalized ? std::max(float(q) / 32767.0f, -1.0f) : float(q);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t u;
      std::memcpy(&u, p, 4);
      return static_cast<float>(u);
    }
    default: throw InputError(where + ": unsupported component type " + std::to_string(component_type));
  }
}

// A sparse accessor's substitutions (glTF 2.0, section 3.6.2.3) applied to `out`: `count` indices of an
// unsigned type, each below the accessor's count, and as many elements of values.
void applySparse(const tinygltf::Model& model, const tinygltf::Accessor& a, int components, int csize,
                 const std::string& where, std::vector<float>& out) {
  const auto& sp = a.sparse;
  if (sp.count < 0 || static_cast<std::size_t>(sp.count) > a.count)
    throw InputError(where + ": sparse.count " + std::to_string(sp.count) + ": expected 0.." + std::to_string(a.count));
  if (sp.count == 0) return;
  if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) throw InputError(where + ": sparse: expected byte offsets of 0 or more");
  tinygltf::Accessor indices;
  indices.bufferView = sp.indices.bufferView;
  indices.byteOffset = static_cast<std::size_t>(sp.indices.byteOffset);
  indices.count = static_cast<std::size_t>(sp.count);
  const int isize = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(sp.indices.componentType));
  if (sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      sp.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    throw InputError(where + ": sparse.indices: expected unsigned bytes, shorts or ints (componentType 5121, 5123 or 5125)");
  const unsigned char* ip =
      elementBytes(model, indices, static_cast<std::size_t>(isize), false, where + ": sparse.indices", "indices run past their buffer").first;
  tinygltf::Accessor values;
  values.bufferView = sp.values.bufferView;
  values.byteOffset = static_cast<std::size_t>(sp.values.byteOffset);
  values.count = indices.count;
  const std::size_t element = static_cast<std::size_t>(csize) * components;
  const unsigned char* vp = elementBytes(model, values, element, false, where + ": sparse.values", "values run past their buffer").first;
  for (std::size_t i = 0; i < indices.count; ++i) {
    const float index = componentValue(ip + i * static_cast<std::size_t>(isize), sp.indices.componentType, false, where);
    if (!(index < static_cast<float>(a.count)))
      throw InputError(where + ": sparse.indices[" + std::to_string(i) + "]: " + std::to_string(static_cast<std::uint64_t>(index)) +
                       " is past the accessor's " + std::to_string(a.count) + " elements");
    const std::size_t at = static_cast<std::size_t>(index);
    for (int k = 0; k < components; ++k)
      out[at * components + k] = componentValue(vp + i * element + static_cast<std::size_t>(csize) * k, a.componentType, a.normalized, where);
  }
}

}  // namespace

std::vector<float> readAccessor(const tinygltf::Model& model, int index, int components, const std::string& where) {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    throw InputError(where + ": accessor " + std::to_string(index) + ": no such accessor (the file has " +
                     std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& a = model.accessors[index];
  if (tinygltf::GetNumComponentsInType(a.type) != components)
    throw InputError(where + ": expected " + std::to_string(components) + " components per element");
  const int csize = tinygltf::GetComponentSizeInBytes(a.componentType);
  if (csize <= 0) throw InputError(where + ": unknown component type " + std::to_string(a.componentType));
  std::vector<float> out;
  if (a.bufferView < 0) {
    // No view: zeros (glTF 2.0, 3.6.2.1), as many as the accessor says, if that is a real count.
    if (a.count > (std::size_t(1) << 28)) throw InputError(where + ": accessor count " + std::to_string(a.count) + " without a buffer view");
    out.assign(a.count * components, 0.0f);
  } else {
    const std::size_t element = static_cast<std::size_t>(csize) * static_cast<std::size_t>(components);
    const auto [first, stride] = elementBytes(model, a, element, true, where, "accessor runs past its buffer");
    out.assign(a.count * components, 0.0f);
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
      // Floats are taken as they are (componentValue's own case), an element at a time: a mesh's
      // positions, normals and weights, most of what a character file holds, read without a switch
      // per component.
      for (std::size_t i = 0; i < a.count; ++i) std::memcpy(out.data() + i * components, first + stride * i, element);
    } else {
      for (std::size_t i = 0; i < a.count; ++i)
        for (int k = 0; k < components; ++k)
          out[i * components + k] = componentValue(first + stride * i + static_cast<std::size_t>(csize) * k, a.componentType, a.normalized, where);
    }
  }
  if (a.sparse.isSparse) applySparse(model, a, components, csize, where, out);
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
