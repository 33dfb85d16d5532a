// Host view of the structs in kernels/shared/types.h, with size checks and GLM conversions.
#pragma once

#include <cstring>

#include <glm/glm.hpp>

#include "kernels/shared/types.h"
// after types.h, whose scalar types it uses
#include "kernels/shared/pass_params.h"

namespace rp::gpu {

static_assert(sizeof(rp_float4) == 16);
static_assert(sizeof(rp_mat4) == 64);
static_assert(sizeof(PunctualLightGpu) == 80);
static_assert(sizeof(ShadowViewGpu) == 96);
static_assert(sizeof(SkyGpu) == 48 + 4 * RP_SKY_MAX_LEVELS);
static_assert(sizeof(FrameConstants) == 6 * 64 + 5 * 16 + 8 * 4 + 4 * 4 +
                                            RP_MAX_PUNCTUAL_LIGHTS * 80 +
                                            RP_MAX_SHADOW_VIEWS * 96 + sizeof(SkyGpu));
static_assert(sizeof(Vertex) == 32);
static_assert(sizeof(Triangle) == 16);
static_assert(sizeof(Instance) == 224);
static_assert(sizeof(Sphere) == 64);
static_assert(sizeof(Material) == 80);
static_assert(sizeof(TextureInfo) == 32 + 4 * RP_TEXTURE_MAX_LEVELS);
static_assert(sizeof(LowResPlanes) == 32);
static_assert(sizeof(IndirectTraceParams) == 48);
static_assert(sizeof(IndirectFilterParams) == 96);
static_assert(sizeof(LightShadeParams) == 16);
static_assert(sizeof(MinZLevel) == 32);
static_assert(sizeof(MotionBlurParams) == 48);
static_assert(sizeof(TaaParams) == 48);
static_assert(sizeof(BloomStep) == 32);
static_assert(sizeof(GBufferParams) == 16);
static_assert(sizeof(PrtVertexParams) == 32);
static_assert(sizeof(ShadowMipStep) == 32);
static_assert(sizeof(BounceParams) == 16);
static_assert(sizeof(ToneMapParams) == 16);
static_assert(sizeof(VoxelMipsParams) == 16);
static_assert(sizeof(VoxelViewParams) == 16);
static_assert(sizeof(VoxelizeParams) == 48);
static_assert(sizeof(SvoBuildParams) == 96);

inline rp_float4 to_gpu(const glm::vec4& v) { return {v.x, v.y, v.z, v.w}; }
inline rp_float4 to_gpu(const glm::vec3& v, float w) { return {v.x, v.y, v.z, w}; }
inline rp_mat4 to_gpu(const glm::mat4& m) {
  rp_mat4 out;
  static_assert(sizeof(out) == sizeof(m));
  std::memcpy(&out, &m, sizeof(out));  // both column-major
  return out;
}

}  // namespace rp::gpu
