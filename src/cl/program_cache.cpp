#include "cl/program_cache.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "cl/error.h"

namespace rp::cl {

std::string join_options(std::initializer_list<std::string_view> parts) {
  std::string out;
  for (const std::string_view part : parts) {
    if (part.empty()) continue;
    if (!out.empty()) out += ' ';
    out += part;
  }
  return out;
}

namespace {

std::string read_file(const std::string& file) {
  if (const char* dir = std::getenv("ROLYPOLY_KERNEL_DIR"); dir && *dir) {
    std::filesystem::path path = std::filesystem::path(dir) / file;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("kernel file not found: " + path.string() + " (ROLYPOLY_KERNEL_DIR)");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  const auto& files = embedded_kernel_files();
  auto it = files.find(file);
  if (it == files.end()) throw Error("kernel file not embedded in this build: kernels/" + file);
  return std::string(it->second);
}

// Textual include expansion. Each file is included at most once per program (the shared
// headers also have include guards; this keeps the expanded source short and readable).
void expand(const std::string& file, std::set<std::string>& seen, std::string& out, int depth) {
  if (depth > 16) throw Error("kernel includes nested too deeply at kernels/" + file);
  if (!seen.insert(file).second) return;
  std::istringstream in(read_file(file));
  std::string line;
  int line_no = 0;
  out += "#line 1 \"" + file + "\"\n";
  while (std::getline(in, line)) {
    ++line_no;
    size_t p = line.find_first_not_of(" \t");
    // `#include <...>` lines are host-only (inside #ifndef __OPENCL_VERSION__ in the shared
    // headers): left for the OpenCL preprocessor, which skips them in the inactive branch.
    if (p != std::string::npos && line.compare(p, 8, "#include") == 0 &&
        line.find('<', p) == std::string::npos) {
      size_t q0 = line.find('"', p);
      size_t q1 = q0 == std::string::npos ? q0 : line.find('"', q0 + 1);
      if (q1 == std::string::npos)
        throw Error("kernels/" + file + ":" + std::to_string(line_no) +
                    ": only #include \"path\" (relative to kernels/) is supported");
      expand(line.substr(q0 + 1, q1 - q0 - 1), seen, out, depth + 1);
      out += "#line " + std::to_string(line_no + 1) + " \"" + file + "\"\n";
      continue;
    }
    out += line;
    out += '\n';
  }
}

// Clang inside PoCL prints its diagnostics' summary ("12 warnings generated.") on the process's
// stderr, besides the build log. Held for the build only: a failed build's output is dropped
// (BuildError carries the full build log), and a successful build's is dropped too unless
// ROLYPOLY_VERBOSE is set, so a first run does not print compiler chatter. (A build that fails
// because SIGINT made LLVM delete its temporary files would otherwise also leave that line
// above the one-line "interrupted" message.)
class StderrHold {
 public:
  StderrHold() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = file_ ? ::dup(STDERR_FILENO) : -1;
    if (saved_ < 0 || ::dup2(::fileno(file_), STDERR_FILENO) < 0) release(false);
  }
  ~StderrHold() { release(false); }
  StderrHold(const StderrHold&) = delete;
  StderrHold& operator=(const StderrHold&) = delete;

  // Puts stderr back; `pass_on`: copy what was printed meanwhile to it.
  void release(bool pass_on) {
    if (saved_ >= 0) {
      std::fflush(stderr);
      ::dup2(saved_, STDERR_FILENO);
      ::close(saved_);
      saved_ = -1;
      if (pass_on && std::fseek(file_, 0, SEEK_SET) == 0) {
        char buffer[4096];
        for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file_)) > 0;)
          std::fwrite(buffer, 1, n, stderr);
      }
    }
    if (file_) {
      std::fclose(file_);
      file_ = nullptr;
    }
  }

 private:
  std::FILE* file_ = nullptr;
  int saved_ = -1;
};

// ROLYPOLY_VERBOSE set to anything but "" or "0": show what kernel builds print, and their logs.
bool verbose_builds() {
  const char* v = std::getenv("ROLYPOLY_VERBOSE");
  return v != nullptr && *v != '\0' && std::string(v) != "0";
}

}  // namespace

std::string kernel_source(const std::string& file) {
  std::set<std::string> seen;
  std::string out;
  expand(file, seen, out, 0);
  return out;
}

const ::cl::Program& ProgramCache::program(const std::string& file, const std::string& options) {
  std::string all_options = common_options_.empty() ? options : common_options_ + " " + options;
  auto key = std::make_tuple(file, all_options);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second;

  std::string source = kernel_source(file);
  ::cl::Program program(context_->context, source);
  StderrHold hold;
  try {
    program.build(std::vector<::cl::Device>{context_->info.device}, all_options.c_str());
    const bool verbose = verbose_builds();
    hold.release(verbose);
    if (verbose) {
      std::string log;
      try {
        log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(context_->info.device);
      } catch (const ::cl::Error&) {
      }
      if (log.find_first_not_of(" \t\r\n") != std::string::npos)
        std::fprintf(stderr, "--- build log of kernels/%s ---\n%s\n", file.c_str(), log.c_str());
    }
  } catch (const ::cl::Error&) {
    hold.release(false);
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(context_->info.device);
    } catch (const ::cl::Error&) {
      log = "(no build log available)";
    }
    throw BuildError("failed to build kernels/" + file + " for '" + context_->info.name +
                         "' with options '" + all_options + "'",
                     log);
  }
  return programs_.emplace(key, std::move(program)).first->second;
}

::cl::Kernel ProgramCache::kernel(const std::string& file, const std::string& name,
                                  const std::string& options) {
  const ::cl::Program& prog = program(file, options);
  try {
    return ::cl::Kernel(prog, name.c_str());
  } catch (const ::cl::Error& e) {
    throw Error("kernel '" + name + "' not found in kernels/" + file + " (" +
                error_name(e.err()) + ")");
  }
}

}  // namespace rp::cl
