#include "render/punctual_shadows.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace rp::render {
namespace {

// The GI volume [-1,1]^3 lies within this radius of the origin.
constexpr float kVolumeRadius = 1.7320508f;
// Nearest a shadow caster may be to a point or spot light (render units; the volume is 2 wide).
constexpr float kLightNear = 0.005f;

uint32_t face_size(uint32_t shadow_size) { return std::max(16u, shadow_size / 2); }

// An up vector not parallel to `dir`.
glm::vec3 up_for(glm::vec3 dir) {
  return std::abs(dir.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

gpu::ShadowViewGpu make_view(const glm::mat4& view_proj, float near, float far, bool ortho,
                             uint32_t size, uint64_t offset) {
  gpu::ShadowViewGpu v{};
  v.view_proj = gpu::to_gpu(view_proj);
  // world size of one texel at clip w = 1 (common/direct_light.h: 2 |w| / (size |row 0|))
  const glm::vec3 row0(view_proj[0][0], view_proj[1][0], view_proj[2][0]);
  v.depth = {near, far, ortho ? 1.0f : 0.0f, 2.0f / (float(size) * glm::length(row0))};
  v.offset = uint32_t(offset);
  v.size = size;
  return v;
}

// Distance from `p` past the far side of the volume.
float far_from(glm::vec3 p) { return glm::length(p) + kVolumeRadius * 1.01f; }

// The orthographic view along unit `dir` over the box [lo, hi]: square (texels as wide as
// high, which common/punctual_light.h's texel size assumes), centred on the box's projection,
// its depth range the box's with a margin.
gpu::ShadowViewGpu directional_view(glm::vec3 dir, glm::vec3 lo, glm::vec3 hi, uint32_t size,
                                    uint64_t offset) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 0.01f);
  const float pad = 0.01f * radius + 1.0e-3f;
  const glm::mat4 view = glm::lookAt(centre - dir * (2.0f * radius + 2.0f * pad), centre,
                                     up_for(dir));
  float half = 0.0f, near = 1.0e30f, far = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 corner(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    const glm::vec4 v = view * glm::vec4(corner, 1.0f);
    half = std::max({half, std::abs(v.x), std::abs(v.y)});
    near = std::min(near, -v.z);
    far = std::max(far, -v.z);
  }
  half = half * 1.01f + 1.0e-3f;
  near -= pad;
  far += pad;
  return make_view(glm::ortho(-half, half, -half, half, near, far) * view, near, far, true, size,
                   offset);
}

}  // namespace

ShadowBounds ShadowBounds::snapped() const {
  if (empty()) return *this;
  ShadowBounds b;
  b.lo = glm::max(glm::floor(lo / kStep) * kStep, glm::vec3(-1.0f));
  b.hi = glm::min(glm::ceil(hi / kStep) * kStep, glm::vec3(1.0f));
  return b;
}

uint64_t punctual_shadow_floats(const std::vector<scene::PunctualLight>& lights,
                                uint32_t shadow_size) {
  uint64_t floats = 0;
  const size_t n = std::min<size_t>(lights.size(), RP_MAX_PUNCTUAL_LIGHTS);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t side = lights[i].type == scene::LightType::kPoint ? face_size(shadow_size)
                                                                     : shadow_size;
    floats += (lights[i].type == scene::LightType::kPoint ? 6u : 1u) * 2u * side * side;
  }
  return floats;
}

PunctualSetup setup_punctual_lights(const std::vector<scene::PunctualLight>& lights,
                                    uint32_t shadow_size, uint64_t first_float,
                                    const ShadowBounds& bounds) {
  // the directional views' box: the frame's bounds, else the whole volume
  ShadowBounds box = bounds.snapped();
  if (box.empty()) box = ShadowBounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
  PunctualSetup setup;
  uint64_t offset = first_float;
  const size_t n = std::min<size_t>(lights.size(), RP_MAX_PUNCTUAL_LIGHTS);
  for (size_t i = 0; i < n; ++i) {
    const scene::PunctualLight& l = lights[i];
    gpu::PunctualLightGpu g{};
    g.position_range = gpu::to_gpu(l.position, l.range);
    g.direction = gpu::to_gpu(l.direction, 0.0f);
    g.intensity = gpu::to_gpu(l.intensity, 0.0f);
    const float cos_outer = std::cos(l.outer_cone), cos_inner = std::cos(l.inner_cone);
    g.cone = {cos_outer, cos_inner - cos_outer > 1.0e-6f ? 1.0f / (cos_inner - cos_outer) : 0.0f,
              0.0f, 0.0f};
    g.first_view = uint32_t(setup.views.size());
    const auto push_view = [&](const gpu::ShadowViewGpu& v) {
      setup.views.push_back(v);
      offset += 2u * uint64_t(v.size) * v.size;
    };
    const auto add_view = [&](const glm::mat4& vp, float near, float far, bool ortho,
                              uint32_t size) {
      push_view(make_view(vp, near, far, ortho, size, offset));
    };
    switch (l.type) {
      case scene::LightType::kDirectional: {
        g.type = RP_LIGHT_DIRECTIONAL;
        push_view(directional_view(l.direction, box.lo, box.hi, shadow_size, offset));
        break;
      }
      case scene::LightType::kSpot: {
        g.type = RP_LIGHT_SPOT;
        const float half = std::min(l.outer_cone * 1.05f + 0.01f, glm::radians(85.0f));
        const glm::mat4 view = glm::lookAt(l.position, l.position + l.direction,
                                           up_for(l.direction));
        const float far = far_from(l.position);
        add_view(glm::perspective(2.0f * half, 1.0f, kLightNear, far) * view, kLightNear, far,
                 false, shadow_size);
        break;
      }
      case scene::LightType::kPoint: {
        g.type = RP_LIGHT_POINT;
        // Faces in the order +x, -x, +y, -y, +z, -z (common/punctual_light.h picks by the
        // major axis); a little wider than 90 degrees so the edges overlap.
        static const glm::vec3 kAxis[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                           {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        const float far = far_from(l.position);
        const glm::mat4 proj = glm::perspective(glm::radians(91.0f), 1.0f, kLightNear, far);
        for (const glm::vec3& axis : kAxis)
          add_view(proj * glm::lookAt(l.position, l.position + axis, up_for(axis)), kLightNear,
                   far, false, face_size(shadow_size));
        break;
      }
    }
    g.view_count = uint32_t(setup.views.size()) - g.first_view;
    setup.lights.push_back(g);
  }
  setup.floats = offset - first_float;
  return setup;
}

}  // namespace rp::render
