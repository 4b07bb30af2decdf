#include "scene/detail_level.h"

#include <cmath>

#include <gtest/gtest.h>

namespace stirrup::scene {
namespace {

Camera perspective(double fov_deg) {
  Camera c;
  c.projection = Camera::Projection::Perspective;
  c.position = {0.0, 0.0, 0.0};
  c.target = {0.0, 0.0, -1.0};  // looking down -z
  c.fov_deg = fov_deg;
  return c;
}

// A perspective camera of 90 degrees sees 2 d cm across its height at distance d, so a film 400 pixels
// high has 200 / d pixels a centimetre there, whichever way the point lies; the reach brings it nearer.
// An orthographic camera's scale is its film over its view's height, anywhere.
TEST(DetailLevel, PixelsPerCentimetreFromTheCamerasDefinition) {
  const Camera c = perspective(90.0);
  EXPECT_NEAR(pixelsPerCm(c, 400, {0.0, 0.0, -1000.0}), 0.2, 1e-12);
  EXPECT_NEAR(pixelsPerCm(c, 400, {600.0, 0.0, -800.0}), 0.2, 1e-12);   // 1000 away, off the axis
  EXPECT_NEAR(pixelsPerCm(c, 400, {0.0, 0.0, 1000.0}), 0.2, 1e-12);     // behind: as if in front
  EXPECT_NEAR(pixelsPerCm(c, 400, {0.0, 0.0, -1000.0}, 500.0), 0.4, 1e-12);
  EXPECT_GT(pixelsPerCm(c, 400, {0.0, 0.0, -100.0}, 250.0), 100.0);    // within its reach: as near as can be
  Camera o = c;
  o.projection = Camera::Projection::Orthographic;
  o.ortho_height_cm = 800.0;
  EXPECT_NEAR(pixelsPerCm(o, 400, {0.0, 0.0, -50000.0}), 0.5, 1e-12);
}

// The default horse's cell is 1.6 cm: level 1 once a 3.2 cm cell spans three quarters of a pixel or
// less, level 2 once a 6.4 cm cell does.
TEST(DetailLevel, SwitchesWhereTheCoarserCellSpansThreeQuartersOfAPixel) {
  EXPECT_EQ(kDetailSwitchCellPixels, 0.75);
  EXPECT_EQ(detailLevel(1.6, 1.0), 0);
  EXPECT_EQ(detailLevel(1.6, 0.75 / 3.2 * 1.001), 0);
  EXPECT_EQ(detailLevel(1.6, 0.75 / 3.2 * 0.999), 1);
  EXPECT_EQ(detailLevel(1.6, 0.75 / 6.4 * 1.001), 1);
  EXPECT_EQ(detailLevel(1.6, 0.75 / 6.4 * 0.999), 2);
  EXPECT_EQ(detailLevel(1.6, 1e-6), 2);
}

// A sphere is in view unless it lies wholly beyond a side of the frustum or behind the camera.
TEST(DetailLevel, SpheresInAndOutOfView) {
  const Camera c = perspective(90.0);  // 400 x 400: the sides are 45 degrees off the axis
  EXPECT_TRUE(sphereInView(c, 400, 400, {0.0, 0.0, -1000.0}, 10.0));
  EXPECT_TRUE(sphereInView(c, 400, 400, {990.0, 0.0, -1000.0}, 10.0));     // inside the right side
  EXPECT_FALSE(sphereInView(c, 400, 400, {1100.0, 0.0, -1000.0}, 10.0));   // 100 cm out: 71 from the plane
  EXPECT_TRUE(sphereInView(c, 400, 400, {1100.0, 0.0, -1000.0}, 80.0));    // its radius reaches back in
  EXPECT_FALSE(sphereInView(c, 400, 400, {0.0, 1100.0, -1000.0}, 10.0));   // above
  EXPECT_FALSE(sphereInView(c, 400, 400, {0.0, 0.0, 500.0}, 100.0));       // behind
  EXPECT_TRUE(sphereInView(c, 400, 400, {0.0, 0.0, 50.0}, 100.0));         // around the eye
  // A wide film sees farther to the sides than up: 2:1 at 90 degrees of height.
  EXPECT_TRUE(sphereInView(c, 800, 400, {1900.0, 0.0, -1000.0}, 10.0));
  EXPECT_FALSE(sphereInView(c, 800, 400, {0.0, 1900.0, -1000.0}, 10.0));
  Camera o = c;
  o.projection = Camera::Projection::Orthographic;
  o.ortho_height_cm = 400.0;  // 400 x 400 cm of view
  EXPECT_TRUE(sphereInView(o, 400, 400, {190.0, 0.0, -5000.0}, 20.0));
  EXPECT_FALSE(sphereInView(o, 400, 400, {230.0, 0.0, -5000.0}, 20.0));
}

// A pair out of view is at the coarsest level however near; in view, by its size.
TEST(DetailLevel, APairOutOfViewIsAtTheCoarsestLevel) {
  const Camera c = perspective(90.0);
  // 200 / d pixels a cm at d = distance - reach: full detail at 500 cm (0.8 px/cm); the 6.4 cm cell
  // is 0.75 pixels at d = 200 * 6.4 / 0.75.
  EXPECT_EQ(pairDetailLevel(c, 400, 400, {0.0, 0.0, -500.0}, 1.6), 0);
  EXPECT_EQ(pairDetailLevel(c, 400, 400, {0.0, 0.0, 500.0}, 1.6), kDetailLevels - 1);  // behind
  const double far = 200.0 * 6.4 / 0.75 + kPairReachCm;
  EXPECT_EQ(pairDetailLevel(c, 400, 400, {0.0, 0.0, -0.99 * far}, 1.6), 1);
  EXPECT_EQ(pairDetailLevel(c, 400, 400, {0.0, 0.0, -1.01 * far}, 1.6), 2);
}

}  // namespace
}  // namespace stirrup::scene
