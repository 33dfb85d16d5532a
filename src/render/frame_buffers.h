// Device buffers that passes read and write. All planar, row-major, top row first
// (index = y * width + x). Sizes change only on resize, never per frame.
#pragma once

#include <cstdint>
#include <string>

#include <CL/opencl.hpp>

#include "cl/buffer.h"
#include "passes/frame_memory.h"

namespace rp::render {

// Output of the visibility pass (compute rasterizer or, later, Embree primary rays).
struct VisibilityBuffer {
  uint32_t width = 0, height = 0;
  ::cl::Buffer depth;  // float: z_ndc * 0.5 + 0.5 of the nearest surface, 1.0 where nothing
  ::cl::Buffer ids;    // uint2: (instance id, primitive id); see RP_ID_* in kernels/shared/types.h
  ::cl::Buffer bary;   // float2: perspective-correct barycentrics (b1, b2) of the triangle's
                       // 2nd and 3rd vertex (b0 = 1 - b1 - b2); (0, 0) for spheres/background

  static constexpr size_t kDepthBytes = sizeof(float), kIdsBytes = 2 * sizeof(uint32_t),
                          kBaryBytes = 2 * sizeof(float);  // per pixel
  static uint64_t frame_bytes(uint32_t w, uint32_t h) {
    return passes::pixel_count(w, h) * (kDepthBytes + kIdsBytes + kBaryBytes);
  }
  uint64_t device_bytes() const { return passes::buffer_bytes({&depth, &ids, &bary}); }

  void resize(const ::cl::Context& context, uint32_t w, uint32_t h) {
    width = w;
    height = h;
    size_t n = size_t(w) * h;
    depth = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * kDepthBytes);
    ids = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * kIdsBytes);
    bary = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * kBaryBytes);
  }
};

// Depth seen from the lamp centre through FrameConstants.light_view_proj.
struct ShadowMap {
  uint32_t size = 0;   // size x size texels
  // Two planes of size x size floats, z_ndc * 0.5 + 0.5: [0, size^2) the NEAREST occluder
  // surface on each texel's ray (1.0 where none), then [size^2, 2 size^2) the FARTHEST (0.0
  // where none). Together they bracket the casters' solid (exact for one closed convex caster
  // per texel ray): PCSS's thick-blocker test reads both.
  ::cl::Buffer depth;
  // The shadow filter pass's mip chain of linear depth (kernels/shared/shadow_mips.h):
  // mip_planes planes (1: MIN, for PCSS; 3: MIN, MEAN, MEAN2, for VSSM; 0: not built).
  ::cl::Buffer mips;
  uint32_t mip_planes = 0;

  // Floats `depth` holds: the lamp's two planes, then the punctual lights' shadow views
  // (kernels/shared/types.h ShadowViewGpu), which grow it on demand (ensure_floats).
  uint64_t depth_floats = 0;
  void ensure_floats(const ::cl::Context& context, uint64_t floats) {
    if (floats <= depth_floats) return;
    depth = rp::cl::make_buffer(context, CL_MEM_READ_WRITE, size_t(floats) * sizeof(float),
                                "the shadow maps of the scene's lights",
                                "a smaller --shadow-size needs less");
    depth_floats = floats;
  }

  // The lamp's two planes; what the punctual lights' views add follows the scene.
  static uint64_t frame_bytes(uint32_t s) { return 2 * uint64_t(s) * s * sizeof(float); }

  void resize(const ::cl::Context& context, uint32_t s) {
    size = s;
    depth_floats = 2 * uint64_t(s) * s;
    depth = rp::cl::make_buffer(context, CL_MEM_READ_WRITE, size_t(frame_bytes(s)),
                                "the lamp's shadow map at " + std::to_string(s) + "x" +
                                    std::to_string(s),
                                "a smaller --shadow-size needs less");
  }
};

// Surface attributes per pixel, resolved from the visibility buffer.
struct GBuffer {
  uint32_t width = 0, height = 0;
  ::cl::Buffer albedo;        // float4: rgb linear albedo (texture decoded from sRGB), a = 1
                              //         where a surface was hit, 0 for background
  ::cl::Buffer normal_depth;  // float4: xyz world-space unit normal, w linear view depth
                              //         (distance along the view axis; far plane for background)
  ::cl::Buffer position;      // float4: xyz world position, w = 1 covered, 0 background
  ::cl::Buffer emission;      // float4: rgb emitted radiance, w the surface's gloss code
                              //         (kernels/shared/brdf_layout.h: roughness, F0 or metal;
                              //         0 = matte and background)
  ::cl::Buffer velocity;      // float2: screen motion in pixels, this frame minus previous
                              //         (unjittered; +x right, +y down); 0 for background

  static uint64_t frame_bytes(uint32_t w, uint32_t h) {
    return passes::pixel_count(w, h) * (4 * 16 + 8);
  }
  uint64_t device_bytes() const {
    return passes::buffer_bytes({&albedo, &normal_depth, &position, &emission, &velocity});
  }

  void resize(const ::cl::Context& context, uint32_t w, uint32_t h) {
    width = w;
    height = h;
    size_t n = size_t(w) * h;
    albedo = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * 16);
    normal_depth = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * 16);
    position = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * 16);
    emission = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * 16);
    velocity = ::cl::Buffer(context, CL_MEM_READ_WRITE, n * 8);
  }
};

}  // namespace rp::render
