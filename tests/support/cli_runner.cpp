#include "support/cli_runner.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace rp::test {
namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

::testing::AssertionResult Contains(const std::string& text, const std::string& needle) {
  if (text.find(needle) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << needle << "' not found in:\n" << text;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  out += "'";
  return out;
}

namespace {

// Runs `command` through the shell (in `cwd` when given), stdout and stderr captured to files
// in a folder of their own.
CommandResult run_captured(const std::string& command, const std::filesystem::path& cwd) {
  TempDir capture;
  std::filesystem::path out_file = capture / "stdout.txt", err_file = capture / "stderr.txt";
  CommandResult r;
  r.command = command;
  std::string full = (cwd.empty() ? "" : "cd " + shell_quote(cwd.string()) + " && ") + command +
                     " >" + shell_quote(out_file.string()) + " 2>" +
                     shell_quote(err_file.string()) + " </dev/null";
  int status = std::system(full.c_str());
  r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out_file);
  r.err = slurp(err_file);
  return r;
}

}  // namespace

CommandResult run_rolypoly(const std::string& args, const std::string& env_prefix) {
  return run_captured(
      (env_prefix.empty() ? "" : env_prefix + " ") + shell_quote(ROLYPOLY_BINARY) + " " + args, {});
}

CommandResult run_program_in(const std::string& program, const std::filesystem::path& cwd,
                             const std::string& args) {
  return run_captured(shell_quote(program) + " " + args, cwd);
}

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_plain(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::vector<std::string> entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

bool have_program(const std::string& program) {
  std::string cmd = "command -v " + shell_quote(program) + " >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("rolypoly-test-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::vector<std::string> files_with_suffix(const std::filesystem::path& dir,
                                           const std::string& suffix) {
  std::vector<std::string> names;
  if (!std::filesystem::is_directory(dir)) return names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name.size() >= suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace rp::test
