#pragma once
// Scoring a module's data association against the detector's true ids (issue 14):
// for each observation that has a true id, the module's assigned landmark (or none), and
// a one-to-one mapping from the module's landmarks to true ids chosen to agree with as
// many observations as possible (optimal assignment on the label x id count table, so a
// landmark maps to the tree most of its observations came from, unless another landmark
// has a stronger claim on that tree).
//   agreement  = #{o : true id g(o) >= 0, module label a(o) >= 0, M(a(o)) = g(o)} / #{o : g(o) >= 0}
//   duplicates = module landmarks with true-id observations that M leaves unmapped
//                (a tree tracked under a second landmark, or a landmark mixing trees)
//   misses     = true ids observed at least once that no module landmark maps to
//   unused     = observations with a true id the module did not use (label -1)
// With known association every label is the true id and agreement is 1.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/estimate.hpp"

namespace slambox {

struct AssociationAgreement {
  std::optional<double> agreement;  ///< null: no observation has a true id, or no assignments
  std::int64_t scored = 0;          ///< observations with a true id
  std::int64_t agreeing = 0;
  std::int64_t unused = 0;
  std::int64_t duplicates = 0;
  std::int64_t misses = 0;
};

/// `true_ids[scan][index]`: the true id of each observation of each landmark event (-1:
/// none, e.g. clutter). Assignments outside `true_ids` are ignored.
AssociationAgreement ScoreAssociation(const std::vector<std::vector<int>>& true_ids,
                                      const std::vector<ObservationAssignment>& assignments);

}  // namespace slambox
