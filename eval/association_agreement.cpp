#include "eval/association_agreement.hpp"

#include <map>
#include <set>

#include "eval/assignment.hpp"

namespace slambox {

AssociationAgreement ScoreAssociation(const std::vector<std::vector<int>>& true_ids,
                                      const std::vector<ObservationAssignment>& assignments) {
  AssociationAgreement r;
  std::map<std::pair<int, int>, std::int64_t> count;  // (module label, true id) -> observations
  std::set<int> ids, labels;
  for (const ObservationAssignment& a : assignments) {
    if (a.scan < 0 || a.scan >= static_cast<int>(true_ids.size())) continue;
    const auto& scan = true_ids[static_cast<size_t>(a.scan)];
    if (a.index < 0 || a.index >= static_cast<int>(scan.size())) continue;
    const int g = scan[static_cast<size_t>(a.index)];
    if (g < 0) continue;
    ++r.scored;
    ids.insert(g);
    if (a.landmark < 0) {
      ++r.unused;
      continue;
    }
    labels.insert(a.landmark);
    ++count[{a.landmark, g}];
  }
  if (r.scored == 0) return r;  // nothing to score: agreement stays null
  // Observations with a true id that the module never reported count as not agreeing.
  std::int64_t with_id = 0;
  for (const auto& scan : true_ids)
    for (int g : scan) with_id += g >= 0 ? 1 : 0;
  const std::vector<int> label_list(labels.begin(), labels.end()), id_list(ids.begin(), ids.end());
  std::map<int, int> row_of, col_of;
  for (size_t i = 0; i < label_list.size(); ++i) row_of[label_list[i]] = static_cast<int>(i);
  for (size_t k = 0; k < id_list.size(); ++k) col_of[id_list[k]] = static_cast<int>(k);
  std::set<int> mapped_ids;
  if (!label_list.empty()) {
    Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(label_list.size()),
                                                 static_cast<Eigen::Index>(id_list.size()));
    for (const auto& [key, n] : count) cost(row_of[key.first], col_of[key.second]) = -static_cast<double>(n);
    const std::vector<int> col = SolveAssignment(cost);
    for (size_t i = 0; i < col.size(); ++i) {
      const std::int64_t n = col[i] >= 0 ? -static_cast<std::int64_t>(cost(static_cast<Eigen::Index>(i), col[i])) : 0;
      if (n == 0) {  // unmapped, or mapped to a tree none of its observations came from
        ++r.duplicates;
        continue;
      }
      r.agreeing += n;
      mapped_ids.insert(id_list[static_cast<size_t>(col[i])]);
    }
  }
  r.misses = static_cast<std::int64_t>(ids.size() - mapped_ids.size());
  r.unused += with_id - r.scored;
  r.scored = with_id;
  r.agreement = static_cast<double>(r.agreeing) / static_cast<double>(r.scored);
  return r;
}

}  // namespace slambox
