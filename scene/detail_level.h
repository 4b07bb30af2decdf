// Levels of detail for a crowd's pairs (issue 19: "distant pairs at a lower level of detail, chosen
// from the pair's size on screen, without a visible pop: switch at a stated pixel size").
//
// A level is the same character generator run on a coarser polygonisation grid: level k's meshes are
// built at 2^k times the character's own cell (HorseParams::cell, RiderParams::cell), so a level has
// about a quarter of the triangles of the one before (the surfaces are the same implicit bodies, only
// sampled more coarsely; the skeleton is the same). A pair is drawn at the coarsest level whose
// horse's cell spans at most kDetailSwitchCellPixels pixels at the pair's nearest point to the camera:
// for the default horse (cell 1.6 cm, 160 cm at the withers) that is level 1 once its withers are
// under 37.5 pixels tall and level 2 under 19, at any resolution. A cell of under a pixel moves the
// silhouette by under a pixel, so a switch changes few pixels (tests/render/shot_test.cpp measures it
// on a frame: under 0.5% of the frame's pixels). A pair wholly outside the view, with room for its
// shadow, is drawn at the coarsest level: only its shadow could reach the frame, and nothing of it
// while its whole reach and its shadow's are out (a telephoto view of a troop sees a few of 30 pairs).
#pragma once

#include <glm/vec3.hpp>

#include "scene/camera.h"

namespace stirrup::scene {

inline constexpr int kDetailLevels = 3;
// Level k's cell is the character's cell times this.
inline constexpr float kDetailCellFactor[kDetailLevels] = {1.0f, 2.0f, 4.0f};
// The switch (our choice): a level is used while its horse cell covers at most this many pixels. At a
// whole pixel the first switch changed 0.53% of a 640 x 360 frame's pixels (by at least 1/255 in one
// channel), at three quarters 0.3% (tests/render/shot_test.cpp).
inline constexpr double kDetailSwitchCellPixels = 0.75;
// How far any part of a pair reaches from its horse's root (the rear pivot): the muzzle is about 200 cm
// ahead of it on the default horse (horse_character.h: hips x -60, muzzle x 140), the largest horse
// of a crowd (175 cm) is 9% larger, and the rider's head is nearer. The level is chosen at the root's
// distance less this, so the pair's nearest part decides.
inline constexpr double kPairReachCm = 250.0;

// How far a pair's shadow reaches past the pair on the ground (our choice, for the scenes' suns, 35
// degrees or more above the horizon): a 250 cm tall pair casts at most 360 cm of shadow, less its reach.
inline constexpr double kPairShadowReachCm = 200.0;

// Whether any of the sphere can be in the view of `camera` on a width x height film: false only when
// it lies wholly outside one of the frustum's four sides or behind the camera.
bool sphereInView(const Camera& camera, int width, int height, const glm::dvec3& centre, double radius);

// Pixels per centimetre at `point` seen through `camera` on a film `height` pixels high: the
// orthographic view's scale, or a perspective camera's at the point's distance (not its depth: a pair
// beside or behind the camera is sized as if in front, so its shadow in view is never coarser than the
// pair would be there).
double pixelsPerCm(const Camera& camera, int height, const glm::dvec3& point, double reach_cm = 0.0);

// The level (0 = full detail) for a horse of this cell at this scale: the coarsest whose cell spans at
// most kDetailSwitchCellPixels.
int detailLevel(double horse_cell_cm, double pixels_per_cm);
// A pair's level: the coarsest when out of view (its reach and shadow, sphereInView), else by its size
// at its nearest point (pixelsPerCm less kPairReachCm).
int pairDetailLevel(const Camera& camera, int width, int height, const glm::dvec3& horse_root, double horse_cell_cm);

}  // namespace stirrup::scene
