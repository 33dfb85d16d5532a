// The accuracy report's marble regions (bench/src/accuracy_metrics.h: marbles, floor_by_marbles)
// on a small frame, against a C++ reference that finds what each pixel centre sees
// analytically: camera rays built from the camera's basis (not its matrices), ray-sphere and
// ray-floor intersections in double precision, the one-pixel erosion applied to its own labels.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "bench/src/accuracy_marbles.h"
#include "bench/src/accuracy_metrics.h"
#include "scene/demo_scene.h"
#include "truth/path_tracer.h"

namespace rp::bench {
namespace {

uint16_t bit(Region r) { return uint16_t(1u << unsigned(r)); }

// Nearest positive t of the ray o + t d (d unit) on a sphere, if any.
std::optional<double> hit_sphere(glm::dvec3 o, glm::dvec3 d, const scene::Sphere& s) {
  const glm::dvec3 oc = o - glm::dvec3(s.center);
  const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - double(s.radius) * s.radius;
  const double disc = b * b - c;
  if (disc < 0.0) return std::nullopt;
  const double t = -b - std::sqrt(disc);
  return t > 0.0 ? std::optional<double>(t) : std::nullopt;
}

// What the reference sees at a pixel centre: 0 anything else, 1 a marble, 2 floor beside a
// resting marble.
enum RefLabel { kOther, kMarbleRef, kRingRef };

std::vector<RefLabel> reference_labels(const scene::FrameScene& frame, uint32_t w, uint32_t h) {
  const scene::Camera& cam = frame.camera;
  const glm::dvec3 eye(cam.position);
  const glm::dvec3 fwd = glm::normalize(glm::dvec3(cam.target) - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(fwd, glm::dvec3(cam.up)));
  const glm::dvec3 up = glm::cross(right, fwd);
  const double tan_half = std::tan(glm::radians(double(cam.fov_y_deg)) / 2.0);
  const double aspect = double(w) / double(h);
  std::vector<RefLabel> out(size_t(w) * h, kOther);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const double sx = 2.0 * (x + 0.5) / w - 1.0, sy = 1.0 - 2.0 * (y + 0.5) / h;
      const glm::dvec3 d =
          glm::normalize(fwd + sx * tan_half * aspect * right + sy * tan_half * up);
      double best = std::numeric_limits<double>::infinity();
      RefLabel label = kOther;
      for (const scene::Sphere& s : frame.spheres)
        if (const auto t = hit_sphere(eye, d, s); t && *t < best) {
          best = *t;
          label = s.emission == glm::vec3(0.0f) ? kMarbleRef : kOther;
        }
      // The floor y = -1 inside the box: from the camera (outside the open side z = 1) a ray to
      // a floor point inside the box meets no wall, the ceiling or the lamp first.
      if (d.y < 0.0) {
        const double t = (-1.0 - eye.y) / d.y;
        const glm::dvec3 p = eye + t * d;
        if (t < best && std::abs(p.x) < 1.0 && std::abs(p.z) < 1.0) {
          label = kOther;
          for (const scene::Sphere& s : frame.spheres) {
            const bool resting = s.emission == glm::vec3(0.0f) &&
                                 std::abs(double(s.center.y) - s.radius + 1.0) < 1e-4;
            const double r = kMarbleContactRadii * double(s.radius);
            const double dx = p.x - s.center.x, dz = p.z - s.center.z;
            if (resting && dx * dx + dz * dz < r * r) label = kRingRef;
          }
        }
      }
      out[size_t(y) * w + x] = label;
    }
  // The erosion: a region keeps a pixel only when its four neighbours carry the same label.
  std::vector<RefLabel> eroded(out.size(), kOther);
  for (uint32_t y = 1; y + 1 < h; ++y)
    for (uint32_t x = 1; x + 1 < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (out[i - 1] == out[i] && out[i + 1] == out[i] && out[i - w] == out[i] &&
          out[i + w] == out[i])
        eroded[i] = out[i];
    }
  return eroded;
}

// The room alone (no tumblers, whose meshes the analytic reference does not trace) with resting
// marbles, a touching pair, a marble in the air and a resting fireball.
scene::FrameScene room_with_spheres() {
  scene::FrameScene f;
  scene::add_room_instances(f);
  auto sphere = [&f](float x, float y, float z, float r, glm::vec3 emission) {
    scene::Sphere s;
    s.center = s.prev_center = glm::vec3(x, y, z);
    s.radius = r;
    s.albedo = glm::vec3(0.9f, 0.2f, 0.2f);
    s.emission = emission;
    f.spheres.push_back(s);
  };
  const glm::vec3 none(0.0f);
  sphere(-0.3f, -0.96f, 0.6f, 0.04f, none);   // resting marbles
  sphere(0.2f, -0.95f, 0.5f, 0.05f, none);
  sphere(-0.05f, -0.96f, 0.75f, 0.04f, none); // a touching pair
  sphere(0.03f, -0.96f, 0.75f, 0.04f, none);
  sphere(0.45f, -0.80f, 0.7f, 0.04f, none);   // in the air: a marble, but no floor disc
  sphere(-0.5f, -0.94f, 0.3f, 0.06f, glm::vec3(8.0f, 3.0f, 0.5f));  // a fireball on the floor
  return f;
}

TEST(AccuracyMarbles, MarbleRegionsMatchAnAnalyticReference) {
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  truth::PathTracer tracer(assets);
  const scene::FrameScene frame = room_with_spheres();
  const uint32_t w = 160, h = 120;  // not square: the aspect enters the rays
  const std::vector<uint16_t> labels =
      classify_regions(tracer.primary_hits(frame, w, h), w, h, frame.spheres);
  const std::vector<RefLabel> ref = reference_labels(frame, w, h);
  size_t marbles = 0, rings = 0, wrong = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    const bool m = labels[i] & bit(Region::kMarble), r = labels[i] & bit(Region::kFloorByMarbles);
    marbles += m;
    rings += r;
    if (m != (ref[i] == kMarbleRef) || r != (ref[i] == kRingRef)) ++wrong;
    // A floor pixel beside a marble is in no other floor region.
    if (r) {
      EXPECT_FALSE(labels[i] & (bit(Region::kFloorLit) | bit(Region::kFloorShadow)));
    }
  }
  EXPECT_EQ(wrong, 0u);
  // Both regions are there (at this size 0.02 world units a pixel on the floor, which the
  // camera sees at about 25 degrees: a disc of radius 0.1 is about 30 pixels before the
  // erosion and the marble's own cover).
  EXPECT_GT(marbles, 15u) << marbles;
  EXPECT_GT(rings, 30u) << rings;

  // Without the sphere list (the main and direct sections), no pixel is in either region and
  // the floor beside the marbles is plain floor again.
  const std::vector<uint16_t> plain = classify_regions(tracer.primary_hits(frame, w, h), w, h);
  size_t floor_plain = 0, floor_marbled = 0;
  for (size_t i = 0; i < plain.size(); ++i) {
    EXPECT_FALSE(plain[i] & (bit(Region::kMarble) | bit(Region::kFloorByMarbles)));
    const uint16_t floor = bit(Region::kFloorLit) | bit(Region::kFloorShadow);
    floor_plain += (plain[i] & floor) != 0;
    floor_marbled += (labels[i] & (floor | bit(Region::kFloorByMarbles))) != 0;
  }
  EXPECT_GE(floor_plain, floor_marbled);  // the discs' pixels lie among the plain floor's
}

// The report's marble frame: every marble rests on the floor and is seen (an eroded marble
// pixel each at 256x256), each with floor beside it.
TEST(AccuracyMarbles, EveryMarbleOfTheMarbleFrameIsMeasured) {
  const scene::SceneAssets assets = scene::make_demo_assets(scene::default_asset_dir());
  truth::PathTracer tracer(assets);
  const scene::FrameScene frame = marble_frame(assets, 0);
  ASSERT_EQ(frame.spheres.size(), size_t(kMarbleFrameCount));
  const uint32_t n = 256;
  const std::vector<truth::PrimaryHit> hits = tracer.primary_hits(frame, n, n);
  const std::vector<uint16_t> labels = classify_regions(hits, n, n, frame.spheres);
  std::vector<int> seen(frame.spheres.size(), 0), beside(frame.spheres.size(), 0);
  for (size_t i = 0; i < hits.size(); ++i) {
    if ((labels[i] & bit(Region::kMarble)) && hits[i].sphere < seen.size()) ++seen[hits[i].sphere];
    if (labels[i] & bit(Region::kFloorByMarbles))
      for (size_t s = 0; s < frame.spheres.size(); ++s) {
        const glm::vec3 c = frame.spheres[s].center;
        const glm::vec2 d(hits[i].position.x - c.x, hits[i].position.z - c.z);
        if (glm::length(d) < kMarbleContactRadii * frame.spheres[s].radius) ++beside[s];
      }
  }
  for (size_t s = 0; s < frame.spheres.size(); ++s) {
    EXPECT_NEAR(frame.spheres[s].center.y - frame.spheres[s].radius, -1.0f, 1e-6f) << s;
    EXPECT_GT(seen[s], 0) << "marble " << s;
    EXPECT_GT(beside[s], 0) << "marble " << s;
  }
}

}  // namespace
}  // namespace rp::bench
