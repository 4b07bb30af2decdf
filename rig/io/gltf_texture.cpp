#include "rig/io/gltf_texture.h"

#include "rig/io/gltf_accessors.h"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include <tiny_gltf.h>

#include "rig/error.h"

namespace stirrup::rig {
namespace {

std::string range(std::size_t n) { return n == 0 ? "none in the file" : "0.." + std::to_string(n - 1); }

// KHR_texture_transform (its README): uv' = T(offset) R(rotation) S(scale) uv. The rotation turns the
// UVs counter-clockwise as the README's example reads ("offset [0, 1], rotation pi/2, scale [0.5, 0.5]
// uses the lower left quadrant"): u' = cos u + sin v, v' = -sin u + cos v, after the scale.
glm::mat3 textureTransform(const tinygltf::Value& v, const std::string& where, int& tex_coord) {
  if (!v.IsObject()) throw InputError(where + ": expected an object");
  const auto number = [&](const tinygltf::Value& x, const std::string& field) {
    if (!x.IsNumber() || !std::isfinite(x.GetNumberAsDouble()))
      throw InputError(where + "." + field + ": expected a number");
    return x.GetNumberAsDouble();
  };
  const auto pair = [&](const char* field, double fallback) {
    if (!v.Has(field)) return glm::dvec2(fallback);
    const tinygltf::Value& a = v.Get(field);
    if (!a.IsArray() || a.ArrayLen() != 2) throw InputError(where + "." + field + ": expected two numbers");
    return glm::dvec2(number(a.Get(0), std::string(field) + "[0]"), number(a.Get(1), std::string(field) + "[1]"));
  };
  const glm::dvec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
  const double rotation = v.Has("rotation") ? number(v.Get("rotation"), "rotation") : 0.0;
  if (v.Has("texCoord")) {
    const tinygltf::Value& t = v.Get("texCoord");
    if (!t.IsInt() || t.Get<int>() < 0) throw InputError(where + ".texCoord: expected a texture coordinate set 0, 1, ...");
    tex_coord = t.Get<int>();
  }
  const double c = std::cos(rotation), s = std::sin(rotation);
  glm::mat3 m(1.0f);
  m[0] = glm::vec3(float(c * scale.x), float(-s * scale.x), 0.0f);
  m[1] = glm::vec3(float(s * scale.y), float(c * scale.y), 0.0f);
  m[2] = glm::vec3(float(offset.x), float(offset.y), 1.0f);
  return m;
}

TextureWrap wrapOf(int wrap, const std::string& where) {
  switch (wrap) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
    default: break;
  }
  throw InputError(where + ": expected 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT), got " +
                   std::to_string(wrap));
}

// The magnification filter when the sampler has one, else the minification filter's choice within a
// level (no mip-maps here): nearest only when asked for, bilinear by default.
TextureFilter filterOf(const tinygltf::Sampler& s) {
  if (s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) return TextureFilter::Nearest;
  if (s.magFilter == -1 &&
      (s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST || s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
       s.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR))
    return TextureFilter::Nearest;
  return TextureFilter::Linear;
}

// "image/png" or "image/jpeg" from the bytes' signature (glTF 2.0 allows these two), else "".
std::string mimeOf(const std::vector<unsigned char>& b) {
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (b.size() >= 8 && std::memcmp(b.data(), png, 8) == 0) return "image/png";
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "image/jpeg";
  return "";
}

}  // namespace

GltfTextureRef baseColorTextureOf(const tinygltf::Model& model, int material, const std::string& where) {
  GltfTextureRef ref;
  if (material < 0) return ref;
  const tinygltf::TextureInfo& info = gltfElement(model.materials, material, where, "material").pbrMetallicRoughness.baseColorTexture;
  if (info.index < 0) return ref;
  if (info.index >= static_cast<int>(model.textures.size()))
    throw InputError(where + ".baseColorTexture.index: expected a texture " + range(model.textures.size()) + ", got " +
                     std::to_string(info.index));
  if (info.texCoord < 0) throw InputError(where + ".baseColorTexture.texCoord: expected a set 0, 1, ...");
  ref.texture = info.index;
  ref.tex_coord = info.texCoord;
  if (const auto it = info.extensions.find("KHR_texture_transform"); it != info.extensions.end())
    ref.uv_transform = textureTransform(it->second, where + ".baseColorTexture.extensions.KHR_texture_transform", ref.tex_coord);
  return ref;
}

std::shared_ptr<const Texture> readGltfTexture(const tinygltf::Model& model, const GltfImageBytes& images, int index,
                                               const std::string& where) {
  const tinygltf::Texture& t = gltfElement(model.textures, index, where + ": texture", "texture");
  const std::string tw = where + ": textures[" + std::to_string(index) + "]";
  if (t.source < 0) {
    std::string extensions;
    for (const auto& [name, value] : t.extensions) extensions += (extensions.empty() ? " (it has " : ", ") + name;
    throw InputError(tw + ": no PNG or JPEG image source" + (extensions.empty() ? "" : extensions + ", which is not read)"));
  }
  if (t.source >= static_cast<int>(model.images.size()))
    throw InputError(tw + ".source: expected an image " + range(model.images.size()) + ", got " + std::to_string(t.source));
  const std::size_t ii = static_cast<std::size_t>(t.source);
  const tinygltf::Image& image = model.images[ii];
  const std::string iw = tw + ": images[" + std::to_string(ii) + "]" + (image.uri.empty() || image.uri.rfind("data:", 0) == 0 ? "" : " (\"" + image.uri + "\")");
  const std::vector<unsigned char> none;
  const std::vector<unsigned char>& encoded = ii < images.encoded.size() ? images.encoded[ii] : none;
  if (encoded.empty()) throw InputError(iw + ": missing (expected a PNG or JPEG image)");
  const std::string mime = mimeOf(encoded);
  if (mime.empty()) throw InputError(iw + ": expected a PNG or JPEG image (glTF 2.0's image formats)");
  if (ii < images.errors.size() && !images.errors[ii].empty()) throw InputError(iw + ": cannot decode it (" + images.errors[ii] + ")");
  const int bytes = image.bits / 8, comps = image.component;
  if ((bytes != 1 && bytes != 2) || comps < 1 || comps > 4 || image.width < 1 || image.height < 1 ||
      image.image.size() != std::size_t(image.width) * std::size_t(image.height) * std::size_t(comps * bytes))
    throw InputError(iw + ": cannot decode it (expected 8 or 16 bits a channel)");

  auto texture = std::make_shared<Texture>();
  texture->name = image.name;
  if (texture->name.empty() && !image.uri.empty() && image.uri.rfind("data:", 0) != 0)
    texture->name = std::filesystem::path(image.uri).stem().string();
  texture->width = image.width;
  texture->height = image.height;
  texture->encoded = encoded;
  texture->mime_type = mime;
  // The glTF spec: base colour textures are sRGB-encoded; the renderer works in linear light.
  const std::vector<float>& table = srgb8ToLinearTable();
  const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
  texture->texels.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    float rgb[3];
    for (int k = 0; k < 3; ++k) {
      const std::size_t at = (p * std::size_t(comps) + std::size_t(comps >= 3 ? k : 0)) * std::size_t(bytes);
      if (bytes == 1) {
        rgb[k] = table[image.image[at]];
      } else {
        std::uint16_t v;
        std::memcpy(&v, image.image.data() + at, 2);
        rgb[k] = float(srgbToLinear(v / 65535.0));
      }
    }
    texture->texels[p] = glm::vec3(rgb[0], rgb[1], rgb[2]);
  }
  if (t.sampler >= 0) {
    if (t.sampler >= static_cast<int>(model.samplers.size()))
      throw InputError(tw + ".sampler: expected a sampler " + range(model.samplers.size()) + ", got " + std::to_string(t.sampler));
    const tinygltf::Sampler& s = model.samplers[static_cast<std::size_t>(t.sampler)];
    const std::string sw = where + ": samplers[" + std::to_string(t.sampler) + "]";
    texture->wrap_s = wrapOf(s.wrapS, sw + ".wrapS");
    texture->wrap_t = wrapOf(s.wrapT, sw + ".wrapT");
    texture->filter = filterOf(s);
  }
  return texture;
}

int appendGltfTexture(tinygltf::Model& model, std::vector<unsigned char>& bin, const Texture& texture,
                      const std::string& name) {
  if (texture.encoded.empty() || texture.mime_type.empty())
    throw std::invalid_argument("appendGltfTexture: texture \"" + texture.name + "\" has no encoded image");
  while (bin.size() % 4) bin.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin.size();
  view.byteLength = texture.encoded.size();
  bin.insert(bin.end(), texture.encoded.begin(), texture.encoded.end());
  model.bufferViews.push_back(view);

  tinygltf::Image image;
  image.name = name;
  image.bufferView = static_cast<int>(model.bufferViews.size()) - 1;
  image.mimeType = texture.mime_type;
  model.images.push_back(image);

  tinygltf::Sampler sampler;
  const bool nearest = texture.filter == TextureFilter::Nearest;
  sampler.magFilter = nearest ? TINYGLTF_TEXTURE_FILTER_NEAREST : TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = sampler.magFilter;  // no mip-maps: as rendered here
  sampler.wrapS = static_cast<int>(texture.wrap_s);
  sampler.wrapT = static_cast<int>(texture.wrap_t);
  model.samplers.push_back(sampler);

  tinygltf::Texture t;
  t.name = name;
  t.sampler = static_cast<int>(model.samplers.size()) - 1;
  t.source = static_cast<int>(model.images.size()) - 1;
  model.textures.push_back(t);
  return static_cast<int>(model.textures.size()) - 1;
}

}  // namespace stirrup::rig
