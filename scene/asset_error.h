// Error for assets that cannot be used (missing or corrupt texture file, ...). The message names
// the file and the reason, so it can be shown to the user as is.
#pragma once

#include <stdexcept>

namespace rp::scene {

class AssetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rp::scene
