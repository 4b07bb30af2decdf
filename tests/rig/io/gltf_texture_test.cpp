// Base colour textures in glTF characters: a small skinned file this test writes (known texels, every
// wrap, both filters, both texture coordinate sets, KHR_texture_transform, textured and untextured
// materials sharing vertices) reads as worked out by hand; the Khronos Fox reads its one texture; a
// textured character written by characterGlb reads back the same, its images byte for byte; bad
// texture data is a one-line error naming the file and the material.
#include "rig/io/gltf_texture.h"
#include "rig/io/character_mapping_json.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <numbers>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "rig/characters/horse_tack.h"
#include "rig/error.h"
#include "rig/io/gltf_character.h"
#include "rig/mapping/character_mapping.h"
#include "tests/input_error.h"
#include "tests/test_files.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path tempDir(const std::string& name) { return stirrup::test::freshTestDir("test_gltf_texture", name); }

std::vector<unsigned char> readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string errorOf(const std::function<void()>& f) {
  return stirrup::test::errorOf([&] { f(); }, "");
}

// The sRGB transfer undone, as IEC 61966-2-1 writes it, for an 8-bit code.
double linear(int code) {
  const double c = code / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
glm::dvec3 linear(int r, int g, int b) { return {linear(r), linear(g), linear(b)}; }

void expectNear(glm::vec3 got, glm::dvec3 want, const std::string& what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], 1e-6) << what << " channel " << k;
}

void writePng(const fs::path& file, int width, int height, const std::vector<unsigned char>& rgb) {
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out);
  ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8)));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
  ASSERT_TRUE(out->close());
}

// The checker: red, blue on the top row; grey 128, (188, 10, 255) below. The stripe: two texels.
const std::vector<unsigned char> kChecker = {255, 0, 0, 0, 0, 255, 128, 128, 128, 188, 10, 255};
const std::vector<unsigned char> kStripe = {200, 60, 20, 20, 60, 200};

// A skinned character (horse or rider: every role is its one joint) of seven quads (two triangles
// each), as .gltf + .bin + two PNGs:
//   primitive 0: vertices A, "checker" (texture 0: nearest, wrapS clamp, wrapT mirrored; factor 0.5, 1, 1)
//   primitive 1: vertices B, "stripe" through TEXCOORD_1 (texture 1: no sampler, so repeat and bilinear);
//                B's TEXCOORD_0 is a decoy at (0.9, 0.9)
//   primitive 2: vertices A, "plain" (untextured, 0.2, 0.3, 0.4)
//   primitive 3: vertices A, "moved": the stripe through KHR_texture_transform (the extension's README
//                example: offset [0, 1], rotation pi/2, scale [0.5, 0.5], "the lower left quadrant"),
//                factor 0.5, 1, 1 as the checker's: only its texture coordinates differ
//   primitive 4: vertices A, "checker" again
//   primitive 5: vertices C, "white" (untextured, factor 1)
//   primitive 6: vertices C, "white checker" (texture 0, factor 1)
struct TexturedFile {
  fs::path dir, gltf;
  json j;
  std::vector<unsigned char> bin;

  explicit TexturedFile(const std::string& name) : dir(tempDir(name)), gltf(dir / "textured.gltf") {
    writePng(dir / "checker.png", 2, 2, kChecker);
    writePng(dir / "stripe.png", 2, 1, kStripe);
    j = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", {{{"nodes", {0, 1}}}}},
         {"bufferViews", json::array()}, {"accessors", json::array()}};
    json roles = json::object();
    for (const CharacterKind kind : {CharacterKind::Horse, CharacterKind::Rider})  // it loads as either
      for (const std::string& role : requiredRoles(kind)) roles[role] = 0;
    for (const char* role : kHorseTackRoles) roles[role] = 0;  // named: the rig adds no tack of its own
    j["nodes"] = {{{"name", "root"}}, {{"name", "body"}, {"mesh", 0}, {"skin", 0}, {"extras", {{"stirrup_roles", roles}}}}};
    j["skins"] = {{{"joints", {0}}}};
    const auto quad = [&](float x) {
      return floats({x, 0, 0, x + 10, 0, 0, x + 10, 10, 0, x, 10, 0}, "VEC3");
    };
    const int joints = [&] {
      const std::vector<std::uint16_t> zero(16, 0);
      return accessor(zero.data(), zero.size() * 2, 5123, 4, "VEC4");
    }();
    const int weights = floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
    const std::vector<std::uint16_t> six = {0, 1, 2, 0, 2, 3};
    const int indices = accessor(six.data(), 12, 5123, 6, "SCALAR");
    const json a = {{"POSITION", quad(0)}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights},
                    {"TEXCOORD_0", floats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2")}};
    const json b = {{"POSITION", quad(20)}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights},
                    {"TEXCOORD_0", floats({0.9f, 0.9f, 0.9f, 0.9f, 0.9f, 0.9f, 0.9f, 0.9f}, "VEC2")},
                    {"TEXCOORD_1", floats({0, 0, 2, 0, 2, 1, 0, 1}, "VEC2")}};
    const json c = {{"POSITION", quad(40)}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights},
                    {"TEXCOORD_0", floats({0, 0, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f}, "VEC2")}};
    json prims = json::array();
    for (const auto& [attributes, material] : std::vector<std::pair<json, int>>{{a, 0}, {b, 1}, {a, 2}, {a, 3}, {a, 0}, {c, 4}, {c, 5}})
      prims.push_back({{"attributes", attributes}, {"indices", indices}, {"material", material}});
    j["meshes"] = {{{"primitives", prims}}};
    const auto pbr = [](json p) { return json{{"pbrMetallicRoughness", p}}; };
    j["materials"] = {
        pbr({{"baseColorTexture", {{"index", 0}}}, {"baseColorFactor", {0.5, 1, 1, 1}}}),
        pbr({{"baseColorTexture", {{"index", 1}, {"texCoord", 1}}}}),
        pbr({{"baseColorFactor", {0.2, 0.3, 0.4, 1}}}),
        pbr({{"baseColorTexture", {{"index", 1}, {"extensions", {{"KHR_texture_transform",
              {{"offset", {0, 1}}, {"rotation", std::numbers::pi / 2}, {"scale", {0.5, 0.5}}}}}}}},
             {"baseColorFactor", {0.5, 1, 1, 1}}}),
        pbr({{"baseColorFactor", {1, 1, 1, 1}}}),
        pbr({{"baseColorTexture", {{"index", 0}}}}),
    };
    const char* names[] = {"checker", "stripe", "plain", "moved", "white", "white checker"};
    for (std::size_t i = 0; i < 6; ++i) j["materials"][i]["name"] = names[i];
    j["extensionsUsed"] = {"KHR_texture_transform"};
    j["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}}};
    j["samplers"] = {{{"magFilter", 9728}, {"minFilter", 9728}, {"wrapS", 33071}, {"wrapT", 33648}}};
    j["images"] = {{{"uri", "checker.png"}}, {{"uri", "stripe.png"}}};
    j["buffers"] = {{{"uri", "textured.bin"}, {"byteLength", bin.size()}}};
    std::ofstream(dir / "textured.bin", std::ios::binary).write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    write();
  }

  int accessor(const void* data, std::size_t bytes, int component_type, std::size_t count, const char* type) {
    while (bin.size() % 4) bin.push_back(0);
    j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    const auto* p = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), p, p + bytes);
    j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1}, {"componentType", component_type},
                              {"count", count}, {"type", type}});
    return int(j["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const char* type) {
    const std::size_t per = std::string(type) == "VEC2" ? 2 : std::string(type) == "VEC3" ? 3 : 4;
    return accessor(v.data(), v.size() * 4, 5126, v.size() / per, type);
  }
  void write() const { std::ofstream(gltf) << j.dump(1); }
  Character load(CharacterKind kind = CharacterKind::Horse) const { return loadCharacterGltf(gltf, kind); }
};

TEST(GltfTexture, ASmallTexturedCharacterReadsAsWorkedOutByHand) {
  const TexturedFile file("small");
  const Character c = file.load();
  const SkinnedMesh& m = c.mesh;
  // Vertices: A for the checker (0-3), B (4-7), A again for "plain" (its colour differs: 8-11) and for
  // "moved" (its texture coordinates differ: 12-15), the second checker primitive reuses 0-3; C (16-19)
  // read for "white" and then textured by "white checker".
  ASSERT_EQ(m.vertexCount(), 20u);
  ASSERT_EQ(m.triangleCount(), 14u);
  EXPECT_EQ(m.triangle_textures, (std::vector<std::int32_t>{0, 0, 1, 1, -1, -1, 1, 1, 0, 0, -1, -1, 0, 0}));
  EXPECT_EQ(std::vector<std::uint32_t>(m.indices.begin() + 24, m.indices.begin() + 30), (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(std::vector<std::uint32_t>(m.indices.begin() + 36, m.indices.end()), (std::vector<std::uint32_t>{16, 17, 18, 16, 18, 19}));
  ASSERT_EQ(m.uvs.size(), 20u);
  const std::vector<glm::vec2> a = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, b1 = {{0, 0}, {2, 0}, {2, 1}, {0, 1}},
                               c0 = {{0, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}},
                               moved = {{0, 1}, {0, 0.5f}, {0.5f, 0.5f}, {0.5f, 1}};  // all in the lower left quadrant
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(m.uvs[v], a[v]) << v;
    EXPECT_EQ(m.uvs[4 + v], b1[v]) << "TEXCOORD_1, not the decoy TEXCOORD_0: " << v;
    EXPECT_NEAR(m.uvs[12 + v].x, moved[v].x, 1e-6f) << v;
    EXPECT_NEAR(m.uvs[12 + v].y, moved[v].y, 1e-6f) << v;
    EXPECT_EQ(m.uvs[16 + v], c0[v]) << v;
    EXPECT_EQ(m.colors[v], glm::vec3(0.5f, 1.0f, 1.0f));
    EXPECT_EQ(m.colors[4 + v], glm::vec3(1.0f));
    EXPECT_EQ(m.colors[8 + v], glm::vec3(0.2f, 0.3f, 0.4f));
    EXPECT_EQ(m.colors[12 + v], glm::vec3(0.5f, 1.0f, 1.0f));
    EXPECT_EQ(m.colors[16 + v], glm::vec3(1.0f));
  }

  ASSERT_EQ(m.textures.size(), 2u);
  const Texture& checker = *m.textures[0];
  ASSERT_EQ(checker.width, 2);
  ASSERT_EQ(checker.height, 2);
  expectNear(checker.texels[0], linear(255, 0, 0), "checker (0, 0)");
  expectNear(checker.texels[1], linear(0, 0, 255), "checker (1, 0)");
  expectNear(checker.texels[2], glm::dvec3(0.2158605), "checker (0, 1)");  // sRGB 128, the standard's value
  expectNear(checker.texels[3], linear(188, 10, 255), "checker (1, 1)");
  EXPECT_EQ(checker.filter, TextureFilter::Nearest);
  EXPECT_EQ(checker.wrap_s, TextureWrap::ClampToEdge);
  EXPECT_EQ(checker.wrap_t, TextureWrap::MirroredRepeat);
  EXPECT_EQ(checker.mime_type, "image/png");
  EXPECT_EQ(checker.encoded, readBytes(file.dir / "checker.png"));
  EXPECT_EQ(checker.name, "checker");
  // Lookups through the file's sampler: past the right edge clamps to the blue column; v = 1.25 is
  // mirrored back onto the bottom row.
  expectNear(checker.sample({1.2f, 0.25f}), linear(0, 0, 255), "clamped");
  expectNear(checker.sample({0.25f, 1.25f}), linear(128, 128, 128), "mirrored");
  expectNear(checker.sample({0.75f, 1.75f}), linear(0, 0, 255), "mirrored twice");

  const Texture& stripe = *m.textures[1];
  ASSERT_EQ(stripe.width, 2);
  ASSERT_EQ(stripe.height, 1);
  EXPECT_EQ(stripe.filter, TextureFilter::Linear);
  EXPECT_EQ(stripe.wrap_s, TextureWrap::Repeat);
  EXPECT_EQ(stripe.wrap_t, TextureWrap::Repeat);
  // Bilinear, halfway between the two texel centres, and on the seam where repeat wraps around.
  const glm::dvec3 mean = 0.5 * (linear(200, 60, 20) + linear(20, 60, 200));
  expectNear(stripe.sample({0.5f, 0.5f}), mean, "between the centres");
  expectNear(stripe.sample({1.0f, 0.5f}), mean, "on the repeat seam");
  expectNear(stripe.sample({1.25f, 0.5f}), linear(200, 60, 20), "a period on");

  // A rider reads its textures the same way.
  const Character rider = file.load(CharacterKind::Rider);
  EXPECT_EQ(rider.mesh.uvs, m.uvs);
  EXPECT_EQ(rider.mesh.triangle_textures, m.triangle_textures);
  ASSERT_EQ(rider.mesh.textures.size(), 2u);
  EXPECT_EQ(rider.mesh.textures[0]->texels, checker.texels);
}

// Written out by characterGlb and read back, a textured character is the same: vertices, texture
// coordinates, per-triangle textures, texels, wraps and filters; the file holds each image's bytes
// as they were read, a material referencing it, and TEXCOORD_0 for every vertex. Untextured files
// keep none of this (the shipped characters' bytes are checked by tests/cli/character_test.cpp).
TEST(GltfTexture, ATexturedCharacterWrittenOutReadsBackTheSame) {
  const TexturedFile file("round_trip");
  const Character c = file.load();
  const std::vector<unsigned char> bytes = characterGlb(c);
  EXPECT_EQ(characterGlb(c), bytes) << "the same character gives the same file";
  const fs::path glb = file.dir / "written.glb";
  std::ofstream(glb, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  const Character back = loadCharacterGltf(glb, CharacterKind::Horse);
  EXPECT_EQ(back.mesh.positions, c.mesh.positions);
  EXPECT_EQ(back.mesh.colors, c.mesh.colors);
  EXPECT_EQ(back.mesh.indices, c.mesh.indices);
  EXPECT_EQ(back.mesh.uvs, c.mesh.uvs);
  EXPECT_EQ(back.mesh.triangle_textures, c.mesh.triangle_textures);
  ASSERT_EQ(back.mesh.textures.size(), c.mesh.textures.size());
  for (std::size_t i = 0; i < c.mesh.textures.size(); ++i) {
    const Texture &x = *back.mesh.textures[i], &y = *c.mesh.textures[i];
    EXPECT_EQ(x.texels, y.texels) << i;
    EXPECT_EQ(x.encoded, y.encoded) << i;
    EXPECT_EQ(x.wrap_s, y.wrap_s) << i;
    EXPECT_EQ(x.wrap_t, y.wrap_t) << i;
    EXPECT_EQ(x.filter, y.filter) << i;
  }

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, glb.string())) << err;
  ASSERT_EQ(model.images.size(), 2u);
  ASSERT_EQ(model.textures.size(), 2u);
  const std::vector<std::vector<unsigned char>> pngs = {readBytes(file.dir / "checker.png"), readBytes(file.dir / "stripe.png")};
  for (std::size_t i = 0; i < 2; ++i) {
    const tinygltf::Image& image = model.images[i];
    EXPECT_EQ(image.mimeType, "image/png");
    ASSERT_GE(image.bufferView, 0);
    const tinygltf::BufferView& view = model.bufferViews.at(std::size_t(image.bufferView));
    const auto* p = model.buffers.at(0).data.data() + view.byteOffset;
    EXPECT_EQ(std::vector<unsigned char>(p, p + view.byteLength), pngs[i]) << "image " << i;
  }
  int textured = 0, plain = 0;
  for (const tinygltf::Primitive& prim : model.meshes.at(0).primitives) {
    ASSERT_TRUE(prim.attributes.count("TEXCOORD_0"));
    EXPECT_EQ(model.accessors.at(std::size_t(prim.attributes.at("TEXCOORD_0"))).count, c.mesh.vertexCount());
    const int index = model.materials.at(std::size_t(prim.material)).pbrMetallicRoughness.baseColorTexture.index;
    (index >= 0 ? textured : plain) += 1;
    EXPECT_LT(index, 2);
  }
  EXPECT_EQ(textured, 5);  // checker, stripe, moved, checker again, white checker: runs of one colour and texture
  EXPECT_EQ(plain, 2);
  EXPECT_EQ(model.samplers.at(std::size_t(model.textures[0].sampler)).wrapS, 33071);
  EXPECT_EQ(model.samplers.at(std::size_t(model.textures[0].sampler)).wrapT, 33648);
  EXPECT_EQ(model.samplers.at(std::size_t(model.textures[0].sampler)).magFilter, 9728);
}

// The Khronos Fox has one base colour texture (a PNG in the .glb) read through TEXCOORD_0 by its one
// material. Every role but the head (beyond the neck) is mapped to its hip here, the tack too (so the
// rig adds none): only the mesh matters to this test.
TEST(GltfTexture, TheFoxReadsItsTexture) {
  const fs::path fox = fs::path(STIRRUP_SHARED_DIR) / "assets" / "fox" / "Fox.glb";
  if (!fs::exists(fox)) GTEST_SKIP() << "no " << fox;
  const fs::path dir = tempDir("fox");
  json roles = json::object();
  for (const std::string& role : requiredRoles(CharacterKind::Horse)) roles[role] = "b_Hip_01";
  for (const char* role : kHorseTackRoles) roles[role] = "b_Hip_01";
  roles["head"] = "b_Head_05";
  std::ofstream(dir / "fox.json") << json{{"character", "horse"}, {"roles", roles}}.dump();
  const CharacterMapping mapping = loadCharacterMapping(dir / "fox.json", CharacterKind::Horse);
  const Character c = loadCharacterGltf(fox, CharacterKind::Horse, &mapping);
  ASSERT_EQ(c.mesh.textures.size(), 1u);
  EXPECT_EQ(c.mesh.uvs.size(), c.mesh.vertexCount());
  EXPECT_EQ(c.mesh.triangle_textures, std::vector<std::int32_t>(c.mesh.triangleCount(), 0));
  const Texture& t = *c.mesh.textures[0];
  EXPECT_EQ(t.mime_type, "image/png");
  EXPECT_EQ(t.texels.size(), std::size_t(t.width) * std::size_t(t.height));
  EXPECT_EQ(t.filter, TextureFilter::Linear);  // magFilter LINEAR
  EXPECT_EQ(t.wrap_s, TextureWrap::Repeat);
  for (const glm::vec3& colour : c.mesh.colors) ASSERT_EQ(colour, glm::vec3(1.0f)) << "no factor: the texture alone";
  // Its texture coordinates fall on the image, and the fur it reads there is orange: red over green
  // over blue, on average over the triangles' corners.
  glm::dvec3 mean(0.0);
  for (std::uint32_t v : c.mesh.indices) {
    const glm::vec2 uv = c.mesh.uvs[v];
    ASSERT_TRUE(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f) << uv.x << ", " << uv.y;
    mean += glm::dvec3(t.sample(uv));
  }
  mean /= double(c.mesh.indices.size());
  EXPECT_GT(mean.x, 1.5 * mean.y) << mean.x << " " << mean.y << " " << mean.z;
  EXPECT_GT(mean.y, 1.5 * mean.z) << mean.x << " " << mean.y << " " << mean.z;
}

// Bad texture data: one line naming the file, then the material (and texture, image, sampler or
// primitive) at fault, and what was expected.
TEST(GltfTexture, BadTextureDataIsAOneLineError) {
  TexturedFile file("bad");
  const std::string f = file.gltf.string();
  const json good = file.j;
  const auto expectError = [&](const std::function<void(json&)>& change, const std::string& want) {
    file.j = good;
    change(file.j);
    file.write();
    const std::string e = errorOf([&] { file.load(); });
    EXPECT_EQ(e.rfind(f + ": ", 0), 0u) << e;
    EXPECT_NE(e.find(want), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  expectError([](json& j) { j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 7; },
              "materials[0] \"checker\".baseColorTexture.index: expected a texture 0..1, got 7");
  expectError([](json& j) { j["meshes"][0]["primitives"][1]["attributes"].erase("TEXCOORD_1"); },
              "meshes[0].primitives[1]: expected a TEXCOORD_1 attribute (the base colour texture of materials[1] \"stripe\" reads it)");
  expectError([](json& j) { j["accessors"][j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"].get<int>()]["count"] = 3; },
              "meshes[0].primitives[0].TEXCOORD_0: expected one texture coordinate a vertex");
  expectError([](json& j) { j["images"][0]["uri"] = "nowhere.png"; },
              "materials[0] \"checker\".baseColorTexture: textures[0]: images[0] (\"nowhere.png\"): missing");
  std::ofstream(file.dir / "text.png") << "not an image\n";
  expectError([](json& j) { j["images"][0]["uri"] = "text.png"; },
              "images[0] (\"text.png\"): expected a PNG or JPEG image");
  const std::vector<unsigned char> png = readBytes(file.dir / "checker.png");
  std::ofstream(file.dir / "cut.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()), 40);
  expectError([](json& j) { j["images"][0]["uri"] = "cut.png"; }, "images[0] (\"cut.png\"): cannot decode it");
  expectError([](json& j) { j["textures"][0]["source"] = 9; }, "textures[0].source: expected an image 0..1, got 9");
  expectError([](json& j) { j["textures"][0]["sampler"] = 4; }, "textures[0].sampler: expected a sampler 0..0, got 4");
  expectError([](json& j) { j["samplers"][0]["wrapS"] = 12345; },
              "samplers[0].wrapS: expected 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT), got 12345");
  expectError([](json& j) { j["textures"][1] = {{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}; },
              "textures[1]: no PNG or JPEG image source (it has KHR_texture_basisu, which is not read)");
  expectError(
      [](json& j) {
        j["materials"][3]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]["scale"] = {1};
      },
      "materials[3] \"moved\".baseColorTexture.extensions.KHR_texture_transform.scale: expected two numbers");
  // An unused image that does not decode is no error: only textures a material reads are.
  file.j = good;
  file.j["images"].push_back({{"uri", "text.png"}});
  file.write();
  EXPECT_EQ(file.load().mesh.textures.size(), 2u);
}

}  // namespace
}  // namespace stirrup::rig
