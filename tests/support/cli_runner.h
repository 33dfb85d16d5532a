// Runs the built `rolypoly` binary (ROLYPOLY_BINARY) through the shell with stdout and stderr
// captured to files, and gives tests scratch folders that clean up after themselves.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace rp::test {

struct CommandResult {
  int exit_code = -1;  // the process's exit status; -1 if it did not exit normally
  std::string out, err;
  std::string command;  // for failure messages
};

// Single-quotes `s` for /bin/sh.
// A gtest assertion: `needle` occurs in `text` (both printed when it does not).
::testing::AssertionResult Contains(const std::string& text, const std::string& needle);

std::string shell_quote(const std::string& s);

// `env_prefix` goes before the binary, e.g. "env -u DISPLAY" or "ROLYPOLY_KERNEL_DIR='/x'";
// `args` is appended as is (quote paths with shell_quote).
CommandResult run_rolypoly(const std::string& args, const std::string& env_prefix = "");

// Runs `program` (a path; quoted here) with `args` in folder `cwd`, output captured elsewhere,
// so `cwd` holds only what the program wrote.
CommandResult run_program_in(const std::string& program, const std::filesystem::path& cwd,
                             const std::string& args);

// True when `program` is found on PATH.
bool have_program(const std::string& program);

// The bytes of a file ("" when it cannot be read), and a plain (unchecked) write of some: for
// setting up and inspecting test files, never for the output under test.
std::string read_all(const std::filesystem::path& path);
void write_plain(const std::filesystem::path& path, const std::string& text);

// Every entry of `dir` (not recursive), hidden temporaries included, sorted by name.
std::vector<std::string> entries(const std::filesystem::path& dir);

// A fresh empty folder under the system temp dir, removed with everything in it on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// Every regular file in `dir` whose name ends with `suffix`, sorted by name.
std::vector<std::string> files_with_suffix(const std::filesystem::path& dir,
                                           const std::string& suffix);

}  // namespace rp::test
