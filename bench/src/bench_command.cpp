// `rolypoly bench`: the device x size x voxels matrix of frame times on the scene of --scene
// (bench/src/bench_scene.h), or one of its other reports (--compare-visibility here;
// --quality-report, --accuracy and --quality pathtraced elsewhere).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/interrupt.h"
#include "app/pathtrace_settings.h"
#include "app/pass_stats.h"
#include "app/png_output.h"
#include "app/progress.h"
#include "bench/src/bench_chart.h"
#include "bench/src/bench_commands.h"
#include "bench/src/bench_matrix.h"
#include "bench/src/bench_report.h"
#include "bench/src/bench_scene.h"
#include "bench/src/quality_report.h"
#include "bench/src/scene_file_facts.h"
#include "io/output_path.h"
#include "passes/pass_names.h"
#include "render/renderer.h"
#include "scene/demo_scene.h"

// The efficiency columns need the work counts and the peak probe; built without
// them the bench reports times only.
#if __has_include("bench/src/pass_work.h") && __has_include("bench/src/peak_probe.h")
#include "bench/src/pass_work.h"
#include "bench/src/peak_probe.h"
#define RP_BENCH_EFFICIENCY 1
#else
#define RP_BENCH_EFFICIENCY 0
#endif

namespace rp::bench {

namespace pass_name = passes::pass_name;

using app::CommonOptions;
using app::PassStats;
using app::ProgressBar;
using app::RenderSession;
using app::describe_device;
using app::ensure_directory;
using app::throw_if_interrupted;
using app::write_text_atomic;

namespace {

constexpr const char* kBenchInterrupted = "while benchmarking; no file was written";

// Visibility cost of one backend: the raster pass's device time, or Embree's host tracing plus
// the device time of uploading its buffer.
double visibility_ms(const PassStats& stats) {
  double ms = 0.0;
  for (const std::string& name : stats.pass_names())
    if (name == pass_name::kVisibility || name == pass_name::kVisibilityHost)
      ms += stats.pass(name).median_ms;
  return ms;
}

// Renders the scene's frames (the same every time) and returns the measured frames'
// statistics.
PassStats measure(const CommonOptions& common, const BenchOptions& options,
                  const BenchScene& scene, rp::cl::DeviceInfo& info) {
  std::unique_ptr<BenchFrames> frames = scene.frames();
  RenderSession session(common, options.size.width, options.size.height, false, scene.assets());
  info = session.device();
  PassStats stats;
  std::vector<uint8_t> rgba;
  ProgressBar progress("bench", size_t(options.warmup) + options.frames);
  progress.update(0);
  for (uint32_t i = 0; i < options.warmup + options.frames; ++i) {
    throw_if_interrupted(kBenchInterrupted);
    double frame_ms = 0.0;
    rp::cl::PassTimes times = frames->render(session, rgba, frame_ms);
    if (i >= options.warmup) stats.add(times, frame_ms);
    progress.update(i + 1);
  }
  progress.finish();
  return stats;
}

int compare_visibility(const CommonOptions& common, const BenchOptions& options,
                       const BenchScene& scene) {
  // Both backends render the same frames one after the other; everything but the visibility
  // buffer's source is shared.
  std::printf("%ux%u, %u warm-up + %u measured frames\n", options.size.width,
              options.size.height, options.warmup, options.frames);
  rp::cl::DeviceInfo info;
  CommonOptions raster = common, embree = common;
  raster.render.visibility = render::VisibilityBackend::kRaster;
  embree.render.visibility = render::VisibilityBackend::kEmbree;
  PassStats r = measure(raster, options, scene, info);
  std::printf("device %s\n", describe_device(info).c_str());
  PassStats e = measure(embree, options, scene, info);
  std::printf("visibility backend     median ms (frame median ms)\n");
  std::printf("raster (device)      %9.3f   (%.3f)\n", visibility_ms(r), r.frame().median_ms);
  std::printf("embree (host+upload) %9.3f   (%.3f)\n", visibility_ms(e), e.frame().median_ms);
  std::printf("embree / raster      %9.2fx\n", visibility_ms(e) / visibility_ms(r));
  return 0;
}

uint32_t voxels_or_default(uint32_t voxels) {
  return voxels ? voxels : render::RenderSettings{}.voxel_resolution;
}

// One cell of the matrix on one device.
RunResult measure_run(const CommonOptions& common, const BenchOptions& options,
                      const BenchScene& scene, const rp::cl::DeviceInfo& device, uint32_t width,
                      uint32_t height, uint32_t voxels) {
  CommonOptions c = common;
  c.device = std::to_string(device.index);
  c.render.voxel_resolution = voxels_or_default(voxels);
  RenderSession session(c, width, height, false, scene.assets());
  std::unique_ptr<BenchFrames> frames = scene.frames();

  PassStats stats;
  std::vector<uint8_t> rgba;
  char label[96];
  std::snprintf(label, sizeof label, "[%d] %ux%u %u^3", device.index, width, height,
                voxels_or_default(voxels));
  ProgressBar progress(label, size_t(options.warmup) + options.frames);
  progress.update(0);
  float scale_min = 1.0f, scale_max = 0.0f, last_scale = -1.0f;
  uint32_t scale_changes = 0;
  for (uint32_t i = 0; i < options.warmup + options.frames; ++i) {
    throw_if_interrupted(kBenchInterrupted);
    const float scale = session.render_scale();  // this frame's (--target-ms moves it after)
    double frame_ms = 0.0;
    rp::cl::PassTimes times = frames->render(session, rgba, frame_ms);
    if (i >= options.warmup) {
      stats.add(times, frame_ms);
      scale_min = std::min(scale_min, scale);
      scale_max = std::max(scale_max, scale);
      scale_changes += last_scale >= 0.0f && scale != last_scale;
      last_scale = scale;
    }
    progress.update(i + 1);
  }
  progress.finish();

  if (common.render.gi_volume == render::GiVolume::kSvo) {
    const render::SvoVolume& o = session.renderer().octree();
    const double mb = 1.0 / (1024.0 * 1024.0);
    std::printf("  octree %u^3 (last frame): %u fragments (list %.1f MiB), %llu nodes (node "
                "pool %.1f MiB), %llu bricks (table %.1f MiB) and %llu samples of %u bytes "
                "(%.1f MiB): pools in use %.1f MiB, buffer %.1f MiB, build scratch %.1f MiB; "
                "the dense chain at %u^3 would be %.1f MiB\n",
                o.resolution, o.fragments, double(o.fragment_bytes) * mb,
                (unsigned long long)o.nodes(), double(o.node_bytes()) * mb,
                (unsigned long long)o.bricks(), double(o.table_bytes()) * mb,
                (unsigned long long)o.samples, o.sample_bytes, double(o.sample_pool_bytes()) * mb,
                double(o.node_bytes() + o.brick_bytes()) * mb, double(o.buffer_bytes()) * mb,
                double(o.scratch_bytes) * mb, o.resolution,
                double(render::SvoVolume::dense_bytes(o.resolution)) * mb);
    std::printf("  octree device memory (CL_MEM_SIZE of its buffers): pools + build scratch "
                "%.1f MiB after the last frame, peak %.1f MiB (pools %.1f with the solid grid "
                "%.1f, scratch %.1f); the fragment voxelizer's own buffers (static surface "
                "cache) %.1f MiB\n",
                double(o.device_bytes) * mb, double(o.peak_device_bytes) * mb,
                double(o.buffer_bytes()) * mb, double(o.solid_capacity) * mb,
                double(o.scratch_bytes) * mb, double(o.voxelizer_bytes) * mb);
    std::printf("  solid grid (last frame): %.2f ms on the host while the device builds\n",
                o.solid_host_ms);
    std::printf("  nodes / bricks / occupied own voxels per depth:");
    for (size_t k = 0; k < o.nodes_per_depth.size(); ++k)
      std::printf(" %u/%u/%u", o.nodes_per_depth[k], o.bricks_per_depth[k],
                  k < o.own_per_depth.size() ? o.own_per_depth[k] : 0u);
    std::printf("\n");
  }
  RunResult run = make_run_result(width, height, voxels_or_default(voxels), stats);
  run.timing = rp::cl::timing_name(session.timing());
  run.gi_volume = name_of(common.render.gi_volume);
  run.render_scale = session.render_scale();
  run.render_width = session.render_width();
  run.render_height = session.render_height();
  if (options.frames > 0) {
    run.scale_min = scale_min;
    run.scale_max = scale_max;
    run.scale_changes = scale_changes;
  }
  if (run.render_width != width || run.render_height != height || common.target_ms > 0.0)
    std::printf("  render scale %.3f: rendered at %ux%u for the %ux%u output%s\n",
                double(run.render_scale), run.render_width, run.render_height, width, height,
                common.target_ms > 0.0 ? " (where --target-ms left it)" : "");
  if (common.target_ms > 0.0)
    std::printf("  the measured frames at scales %.3f-%.3f, %u change%s of scale among them\n",
                double(run.scale_min), double(run.scale_max), run.scale_changes,
                run.scale_changes == 1 ? "" : "s");
  const render::FrameMemory held = session.renderer().frame_device_memory();
  for (const auto& [part, bytes] : held.parts)
    if (bytes > 0) run.frame_memory.emplace_back(std::string(part), bytes);
  const uint64_t shadow_bytes = held.of(passes::pass_name::kShadowMap) +
                                held.of(passes::pass_name::kShadowFilter);
  std::printf("  device memory that follows the frame (CL_MEM_SIZE): image buffers %.1f MiB "
              "(%.1f bytes per output pixel), shadow map and its mips %.1f MiB\n",
              double(held.total() - shadow_bytes) / double(1 << 20),
              double(held.total() - shadow_bytes) / run.pixels(),
              double(shadow_bytes) / double(1 << 20));
  if (common.render.gi_volume == render::GiVolume::kSvo) {
    const render::SvoVolume& o = session.renderer().octree();
    run.octree_device_bytes = o.device_bytes;
    run.octree_peak_bytes = o.peak_device_bytes;
    run.octree_pool_bytes = o.buffer_bytes();
    run.octree_node_bytes = o.node_bytes();
    run.octree_brick_bytes = o.brick_bytes();
    run.octree_fragments = o.fragments;
    run.octree_fragment_bytes = o.fragment_bytes;
  }
  const scene::FrameScene last = frames->last();
  run.spheres = static_cast<uint32_t>(last.spheres.size());
  run.instances = static_cast<uint32_t>(last.instances.size());
  const std::vector<scene::Mesh>& meshes = session.assets().meshes;
  const uint32_t shadow_size = common.render.shadow_size;
  auto triangles = [&](uint32_t mesh) {
    return mesh < meshes.size() ? static_cast<uint32_t>(meshes[mesh].triangles.size()) : 0u;
  };
  for (const scene::MeshInstance& inst : last.instances) {
    run.instance_triangles += triangles(inst.mesh);
    if (inst.voxelize)
      run.voxel_triangles +=
          triangles(scene::voxel_mesh(meshes, inst.mesh, voxels_or_default(voxels)));
    if (inst.casts_shadow)
      run.shadow_triangles += triangles(scene::shadow_mesh(meshes, inst.mesh, shadow_size));
  }
  return run;
}

#if RP_BENCH_EFFICIENCY
// Measures the device's peak and fills every pass's work and share of that peak.
void add_efficiency(const CommonOptions& common, const BenchScene& scene,
                    const rp::cl::DeviceInfo& info, DeviceResult& result) {
  rp::cl::Context context = rp::cl::Context::create(info);
  rp::cl::ProgramCache programs(context);
  DevicePeak peak = measure_peak(context, programs);
  result.timing = rp::cl::timing_name(peak.timing);
  result.peak_bandwidth_gbps = peak.bandwidth_gbps;
  result.peak_gflops = peak.gflops;
  result.bandwidth_levels = peak.levels;
  result.bandwidth_note = peak.bandwidth_note;
  result.compute_note = peak.compute_note;
  const scene::SceneAssets assets =
      scene.assets() ? *scene.assets() : app::load_demo_assets(common);
  uint32_t triangles = 0;
  for (const scene::Mesh& m : assets.meshes) triangles += static_cast<uint32_t>(m.triangles.size());
  for (RunResult& run : result.runs) {
    WorkParams p{};
    p.width = run.width;
    p.height = run.height;
    p.voxel_resolution = run.voxels;
    p.shadow_size = common.render.shadow_size;
    p.triangles = triangles;
    p.instance_triangles = run.instance_triangles;
    p.voxel_triangles = run.voxel_triangles;
    p.shadow_triangles = run.shadow_triangles;
    p.spheres = run.spheres;
    p.taa = common.render.effects.taa;
    p.bloom = common.render.effects.bloom;
    p.motion_blur = common.render.effects.motion_blur;
    p.reference_quality = common.render.quality == render::Quality::kReference;
    for (PassResult& pass : run.passes)
      pass.efficiency =
          pass_efficiency(pass_work(pass.name, p), pass.ms.median_ms, peak.levels, peak.gflops);
  }
}
#endif

// Every file and folder the bench will write, checked before minutes of measuring: a folder
// that cannot be created or written, or a path that is a directory, socket or block device.
void check_outputs(const BenchOptions& given) {
  const BenchOptions options = with_default_outputs(given);
  if (!options.json.empty()) io::check_output_file(options.json, "--json");
  if (!options.markdown.empty()) io::check_output_file(options.markdown, "--markdown");
  if (!options.chart.empty()) io::check_output_file(options.chart, "--chart");
  if (options.accuracy) ensure_directory(options.out_dir);
}

void write_outputs(const BenchOptions& given, const BenchMatrix& matrix) {
  const BenchOptions options = with_default_outputs(given);
  if (!options.json.empty()) {
    write_text_atomic(options.json, matrix_json(matrix));
    std::printf("wrote %s\n", options.json.c_str());
  }
  if (!options.markdown.empty()) {
    write_text_atomic(options.markdown, matrix_markdown(matrix));
    std::printf("wrote %s\n", options.markdown.c_str());
  }
  if (!options.chart.empty()) {
    write_text_atomic(options.chart, matrix_svg(matrix));
    std::printf("wrote %s\n", options.chart.c_str());
  }
}

}  // namespace

// A device sweep (--devices) always leaves its JSON and chart behind: out/bench.json and
// out/bench.svg unless --json / --chart name other files.
BenchOptions with_default_outputs(const BenchOptions& given) {
  BenchOptions options = given;
  if (!options.devices.empty()) {
    if (options.json.empty()) options.json = "out/bench.json";
    if (options.chart.empty()) options.chart = "out/bench.svg";
  }
  return options;
}

int bench_command(const CommonOptions& common, const BenchOptions& options) {
  check_outputs(options);
  if (options.accuracy) {  // opens the scene itself: the demo's or the file's report
    CommonOptions c = common;
    if (!options.voxels.empty()) c.render.voxel_resolution = options.voxels.front();
    return accuracy_command(c, options);
  }
  if (options.quality_report) {  // the demo only (parse_cli refuses a file)
    CommonOptions c = common;
    if (!options.voxels.empty()) c.render.voxel_resolution = options.voxels.front();
    return quality_report_command(c, options);
  }
  // A malformed scene file fails here, before any device is opened or anything is traced.
  const BenchScene scene(common, options);
  if (scene.facts()) std::printf("scene %s\n", describe_scene_file(*scene.facts()).c_str());
  if (common.pathtraced) {
    if (!scene.file()) return pathtrace_bench_command(common, options);
    const auto facts = scene_file_json<nlohmann::ordered_json>(*scene.facts());
    return pathtrace_bench_command(common, options, scene.file(), &facts);
  }
  if (options.compare_visibility) {
    CommonOptions c = common;
    if (!options.voxels.empty()) c.render.voxel_resolution = options.voxels.front();
    return compare_visibility(c, options, scene);
  }

  MatrixPlan plan;
  if (!options.devices.empty())
    plan.devices = select_devices(options.devices, rp::cl::list_devices());
  else
    plan.devices = {rp::cl::choose_device(common.device)};
  if (options.sizes.empty())
    plan.sizes = {{options.size.width, options.size.height}};
  else
    for (uint32_t s : options.sizes) plan.sizes.push_back({s, s});
  plan.voxels = options.voxels.empty() ? std::vector<uint32_t>{0u} : options.voxels;

  BenchMatrix matrix;
  matrix.command = options.command_line;
  matrix.scene = scene.kind();
  matrix.file = scene.facts();
  matrix.seed = options.sim.seed;
  matrix.bounces = common.render.bounces;
  matrix.frames = options.frames;
  matrix.warmup = options.warmup;
  matrix.sizes = plan.sizes;
  for (uint32_t v : plan.voxels) matrix.voxels.push_back(voxels_or_default(v));

  std::printf("bench: %zu device(s) x %zu size(s) x %zu voxel resolution(s), scene %s, "
              "shadows %s, %u warm-up + %u measured frames each\n",
              plan.devices.size(), plan.sizes.size(), plan.voxels.size(), matrix.scene.c_str(),
              name_of(common.render.shadows).data(), options.warmup, options.frames);
  std::fflush(stdout);
  // A signal ends the whole bench, with no file written: a kernel build that LLVM failed on
  // the signal is the interruption, not a device to skip (whose record would replace the
  // previous --json).
  MeasureRun measure_cell = [&](const rp::cl::DeviceInfo& d, uint32_t w, uint32_t h,
                                uint32_t v) {
    throw_if_interrupted(kBenchInterrupted);
    try {
      return measure_run(common, options, scene, d, w, h, v);
    } catch (const std::exception&) {
      throw_if_interrupted(kBenchInterrupted);
      throw;
    }
  };
  FinishDevice finish;
#if RP_BENCH_EFFICIENCY
  finish = [&](const rp::cl::DeviceInfo& d, DeviceResult& r) {
    add_efficiency(common, scene, d, r);
  };
#endif
  run_matrix(plan, measure_cell, finish, matrix, stderr);
  throw_if_interrupted(kBenchInterrupted);
  for (DeviceResult& d : matrix.devices)
    for (const RunResult& r : d.runs)
      if (r.timing == "host") d.timing = "host";

  std::printf("%s", matrix_table(matrix).c_str());
  std::printf("(passes: device time from OpenCL profiling events, or host wall clock with a "
              "finish after each pass where a device says \"host timing\"; frame: wall clock "
              "of one Renderer::render call)\n");
  write_outputs(options, matrix);
  if (matrix.devices_ok() == 0) {
    std::fflush(stdout);
    std::fprintf(stderr, "rolypoly: error: no device completed the bench (every device was "
                         "skipped; see the messages above)\n");
    return 1;
  }
  return 0;
}

}  // namespace rp::bench
