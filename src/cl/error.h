// Errors the user can act on. The message is complete and printed as-is by main(); anything
// that reaches the user is one of these (or a std::exception that main() wraps).
#pragma once

#include <stdexcept>
#include <string>

namespace rp::cl {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A kernel program that failed to compile: the message names the file, device and options and
// carries the full build log.
class BuildError : public Error {
 public:
  BuildError(const std::string& message, std::string log)
      : Error(message + "\n--- build log ---\n" + log), log_(std::move(log)) {}
  const std::string& log() const { return log_; }

 private:
  std::string log_;
};

// Human-readable name of an OpenCL error code ("CL_OUT_OF_RESOURCES").
const char* error_name(int code);

}  // namespace rp::cl
