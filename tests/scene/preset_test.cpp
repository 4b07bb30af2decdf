#include "scene/preset.h"

#include <set>
#include <string>

#include <gtest/gtest.h>

#include "rig/error.h"

namespace stirrup::scene {
namespace {

std::string presetError(const std::string& name) {
  try {
    findPreset(name);
  } catch (const rig::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(QualityPreset, DraftReviewFinalInThatOrder) {
  const auto presets = qualityPresets();
  ASSERT_EQ(presets.size(), 3u);
  EXPECT_EQ(presets[0].name, "draft");
  EXPECT_EQ(presets[1].name, "review");
  EXPECT_EQ(presets[2].name, "final");
}

TEST(QualityPreset, EachPresetCostsMoreThanTheOneBefore) {
  const auto p = qualityPresets();
  for (size_t i = 0; i < p.size(); ++i) {
    EXPECT_GE(p[i].samples, 1);
    EXPECT_GE(p[i].light_samples, 1);
    EXPECT_GE(p[i].ao_samples, 1);
  }
  auto rays = [](const QualityPreset& q) { return q.samples * (1 + q.light_samples + q.ao_samples); };
  EXPECT_LT(rays(p[0]), rays(p[1]));
  EXPECT_LT(rays(p[1]), rays(p[2]));
}

TEST(QualityPreset, DraftWritesItsPngsStoredTheOthersAtLevelOne) {
  SceneSpec scene;
  applyPreset(scene, findPreset("draft"));
  EXPECT_EQ(defaultPngCompression(scene), 0);
  applyPreset(scene, findPreset("review"));
  EXPECT_EQ(defaultPngCompression(scene), 1);
  applyPreset(scene, findPreset("final"));
  EXPECT_EQ(defaultPngCompression(scene), 1);
  // One camera sample a pixel but four sky rays each is not a draft.
  applyPreset(scene, findPreset("draft"));
  scene.ao_samples = 4;
  EXPECT_EQ(defaultPngCompression(scene), 1);
}

TEST(QualityPreset, FindsEachByName) {
  for (const QualityPreset& p : qualityPresets()) EXPECT_EQ(&findPreset(p.name), &p);
}

TEST(QualityPreset, AnUnknownNameIsAOneLineError) {
  EXPECT_EQ(presetError("fast"), "--preset: expected draft, review or final, got fast");
  EXPECT_EQ(presetError("Draft"), "--preset: expected draft, review or final, got Draft");
}

TEST(QualityPreset, ApplySetsTheScenesSampleCounts) {
  SceneSpec scene;
  const QualityPreset& final_preset = findPreset("final");
  applyPreset(scene, final_preset);
  EXPECT_EQ(scene.samples, final_preset.samples);
  EXPECT_EQ(scene.light_samples, final_preset.light_samples);
  EXPECT_EQ(scene.ao_samples, final_preset.ao_samples);
}

TEST(QualityPreset, ASceneNamesItsPreset) {
  const SceneSpec s = parseScene(nlohmann::json::parse(R"({"quality": "draft"})"), "scenes/x.json");
  const QualityPreset& draft = findPreset("draft");
  EXPECT_EQ(s.samples, draft.samples);
  EXPECT_EQ(s.light_samples, draft.light_samples);
  EXPECT_EQ(s.ao_samples, draft.ao_samples);
}

TEST(QualityPreset, ExplicitFieldsOverrideTheScenesPreset) {
  const SceneSpec s =
      parseScene(nlohmann::json::parse(R"({"quality": {"preset": "final", "samples": 8}})"), "scenes/x.json");
  const QualityPreset& final_preset = findPreset("final");
  EXPECT_EQ(s.samples, 8);
  EXPECT_EQ(s.light_samples, final_preset.light_samples);
  EXPECT_EQ(s.ao_samples, final_preset.ao_samples);
}

TEST(QualityPreset, ASceneWithAnUnknownPresetIsAOneLineError) {
  for (const char* text : {R"({"quality": "fast"})", R"({"quality": {"preset": "fast"}})"}) {
    try {
      parseScene(nlohmann::json::parse(text), "scenes/x.json");
      ADD_FAILURE() << text << " was accepted";
    } catch (const rig::InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("scenes/x.json: quality", 0), 0u) << message;
      EXPECT_NE(message.find("expected \"draft\", \"review\" or \"final\", got \"fast\""), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace stirrup::scene
