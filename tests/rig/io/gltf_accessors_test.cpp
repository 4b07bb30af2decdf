// Checked glTF reads (rig/io/gltf_accessors.cpp) on small in-memory models whose bytes are written
// here: floats, normalised and plain integers, strided views, indices, and one-line errors naming
// `where` for an accessor that does not fit its buffer or a file that is no glTF.
#include "rig/io/gltf_accessors.h"

#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "tests/input_error.h"

namespace stirrup::rig {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

// A model with one buffer holding `bytes`, one view over all of it (with `stride`), and one accessor.
template <typename T>
tinygltf::Model model(const std::vector<T>& values, int component_type, int type, std::size_t count, bool normalized = false,
                      int stride = 0) {
  tinygltf::Model m;
  tinygltf::Buffer b;
  b.data.resize(values.size() * sizeof(T));
  std::memcpy(b.data.data(), values.data(), b.data.size());
  m.buffers.push_back(b);
  tinygltf::BufferView v;
  v.buffer = 0;
  v.byteLength = b.data.size();
  v.byteStride = static_cast<std::size_t>(stride);
  m.bufferViews.push_back(v);
  tinygltf::Accessor a;
  a.bufferView = 0;
  a.componentType = component_type;
  a.type = type;
  a.count = count;
  a.normalized = normalized;
  m.accessors.push_back(a);
  return m;
}

TEST(GltfAccessors, FloatsAndIntegersAsFloats) {
  EXPECT_EQ(readAccessor(model<float>({1.5f, -2, 3, 4, 5, 6}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 2), 0, 3, "w"),
            (std::vector<float>{1.5f, -2, 3, 4, 5, 6}));
  // Normalised bytes are 0..1 (51 / 255 = 0.2); plain bytes are their value.
  EXPECT_EQ(readAccessor(model<std::uint8_t>({0, 51, 255}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 3, true),
                         0, 1, "w"),
            (std::vector<float>{0.0f, 51.0f / 255.0f, 1.0f}));
  EXPECT_EQ(readAccessor(model<std::uint8_t>({0, 51, 255}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 3), 0, 1, "w"),
            (std::vector<float>{0, 51, 255}));
  EXPECT_EQ(readAccessor(model<std::uint16_t>({65535, 1000}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, 1, true),
                         0, 2, "w"),
            (std::vector<float>{1.0f, 1000.0f / 65535.0f}));
  EXPECT_EQ(readAccessor(model<std::uint32_t>({7, 70000}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, 2), 0, 1, "w"),
            (std::vector<float>{7, 70000}));
}

// Interleaved: each element is a VEC2 of floats followed by two floats of something else (16 bytes).
TEST(GltfAccessors, AStrideSkipsTheOtherAttributes) {
  const tinygltf::Model m =
      model<float>({1, 2, 99, 99, 3, 4, 99, 99, 5, 6, 99, 99}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 3, false, 16);
  EXPECT_EQ(readAccessor(m, 0, 2, "w"), (std::vector<float>{1, 2, 3, 4, 5, 6}));
}

TEST(GltfAccessors, AnAccessorWithoutAViewIsZeros) {
  tinygltf::Model m = model<float>({1, 2, 3}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 1);
  m.accessors[0].bufferView = -1;
  m.accessors[0].count = 2;
  EXPECT_EQ(readAccessor(m, 0, 3, "w"), std::vector<float>(6, 0.0f));
}

TEST(GltfAccessors, AccessorsThatDoNotFitAreOneLineErrors) {
  const tinygltf::Model floats = model<float>({1, 2, 3}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 1);
  EXPECT_EQ(errorOf([&] { readAccessor(floats, 1, 3, "x.glb: POSITION"); }),
            "x.glb: POSITION: accessor 1: no such accessor (the file has 1)");
  EXPECT_EQ(errorOf([&] { readAccessor(floats, 0, 2, "x.glb: POSITION"); }), "x.glb: POSITION: expected 2 components per element");
  tinygltf::Model past = floats;
  past.accessors[0].count = 2;  // 24 bytes from a 12-byte buffer
  EXPECT_EQ(errorOf([&] { readAccessor(past, 0, 3, "x.glb: POSITION"); }), "x.glb: POSITION: accessor runs past its buffer");
  tinygltf::Model unknown = floats;
  unknown.accessors[0].componentType = 5000;  // no type of glTF's
  EXPECT_EQ(errorOf([&] { readAccessor(unknown, 0, 3, "w"); }), "w: unknown component type 5000");
}

// Signed integers: normalised, -127 and -32767 are -1 and the one value below them clamps to -1 (glTF 2.0,
// section 3.11); plain, their value. Animation samplers use them for rotations.
TEST(GltfAccessors, SignedIntegers) {
  EXPECT_EQ(readAccessor(model<std::int8_t>({-128, -127, 0, 127}, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, 1, true), 0, 4, "w"),
            (std::vector<float>{-1.0f, -1.0f, 0.0f, 1.0f}));
  EXPECT_EQ(readAccessor(model<std::int16_t>({-32768, 16384}, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC2, 1, true), 0, 2, "w"),
            (std::vector<float>{-1.0f, 16384.0f / 32767.0f}));
  EXPECT_EQ(readAccessor(model<std::int8_t>({-5, 7}, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC2, 1), 0, 2, "w"),
            (std::vector<float>{-5.0f, 7.0f}));
}

// A sparse accessor: four zeros (no view) with elements 1 and 3 replaced (glTF 2.0, section 3.6.2.3);
// indices past the accessor and values past their buffer are one-line errors.
TEST(GltfAccessors, SparseElementsReplaceTheBase) {
  // Buffer: two unsigned short indices (1, 3), then two float values (10, 30).
  tinygltf::Model m = model<std::uint16_t>({1, 3, 0, 0x4120, 0, 0x41F0}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 2);
  tinygltf::BufferView values;
  values.buffer = 0;
  values.byteOffset = 4;
  values.byteLength = 8;
  m.bufferViews[0].byteLength = 4;
  m.bufferViews.push_back(values);
  tinygltf::Accessor& a = m.accessors[0];
  a.bufferView = -1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = 4;
  a.sparse.isSparse = true;
  a.sparse.count = 2;
  a.sparse.indices.bufferView = 0;
  a.sparse.indices.byteOffset = 0;  // (tinygltf leaves these unset until it reads a file)
  a.sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  a.sparse.values.bufferView = 1;
  a.sparse.values.byteOffset = 0;
  EXPECT_EQ(readAccessor(m, 0, 1, "w"), (std::vector<float>{0.0f, 10.0f, 0.0f, 30.0f}));
  tinygltf::Model past = m;
  past.accessors[0].count = 3;
  EXPECT_EQ(errorOf([&] { readAccessor(past, 0, 1, "w"); }), "w: sparse.indices[1]: 3 is past the accessor's 3 elements");
  tinygltf::Model short_values = m;
  short_values.bufferViews[1].byteLength = 4;
  EXPECT_EQ(errorOf([&] { readAccessor(short_values, 0, 1, "w"); }), "w: sparse.values: values run past their buffer");
  tinygltf::Model float_indices = m;
  float_indices.accessors[0].sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  EXPECT_EQ(errorOf([&] { readAccessor(float_indices, 0, 1, "w"); }),
            "w: sparse.indices: expected unsigned bytes, shorts or ints (componentType 5121, 5123 or 5125)");
}

TEST(GltfAccessors, IndicesOfEveryWidth) {
  EXPECT_EQ(readIndices(model<std::uint8_t>({0, 1, 2}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 3), 0, "w"),
            (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(readIndices(model<std::uint16_t>({3, 60000}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 2), 0, "w"),
            (std::vector<std::uint32_t>{3, 60000}));
  EXPECT_EQ(readIndices(model<std::uint32_t>({70000}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, 1), 0, "w"),
            (std::vector<std::uint32_t>{70000}));
  EXPECT_EQ(errorOf([] {
              readIndices(model<std::uint16_t>({1, 2}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 3), 0, "x.glb: indices");
            }),
            "x.glb: indices: indices run past the buffer");
}

// Whatever a file's accessors point at, a read is a one-line error naming `where` and what is missing,
// never an exception of another kind (the indices once threw std::out_of_range).
TEST(GltfAccessors, BadReferencesAreOneLineErrors) {
  const auto shorts = [] { return model<std::uint16_t>({0, 1, 2}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 3); };
  const tinygltf::Model m = shorts();
  EXPECT_EQ(errorOf([&] { readIndices(m, 4, "x.glb: meshes[0].primitives[0].indices"); }),
            "x.glb: meshes[0].primitives[0].indices: accessor 4: no such accessor (the file has 1)");
  EXPECT_EQ(errorOf([&] { readIndices(m, -1, "w"); }), "w: accessor -1: no such accessor (the file has 1)");
  tinygltf::Model bad_view = shorts();
  bad_view.accessors[0].bufferView = 3;
  EXPECT_EQ(errorOf([&] { readIndices(bad_view, 0, "w"); }), "w: bufferView 3: no such buffer view (the file has 1)");
  EXPECT_EQ(errorOf([&] { readAccessor(bad_view, 0, 1, "w"); }), "w: bufferView 3: no such buffer view (the file has 1)");
  tinygltf::Model no_view = shorts();
  no_view.accessors[0].bufferView = -1;
  EXPECT_EQ(errorOf([&] { readIndices(no_view, 0, "w"); }), "w: expected indices in a buffer view, got none");
  tinygltf::Model bad_buffer = shorts();
  bad_buffer.bufferViews[0].buffer = 2;
  EXPECT_EQ(errorOf([&] { readIndices(bad_buffer, 0, "w"); }), "w: bufferView 0.buffer 2: no such buffer (the file has 1)");
  EXPECT_EQ(errorOf([&] { readAccessor(bad_buffer, 0, 1, "w"); }), "w: bufferView 0.buffer 2: no such buffer (the file has 1)");
  const tinygltf::Model floats = model<float>({0, 1, 2}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 3);
  EXPECT_EQ(errorOf([&] { readIndices(floats, 0, "w"); }),
            "w: expected indices of unsigned bytes, shorts or ints (componentType 5121, 5123 or 5125), got 5126");
  tinygltf::Model pairs = shorts();
  pairs.accessors[0].type = TINYGLTF_TYPE_VEC2;
  EXPECT_EQ(errorOf([&] { readIndices(pairs, 0, "w"); }), "w: expected scalar indices, one a vertex");
  // A count no buffer could hold (its byte size would overflow 64 bits) runs past the buffer.
  tinygltf::Model huge = shorts();
  huge.accessors[0].count = std::size_t(1) << 62;
  EXPECT_EQ(errorOf([&] { readIndices(huge, 0, "w"); }), "w: indices run past the buffer");
  EXPECT_EQ(errorOf([&] { readAccessor(huge, 0, 1, "w"); }), "w: accessor runs past its buffer");
  // Within the buffer but past its view.
  tinygltf::Model past_view = shorts();
  past_view.bufferViews[0].byteLength = 4;
  EXPECT_EQ(errorOf([&] { readIndices(past_view, 0, "w"); }), "w: indices run past the buffer");
  EXPECT_EQ(readIndices(shorts(), 0, "w"), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(GltfAccessors, FilesReadOrSayWhyNot) {
  const fs::path dir = fs::temp_directory_path() / ("stirrup_gltf_accessors_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  tinygltf::Model m = model<float>({1, 2, 3}, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 1);
  m.asset.version = "2.0";
  tinygltf::TinyGLTF w;
  ASSERT_TRUE(w.WriteGltfSceneToFile(&m, (dir / "one.glb").string(), true, true, true, true));
  const tinygltf::Model back = readGltfFile(dir / "one.glb", "one.glb");
  EXPECT_EQ(readAccessor(back, 0, 3, "one.glb"), (std::vector<float>{1, 2, 3}));
  std::ofstream(dir / "junk.glb") << "not a glb";
  EXPECT_EQ(errorOf([&] { readGltfFile(dir / "junk.glb", "scene.json: horse"); }).rfind("scene.json: horse: not a readable glTF file (", 0),
            0u);
  const std::string missing = errorOf([&] { readGltfFile(dir / "gone.gltf", "scene.json: rider"); });
  EXPECT_EQ(missing.rfind("scene.json: rider: not a readable glTF file (", 0), 0u) << missing;
  EXPECT_EQ(missing.find('\n'), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace stirrup::rig
