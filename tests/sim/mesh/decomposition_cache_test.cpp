// The on-disk cache of convex decompositions: what is stored is read back bit for bit, under
// its key only, and a file that is not whole is never used.
#include "sim/mesh/decomposition_cache.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/mesh/primitives.hpp"
#include "tests/scratch.hpp"

namespace gf::sim {
namespace {

namespace fs = std::filesystem;

HullParts twoParts() {
  return {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)},
          {Vec3(0.1, 0.2, 0.3), Vec3(-1e-300, 1e300, 0.5), Vec3(3, 2, 1)}};
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = gf::test::scratchRoot() / name;
  fs::remove_all(dir);
  return dir;
}

TEST(DecompositionCache, StoredPartsReadBackBitForBitUnderTheirKeyOnly) {
  const fs::path dir = freshDir("gf_decomposition_cache_roundtrip");
  const HullParts parts = twoParts();
  ASSERT_TRUE(storeDecomposition(dir.string(), 42, parts));
  const std::optional<HullParts> back = loadDecomposition(dir.string(), 42);
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->size(), parts.size());
  for (std::size_t i = 0; i < parts.size(); ++i) EXPECT_EQ((*back)[i], parts[i]) << "part " << i;
  EXPECT_FALSE(loadDecomposition(dir.string(), 43).has_value()) << "another key";
  EXPECT_FALSE(loadDecomposition("", 42).has_value()) << "no cache folder";
  EXPECT_FALSE(storeDecomposition("", 42, parts));
}

// Truncated, extended, or with a key that is not its name's: decomposed again, not misread.
TEST(DecompositionCache, AFileThatIsNotWholeIsNotUsed) {
  const fs::path dir = freshDir("gf_decomposition_cache_broken");
  ASSERT_TRUE(storeDecomposition(dir.string(), 7, twoParts()));
  const fs::path file = dir / "hull-0000000000000007.bin";
  ASSERT_TRUE(fs::exists(file));
  const std::uintmax_t size = fs::file_size(file);
  for (const std::uintmax_t cut : {std::uintmax_t{0}, std::uintmax_t{8}, std::uintmax_t{30}, size - 1}) {
    ASSERT_TRUE(storeDecomposition(dir.string(), 7, twoParts()));
    fs::resize_file(file, cut);
    EXPECT_FALSE(loadDecomposition(dir.string(), 7).has_value()) << "cut to " << cut << " bytes";
  }
  ASSERT_TRUE(storeDecomposition(dir.string(), 7, twoParts()));
  std::ofstream(file, std::ios::binary | std::ios::app) << "x";
  EXPECT_FALSE(loadDecomposition(dir.string(), 7).has_value()) << "a byte more";
  ASSERT_TRUE(storeDecomposition(dir.string(), 8, twoParts()));
  fs::rename(dir / "hull-0000000000000008.bin", file);
  EXPECT_FALSE(loadDecomposition(dir.string(), 7).has_value()) << "key 8's file under key 7's name";
}

TEST(DecompositionCache, TheKeyFollowsTheMeshAndTheSettings) {
  const Mesh a = tessellateBox(Vec3(0.02, 0.02, 0.02), 1);
  const Mesh b = tessellateBox(Vec3(0.02, 0.02, 0.0200001), 1);
  EXPECT_EQ(decompositionKey(a, "s"), decompositionKey(tessellateBox(Vec3(0.02, 0.02, 0.02), 1), "s"));
  EXPECT_NE(decompositionKey(a, "s"), decompositionKey(b, "s"));
  EXPECT_NE(decompositionKey(a, "s"), decompositionKey(a, "t"));
}

}  // namespace
}  // namespace gf::sim
