#pragma once
// Bounds of the module accuracy tests (issue 20). A module run on a fixed-seed synthetic
// stream is deterministic, so a test pins the value it measured there: an error may grow to
// kAccuracyHeadroom times it (no noise to absorb: a 1.5x regression fails), an ANEES may move
// by that factor either way and must stay inside its chi-square window. Each test keeps its
// measured values in one named constant beside it, with the command that prints them; a
// deliberate change of results updates that constant.
//
// The chi-square window counts one independent NEES sample per run, not one per step: a
// run's errors are correlated over its whole length (the map's error is shared by every later
// pose), so its time-averaged ANEES spreads over seeds almost like a single chi^2(3) draw (std
// 1.03 / 1.28 for ekf-slam / graphslam over their tests' 10 seeds, vs sqrt(6) = 2.45 for one
// draw and 0.05 for 2237 independent steps). A per-step window (2.96..3.04 for their 22370 poses)
// would reject both; tests/core/accuracy_bound_test.cpp shows it failing on correlated
// consistent errors where this one holds.
#include <gtest/gtest.h>

#include "core/chi_square.hpp"

namespace slambox::testing {

inline constexpr double kAccuracyHeadroom = 1.5;
inline constexpr double kAneesConfidence = 0.99;

/// value <= kAccuracyHeadroom * measured (an error: lower is better).
inline ::testing::AssertionResult NoWorseThanMeasured(double value, double measured) {
  if (value <= kAccuracyHeadroom * measured) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << value << " > " << kAccuracyHeadroom << " x measured " << measured
                                       << " (update the measured constant if the change is intended)";
}

/// The 99 % window for the ANEES of 3-dof pose errors averaged over `runs` independent runs.
inline NeesBand PoseAneesWindow(int runs) { return AneesBand(3, runs, kAneesConfidence); }

/// anees inside `window` and within kAccuracyHeadroom x of `measured` either way.
inline ::testing::AssertionResult AneesNearMeasured(double anees, double measured, NeesBand window) {
  if (!(anees >= window.lo && anees <= window.hi))
    return ::testing::AssertionFailure() << "ANEES " << anees << " outside its chi-square window [" << window.lo
                                         << ", " << window.hi << "]";
  if (!(anees >= measured / kAccuracyHeadroom && anees <= kAccuracyHeadroom * measured))
    return ::testing::AssertionFailure() << "ANEES " << anees << " not within " << kAccuracyHeadroom
                                         << "x of measured " << measured
                                         << " (update the measured constant if the change is intended)";
  return ::testing::AssertionSuccess();
}

}  // namespace slambox::testing
