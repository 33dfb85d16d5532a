// The name of every pass as the profiler records it (rp::cl::PassTimes keys): the render and
// run summaries, the window title, the bench's tables, JSON and work model, and the tests all
// use these constants instead of string literals. kPipelineOrder is the order
// render::Renderer::render runs them in, for tables.
#pragma once

#include <array>
#include <string_view>

namespace rp::passes::pass_name {

inline constexpr const char* kVisibilityHost = "visibility_host";  // Embree rays, host ms
inline constexpr const char* kVisibility = "visibility";  // the raster, or Embree's upload
inline constexpr const char* kGBuffer = "gbuffer";
inline constexpr const char* kShadowMap = "shadow_map";  // the lamp's shadow view
inline constexpr const char* kShadowMapLights = "shadow_map_lights";  // punctual lights' views
inline constexpr const char* kShadowFilter = "shadow_filter";
inline constexpr const char* kVoxelize = "voxelize";
inline constexpr const char* kVoxelMips = "voxel_mips";
inline constexpr const char* kSvoNodes = "svo_nodes";    // the octree: nodes and bricks
inline constexpr const char* kSvoInject = "svo_inject";  // leaves from the fragments
inline constexpr const char* kSvoBorder = "svo_border";
inline constexpr const char* kSvoMips = "svo_mips";
inline constexpr const char* kBounce = "bounce";
inline constexpr const char* kPrt = "prt";
inline constexpr const char* kSsrMinZ = "ssr_min_z";
inline constexpr const char* kIndirectTrace = "indirect_trace";
inline constexpr const char* kIndirectFilter = "indirect_filter";
inline constexpr const char* kLight = "light";
inline constexpr const char* kPunctualLight = "punctual_light";
inline constexpr const char* kSky = "sky";
inline constexpr const char* kTaa = "taa";  // also temporal upsampling
inline constexpr const char* kBloom = "bloom";
inline constexpr const char* kMotionBlur = "motion_blur";
inline constexpr const char* kToneMap = "tone_map";
inline constexpr const char* kDebugView = "debug_view";

inline constexpr std::array<std::string_view, 25> kPipelineOrder = {
    kVisibilityHost, kVisibility,   kShadowMapLights, kShadowMap,     kShadowFilter,
    kGBuffer,        kVoxelize,     kSvoNodes,        kSvoInject,     kSvoBorder,
    kSvoMips,        kVoxelMips,    kBounce,          kSsrMinZ,       kIndirectTrace,
    kIndirectFilter, kPrt,          kLight,           kPunctualLight, kSky,
    kTaa,            kBloom,        kMotionBlur,      kToneMap,       kDebugView};

}  // namespace rp::passes::pass_name
