// What `rolypoly bench` draws (--scene): the simulated demo ("default"; the command line also
// takes "demo"), the busy animation ("busy", below) or a scene file (glTF 2.0: its still frame
// seen from the file's camera, as `render --scene FILE` draws it, FileFrameSource). Every run
// (device x size x voxels) takes its frames from a fresh source, so all draw the same frames.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/scene_input.h"
#include "bench/src/bench_matrix.h"
#include "bench/src/bench_options.h"

namespace rp::bench {

// --scene names a file: anything but the demo's names ("demo" became "default" in parse_cli).
inline bool is_bench_scene_file(const std::string& scene) {
  return scene != "default" && scene != "busy" && !app::is_demo_scene(scene);
}

// The frames of one run.
class BenchFrames {
 public:
  virtual ~BenchFrames() = default;
  // Renders the next frame (with the command line's effects; the demo's as its toggles leave
  // them) into `rgba`; returns the pass times, frame_ms as RenderSession::render.
  virtual rp::cl::PassTimes render(app::RenderSession& session, std::vector<uint8_t>& rgba,
                                   double& frame_ms) = 0;
  // What the last rendered frame drew.
  virtual scene::FrameScene last() const = 0;
};

class BenchScene {
 public:
  // Opens the scene file when --scene names one (scene::SceneFileError: exit 2, before any
  // device is opened) and records its facts; the demo's names open nothing.
  BenchScene(const app::CommonOptions& common, const BenchOptions& options);

  // The loaded file, or nullptr for the demo and the busy animation.
  const app::FileScene* file() const { return file_.get(); }
  // What RenderSession draws from: the file's assets, or nullptr (the demo's, from --assets).
  const scene::SceneAssets* assets() const { return file_ ? &file_->loaded.assets : nullptr; }
  const std::optional<SceneFileFacts>& facts() const { return facts_; }
  // "default", "busy" or "file" (the JSON's "scene").
  std::string kind() const;

  // A fresh source of the scene's frames for one run.
  std::unique_ptr<BenchFrames> frames() const;

 private:
  const app::CommonOptions& common_;
  const BenchOptions& options_;
  std::unique_ptr<app::FileScene> file_;
  std::optional<SceneFileFacts> facts_;
};

}  // namespace rp::bench
