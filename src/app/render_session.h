// Everything one rendering command needs, built in the order that reports errors cheapest first:
// assets (missing/corrupt textures), then the OpenCL device and context (no platform, unknown
// device), then the renderer (kernel build failures with the build log).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/frame_time_scale.h"
#include "app/scene_memory.h"
#include "cl/context.h"
#include "cl/profiler.h"
#include "cl/program_cache.h"
#include "passes/debug_view.h"
#include "render/renderer.h"
#include "scene/frame_scene.h"
#include "truth/prt_transfer.h"

namespace rp::app {

// --env / --sky clear and their settings: light from afar (scene/environment.h) for the path
// tracer. Only the path tracer lights with it so far; parse_cli refuses it elsewhere.
// app/sky_input.h turns it into the frame's environment (and the clear sky's sun).
struct SkyOptions {
  std::string env_file;     // --env: an equirectangular .exr or .hdr ("" = none)
  bool clear_sky = false;   // --sky clear: scene/clear_sky.h's Preetham sky and its sun
  float rotate_deg = 0.0f;  // --env-rotate: turn about +y (counter-clockwise seen from above)
  float strength = 1.0f;    // --env-strength: multiplies the map (the clear sky's sun too)
  float sun_azimuth_deg = 135.0f;   // --sun AZ,EL: compass angle from -z towards +x,
  float sun_elevation_deg = 45.0f;  // and degrees above the horizon (scene::ClearSkySettings)
  // --env-suns: the map's suns taken out and lit as directional lights, at most this many
  // (0: the cones and PRT gather the whole map; scene/environment_suns.h)
  int env_suns = 4;
  bool given() const { return !env_file.empty() || clear_sky; }
  // --sky-light prt: the sky's diffuse light by precomputed radiance transfer (passes/
  // prt_sky.h) instead of through the cones; the transfer of the scene's (static) instances
  // computed on the first frame (truth/prt_transfer.h) and cached on disk (truth/prt_cache.h).
  // --prt-bands, --prt-transfer, --prt-bounces, --prt-samples set it.
  bool prt = false;
  truth::PrtSettings prt_settings = default_prt_settings();
  static truth::PrtSettings default_prt_settings() {
    truth::PrtSettings s;
    s.kind = truth::PrtKind::kInterreflected;
    s.bounces = 3;
    return s;
  }
};

struct CommonOptions {
  std::string device;      // --device: index or name substring ("" = first GPU, else CPU)
  std::string asset_dir;   // --assets: folder with the demo's textures
  bool open_demo = false;  // --open: the demo with its skylight (scene::demo::kSkylight)
  std::string scene = "demo";  // --scene (render): "demo" or a glTF 2.0 file (app/scene_input.h)
  // What the real-time modes render: --shadow-size, --voxels, --gi-volume, --no-taa /
  // --no-bloom / --no-motion-blur / --bloom-strength, --visibility, --quality fast|reference,
  // --bounces, --shadows, --texture-filter, --render-scale. Its size is the command's (--size;
  // the session sets it) and scale_follows_time follows target_ms.
  render::RenderSettings render;
  passes::DebugViewSettings view;  // --view / --level / --dir (render, run): what is shown
  // --quality pathtraced (render, bench): the host path tracer (truth/path_tracer.h) instead of
  // the OpenCL renderer; render.quality is then unused. --spp is its samples per pixel and
  // render.bounces its gathers (0..1000; the real-time modes take 1..1000).
  bool pathtraced = false;
  uint32_t spp = 256;  // --spp: samples per pixel, 1..1000000
  bool area_lamp = false;  // --lamp area (pathtraced): the emitting cap (truth::LampModel::kArea)
  double target_ms = 0.0;     // --target-ms: 0 = a fixed scale; else the scale follows the time
  SkyOptions sky;             // --env, --env-rotate, --env-strength, --sky clear, --sun
};

struct SkyLight;  // app/sky_input.h

// Not copyable or movable: the program cache and renderer point at the context.
class RenderSession {
 public:
  // keep_components: set_keep_components(true) from the start, counted in the memory check
  // that runs before anything is allocated (`render --exr`).
  // assets: what the scene draws (a loaded file's); nullptr = the demo's (load_demo_assets).
  RenderSession(const CommonOptions& options, uint32_t width, uint32_t height,
                bool keep_components = false, const scene::SceneAssets* assets = nullptr);
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;
  ~RenderSession();

  // Renders `frame` (blocking) and reads the RGBA8 result into `rgba` (top row first), lit by
  // the options' sky too (--env / --sky clear: app/sky_input.h's add_sky; frames come without
  // it).
  // Returns the device ms per pass; `frame_ms` gets the wall-clock ms of Renderer::render
  // (enqueue of every pass until all finished; the read-back is not included).
  rp::cl::PassTimes render(const scene::FrameScene& frame, std::vector<uint8_t>& rgba,
                           double& frame_ms);

  // Switches what render() produces: the final image or a debug view (passes/debug_view.h).
  // Throws rp::cl::Error for a voxel level or direction the renderer's chain does not have.
  void set_view(const passes::DebugViewSettings& view);
  const passes::DebugViewSettings& view() const { return view_; }

  // Turns the sky (--env / --sky clear) about +y by `degrees` for the next frames (key O in
  // the window); returns the map's turn now in degrees, or nothing without a sky.
  std::optional<float> turn_sky(float degrees);
  // The sky and the suns taken out of its map, for the log ("" without a sky).
  const std::string& sky_description() const { return sky_description_; }

  // Post-processing switches for the next frames (keys T, B, M in the window).
  void set_effects(const render::Effects& effects) { renderer_->set_effects(effects); }
  // The shadow mode for the next frames (key H in the window).
  void set_shadows(render::ShadowMode mode) { renderer_->set_shadows(mode); }
  render::ShadowMode shadows() const { return renderer_->settings().shadows; }
  // Keeps the light pass's direct / indirect terms for read_components whatever the view
  // (`render --exr`); checks the device memory with them counted first (rp::cl::Error).
  void set_keep_components(bool keep);
  // The last frame's linear images (render::Renderer::read_components; blocking).
  void read_components(render::LinearComponents& out) { renderer_->read_components(out); }
  void reset_history() { renderer_->reset_history(); }

  const rp::cl::DeviceInfo& device() const { return context_.info; }
  // How pass times are taken on this device (host timing where its timestamps are unusable).
  rp::cl::Timing timing() const { return context_.timing; }
  const scene::SceneAssets& assets() const { return assets_; }
  uint32_t width() const { return renderer_->settings().width; }
  const render::Renderer& renderer() const { return *renderer_; }
  // What estimate_device_memory counted for this session (bytes).
  uint64_t device_memory_estimate() const { return device_memory_estimate_; }
  uint32_t height() const { return renderer_->settings().height; }
  // The render scale of the next frame and the size the last one was rendered at (the output
  // size for debug views); the controller of --target-ms (nullptr without it).
  float render_scale() const { return renderer_->settings().render_scale; }
  uint32_t render_width() const { return renderer_->render_width(); }
  uint32_t render_height() const { return renderer_->render_height(); }
  const FrameTimeScale* frame_scale() const { return frame_scale_ ? &*frame_scale_ : nullptr; }

 private:
  // The scene's device memory (app/scene_memory.h), the sky's map included.
  SceneMemory scene_memory() const;
  // --sky-light prt: the transfer of `frame`'s instances (from the cache or computed, with a
  // progress bar on a terminal and one line on stderr), handed to the renderer. Throws
  // Interrupted when a signal stops the computation.
  void prepare_prt(const scene::FrameScene& frame);
  // On the first frame: counts its punctual lights' shadow views (the frame, not the assets,
  // holds the lights) and checks the device memory again before they are allocated.
  void check_light_views(const scene::FrameScene& frame);

  scene::SceneAssets assets_;
  rp::cl::Context context_;
  rp::cl::ProgramCache programs_;
  std::unique_ptr<render::Renderer> renderer_;
  passes::DebugViewSettings view_;
  uint64_t device_memory_estimate_ = 0;
  std::optional<FrameTimeScale> frame_scale_;  // --target-ms
  std::unique_ptr<SkyLight> sky_;              // --env / --sky clear; nullptr: none
  std::string sky_description_;                // app/sky_input.h describe_sky, "" without
  scene::FrameScene lit_frame_;                // with sky_: the frame render() adds it to
  std::optional<truth::PrtSettings> prt_;      // --sky-light prt
  bool prt_ready_ = false;                     // prepare_prt ran: the renderer has the transfer
  bool light_views_checked_ = false;           // check_light_views ran
  uint64_t light_shadow_bytes_ = 0;            // the lights' shadow views (SceneMemory)
  std::string scene_name_;                     // "--scene NAME", for the memory messages
};

// Device memory a session needs (bytes, an estimate that errs high where the window may switch
// modes): the buffers that follow the image (render/frame_memory.h, summed from the passes'
// own figures: exact for the final view), the GI volume (the dense chain and the voxelizer's
// sums and overflow bits, or the octree at 640 bytes per R^2, measured high), and the
// scene (a loaded one's counted buffers, at least kSceneReserveBytes for meshes, textures and
// draw lists).
struct DeviceMemoryNeed {
  uint64_t total_bytes = 0;
  uint64_t largest_buffer_bytes = 0;  // the biggest single allocation (per pixel, volume, scene)
  // The parts of total_bytes, for the message: the image's buffers, the GI volume, the lamp's
  // shadow map and its mips, the scene.
  uint64_t image_bytes = 0, volume_bytes = 0, shadow_bytes = 0, scene_bytes = 0;
  uint64_t volume_buffer_bytes = 0;  // the volume's one large buffer (chain, or octree pools)
};

// The frame memory the estimate counts for `settings`: every effect on (the window's keys turn
// them on) and the buffers of pcss and vssm together (key H switches; pcss's chunk verdicts
// stay allocated), each part at its largest.
render::FrameMemory frame_memory_worst_case(render::RenderSettings settings,
                                            const render::FrameMemoryOptions& frame);

// settings: the size, shadow map, volume, quality and render scale; frame: the light
// components (the direct / indirect views, `render --exr`) and PRT; scene: a loaded scene's
// counted buffers (nullptr: kSceneReserveBytes, enough for the demo).
DeviceMemoryNeed estimate_device_memory(const render::RenderSettings& settings,
                                        const render::FrameMemoryOptions& frame = {},
                                        const SceneMemory* scene = nullptr);

// Throws rp::cl::Error before anything is allocated when the estimate exceeds the device's
// global memory or one buffer exceeds its largest allocation, naming what decides:
// - the scene (`scene_name`, e.g. "--scene big.glb"), when it does not fit even with a 1x1
//   image and the smallest volume: "the scene --scene big.glb needs 3100 MiB of device memory
//   (... vertices, ... triangles, ...), but the device has 1024 MiB; use a smaller scene";
// - the GI volume, when a smaller --voxels fits at this size: "--gi-volume svo --voxels 512 at
//   2000x2000 needs 1100 MiB of device memory (the image's buffers 764 MiB, ...), the device
//   has 1024 MiB; the largest --voxels that fits at this size is 256 (--voxels 256), or at
//   --voxels 512 the largest square size is about 1900 (--size 1900)";
// - else the image: "16384x16384 needs 51.2 GiB of device memory, the device has 5.6 GiB; the
//   largest square size that fits is about 5400 (--size 5400)".
void check_device_memory(const rp::cl::DeviceInfo& device, const render::RenderSettings& settings,
                         const render::FrameMemoryOptions& frame = {},
                         const SceneMemory* scene = nullptr, const std::string& scene_name = "");

// The largest square side s (0 if none) whose estimate with settings at s x s fits
// `global_bytes` with every buffer within `max_alloc_bytes`.
uint32_t largest_square_that_fits(uint64_t global_bytes, uint64_t max_alloc_bytes,
                                  render::RenderSettings settings,
                                  const render::FrameMemoryOptions& frame = {},
                                  const SceneMemory* scene = nullptr);

// The largest --voxels the app offers for settings.gi_volume (dense 128, 64, 32; octree 512,
// 256) whose estimate fits at settings' size; 0 if none.
uint32_t largest_voxels_that_fit(uint64_t global_bytes, uint64_t max_alloc_bytes,
                                 render::RenderSettings settings,
                                 const render::FrameMemoryOptions& frame = {},
                                 const SceneMemory* scene = nullptr);

// "[0] pthread-... (CPU, Portable Computing Language)"
std::string describe_device(const rp::cl::DeviceInfo& info);

// Milliseconds since `start` on the steady clock.
double ms_since(std::chrono::steady_clock::time_point start);

}  // namespace rp::app
