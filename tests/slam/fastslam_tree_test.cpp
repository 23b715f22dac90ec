// Copy-on-write landmark trees: isolation between particles, O(log N) copies per update,
// box queries against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "slam/landmark_tree.hpp"

namespace slambox {
namespace {

LandmarkGaussian At(double x, double y) {
  LandmarkGaussian lm;
  lm.mean = {x, y};
  return lm;
}

LandmarkTree MakeTree(int n) {
  LandmarkTree t;
  for (int k = 0; k < n; ++k) SetLandmark(t, k, At(k, -k));
  return t;
}

TEST(LandmarkTree, StoresFindsAndGrows) {
  LandmarkTree t;
  EXPECT_EQ(FindLandmark(t, 0), nullptr);
  SetLandmark(t, 5, At(1, 2));
  SetLandmark(t, 0, At(3, 4));
  SetLandmark(t, 1000, At(5, 6));
  EXPECT_EQ(t.size, 3);
  EXPECT_EQ(t.height, 10);  // 1000 < 2^10
  ASSERT_NE(FindLandmark(t, 1000), nullptr);
  EXPECT_EQ(FindLandmark(t, 1000)->mean, Eigen::Vector2d(5, 6));
  EXPECT_EQ(FindLandmark(t, 5)->mean, Eigen::Vector2d(1, 2));
  EXPECT_EQ(FindLandmark(t, 4), nullptr);
  EXPECT_EQ(FindLandmark(t, 1 << 20), nullptr);
  EXPECT_EQ(FindLandmark(t, -1), nullptr);
  std::vector<int> keys;
  ForEachLandmark(t, [&](int k, const LandmarkGaussian&) { keys.push_back(k); });
  EXPECT_EQ(keys, (std::vector<int>{0, 5, 1000}));
}

TEST(LandmarkTree, ModifyingOneParticlesCopyNeverChangesAnother) {
  LandmarkTree a = MakeTree(100);
  LandmarkTree b = a;  // resampling: b shares every node of a
  SetLandmark(b, 37, At(-1, -1));
  EraseLandmark(b, 12);
  SetLandmark(b, 100, At(7, 7));
  for (int k = 0; k < 100; ++k) {
    ASSERT_NE(FindLandmark(a, k), nullptr);
    EXPECT_EQ(FindLandmark(a, k)->mean, Eigen::Vector2d(k, -k)) << k;
  }
  EXPECT_EQ(FindLandmark(a, 100), nullptr);
  EXPECT_EQ(a.size, 100);
  EXPECT_EQ(FindLandmark(b, 37)->mean, Eigen::Vector2d(-1, -1));
  EXPECT_EQ(FindLandmark(b, 12), nullptr);
  EXPECT_EQ(b.size, 100);
  // and the other way round
  SetLandmark(a, 3, At(9, 9));
  EXPECT_EQ(FindLandmark(b, 3)->mean, Eigen::Vector2d(3, -3));
}

TEST(LandmarkTree, AnUpdateOfASharedTreeCopiesOnlyOnePath) {
  for (int n : {16, 100, 1000, 5000}) {
    const LandmarkTree a = MakeTree(n);
    const size_t base = CountDistinctNodes({&a});
    EXPECT_GE(base, 2 * static_cast<size_t>(n) - 1);  // n leaves, >= n - 1 inner nodes
    EXPECT_LE(base, 2 * static_cast<size_t>(n) - 1 + a.height);
    LandmarkTree b = a;
    SetLandmark(b, n / 3, At(0, 0));
    // exactly the root-to-leaf path is new: height + 1 nodes, height = ceil(log2 n)
    EXPECT_EQ(CountDistinctNodes({&a, &b}), base + a.height + 1) << n;
    EXPECT_EQ(a.height, static_cast<int>(std::ceil(std::log2(n))));
    // a second update of b on a path already copied allocates nothing new
    SetLandmark(b, n / 3, At(1, 1));
    EXPECT_EQ(CountDistinctNodes({&a, &b}), base + a.height + 1) << n;
  }
}

TEST(LandmarkTree, UniquelyOwnedTreeIsUpdatedInPlace) {
  LandmarkTree a = MakeTree(64);
  const LandmarkTreeNode* root = a.root.get();
  SetLandmark(a, 10, At(5, 5));
  EXPECT_EQ(a.root.get(), root);
  EXPECT_EQ(CountDistinctNodes({&a}), 127u);
}

TEST(LandmarkTree, EraseAllPrunesEverything) {
  LandmarkTree a = MakeTree(10);
  for (int k = 0; k < 10; ++k) EraseLandmark(a, k);
  EXPECT_EQ(a.size, 0);
  EXPECT_EQ(a.root, nullptr);
  EraseLandmark(a, 3);  // absent: no-op
  EXPECT_EQ(a.size, 0);
}

TEST(LandmarkTree, BoxQueryMatchesBruteForceAfterUpdates) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-50, 50);
  LandmarkTree t;
  std::vector<Eigen::Vector2d> truth(300);
  std::vector<char> present(300, 1);
  for (int k = 0; k < 300; ++k) SetLandmark(t, k, At(truth[k].x() = u(rng), truth[k].y() = u(rng)));
  LandmarkTree shared = t;
  for (int k = 0; k < 300; k += 7) {  // move some, erase some
    SetLandmark(t, k, At(truth[k].x() = u(rng), truth[k].y() = u(rng)));
    if (k % 3 == 0) EraseLandmark(t, k + 1), present[k + 1] = 0;
  }
  for (int q = 0; q < 50; ++q) {
    const Eigen::Vector2d c(u(rng), u(rng)), lo = c.array() - 10, hi = c.array() + 10;
    std::vector<int> expected;
    for (int k = 0; k < 300; ++k)
      if (present[k] && (truth[k].array() >= lo.array()).all() && (truth[k].array() <= hi.array()).all())
        expected.push_back(k);
    EXPECT_EQ(LandmarksInBox(t, lo, hi), expected);
  }
}

}  // namespace
}  // namespace slambox
