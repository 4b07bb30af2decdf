// A scene's horse and rider as the rig rides them (scene/ridden_pair.cpp): the generated pair as it was
// built, and a user's standing rider seated by the rig with the profile's stirrup leathers and a fold
// guard. How well she sits is tested with the seating (rig/characters/seating_test.cpp).
#include "scene/ridden_pair.h"

#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "rig/rig_profile.h"
#include "tests/rig/default_characters.h"
#include "tests/rig/user_riders.h"

namespace stirrup::scene {
namespace {

namespace fs = std::filesystem;

TEST(RiddenPair, TheGeneratedPairRidesAsBuilt) {
  const RiddenPair pair = resolveRiddenPair("default", "", "default", "", rig::RigProfile::thesis());
  EXPECT_FALSE(pair.seat.seated_by_rig);
  EXPECT_TRUE(pair.seat.added_points.empty());
  EXPECT_TRUE(pair.rider.fold_guard.empty());
  const rig::Character& built = rig::test::defaultRider();
  ASSERT_EQ(pair.rider.skeleton.size(), built.skeleton.size());
  for (int j = 0; j < int(built.skeleton.size()); ++j)
    EXPECT_EQ(pair.rider.skeleton.restPosition(j), built.skeleton.restPosition(j)) << j;
  EXPECT_EQ(pair.horse.skeleton.restPosition(pair.horse.role("lStirrup")),
            rig::test::defaultHorse().skeleton.restPosition(rig::test::defaultHorse().role("lStirrup")));
}

// A standing user's rider: the rig seats her and sets the leathers by the profile's holes; two holes
// up hang the treads higher under the seat than none.
TEST(RiddenPair, AUsersRiderIsSeatedWithTheProfilesLeathers) {
  const fs::path dir = fs::temp_directory_path() / ("stirrup_ridden_pair_test_" + std::to_string(::getpid()));
  const rig::test::UserRiderFiles files = rig::test::writeUserRider(rig::test::userRiderSpecs().front(), dir);
  rig::RigProfile none = rig::RigProfile::thesis(), two = rig::RigProfile::thesis();
  none.seat.stirrup_holes_up = 0;
  two.seat.stirrup_holes_up = 2;
  const RiddenPair low = resolveRiddenPair("default", "", files.glb.string(), files.mapping.string(), none);
  const RiddenPair high = resolveRiddenPair("default", "", files.glb.string(), files.mapping.string(), two);
  fs::remove_all(dir);
  ASSERT_TRUE(low.seat.seated_by_rig);
  ASSERT_TRUE(high.seat.seated_by_rig);
  EXPECT_EQ(low.seat.stirrup_holes_up, 0.0f);
  EXPECT_EQ(high.seat.stirrup_holes_up, 2.0f);
  EXPECT_LT(high.seat.tread_below_seat_cm, low.seat.tread_below_seat_cm);
  const auto tread = [](const RiddenPair& p) { return p.horse.skeleton.restPosition(p.horse.role("lStirrup")).y; };
  EXPECT_GT(tread(high), tread(low));
  EXPECT_FALSE(low.rider.fold_guard.empty());  // a rider the rig seated keeps out of the horse's neck
}

}  // namespace
}  // namespace stirrup::scene
