// Determinism of the whole app: the same busy animation (30 marbles, a fireball
// and its particles, a replayed mouse drag on the centre tumbler) rendered several times by
// separate `rolypoly render` processes gives byte-identical PNGs, frame for frame (identical
// bytes: a stronger check than identical SHA-256 hashes). DESIGN.md forbids float atomics and
// every reduction has a fixed order, so nothing may differ, not even one bit.
//
// CI runs 3 renders of 60 frames at 32x32 (~10 s). The measurement recorded in
// bench/results/reliability-epyc-2core-pocl.md is 10 renders at 64x64:
//   ROLYPOLY_DETERMINISM_RUNS=10 ROLYPOLY_DETERMINISM_SIZE=64
//     build/tests/test_render --gtest_filter='*Determinism*'   (one command line)
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 60;

// A drag across the centre tumbler (its body is at about pixel (32, 44) of a 64x64 frame; the
// log stores the viewport, so the same NDC is used at any --size), held for 80 steps (20 frames
// at the headless 4 steps per frame), moved right, then back left past the start.
const char* kDragLog =
    "rolypoly-input 1\n"
    "step 40 mouse_down 32 44 64 64\n"
    "step 44 mouse_move 36 44 64 64\n"
    "step 48 mouse_move 40 45 64 64\n"
    "step 52 mouse_move 44 46 64 64\n"
    "step 60 mouse_move 48 46 64 64\n"
    "step 70 mouse_move 40 42 64 64\n"
    "step 80 mouse_move 30 40 64 64\n"
    "step 100 mouse_move 24 40 64 64\n"
    "step 120 mouse_up 24 40 64 64\n";

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// FNV-1a over a run's frames in order, for the log line (not for the comparison).
uint64_t fnv1a(const std::vector<std::string>& frames) {
  uint64_t h = 1469598103934665603ULL;
  for (const std::string& f : frames)
    for (unsigned char c : f) h = (h ^ c) * 1099511628211ULL;
  return h;
}

class ScratchDir {
 public:
  ScratchDir() {
    path_ = fs::temp_directory_path() /
            ("rolypoly-determinism-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "-" + std::to_string(reinterpret_cast<uintptr_t>(this)));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The binary under test: the build's, or ROLYPOLY_TEST_BINARY where the tests run from a
// bundle on another machine (tools/gpu_check.sh).
std::string rolypoly_binary() {
  const char* bundled = std::getenv("ROLYPOLY_TEST_BINARY");
  return bundled && *bundled ? bundled : ROLYPOLY_BINARY;
}

// Renders the animation into `out` and returns the frames' bytes (empty on failure, with the
// command's output in `error`).
std::vector<std::string> render(const fs::path& out, int size, const std::string& extra,
                                std::string& error) {
  const fs::path log_path = out.string() + ".out";
  const std::string cmd = quote(rolypoly_binary()) + " render --size " + std::to_string(size) +
                          " --frames " + std::to_string(kFrames) + " --marbles --fireball " +
                          extra + " --out " + quote(out.string()) + " > " +
                          quote(log_path.string()) + " 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    error = cmd + "\n" + read_bytes(log_path);
    return {};
  }
  std::vector<std::string> frames;
  for (int i = 0; i < kFrames; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", i);
    if (!fs::exists(out / name)) {
      error = "missing " + (out / name).string();
      return {};
    }
    frames.push_back(read_bytes(out / name));
  }
  return frames;
}

TEST(Determinism, BusyAnimationRendersBitIdenticallyInSeparateProcesses) {
  const int runs = env_int("ROLYPOLY_DETERMINISM_RUNS", 3);
  const int size = env_int("ROLYPOLY_DETERMINISM_SIZE", 32);
  ASSERT_GE(runs, 2);
  ScratchDir dir;
  const fs::path log = dir.path() / "drag.log";
  std::ofstream(log) << kDragLog;
  const std::string replay = "--replay " + quote(log.string());

  std::string error;
  const std::vector<std::string> first = render(dir.path() / "run0", size, replay, error);
  ASSERT_EQ(first.size(), static_cast<size_t>(kFrames)) << error;
  std::cout << "[ info ] run 0: frames digest " << std::hex << fnv1a(first) << std::dec << "\n";
  for (int r = 1; r < runs; ++r) {
    const std::vector<std::string> again =
        render(dir.path() / ("run" + std::to_string(r)), size, replay, error);
    ASSERT_EQ(again.size(), static_cast<size_t>(kFrames)) << error;
    std::cout << "[ info ] run " << r << ": frames digest " << std::hex << fnv1a(again) << std::dec
              << "\n";
    int differing = 0;
    for (int i = 0; i < kFrames; ++i) {
      if (again[static_cast<size_t>(i)] != first[static_cast<size_t>(i)]) {
        ADD_FAILURE() << "run " << r << " frame " << i << " differs from run 0";
        if (++differing == 5) break;
      }
    }
  }

  // The animation is busy: frames change all along (marbles fall, the fireball moves) ...
  int unchanged = 0;
  for (int i = 1; i < kFrames; ++i) unchanged += first[static_cast<size_t>(i)] == first[static_cast<size_t>(i - 1)];
  EXPECT_EQ(unchanged, 0) << "consecutive identical frames: the scene is not moving";
  // ... and the replayed drag took effect: without it the frames after the grab differ.
  const std::vector<std::string> no_drag = render(dir.path() / "nodrag", size, "", error);
  ASSERT_EQ(no_drag.size(), static_cast<size_t>(kFrames)) << error;
  EXPECT_EQ(no_drag[5], first[5]) << "before the drag (step 40 = frame 10) nothing differs";
  int drag_changed = 0;
  for (int i = 12; i < kFrames; ++i) drag_changed += no_drag[static_cast<size_t>(i)] != first[static_cast<size_t>(i)];
  EXPECT_GT(drag_changed, 40) << "the replayed drag did not change the picture (missed the tumbler?)";
}

}  // namespace
