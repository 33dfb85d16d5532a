// A real full disk for the output tests: a tmpfs of a few KiB mounted on a scratch folder. Only
// root may mount (and a container may forbid it even then), so tests check ok() and skip with
// reason() otherwise; the injected failure (ROLYPOLY_FAIL_WRITE_AFTER) covers every machine.
#pragma once

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <sys/mount.h>
#include <unistd.h>

#include "support/cli_runner.h"

namespace rp::test {

class TinyTmpfs {
 public:
  explicit TinyTmpfs(size_t kib) : mount_point_(dir_ / "tmpfs") {
    std::filesystem::create_directories(mount_point_);
    if (::geteuid() != 0) {
      reason_ = "not root: cannot mount a tmpfs to fill";
      return;
    }
    const std::string options = "size=" + std::to_string(kib) + "k";
    if (::mount("tmpfs", mount_point_.c_str(), "tmpfs", 0, options.c_str()) != 0) {
      reason_ = std::string("mount -t tmpfs failed: ") + std::strerror(errno);
      return;
    }
    mounted_ = true;
  }
  ~TinyTmpfs() {
    if (mounted_) ::umount2(mount_point_.c_str(), MNT_DETACH);
  }
  TinyTmpfs(const TinyTmpfs&) = delete;
  TinyTmpfs& operator=(const TinyTmpfs&) = delete;

  bool ok() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  const std::filesystem::path& path() const { return mount_point_; }

 private:
  TempDir dir_;
  std::filesystem::path mount_point_;
  bool mounted_ = false;
  std::string reason_;
};

}  // namespace rp::test
