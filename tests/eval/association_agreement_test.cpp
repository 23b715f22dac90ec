#include "eval/association_agreement.hpp"

#include <gtest/gtest.h>

namespace slambox {
namespace {

// Assignments for every observation of `labels[scan][index]` (-1 = not used).
std::vector<ObservationAssignment> Assign(const std::vector<std::vector<int>>& labels) {
  std::vector<ObservationAssignment> out;
  for (size_t s = 0; s < labels.size(); ++s)
    for (size_t i = 0; i < labels[s].size(); ++i)
      out.push_back({static_cast<int>(s), static_cast<int>(i), labels[s][i], false});
  return out;
}

TEST(AssociationAgreement, KnownAssociationAgreesFully) {
  const std::vector<std::vector<int>> ids = {{3, 7}, {7}, {3, 9, 7}};
  const AssociationAgreement r = ScoreAssociation(ids, Assign(ids));
  ASSERT_TRUE(r.agreement);
  EXPECT_DOUBLE_EQ(*r.agreement, 1.0);
  EXPECT_EQ(r.scored, 6);
  EXPECT_EQ(r.duplicates, 0);
  EXPECT_EQ(r.misses, 0);
  EXPECT_EQ(r.unused, 0);
}

TEST(AssociationAgreement, RelabelledLandmarksStillAgree) {
  // The module's own ids (0, 1, 2) for trees 3, 7, 9: a consistent renaming agrees.
  const AssociationAgreement r = ScoreAssociation({{3, 7}, {7}, {3, 9, 7}}, Assign({{0, 1}, {1}, {0, 2, 1}}));
  EXPECT_DOUBLE_EQ(*r.agreement, 1.0);
}

TEST(AssociationAgreement, DuplicateTrackCountsOnlyTheMajorityLandmark) {
  // Tree 5 seen 5 times: three times as landmark 10, twice as a second landmark 11.
  // Tree 6 seen twice as landmark 12. Mapping 10->5, 12->6; 11 is a duplicate.
  const AssociationAgreement r =
      ScoreAssociation({{5, 6}, {5}, {5, 6}, {5}, {5}}, Assign({{10, 12}, {10}, {11, 12}, {11}, {10}}));
  EXPECT_DOUBLE_EQ(*r.agreement, 5.0 / 7.0);
  EXPECT_EQ(r.agreeing, 5);
  EXPECT_EQ(r.duplicates, 1);
  EXPECT_EQ(r.misses, 0);
}

TEST(AssociationAgreement, MergedTreesMissOne) {
  // One landmark 0 takes trees 1 (3 times) and 2 (once): 2 is missed, 3 of 4 agree.
  const AssociationAgreement r = ScoreAssociation({{1}, {1, 2}, {1}}, Assign({{0}, {0, -1}, {0}}));
  // The second observation of scan 1 was not used; make it used by the same landmark:
  const AssociationAgreement merged = ScoreAssociation({{1}, {1, 2}, {1}}, Assign({{0}, {0, 0}, {0}}));
  EXPECT_DOUBLE_EQ(*merged.agreement, 3.0 / 4.0);
  EXPECT_EQ(merged.misses, 1);
  EXPECT_EQ(merged.duplicates, 0);
  EXPECT_EQ(merged.unused, 0);
  // Not used: the same agreement, counted as unused, and tree 2 missed as well.
  EXPECT_DOUBLE_EQ(*r.agreement, 3.0 / 4.0);
  EXPECT_EQ(r.unused, 1);
  EXPECT_EQ(r.misses, 1);
}

TEST(AssociationAgreement, MappingIsOneToOneAndOptimal) {
  // Landmark A: tree 1 x2, tree 2 x1. Landmark B: tree 1 x2. Greedy by A's majority would
  // give A->1 and B nothing (2 agreeing); the best one-to-one mapping is A->2, B->1 (3).
  const AssociationAgreement r = ScoreAssociation({{1, 1, 2, 1, 1}}, Assign({{0, 0, 0, 1, 1}}));
  EXPECT_EQ(r.agreeing, 3);
  EXPECT_DOUBLE_EQ(*r.agreement, 3.0 / 5.0);
  EXPECT_EQ(r.duplicates, 0);
  EXPECT_EQ(r.misses, 0);
}

TEST(AssociationAgreement, ClutterIsNotScoredAndUnreportedObservationsDoNotAgree) {
  // Scan 0's second detection is clutter (-1): not scored even when assigned. Scan 1 is
  // not in the assignments at all: its observation counts, unused.
  std::vector<ObservationAssignment> a = {{0, 0, 4, true}, {0, 1, 8, true}};
  const AssociationAgreement r = ScoreAssociation({{2, -1}, {2}}, a);
  EXPECT_EQ(r.scored, 2);
  EXPECT_EQ(r.agreeing, 1);
  EXPECT_EQ(r.unused, 1);
  EXPECT_DOUBLE_EQ(*r.agreement, 0.5);
}

TEST(AssociationAgreement, NullWithoutTrueIdsOrAssignments) {
  EXPECT_FALSE(ScoreAssociation({{-1, -1}, {-1}}, Assign({{0, 1}, {0}})).agreement);  // no true id
  EXPECT_FALSE(ScoreAssociation({}, Assign({{0}})).agreement);                       // no landmark events
  EXPECT_FALSE(ScoreAssociation({{1, 2}}, {}).agreement);                           // module reports nothing
  // Out-of-range scans or indices are ignored, not scored.
  EXPECT_FALSE(ScoreAssociation({{1}}, {{3, 0, 1, false}, {0, 5, 1, false}}).agreement);
}

}  // namespace
}  // namespace slambox
