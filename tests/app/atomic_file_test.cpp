// io::write_file and the output path rules (src/io): whole files or none on a full disk,
// devices and FIFOs written in place (never replaced), symlinks followed, directories and
// sockets refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include "app/png_output.h"
#include "io/atomic_file.h"
#include "io/output_path.h"
#include "support/cli_runner.h"
#include "tiny_tmpfs.h"
#include "truth/exr_io.h"

namespace rp::io {
namespace {

using rp::test::entries;
using rp::test::read_all;
using rp::test::TempDir;
using rp::test::write_plain;

// The message of what `f` throws ("" when it throws nothing).
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

bool is_char_device(const char* path) {
  struct stat st {};
  return ::lstat(path, &st) == 0 && S_ISCHR(st.st_mode);
}

// Sets ROLYPOLY_FAIL_WRITE_AFTER for one scope.
class FailWritesAfter {
 public:
  explicit FailWritesAfter(size_t bytes) {
    ::setenv("ROLYPOLY_FAIL_WRITE_AFTER", std::to_string(bytes).c_str(), 1);
  }
  ~FailWritesAfter() { ::unsetenv("ROLYPOLY_FAIL_WRITE_AFTER"); }
};

TEST(AtomicFile, ReplacesARegularFileKeepingItsPermissions) {
  TempDir dir;
  const auto path = dir / "r.json";
  write_plain(path, "an older and longer version\n");
  std::filesystem::permissions(path, std::filesystem::perms(0640));
  write_file(path, "{}\n");
  EXPECT_EQ(read_all(path), "{}\n");
  EXPECT_EQ(int(std::filesystem::status(path).permissions()), 0640);
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"r.json"});
}

TEST(AtomicFile, InjectedFullDiskLeavesTheOldFileAndNoTemporary) {
  TempDir dir;
  const auto path = dir / "frame.png";
  write_plain(path, "old frame");
  {
    // The limit counts this process's bytes, so earlier tests may have used it up: the write
    // fails at once or after 3 bytes (a render's frames fail midway in OutputIntegrityCli).
    FailWritesAfter fail(3);
    const std::string error = error_of([&] { write_file(path, std::string(10000, 'x')); });
    EXPECT_EQ(error, "cannot write " + path.string() + ": No space left on device");
  }
  EXPECT_EQ(read_all(path), "old frame");
  EXPECT_EQ(entries(dir.path()), std::vector<std::string>{"frame.png"});
}

TEST(AtomicFile, PngAndExrWritersReportTheFullDisk) {
  TempDir dir;
  FailWritesAfter fail(0);
  const std::vector<uint8_t> rgba(4 * 4 * 4, 200);
  const std::string png =
      error_of([&] { rp::app::write_png_atomic(dir / "a.png", 4, 4, rgba); });
  EXPECT_TRUE(contains(png, "a.png: No space left on device")) << png;
  const std::vector<float> rgb(4 * 4 * 3, 0.5f);
  const std::string exr =
      error_of([&] { rp::truth::write_exr_atomic(dir / "a.exr", 4, 4, {{"", &rgb}}); });
  EXPECT_EQ(exr, "cannot write EXR " + (dir / "a.exr").string() + ": No space left on device");
  EXPECT_TRUE(entries(dir.path()).empty());
}

TEST(AtomicFile, RealFullDiskOnATinyTmpfs) {
  rp::test::TinyTmpfs disk(16);
  if (!disk.ok()) GTEST_SKIP() << disk.reason();
  const auto path = disk.path() / "log.txt";
  write_file(path, std::string(4096, 'a'));
  const std::string error = error_of([&] { write_file(path, std::string(64 * 1024, 'b')); });
  EXPECT_EQ(error, "cannot write " + path.string() + ": No space left on device");
  EXPECT_EQ(read_all(path), std::string(4096, 'a')) << "the old file must stay whole";
  EXPECT_EQ(entries(disk.path()), std::vector<std::string>{"log.txt"});
}

TEST(AtomicFile, DevFullFailsAndStaysADevice) {
  ASSERT_TRUE(is_char_device("/dev/full"));
  const std::string error = error_of([] { write_file("/dev/full", "{}\n"); });
  EXPECT_EQ(error, "cannot write /dev/full: No space left on device");
  EXPECT_TRUE(is_char_device("/dev/full"));
}

TEST(AtomicFile, DevNullTakesTheBytesAndStaysADevice) {
  EXPECT_EQ(error_of([] { write_file("/dev/null", "{}\n"); }), "");
  EXPECT_EQ(error_of([] { check_output_file("/dev/null", "--json"); }), "");
  EXPECT_TRUE(is_char_device("/dev/null"));
}

TEST(AtomicFile, FifoReaderGetsTheBytes) {
  TempDir dir;
  const auto fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_all(fifo); });  // blocks until the writer opens
  const std::string text(200000, 'z');  // more than a pipe holds: the writer must wait
  EXPECT_EQ(error_of([&] { write_file(fifo, text); }), "");
  reader.join();
  EXPECT_EQ(received.size(), text.size());
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO must not be replaced by a file";
}

TEST(AtomicFile, FifoWhoseReaderLeavesIsAnErrorNotSigpipe) {
  TempDir dir;
  const auto fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread reader([&] {
    const int fd = ::open(fifo.c_str(), O_RDONLY);
    char c = 0;
    (void)!::read(fd, &c, 1);  // one byte, then the reader goes away mid-write
    ::close(fd);
  });
  const std::string error = error_of([&] { write_file(fifo, std::string(1 << 20, 'p')); });
  reader.join();
  EXPECT_EQ(error, "cannot write " + fifo.string() + ": Broken pipe");
}

TEST(AtomicFile, AnOpenFileInProcFdIsWrittenInPlace) {
  // /dev/stdout and /dev/fd/N lead here: the file the shell opened for us, not a path to replace.
  TempDir dir;
  const auto path = dir / "stdout.txt";
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::write(fd, "head\n", 5), 5);
  struct stat before {};
  ::fstat(fd, &before);
  const std::string proc = "/proc/self/fd/" + std::to_string(fd);
  EXPECT_EQ(resolve_output(proc).kind, OutputTarget::Kind::kInPlace);
  EXPECT_EQ(resolve_output(proc).fd, fd) << "our own descriptor is written through a dup";
  write_file(proc, "body\n");
  ASSERT_EQ(::write(fd, "tail\n", 5), 5) << "the descriptor goes on after what write_file wrote";
  ::close(fd);
  EXPECT_EQ(read_all(path), "head\nbody\ntail\n");
  struct stat after {};
  ::stat(path.c_str(), &after);
  EXPECT_EQ(before.st_ino, after.st_ino) << "the open file must not be replaced";
}

TEST(AtomicFile, SymlinksAreFollowedAndStayLinks) {
  TempDir dir;
  std::filesystem::create_directories(dir / "real");
  std::filesystem::create_directories(dir / "links");
  write_plain(dir / "real" / "out.json", "old");
  // A relative link is relative to its own folder; the temporary goes beside the real file.
  std::filesystem::create_symlink("../real/out.json", dir / "links" / "out.json");
  write_file(dir / "links" / "out.json", "new");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "links" / "out.json"));
  EXPECT_EQ(read_all(dir / "real" / "out.json"), "new");
  EXPECT_EQ(entries(dir / "real"), std::vector<std::string>{"out.json"});
  EXPECT_EQ(entries(dir / "links"), std::vector<std::string>{"out.json"});
  // A dangling link creates its target, as a shell's `>` does.
  std::filesystem::create_symlink("made.txt", dir / "real" / "dangling");
  write_file(dir / "real" / "dangling", "made");
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "real" / "dangling"));
  EXPECT_EQ(read_all(dir / "real" / "made.txt"), "made");
  // A loop is an error, not a hang.
  std::filesystem::create_symlink("loop_b", dir / "loop_a");
  std::filesystem::create_symlink("loop_a", dir / "loop_b");
  EXPECT_TRUE(contains(error_of([&] { write_file(dir / "loop_a", "x"); }),
                       "Too many levels of symbolic links"));
}

TEST(AtomicFile, DirectoriesAndSocketsAreRefused) {
  TempDir dir;
  std::filesystem::create_directories(dir / "folder");
  write_plain(dir / "folder" / "keep", "kept");
  EXPECT_EQ(error_of([&] { write_file(dir / "folder", "x"); }),
            "cannot write " + (dir / "folder").string() + ": it is a directory");
  EXPECT_EQ(error_of([&] { check_output_file(dir / "folder", "--json"); }),
            "--json: cannot write " + (dir / "folder").string() + ": it is a directory");
  EXPECT_EQ(read_all(dir / "folder" / "keep"), "kept");

  const auto socket_path = dir / "sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(socket_path.string().size(), sizeof address.sun_path);
  std::strncpy(address.sun_path, socket_path.c_str(), sizeof address.sun_path - 1);
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  EXPECT_EQ(error_of([&] { write_file(socket_path, "x"); }),
            "cannot write " + socket_path.string() + ": it is a socket");
  ::close(fd);
}

TEST(AtomicFile, CheckOutputFileCreatesTheFolderAndRefusesUnwritableOnes) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { check_output_file(dir / "a" / "b" / "out.svg"); }), "");
  EXPECT_TRUE(std::filesystem::is_directory(dir / "a" / "b"));
  EXPECT_TRUE(entries(dir / "a" / "b").empty()) << "the probe file is removed";
  EXPECT_TRUE(contains(error_of([] { check_output_file("/proc/rolypoly/out.md", "--markdown"); }),
                       "--markdown: cannot create output folder /proc/rolypoly"));
  // A bare file name goes to the current folder, which is checked too.
  const std::filesystem::path here = std::filesystem::current_path();
  std::filesystem::current_path("/proc");
  const std::string bare = error_of([] { check_output_file("out.json"); });
  std::filesystem::current_path(here);
  EXPECT_TRUE(contains(bare, "cannot write into output folder /proc: ")) << bare;
}

}  // namespace
}  // namespace rp::io
