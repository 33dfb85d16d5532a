#include "cl/pocl_cache.h"

#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <set>
#include <system_error>

namespace rp::cl {
namespace {

namespace fs = std::filesystem;

// The folder chosen, and PoCL's probe files that were there before PoCL started (those are
// another process's until they are stale).
struct CacheState {
  fs::path dir;
  std::set<std::string> probes_before;
  bool tidied = false;
  fs::path private_dir;  // the temporary fallback, removed at exit

  ~CacheState() {
    if (private_dir.empty()) return;
    std::error_code ec;
    fs::remove_all(private_dir, ec);
  }
};

CacheState& state() {
  static CacheState s;  // destroyed at exit: removes the private folder
  return s;
}

// "tempfile_" and six characters, nothing after: the name PoCL's probe gets from mkstemp.
// Its real temporary files carry a suffix (.cl, .o, .so, .temp...).
bool is_probe_name(const std::string& name) {
  return name.size() == 15 && name.compare(0, 9, "tempfile_") == 0;
}

std::set<std::string> probe_files(const fs::path& dir) {
  std::set<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (is_probe_name(it->path().filename().string())) names.insert(it->path().filename());
  return names;
}

// "" when `dir` exists (or can be created) and takes a new file; else why not.
std::string unusable_reason(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return "cannot create it: " + ec.message();
  if (!fs::is_directory(dir, ec)) return "not a folder";
  std::string probe = (dir / ".rolypoly-probe-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0) return "cannot write into it: " + std::string(std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  return "";
}

fs::path default_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "rolypoly" / "pocl";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "rolypoly" / "pocl";
  return {};
}

}  // namespace

std::string ensure_pocl_cache_dir() {
  CacheState& s = state();
  if (!s.dir.empty()) return s.dir.string();  // chosen before (tests call this repeatedly)
  const char* set = std::getenv("POCL_CACHE_DIR");
  const bool user_set = set && *set;  // empty: as if unset (PoCL would abort on it)
  const fs::path wanted = user_set ? fs::path(set) : default_dir();
  const std::string why =
      wanted.empty() ? "neither HOME nor XDG_CACHE_HOME is set" : unusable_reason(wanted);
  if (why.empty()) {
    s.dir = wanted;
  } else {
    std::string tmp = (fs::temp_directory_path() / "rolypoly-pocl-XXXXXX").string();
    if (!::mkdtemp(tmp.data())) {
      std::fprintf(stderr,
                   "rolypoly: warning: PoCL's kernel cache folder %s is unusable (%s), and no "
                   "temporary one could be made: %s\n",
                   wanted.c_str(), why.c_str(), std::strerror(errno));
      return "";
    }
    s.dir = s.private_dir = tmp;
    std::fprintf(stderr,
                 "rolypoly: warning: PoCL's kernel cache folder %s is unusable (%s); using the "
                 "temporary folder %s, removed at exit (kernels compile afresh every run: set "
                 "POCL_CACHE_DIR to a writable folder to keep them)\n",
                 wanted.empty() ? "(none)" : wanted.c_str(), why.c_str(), tmp.c_str());
  }
  ::setenv("POCL_CACHE_DIR", s.dir.c_str(), 1);
  s.probes_before = probe_files(s.dir);
  return s.dir.string();
}

void remove_pocl_probe_files() {
  CacheState& s = state();
  if (s.tidied || s.dir.empty()) return;
  s.tidied = true;
  const auto stale = fs::file_time_type::clock::now() - std::chrono::minutes(10);
  std::error_code ec;
  for (const std::string& name : probe_files(s.dir)) {
    const fs::path path = s.dir / name;
    // Empty only: a probe is never written. Ours are new; another process's (present before
    // PoCL started here) only once stale, in case that process is still starting.
    if (fs::file_size(path, ec) != 0 || ec) continue;
    if (s.probes_before.count(name) && fs::last_write_time(path, ec) > stale) continue;
    fs::remove(path, ec);
  }
}

}  // namespace rp::cl
