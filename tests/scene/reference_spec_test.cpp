// scene/reference_spec.h: a scene's "reference" block read from JSON (every field, resolved
// against the scene file; bad fields are one-line errors naming the field), layer mode names and pixel
// rectangles as the command line gives them.
#include "scene/reference_spec.h"

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rig/error.h"
#include "scene/scene.h"
#include "tests/input_error.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;
using test::errorOf;

TEST(ReferenceBlock, ParsesEveryFieldRelativeToTheSceneFile) {
  const nlohmann::json j = nlohmann::json::parse(R"({
    "reference": {"file": "plates/p.jpg",
                  "grid": {"rows": 2, "columns": 6, "margins": [1, 2, 3, 4], "cell_crop": [5, 6, 7, 8], "snap": true},
                  "offset": 3, "rate": 0.5, "edge": "hold", "crop": [1, 1, 10, 10], "scale": 0.8,
                  "position": [12, -4], "flip_x": true, "shift_x": [1, 2], "mode": "side-by-side", "opacity": 0.25,
                  "label": "PLATE"}})");
  const SceneSpec s = parseScene(j, "/tmp/scenes/x.json");
  ASSERT_TRUE(s.reference.has_value());
  const ReferenceSpec& r = *s.reference;
  EXPECT_EQ(r.file, fs::path("/tmp/scenes/plates/p.jpg"));
  ASSERT_TRUE(r.grid.has_value());
  EXPECT_EQ(r.grid->columns, 6);
  EXPECT_EQ(r.grid->margin_bottom, 4);
  EXPECT_EQ(r.grid->cell_crop.height, 8);
  EXPECT_TRUE(r.grid->snap);
  EXPECT_EQ(r.offset, 3);
  EXPECT_DOUBLE_EQ(r.rate, 0.5);
  EXPECT_EQ(r.edge, FootageEdge::Hold);
  EXPECT_EQ(r.crop.width, 10);
  EXPECT_FLOAT_EQ(r.scale, 0.8f);
  EXPECT_FLOAT_EQ(r.position.y, -4.0f);
  EXPECT_TRUE(r.flip_x);
  EXPECT_EQ(r.shift_x, (std::vector<float>{1, 2}));
  EXPECT_EQ(r.mode, LayerMode::SideBySide);
  EXPECT_FLOAT_EQ(r.opacity, 0.25f);
  EXPECT_EQ(r.label, "PLATE");
  EXPECT_FALSE(parseScene(nlohmann::json::object(), "x.json").reference.has_value());
}

TEST(ReferenceBlock, BadFieldsAreOneLineErrorsNamingTheField) {
  const auto error = [](const std::string& reference) {
    return errorOf([&] { parseScene(nlohmann::json::parse("{\"reference\": " + reference + "}"), "s.json"); });
  };
  EXPECT_EQ(error(R"({})").rfind("s.json: reference.file:", 0), 0u) << error(R"({})");
  EXPECT_EQ(error(R"({"file": "a.jpg", "rate": 0})").rfind("s.json: reference.rate:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "scale": -2})").rfind("s.json: reference.scale:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "crop": [0, 0, 0, 4]})").rfind("s.json: reference.crop:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "grid": {"rows": 0}})").rfind("s.json: reference.grid.rows:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "grid": {"margins": [1, 2]}})").rfind("s.json: reference.grid.margins:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "edge": "wrap"})").rfind("s.json: reference.edge:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "mode": "multiply"})").rfind("s.json: reference.mode:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "opacity": 2})").rfind("s.json: reference.opacity:", 0), 0u);
  EXPECT_EQ(error(R"({"file": "a.jpg", "shift_x": [1, "x"]})").rfind("s.json: reference.shift_x[1]:", 0), 0u);
  EXPECT_NE(error(R"({"file": "a.jpg", "colour": 1})").find("colour"), std::string::npos);
  for (const std::string& e : {error(R"({"file": "a.jpg", "rate": 0})"), error(R"({"file": "a.jpg", "edge": "wrap"})")})
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(LayerMode, NamesRoundTripAndBadNameIsAnError) {
  for (LayerMode m : {LayerMode::SideBySide, LayerMode::Over, LayerMode::Difference, LayerMode::OnionSkin})
    EXPECT_EQ(parseLayerMode(layerModeName(m), "--mode"), m);
  EXPECT_EQ(parseLayerMode("onion", "x"), LayerMode::OnionSkin);
  const std::string e = errorOf([] { parseLayerMode("multiply", "--mode"); });
  EXPECT_EQ(e.rfind("--mode: expected side-by-side, over, difference or onion-skin, got \"multiply\"", 0), 0u) << e;
}

TEST(PixelRectText, XYWidthHeightOrAnErrorNamingTheOption) {
  const std::string e = errorOf([] { parsePixelRect("1,2,3", "--crop"); });
  EXPECT_EQ(e.rfind("--crop: expected x,y,width,height", 0), 0u) << e;
  EXPECT_NE(errorOf([] { parsePixelRect("0,0,0,5", "--crop"); }).find("--crop"), std::string::npos);
  EXPECT_NE(errorOf([] { parsePixelRect("-1,0,4,5", "--crop"); }).find("--crop"), std::string::npos);
  EXPECT_NE(errorOf([] { parsePixelRect("1,2,3,4 x", "--crop"); }).find("--crop"), std::string::npos);
  const PixelRect r = parsePixelRect("6,2,446,422", "--crop");
  EXPECT_EQ(r.x, 6);
  EXPECT_EQ(r.y, 2);
  EXPECT_EQ(r.width, 446);
  EXPECT_EQ(r.height, 422);
}

}  // namespace
}  // namespace stirrup::scene
