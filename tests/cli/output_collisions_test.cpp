// Outputs that collide are refused before any work (exit 2, one message naming both options),
// and the file they name keeps its content: `bench --json F --markdown F` used to leave only
// the Markdown, `run --replay F --record F` overwrote the log it replayed. Paths are compared as
// files: through symlinks, hard links and "dir/../F" spellings; in-place outputs (/dev/null)
// never collide.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "cli/output_collisions.h"
#include "support/cli_runner.h"

namespace rp::test {
namespace {

namespace fs = std::filesystem;

TEST(OutputCollisions, SameFileFollowsLinksAndSpellings) {
  TempDir dir;
  write_plain(dir / "f", "x");
  fs::create_directories(dir / "sub");
  fs::create_symlink(dir / "f", dir / "link");
  fs::create_symlink("f", dir / "relative_link");
  fs::create_hard_link(dir / "f", dir / "hard");
  fs::create_symlink(dir / "not_yet", dir / "dangling");
  EXPECT_TRUE(cli::same_file(dir / "f", dir / "f"));
  EXPECT_TRUE(cli::same_file(dir / "link", dir / "f"));
  EXPECT_TRUE(cli::same_file(dir / "relative_link", dir / "f"));
  EXPECT_TRUE(cli::same_file(dir / "hard", dir / "f"));
  EXPECT_TRUE(cli::same_file(dir / "sub" / ".." / "f", dir / "f"));
  // Files that do not exist yet: the same name after resolving, including a dangling link.
  EXPECT_TRUE(cli::same_file(dir / "new", dir / "sub" / ".." / "new"));
  EXPECT_TRUE(cli::same_file(dir / "dangling", dir / "not_yet"));
  EXPECT_FALSE(cli::same_file(dir / "f", dir / "other"));
  EXPECT_FALSE(cli::same_file(dir / "new", dir / "f"));
  // Written in place, appended to: never a collision.
  EXPECT_FALSE(cli::same_file("/dev/null", "/dev/null"));
}

struct Case {
  std::string args;     // the command line, with F for the file that must survive
  std::string options;  // what the message names
};

// Each case: exit 2 at once, the message names both options, F is untouched, nothing ran.
void expect_refused(const TempDir& dir, const Case& c) {
  SCOPED_TRACE(c.args);
  const std::string f = (dir / "F").string();
  write_plain(f, "precious\n");
  std::string args = c.args, quoted = " ";  // appends: GCC 12 -Wrestrict false positive
  quoted += shell_quote(f);
  for (size_t at; (at = args.find(" F")) != std::string::npos;) args.replace(at, 2, quoted);
  const CommandResult r = run_rolypoly(args, "cd " + shell_quote(dir.path().string()) + " &&");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, c.options));
  EXPECT_EQ(r.out, "") << "refused before any work";
  EXPECT_EQ(read_all(f), "precious\n");
}

TEST(OutputCollisions, BenchOutputsOfOneFileAreRefused) {
  TempDir dir;
  fs::create_symlink(dir / "F", dir / "link.md");
  fs::create_directories(dir / "sub");
  write_plain(dir / "F", "precious\n");
  fs::create_hard_link(dir / "F", dir / "hard.svg");
  const Case cases[] = {
      {"bench --json F --markdown F", "--json and --markdown both name "},
      {"bench --json F --chart F", "--json and --chart both name "},
      {"bench --markdown F --chart F", "--markdown and --chart both name "},
      {"bench --json F --markdown link.md", "are the same file"},
      {"bench --json F --chart hard.svg", "are the same file"},
      {"bench --json F --markdown sub/../F", "are the same file"},
  };
  for (const Case& c : cases) expect_refused(dir, c);
  // The default outputs of a device sweep count too.
  fs::create_directories(dir / "out");
  const CommandResult r = run_rolypoly("bench --devices 0 --markdown out/bench.json",
                                       "cd " + shell_quote(dir.path().string()) + " &&");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--json (the default with --devices) and --markdown both name "
                              "out/bench.json"));
}

TEST(OutputCollisions, OutputThatIsAnInputIsRefused) {
  TempDir dir;
  const Case cases[] = {
      {"run --replay F --record F", "--record would overwrite the file --replay reads"},
      {"run --replay F --capture F", "--capture would overwrite the file --replay reads"},
      {"run --record F --capture F", "--record and --capture both name"},
      {"render --replay F --video F", "--video would overwrite the file --replay reads"},
      {"bench --replay F --json F", "--json would overwrite the file --replay reads"},
      {"bench --scene F --json F", "--json would overwrite the file --scene reads"},
      {"render --scene F --video F", "--video would overwrite the file --scene reads"},
  };
  for (const Case& c : cases) expect_refused(dir, c);
}

// A dangling symlink as an output creates its target file, but not the folders the target
// names (they used to be created before the run).
TEST(OutputCollisions, DanglingLinkDoesNotCreateTheFoldersOfItsTarget) {
  TempDir dir;
  fs::create_symlink(dir / "missing" / "deeper" / "r.json", dir / "link.json");
  const CommandResult r =
      run_rolypoly("bench --json " + shell_quote((dir / "link.json").string()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "--json: cannot write " + (dir / "link.json").string() +
                                  ": it is a symbolic link to "));
  EXPECT_TRUE(Contains(r.err, "whose folder does not exist"));
  EXPECT_FALSE(fs::exists(dir / "missing"));
}

}  // namespace
}  // namespace rp::test
