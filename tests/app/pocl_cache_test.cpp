// PoCL's kernel cache folder. An unusable one (a path under a file, HOME without a
// cache, read-only) used to lose the device ("OpenCL platforms were found but none has a
// device"); POCL_CACHE_DIR="" made PoCL abort (exit 134); every run left an empty
// tempfile_XXXXXX (PoCL's writability probe) in the cache. `rolypoly devices` initialises PoCL
// like every command, in a fraction of a second.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "support/cli_runner.h"

namespace rp::test {
namespace {

namespace fs = std::filesystem;

// The one warning line and the temporary folder it names; checks the device list came out.
void expect_fallback(const CommandResult& r, const std::string& folder, const std::string& why) {
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("platform 0:"), std::string::npos) << r.out;
  std::smatch m;
  const std::regex warning("^rolypoly: warning: PoCL's kernel cache folder (.*) is unusable "
                           "\\((.*)\\); using the temporary folder (\\S+), removed at exit .*\n$");
  ASSERT_TRUE(std::regex_match(r.err, m, warning)) << r.err;
  EXPECT_EQ(m[1].str(), folder);
  EXPECT_NE(m[2].str().find(why), std::string::npos) << m[2];
  EXPECT_FALSE(fs::exists(m[3].str())) << "the temporary cache must be removed at exit";
}

std::vector<std::string> probe_files(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().rfind("tempfile_", 0) == 0)
      names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(PoclCache, PathUnderAFileFallsBackToATemporaryCache) {
  TempDir dir;
  std::ofstream(dir / "file") << "x";
  const std::string wanted = (dir / "file" / "cache").string();
  expect_fallback(run_rolypoly("devices", "POCL_CACHE_DIR=" + shell_quote(wanted)), wanted,
                  "cannot create it: Not a directory");
}

TEST(PoclCache, HomeWithoutAUsableCacheFallsBack) {
  TempDir dir;
  std::ofstream(dir / "home") << "a file, not a folder";
  expect_fallback(run_rolypoly("devices", "env -u POCL_CACHE_DIR -u XDG_CACHE_HOME HOME=" +
                                              shell_quote((dir / "home").string())),
                  (dir / "home" / ".cache" / "rolypoly" / "pocl").string(), "Not a directory");
}

// As a user who may not write the folder: as root through setpriv (root writes anywhere).
TEST(PoclCache, ReadOnlyCacheFallsBack) {
  TempDir dir;
  const fs::path ro = dir / "read-only";
  fs::create_directories(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                          fs::perms::group_exec | fs::perms::others_read |
                          fs::perms::others_exec);
  std::string prefix = "POCL_CACHE_DIR=" + shell_quote(ro.string());
  if (geteuid() == 0) {
    if (!have_program("setpriv")) GTEST_SKIP() << "root without setpriv";
    fs::permissions(dir.path(), fs::perms::others_exec | fs::perms::others_read,
                    fs::perm_options::add);
    prefix = "setpriv --reuid=nobody --regid=nogroup --clear-groups env " + prefix;
  }
  CommandResult r = run_rolypoly("devices", prefix);
  if (r.exit_code == 126 || r.exit_code == 127)
    GTEST_SKIP() << "user nobody cannot run the binary here: " << r.err;
  expect_fallback(r, ro.string(), "Permission denied");
}

TEST(PoclCache, EmptyPoclCacheDirCountsAsUnset) {
  TempDir dir;
  CommandResult r = run_rolypoly(
      "devices", "POCL_CACHE_DIR= XDG_CACHE_HOME=" + shell_quote((dir / "xdg").string()));
  EXPECT_EQ(r.exit_code, 0) << "PoCL aborts (134) on an empty POCL_CACHE_DIR: " << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(fs::is_directory(dir / "xdg" / "rolypoly" / "pocl"));
}

// PoCL's probe files: this run's are removed at once; another process's only once stale
// (10 minutes), in case it is still starting; files with content are never touched.
TEST(PoclCache, RunsLeaveNoProbeFiles) {
  TempDir dir;
  const fs::path cache = dir / "cache";
  fs::create_directories(cache);
  std::ofstream(cache / "tempfile_OLDone");
  std::ofstream(cache / "tempfile_NEWone");
  std::ofstream(cache / "tempfile_FULLon") << "data";
  fs::last_write_time(cache / "tempfile_OLDone",
                      fs::file_time_type::clock::now() - std::chrono::hours(2));
  fs::last_write_time(cache / "tempfile_FULLon",
                      fs::file_time_type::clock::now() - std::chrono::hours(2));
  for (int run = 0; run < 2; ++run) {
    CommandResult r = run_rolypoly("devices", "POCL_CACHE_DIR=" + shell_quote(cache.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(probe_files(cache), (std::vector<std::string>{"tempfile_FULLon", "tempfile_NEWone"}));
}

}  // namespace
}  // namespace rp::test
