// Where tests write their files: a folder of this build tree (two build trees, or CI's fresh
// clone beside a work tree, can run their tests at once without removing each other's files).
#pragma once

#include <filesystem>

namespace gf::test {

/// <build>/test-outputs, created on first use.
inline std::filesystem::path scratchRoot() {
  const std::filesystem::path root = std::filesystem::path(GF_BINARY_DIR) / "test-outputs";
  std::filesystem::create_directories(root);
  return root;
}

}  // namespace gf::test
