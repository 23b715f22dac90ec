#pragma once
// No NaN in a file: what of an estimate is written. A module whose output turns
// non-finite is scored `diverged` from the full estimate (eval/divergence, with the first
// bad time); its files get this finite part, so that every reader (figures, report,
// evo on the .tum) sees plain numbers.
#include "core/estimate.hpp"

namespace slambox {

/// The trajectory up to (not including) its first non-finite pose or time, a non-finite
/// covariance dropped (has_covariance = false); landmarks, map points, pose-graph nodes,
/// particles and diagnostics with a non-finite value left out (a landmark with a
/// non-finite covariance keeps its position). Everything else is copied.
Estimate FiniteEstimate(const Estimate& estimate);

}  // namespace slambox
