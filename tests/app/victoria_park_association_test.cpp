// Victoria Park (the 2D-I-SLSJF preprocessed file) with the tree ids hidden from the
// modules (`run --hide-landmark-ids`): association_agreement against the file's ids, and
// the hidden-id map against the known-id one. Skips without the public data
// ($SLAMBOX_DATA or ../shared/data). Measured values and commands:
// slam/README_landmark_slam.md, "Victoria Park with the ids hidden".
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <tuple>

#include "app/registry.hpp"
#include "app/run_modules.hpp"
#include "datasets/victoria_park.hpp"
#include "eval/association_agreement.hpp"
#include "tests/support/public_data.hpp"

namespace slambox {
namespace {

struct Expected {
  const char* module;
  double min_agreement;  ///< measured minus a margin a regression would cross
  int min_matched;       ///< hidden-id landmarks within 1 m of a known-id one (one-to-one)
};

/// One-to-one matches within 1 m, greedy by distance.
int MatchedWithin1m(const std::vector<LandmarkEstimate>& a, const std::vector<LandmarkEstimate>& b) {
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j)
      if (const double d = (a[i].position - b[j].position).norm(); d < 1.0) pairs.emplace_back(d, i, j);
  std::sort(pairs.begin(), pairs.end());
  std::set<size_t> used_a, used_b;
  int n = 0;
  for (const auto& [d, i, j] : pairs)
    if (!used_a.count(i) && !used_b.count(j)) used_a.insert(i), used_b.insert(j), ++n;
  return n;
}

TEST(VictoriaParkAssociation, HiddenIdsAgreeWithTheFile) {
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/victoria_park/islsjf/VicPark_clean_data.txt");
  if (path.empty()) GTEST_SKIP() << "landmark/victoria_park/islsjf/VicPark_clean_data.txt not found; set SLAMBOX_DATA";
  const Stream known = ReadVictoriaPark(path);
  Stream hidden = known;
  const std::vector<std::vector<int>> ids = HideLandmarkIds(hidden);
  // Measured (this test prints them): ekf-slam agreement 0.9928 (60 duplicates), 295 of its
  // 296 landmarks within 1 m of the known-id map; graphslam 0.9928 (its front end
  // associates), 295 of 296 (292 of 295 when it made a keyframe of every fifth scan only,
  // keyframe_every_odometry = 5, before every scan became one). With tentative_existence=counts (the default before): 0.9887,
  // 288 of 292 / 285 of 291. Before the sequential existence test for confirmed landmarks
  // (confirmed_existence=sprt): 0.9098, 158 of 168 / 167 of 168; before the detection-rate
  // existence and the fitted odometry noise: 0.2660 (ekf-slam kept 107 landmarks, 3 within
  // 1 m; graphslam diverged). Issue 14's target: 0.99.
  for (const Expected& x : {Expected{"ekf-slam", 0.99, 290}, Expected{"graphslam", 0.99, 287}}) {
    const Estimate with_ids = Replay(*FindModule(x.module).create({}), known);
    const Estimate e = Replay(*FindModule(x.module).create({}), hidden);
    const AssociationAgreement r = ScoreAssociation(ids, e.observation_assignments);
    ASSERT_TRUE(r.agreement) << x.module;
    const int matched = MatchedWithin1m(e.landmarks, with_ids.landmarks);
    std::printf("%s: agreement %.4f (%lld duplicates, %lld misses, %lld unused of %lld); %zu landmarks, %d within 1 m "
                "of the %zu known-id ones\n",
                x.module, *r.agreement, static_cast<long long>(r.duplicates), static_cast<long long>(r.misses),
                static_cast<long long>(r.unused), static_cast<long long>(r.scored), e.landmarks.size(), matched,
                with_ids.landmarks.size());
    EXPECT_GE(*r.agreement, x.min_agreement) << x.module;
    EXPECT_GE(matched, x.min_matched) << x.module;
  }
}

// FastSLAM's existence on the same log: Thrun's -1 per miss in view assumes a detector that
// sees every tree in view, and this one sees a tree in view in at most about half of the
// scans, so every particle's trees count down to removal and are mapped again. With the
// estimated detection rate a miss costs P_D at the tree's range (slam/detection_rate.hpp);
// with the sequential test (as ekf-slam's) a miss weighs log(1 - P_D P_G) and a sighting
// log(P_D P_G / P[clutter in the gate]). The converter cannot know the detector's P_D and
// says so (detection_prob_known false), so FastSLAM's defaults (auto) estimate the rate and
// use the test here. Measured (this test prints them): fastslam2 agreement 0.2640 (3600
// duplicates) with -1 per miss, 0.8683 (1465) with the rate and the counters, 0.9956 (83)
// with the rate and the test; `slambox run vp.stream --algo fastslam2 --hide-landmark-ids
// --no-figures [--set algo.fastslam2.existence=counts] [--set
// algo.fastslam2.estimate_detection_rate=false]`.
TEST(VictoriaParkAssociation, FastSlamCountsMissesByTheDetectionRate) {
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/victoria_park/islsjf/VicPark_clean_data.txt");
  if (path.empty()) GTEST_SKIP() << "landmark/victoria_park/islsjf/VicPark_clean_data.txt not found; set SLAMBOX_DATA";
  Stream hidden = ReadVictoriaPark(path);
  ASSERT_TRUE(hidden.header.sensors.landmarks);
  EXPECT_FALSE(hidden.header.sensors.landmarks->detection_prob_known);
  const std::vector<std::vector<int>> ids = HideLandmarkIds(hidden);
  const ParamOverrides runs[3] = {{{"estimate_detection_rate", "false"}, {"existence", "counts"}},
                                  {{"existence", "counts"}},
                                  {}};
  const char* names[3] = {"counters, -1 per miss", "counters, the rate", "defaults (the test, the rate)"};
  double agreement[3] = {0.0, 0.0, 0.0};
  for (int k = 0; k < 3; ++k) {
    const Estimate e = Replay(*FindModule("fastslam2").create(runs[k]), hidden);
    const AssociationAgreement r = ScoreAssociation(ids, e.observation_assignments);
    ASSERT_TRUE(r.agreement);
    agreement[k] = *r.agreement;
    std::printf("fastslam2, %s: agreement %.4f (%lld duplicates); %zu landmarks\n", names[k], *r.agreement,
                static_cast<long long>(r.duplicates), e.landmarks.size());
  }
  EXPECT_LT(agreement[0], 0.5);
  EXPECT_GE(agreement[1], 0.85);
  EXPECT_GE(agreement[2], 0.99);
}

}  // namespace
}  // namespace slambox
