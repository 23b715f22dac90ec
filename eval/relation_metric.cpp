#include "eval/relation_metric.hpp"

#include "eval/statistics.hpp"

namespace slambox {

namespace {
std::vector<double> Squares(const std::vector<double>& v) {
  std::vector<double> out;
  out.reserve(v.size());
  for (double x : v) out.push_back(x * x);
  return out;
}
}  // namespace

RelationMetric ComputeRelationMetric(const std::vector<double>& t, const std::vector<double>& r) {
  RelationMetric m;
  m.relations = static_cast<int>(t.size());
  const ErrorStatistics st = ComputeStatistics(t), sr = ComputeStatistics(r);
  const ErrorStatistics st2 = ComputeStatistics(Squares(t)), sr2 = ComputeStatistics(Squares(r));
  m.trans_mean_m = st.mean;
  m.trans_std_m = st.std;
  m.trans_sq_mean_m2 = st2.mean;
  m.trans_sq_std_m2 = st2.std;
  m.rot_mean_deg = sr.mean;
  m.rot_std_deg = sr.std;
  m.rot_sq_mean_deg2 = sr2.mean;
  m.rot_sq_std_deg2 = sr2.std;
  return m;
}

}  // namespace slambox
