#include "scene/rig_profile_json.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <charconv>
#include <map>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "tests/input_error.h"

#include "rig/error.h"
#include "rig/io/json_fields.h"
#include "rig/rider_rig.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;
using H = rig::HorseChannel;
using R = rig::RiderChannel;

const fs::path kProfiles = fs::path(STIRRUP_SOURCE_DIR) / "scenes" / "profiles";

using test::errorOf;

// A scratch JSON file in the test's own folder, removed with the fixture.
class ProfileFiles : public ::testing::Test {
 protected:
  fs::path dir_ = fs::temp_directory_path() / ("stirrup_profile_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                               "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path f = dir_ / name;
    std::ofstream(f) << text;
    return f;
  }
};

TEST(RigProfile, ThesisJsonHoldsTheThesisValuesAndCitesEveryKey) {
  const nlohmann::json j = rig::readJsonFile(kProfiles / "thesis.json");
  const rig::RigProfile thesis = rig::RigProfile::thesis();
  for (const rig::RigParameter& param : rig::rigParameters()) {
    const std::string key(param.key);
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_DOUBLE_EQ(j[key].get<double>(), param.get(thesis)) << key;
    ASSERT_TRUE(j["notes"].contains(key)) << key;
    const std::string note = j["notes"][key];
    const bool cites = note.rfind("Eq ", 0) == 0 || note.rfind("Units", 0) == 0 || note.find("Appendix B") != std::string::npos ||
                       note.rfind("Balance", 0) == 0 || note.rfind("Seat", 0) == 0;
    EXPECT_TRUE(cites) << key << ": " << note;
  }
  const rig::RigProfile loaded = loadRigProfile("thesis", kProfiles);
  EXPECT_EQ(loaded.name, "thesis");
  for (const rig::RigParameter& param : rig::rigParameters())
    EXPECT_DOUBLE_EQ(param.get(loaded), param.get(thesis)) << param.key;
}

TEST(RigProfile, EveryShippedProfileLoadsAndIsDocumented) {
  int count = 0;
  for (const auto& e : fs::directory_iterator(kProfiles)) {
    if (e.path().extension() != ".json") continue;
    ++count;
    const rig::RigProfile p = loadRigProfile(e.path().stem().string(), kProfiles);
    EXPECT_EQ(p.name, e.path().stem().string());
    EXPECT_FALSE(p.doc.empty()) << e.path();
    // Every parameter a profile sets has a note saying why.
    const nlohmann::json j = rig::readJsonFile(e.path());
    for (const auto& [key, value] : j.items())
      if (key != "name" && key != "doc" && key != "notes") {
        EXPECT_TRUE(j["notes"].contains(key)) << e.path() << " " << key;
      }
  }
  EXPECT_GE(count, 3);
}

TEST(RigProfile, LoadsByPathToo) {
  const rig::RigProfile p = loadRigProfile((kProfiles / "english.json").string(), "/nonexistent");
  EXPECT_EQ(p.name, "english");
}

// A gallop stride with the pairs spread out: the rider leans forward.
rig::HorseChannels spreadGallop() {
  rig::HorseChannels h;
  h[H::lfHoofTx] = h[H::rfHoofTx] = 50;
  h[H::lbHoofTx] = h[H::rbHoofTx] = -40;
  h[H::lfHoofTy] = 25;
  h[H::rearPivotRz] = 4;
  return h;
}

// The widest moment of a 2.8 m trot stride, hooves on the ground.
rig::HorseChannels trotSpread() {
  rig::HorseChannels h;
  h[H::lfHoofTx] = h[H::lbHoofTx] = 70;
  h[H::rfHoofTx] = h[H::rbHoofTx] = -70;
  h[H::lfHoofTy] = 8;
  h[H::rbHoofTy] = 8;
  return h;
}

TEST(RigProfile, EnglishSitsMoreUprightAndQuieterThanThesis) {
  const rig::RigProfile thesis = loadRigProfile("thesis", kProfiles);
  const rig::RigProfile english = loadRigProfile("english", kProfiles);
  const rig::RiderChannels t = rig::evaluateRider(spreadGallop(), thesis);
  const rig::RiderChannels e = rig::evaluateRider(spreadGallop(), english);
  EXPECT_GT(t[R::lowerBackRz], 0);
  EXPECT_LT(e[R::lowerBackRz], t[R::lowerBackRz]);                       // less lean
  EXPECT_LT(e[R::waistRz] / e[R::lowerBackRz], t[R::waistRz] / t[R::lowerBackRz]);  // straighter spine
  EXPECT_LT(e[R::headRz] - (-e[R::lowerBackRz] * .9), t[R::headRz] - (-t[R::lowerBackRz] * .9));  // eyes up
  EXPECT_LT(rig::evaluateRider(trotSpread(), english)[R::lWristTy], rig::evaluateRider(trotSpread(), thesis)[R::lWristTy]);
  rig::HorseChannels pitch;
  pitch[H::rearPivotRz] = 30;  // seat shift at its limit in both
  EXPECT_LT(rig::evaluateRider(pitch, english)[R::cogTx], rig::evaluateRider(pitch, thesis)[R::cogTx]);
}

TEST(RigProfile, NoviceBouncesMoreThanThesis) {
  const rig::RigProfile thesis = loadRigProfile("thesis", kProfiles);
  const rig::RigProfile novice = loadRigProfile("novice", kProfiles);
  const rig::RiderChannels t = rig::evaluateRider(trotSpread(), thesis);
  const rig::RiderChannels n = rig::evaluateRider(trotSpread(), novice);
  EXPECT_GT(n[R::cogTy], t[R::cogTy]);        // more lift
  EXPECT_GT(n[R::spineCTy], t[R::spineCTy]);  // more squash and stretch
  EXPECT_GT(n[R::neckTy], t[R::neckTy]);
  EXPECT_LT(n[R::headRz], t[R::headRz]);      // head nods further up with the bigger bounce
  EXPECT_GT(n[R::lWristTy], t[R::lWristTy]);  // hands bounce
  EXPECT_LT(n[R::lFootTz], t[R::lFootTz]);    // legs flap in against the belly
  rig::HorseChannels roll;
  roll[H::rearPivotRx] = 10;
  EXPECT_LT(rig::evaluateRider(roll, novice)[R::lowerBackRx], rig::evaluateRider(roll, thesis)[R::lowerBackRx]);
  rig::HorseChannels pitch;
  pitch[H::rearPivotRz] = 30;
  EXPECT_GT(rig::evaluateRider(pitch, novice)[R::cogTx], rig::evaluateRider(pitch, thesis)[R::cogTx]);
}

TEST(RigProfile, OverridesSetSingleParameters) {
  rig::RigProfile p = rig::RigProfile::thesis();
  applyProfileOverrides(p, {{"eq7.w2_scale", 0.02}, {"horse_unit_cm", 2.54}, {"eq10.lower_back_min", -25}}, "ctx");
  EXPECT_DOUBLE_EQ(p.eq7.w2_scale, 0.02);
  EXPECT_DOUBLE_EQ(p.horse_unit_cm, 2.54);
  EXPECT_DOUBLE_EQ(p.eq10.lower_back_min, -25);
  EXPECT_DOUBLE_EQ(p.eq7.w1_front_height, 2);  // untouched
  applyProfileOverrides(p, nlohmann::json::object(), "ctx");
  applyProfileOverrides(p, nullptr, "ctx");
  EXPECT_DOUBLE_EQ(p.eq7.w2_scale, 0.02);
}

TEST(RigProfile, OverrideErrorsNameTheContextAndTheKey) {
  rig::RigProfile p = rig::RigProfile::thesis();
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq1.w9", 1}}, "scenes/trot.json: profile_overrides"); }),
            "scenes/trot.json: profile_overrides: eq1.w9: unknown rig profile parameter (see docs/rider-rig.md for "
            "the parameter keys)");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq1.w1_pivot_pitch", "big"}}, "--set"); }),
            "--set: eq1.w1_pivot_pitch: expected a number, got \"big\"");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq8.shift_limit", true}}, "--set"); }),
            "--set: eq8.shift_limit: expected a number, got true");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"horse_unit_cm", 0}}, "--set"); }),
            "--set: horse_unit_cm: expected a number from 0.1 to 1000 (docs/rider-rig.md, valid ranges), got 0");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, nlohmann::json::array({1, 2}), "--set"); }),
            "--set: expected an object of parameter keys and numbers, got an array of 2");
}

TEST_F(ProfileFiles, FileErrorsNameTheFileAndTheKey) {
  const fs::path bad_type = write("x.json", R"({"eq1.w1_pivot_pitch": "big"})");
  EXPECT_EQ(errorOf([&] { loadRigProfile(bad_type.string(), dir_); }),
            bad_type.string() + ": eq1.w1_pivot_pitch: expected a number, got \"big\"");
  const fs::path unknown = write("y.json", R"({"doc": "d", "eq1.w1_pivotpitch": 0.1})");
  EXPECT_EQ(errorOf([&] { loadRigProfile("y", dir_); }),
            unknown.string() + ": eq1.w1_pivotpitch: unknown rig profile parameter (see docs/rider-rig.md for the "
                               "parameter keys)");
  const fs::path bad_note = write("z.json", R"({"notes": {"eq99.w1": "why"}})");
  EXPECT_EQ(errorOf([&] { loadRigProfile("z", dir_); }),
            bad_note.string() + ": notes.eq99.w1: unknown rig profile parameter (see docs/rider-rig.md for the "
                                "parameter keys)");
  const fs::path bad_doc = write("d.json", R"({"doc": 3})");
  EXPECT_EQ(errorOf([&] { loadRigProfile("d", dir_); }), bad_doc.string() + ": doc: expected a string, got 3");
  const fs::path not_object = write("a.json", "[1]");
  EXPECT_EQ(errorOf([&] { loadRigProfile("a", dir_); }), not_object.string() + ": expected a JSON object, got an array of 1");
  // A missing profile lists the ones that exist.
  EXPECT_EQ(errorOf([&] { loadRigProfile("cowboy", kProfiles); }),
            (kProfiles / "cowboy.json").string() + ": no such rig profile (expected one of english, novice, thesis)");
  // Every message is one line.
  EXPECT_EQ(errorOf([&] { loadRigProfile("y", dir_); }).find('\n'), std::string::npos);
  // A syntax error names the file (readJsonFile's message).
  write("s.json", "{\"eq1.w1_pivot_pitch\": ");
  EXPECT_NE(errorOf([&] { loadRigProfile("s", dir_); }).find("s.json"), std::string::npos);
}

// The issue's example: --set eq7.w2_scale=1e300 rendered a broken rider. Every parameter has a range.
TEST(RigProfileRanges, AValuePastItsRangeIsOneLineNamingKeyValueAndRange) {
  rig::RigProfile p = rig::RigProfile::thesis();
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq7.w2_scale", 1e300}}, "--set"); }),
            "--set: eq7.w2_scale: expected a number from -0.1 to 0.1 (docs/rider-rig.md, valid ranges), got 1e+300");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq9.w1_spine_divisor", 0}}, "scene.json: profile_overrides"); }),
            "scene.json: profile_overrides: eq9.w1_spine_divisor: expected a number from 0.6 to 60 (docs/rider-rig.md, "
            "valid ranges), got 0");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq8.shift_limit", -1}}, "--set"); }),
            "--set: eq8.shift_limit: expected a number from 0 to 1000 (docs/rider-rig.md, valid ranges), got -1");
  EXPECT_EQ(errorOf([&] { applyProfileOverrides(p, {{"eq10.lower_back_min", 5}}, "--set"); }),
            "--set: eq10.lower_back_min: expected a number from -180 to 0 (docs/rider-rig.md, valid ranges), got 5");
  // A rejected value leaves the profile as it was.
  EXPECT_EQ(p.eq7.w2_scale, 0.01);
  // The ends of a range are valid.
  applyProfileOverrides(p, {{"eq7.w2_scale", -0.1}, {"eq9.w1_spine_divisor", 60}, {"horse_unit_cm", 0.1}}, "--set");
  EXPECT_EQ(p.eq7.w2_scale, -0.1);
}

TEST_F(ProfileFiles, AFileValuePastItsRangeNamesTheFile) {
  const fs::path f = write("huge.json", R"({"doc": "d", "eq4.w1_lower_back": 170})");
  EXPECT_EQ(errorOf([&] { loadRigProfile("huge", dir_); }),
            f.string() + ": eq4.w1_lower_back: expected a number from -17 to 17 (docs/rider-rig.md, valid ranges), got 170");
}

// The ranges hold every value the project ships or tests: the thesis's, the shipped profiles', the golden
// sensitivity test's 10% perturbations (tests/cli/golden_sensitivity_test.cpp) and the prose's
// alternatives the thesis's code overrides (docs/rider-rig.md, decisions).
TEST(RigProfileRanges, HoldEveryShippedAndTestedValue) {
  for (const rig::RigParameter& param : rig::rigParameters()) {
    const double thesis = param.get(rig::RigProfile::thesis());
    EXPECT_TRUE(param.accepts(thesis)) << param.key << " = " << thesis;
    // A share or a blend (balance 1, the default) has no 10% headroom above 1.
    if (param.kind != rig::RangeKind::Fraction) {
      EXPECT_TRUE(param.accepts(thesis * 1.1)) << param.key;
    }
    EXPECT_TRUE(param.accepts(thesis * 0.9)) << param.key;
    EXPECT_LT(param.min, param.max) << param.key;
    if (param.kind == rig::RangeKind::Weight) {
      EXPECT_DOUBLE_EQ(param.max, 10 * std::abs(thesis)) << param.key;
      EXPECT_DOUBLE_EQ(param.min, -10 * std::abs(thesis)) << param.key;
    }
  }
  std::set<std::string> files;
  for (const auto& e : fs::directory_iterator(kProfiles)) {
    if (e.path().extension() != ".json") continue;
    files.insert(e.path().stem().string());
    const nlohmann::json j = rig::readJsonFile(e.path());
    for (const auto& [key, value] : j.items()) {
      const rig::RigParameter* param = rig::findRigParameter(key);
      if (param) {
        EXPECT_TRUE(param->accepts(value.get<double>())) << e.path() << ": " << key;
      }
    }
    EXPECT_NO_THROW(loadRigProfile(e.path().stem().string(), kProfiles)) << e.path();
  }
  EXPECT_EQ(files, (std::set<std::string>{"english", "novice", "thesis"}));
  // The prose's and the thesis code's alternatives (docs/rider-rig.md, decisions): a user restoring them
  // must not be refused.
  for (const auto& [key, value] : std::initializer_list<std::pair<const char*, double>>{
           {"eq14.h1_reach_gain", 0.8}, {"eq11.w1_pivot_roll", -1}, {"eq1.front_limited_lf_tx_offset", 2.5},
           {"eq12.rear_pivot_rz_rest", 0.572}, {"eq15.foot_tx_rest", 3}, {"eq15.w2_rig_scale", -6},
           {"eq17.rest_offset", 2}, {"knee.rest_offset", -1}, {"eq10.lower_back_min", -17}})
    EXPECT_TRUE(rig::findRigParameter(key)->accepts(value)) << key << " = " << value;
}

// docs/rider-rig.md's "Valid ranges" table lists every key with the range the code checks.
TEST(RigProfileRanges, DocumentedInTheRiderRigDoc) {
  std::ifstream in(fs::path(STIRRUP_SOURCE_DIR) / "docs" / "rider-rig.md");
  ASSERT_TRUE(in) << "docs/rider-rig.md";
  std::map<std::string, std::string> rows;  // key -> the rest of the row
  bool in_section = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) == 0) in_section = line.find("Valid ranges") != std::string::npos;
    if (!in_section || line.rfind("| `", 0) != 0) continue;
    const std::size_t end = line.find('`', 3);
    rows[line.substr(3, end - 3)] = line.substr(end + 1);
  }
  const auto text = [](double v) {
    char buf[32];
    const auto [e, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, e);
  };
  for (const rig::RigParameter& param : rig::rigParameters()) {
    ASSERT_TRUE(rows.count(std::string(param.key))) << param.key << " has no row in docs/rider-rig.md";
    const std::string& row = rows[std::string(param.key)];
    const std::string range = "| " + text(param.min) + " to " + text(param.max) + " | " + std::string(rig::rangeKindName(param.kind)) + " |";
    EXPECT_NE(row.find(range), std::string::npos) << param.key << ": expected \"" << range << "\" in its row:" << row;
  }
}

TEST_F(ProfileFiles, PartialProfileKeepsThesisValues) {
  write("p.json", R"({"name": "mine", "doc": "d", "eq4.w1_lower_back": 2.0, "notes": {"eq4.w1_lower_back": "why"}})");
  const rig::RigProfile p = loadRigProfile("p", dir_);
  EXPECT_EQ(p.name, "mine");
  EXPECT_DOUBLE_EQ(p.eq4.w1_lower_back, 2.0);
  EXPECT_DOUBLE_EQ(p.eq5.w1_lower_back, 0.8);
}

TEST(RigProfile, ToJsonRoundTripsThroughOverrides) {
  const rig::RigProfile english = loadRigProfile("english", kProfiles);
  nlohmann::json j = profileToJson(english);
  j.erase("name");
  j.erase("doc");
  rig::RigProfile p = rig::RigProfile::thesis();
  applyProfileOverrides(p, j, "roundtrip");
  for (const rig::RigParameter& param : rig::rigParameters()) EXPECT_DOUBLE_EQ(param.get(p), param.get(english)) << param.key;
}

}  // namespace
}  // namespace stirrup::scene
