#include "render/review/spine_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include <glm/geometric.hpp>

#include "render/review/plot_canvas.h"
#include "rig/error.h"

namespace stirrup::render {
namespace {

const Color kBackground = {0.97f, 0.97f, 0.95f};
const Color kPanelEdge = {0.80f, 0.80f, 0.78f};
const Color kGround = {0.70f, 0.70f, 0.68f};
const Color kFkColor = {0.55f, 0.55f, 0.55f};
const Color kCurveColor = {0.15f, 0.35f, 0.85f};
const Color kChainColor = {0.95f, 0.45f, 0.10f};
const Color kTwistColor = {0.10f, 0.60f, 0.25f};

}  // namespace

void writeSpinePlot(const std::vector<rig::SpineResult>& poses, const std::filesystem::path& file,
                    const SpinePlotStyle& style) {
  if (poses.empty()) throw rig::InputError(file.string() + ": no poses to plot");
  const int count = static_cast<int>(poses.size());
  const int perRow = std::min(count, style.poses_per_row);
  const int rows = (count + perRow - 1) / perRow;
  Canvas canvas(2 * perRow * style.panel_size, rows * style.panel_size, kBackground);

  // One scale for every panel, from the bounding box of everything drawn (FK chain included).
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const rig::SpineResult& r : poses) {
    for (const glm::dvec3& p : r.fk) lo = glm::min(lo, p), hi = glm::max(hi, p);
    for (const glm::dvec3& p : r.samples) lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  const glm::dvec3 size = glm::max(hi - lo, glm::dvec3(1e-9));
  const double usable = style.panel_size - 2.0 * style.margin;
  const double scale = usable / std::max({size.x, size.y, size.z});
  const glm::dvec3 mid = 0.5 * (lo + hi);
  const double tick = 0.05 * std::max({size.x, size.y, size.z});  // twist ticks, cm

  for (int i = 0; i < count; ++i) {
    const rig::SpineResult& r = poses[i];
    const int row = i / perRow, column = i % perRow;
    for (int view = 0; view < 2; ++view) {
      const double cx = (2.0 * column + view + 0.5) * style.panel_size, cy = (row + 0.5) * style.panel_size;
      // view 0: horizontal = world x; view 1: horizontal = world z. Image y grows downward.
      const auto project = [&](const glm::dvec3& p) {
        return glm::dvec2(cx + scale * (view == 0 ? p.x - mid.x : p.z - mid.z), cy - scale * (p.y - mid.y));
      };
      const double rootY = project(glm::dvec3(0.0)).y;
      const double left = cx - 0.5 * style.panel_size;
      const double top = cy - 0.5 * style.panel_size;
      // Panel frame: a strong line between poses, a faint one between the two views of a pose.
      canvas.line({left + 0.5, top}, {left + 0.5, top + style.panel_size}, view == 0 ? 2.0 : 1.0, kPanelEdge);
      canvas.line({left, top + 0.5}, {left + style.panel_size, top + 0.5}, 2.0, kPanelEdge);
      canvas.line({left + 8, rootY}, {left + style.panel_size - 8, rootY}, 1.0, kGround);  // the root's level
      for (int k = 0; k < 3; ++k) canvas.line(project(r.fk[k]), project(r.fk[k + 1]), 5.0, kFkColor);
      for (const glm::dvec3& p : r.fk) canvas.disk(project(p), 4.0, kFkColor);
      for (std::size_t k = 0; k + 1 < r.samples.size(); ++k)
        canvas.line(project(r.samples[k]), project(r.samples[k + 1]), 2.0, kCurveColor);
      for (std::size_t j = 0; j < r.joints.size(); ++j) {
        const rig::SpineJoint& joint = r.joints[j];
        if (j + 1 < r.joints.size())
          canvas.line(project(joint.position), project(r.joints[j + 1].position), 2.5, kChainColor);
        canvas.line(project(joint.position), project(joint.position + tick * (joint.rotation * glm::dvec3(0, 1, 0))),
                    1.5, kTwistColor);
        canvas.disk(project(joint.position), 2.5, kChainColor);
      }
      for (const glm::dvec3& p : r.curve_points) canvas.disk(project(p), 2.0, kCurveColor);
    }
  }

  if (!file.parent_path().empty()) std::filesystem::create_directories(file.parent_path());
  canvas.write(file);
}

}  // namespace stirrup::render
