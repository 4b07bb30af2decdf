// A horse-sized stand-in (about 100k triangles: body, neck, head, four swinging legs, a rider) for
// judging the look and measuring speed. Off by default; run with
//   STIRRUP_RENDER_SAMPLE=/tmp/render_sample.png render_tests --gtest_filter='RendererBenchmark.*'
// to write the sample frame and print ms/frame for each BVH update mode.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <ctime>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "render/renderer.h"

namespace stirrup::render {
namespace {

// An ellipsoid that can swing about a pivot around the Z axis (legs swing fore and aft).
struct Part {
  glm::vec3 centre, radii;
  int rings, segments;
  glm::vec3 color;
  glm::vec3 pivot{0.0f};
  float swing_deg = 0.0f, phase = 0.0f;
};

struct StandIn {
  std::vector<Part> parts;
  std::vector<uint32_t> indices;
  std::vector<glm::vec3> colors, positions, normals;

  StandIn() {
    const glm::vec3 coat{0.22f, 0.11f, 0.05f}, leg{0.10f, 0.06f, 0.04f}, shirt{0.70f, 0.70f, 0.66f},
        skin{0.55f, 0.36f, 0.27f}, breeches{0.55f, 0.50f, 0.40f};
    parts = {
        {{0, 128, 0}, {105, 36, 32}, 100, 200, coat},                        // barrel
        {{95, 165, 0}, {22, 45, 16}, 30, 60, coat},                          // neck
        {{128, 190, 0}, {30, 13, 11}, 30, 60, coat},                         // head
        {{-95, 140, 0}, {8, 30, 8}, 20, 40, leg, {0, 0, 0}, 0.0f, 0.0f},     // tail
        {{0, 196, 0}, {16, 34, 19}, 60, 120, shirt},                         // rider torso
        {{2, 244, 0}, {11, 12, 11}, 40, 80, skin},                           // rider head
        {{5, 150, 24}, {26, 8, 8}, 20, 40, breeches},                        // rider thighs
        {{5, 150, -24}, {26, 8, 8}, 20, 40, breeches},
    };
    // Legs: hip at y = 110, hoof at the ground; diagonal pairs in phase, as in a trot.
    const float xs[4] = {70, 70, -70, -70}, zs[4] = {18, -18, 18, -18}, phases[4] = {0, 0.5f, 0.5f, 0};
    for (int i = 0; i < 4; ++i) {
      parts.push_back({{xs[i], 55, zs[i]}, {7, 55, 7}, 40, 80, leg, {xs[i], 110, zs[i]}, 22.0f, phases[i]});
    }
    for (const Part& p : parts) {
      const auto base = uint32_t(colors.size());
      const auto at = [&](int r, int s) { return base + uint32_t(r * (p.segments + 1) + s); };
      for (int i = 0; i < (p.rings + 1) * (p.segments + 1); ++i) colors.push_back(p.color);
      for (int r = 0; r < p.rings; ++r) {
        for (int s = 0; s < p.segments; ++s) {
          indices.insert(indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s)});
          indices.insert(indices.end(), {at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
        }
      }
    }
    positions.resize(colors.size());
    normals.resize(colors.size());
  }

  // The pose at time t (seconds): legs swing, the body bobs, everything travels along +X.
  void pose(double t, float travel) {
    size_t v = 0;
    const float bob = 4.0f * float(std::sin(2.0 * std::numbers::pi * 2.5 * t));
    for (const Part& p : parts) {
      const float angle = p.swing_deg * std::numbers::pi_v<float> / 180.0f *
                          float(std::sin(2.0 * std::numbers::pi * (1.25 * t + p.phase)));
      const float c = std::cos(angle), s = std::sin(angle);
      const float lift = p.swing_deg > 0.0f ? 0.0f : bob;
      for (int r = 0; r <= p.rings; ++r) {
        const float theta = std::numbers::pi_v<float> * float(r) / float(p.rings);
        for (int k = 0; k <= p.segments; ++k, ++v) {
          const float phi = 2.0f * std::numbers::pi_v<float> * float(k) / float(p.segments);
          const glm::vec3 u(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
          glm::vec3 q = p.centre + p.radii * u - p.pivot;
          glm::vec3 n = glm::normalize(u / p.radii);
          q = {c * q.x - s * q.y, s * q.x + c * q.y, q.z};
          n = {c * n.x - s * n.y, s * n.x + c * n.y, n.z};
          positions[v] = q + p.pivot + glm::vec3(travel, lift, 0.0f);
          normals[v] = n;
        }
      }
    }
  }
};

TEST(RendererBenchmark, ReviewQualityStandIn) {
  const char* sample = std::getenv("STIRRUP_RENDER_SAMPLE");
  if (!sample) GTEST_SKIP() << "set STIRRUP_RENDER_SAMPLE=/path/to/sample.png to run";
  auto env = [](const char* name, int fallback) {
    const char* v = std::getenv(name);
    return v ? std::atoi(v) : fallback;
  };
  const int frames = env("STIRRUP_BENCH_FRAMES", 6);
  const int modes = env("STIRRUP_BENCH_MODES", 3);  // 1: Rebuild only
  StandIn horse;
  std::printf("stand-in: %zu triangles\n", horse.indices.size() / 3);
  const BvhUpdate all_modes[3] = {BvhUpdate::Rebuild, BvhUpdate::RebuildPerMesh, BvhUpdate::Refit};
  for (int m = 0; m < modes; ++m) {
    const BvhUpdate mode = all_modes[m];
    RenderSettings settings;  // review quality: 640 x 360, 16 spp, 4 sun, 4 sky rays
    settings.bvh_update = mode;
    settings.samples_per_pixel = env("STIRRUP_BENCH_SPP", settings.samples_per_pixel);
    settings.light_samples = env("STIRRUP_BENCH_LIGHT", settings.light_samples);
    settings.ao_samples = env("STIRRUP_BENCH_AO", settings.ao_samples);
    settings.threads = env("STIRRUP_BENCH_THREADS", 0);
    Renderer renderer(settings);
    const int mesh = renderer.addMesh({ObjectId::Horse, horse.indices, horse.colors, horse.positions.size()});
    double commit = 0, trace = 0, total = 0;
    const std::clock_t cpu0 = std::clock();
    Image image;
    for (int frame = 1; frame <= frames; ++frame) {
      const double t = (frame - 1) / 24.0;
      const float travel = float(360.0 * t);
      Camera camera;
      camera.position = {travel + 250.0, 170.0, 750.0};
      camera.target = {travel, 100.0, 0.0};
      camera.fov_deg = 30.0;
      const auto t0 = std::chrono::steady_clock::now();
      horse.pose(t, travel);
      renderer.updateMesh(mesh, horse.positions, horse.normals);
      image = renderer.render(camera, frame);
      total += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      commit += renderer.lastStats().commit_ms;
      trace += renderer.lastStats().trace_ms;
    }
    const double cpu_ms = 1000.0 * double(std::clock() - cpu0) / CLOCKS_PER_SEC / frames;
    std::printf("%-15s %dx%d %d spp %d sun %d sky, %d frames: %.1f ms/frame wall (commit %.1f, trace %.1f), "
                "%.1f ms/frame CPU over all threads\n",
                mode == BvhUpdate::Rebuild ? "Rebuild" : mode == BvhUpdate::Refit ? "Refit" : "RebuildPerMesh",
                settings.width, settings.height, settings.samples_per_pixel, settings.light_samples,
                settings.ao_samples, frames, total / frames, commit / frames, trace / frames, cpu_ms);
    if (mode == BvhUpdate::Rebuild) {
      writePng(image, sample);
      std::filesystem::path exr = sample;
      writeExr(image, exr.replace_extension(".exr"), {{"stirrup:frame", std::to_string(frames)}});
    }
  }
}

}  // namespace
}  // namespace stirrup::render
