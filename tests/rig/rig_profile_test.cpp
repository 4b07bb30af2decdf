#include "rig/rig_profile.h"

#include <set>
#include <string>

#include <gtest/gtest.h>

namespace stirrup::rig {
namespace {

TEST(RigProfile, EveryKeyNamesItsEquationOrSource) {
  std::set<std::string> keys;
  for (const RigParameter& param : rigParameters()) {
    const std::string key(param.key);
    EXPECT_TRUE(keys.insert(key).second) << "duplicate " << key;
    const bool named = key.rfind("eq", 0) == 0 || key.rfind("knee.", 0) == 0 || key.rfind("hair.", 0) == 0 ||
                       key.rfind("cloth.", 0) == 0 || key.find("_unit_cm") != std::string::npos ||
                       key.rfind("balance", 0) == 0 || key.rfind("seat.", 0) == 0;
    EXPECT_TRUE(named) << key;
    EXPECT_FALSE(param.cites.empty()) << key;
  }
  // Each parameter's accessor reaches its own field: setting one key changes exactly one value.
  for (const RigParameter& param : rigParameters()) {
    RigProfile p = RigProfile::thesis();
    param.field(p) = 12345;
    for (const RigParameter& other : rigParameters())
      if (other.key != param.key) {
        EXPECT_NE(other.get(p), 12345) << param.key << " aliases " << other.key;
      }
  }
}

TEST(RigProfile, RigidRiderIsTheThesisWithEveryChannelAtRest) {
  const RigProfile rigid = RigProfile::rigidRider();
  EXPECT_TRUE(rigid.rigid);
  EXPECT_EQ(rigid.name, "rigid");
  EXPECT_FALSE(RigProfile::thesis().rigid);
  for (const RigParameter& param : rigParameters())
    EXPECT_DOUBLE_EQ(param.get(rigid), param.get(RigProfile::thesis())) << param.key;
}

}  // namespace
}  // namespace stirrup::rig
