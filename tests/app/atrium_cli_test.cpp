// `--scene atrium`: the first use generates the courtyard (scene/atrium.h) into the cache
// folder (app/atrium_scene.h) and renders it like any scene file; the file is the one
// `gen_load_scene OUT --atrium` writes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cl/pocl_cache.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

TEST(AtriumCli, RenderGeneratesTheCachedFileAndDrawsIt) {
  // The scene cache goes to a fresh folder; the kernels keep the usual PoCL cache (inherited
  // through POCL_CACHE_DIR), so only the scene is made anew.
  rp::cl::ensure_pocl_cache_dir();
  const TempDir dir;
  const std::filesystem::path cache = dir / "cache";
  const std::filesystem::path file = cache / "rolypoly" / "scenes" / "atrium-1.glb";
  const CommandResult r =
      run_rolypoly("render --scene atrium --size 64 --frames 1 --out " +
                       shell_quote((dir / "out").string()),
                   "XDG_CACHE_HOME=" + shell_quote(cache.string()));
  ASSERT_EQ(r.exit_code, 0) << r.command << "\n" << r.err;
  EXPECT_NE(r.err.find("generated the atrium into " + file.string()), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("scene " + file.string() + ": "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("43 textures, 6 lights"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "frame_0000.png"));

  const std::string generated = (dir / "generated.glb").string();
  ASSERT_EQ(std::system((std::string(ROLYPOLY_GEN_LOAD_SCENE) + " " + shell_quote(generated) +
                         " --atrium > /dev/null")
                            .c_str()),
            0);
  EXPECT_TRUE(read_all(file) == read_all(generated)) << "the cache holds another atrium";
}

}  // namespace
}  // namespace rp::test
