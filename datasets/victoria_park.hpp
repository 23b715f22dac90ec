#pragma once
// Victoria Park (Guivant & Nebot; the preprocessed "VicPark_clean_data" of the 2D-I-SLSJF
// release, ../shared/data/landmark/victoria_park/islsjf/) -> Stream, so the landmark
// modules replay a real run. Rows (whitespace separated, one per line):
//   1 i j dx dy dphi Pxx Pxy Pxphi Pyy Pyphi Pphiphi   odometry: pose j in pose i's frame (j = i + 1)
//   0 k f dx dy Pxx Pxy Pyy 0 0 0 0                   tree f seen from pose k at (dx, dy) in its frame
// The file has no timestamps: pose k is put at t = k * pose_period_s. Observations become
// (range, bearing) with the tree index as a known id. The header's landmark noise is the
// median over all observations of their covariance in polar coordinates (J P J^T), and the
// odometry noise is Thrun's model fitted to the file's odometry covariances, so filters
// weight the data as the file does; there is no ground truth.
#include <array>
#include <optional>
#include <string>

#include "core/stream.hpp"

namespace slambox {

struct VictoriaParkImportOptions {
  double pose_period_s = 0.2;  ///< [s] time between consecutive poses (the file has no times)
  double fov_deg = 180.0;      ///< the laser's field of view, centred ahead (header only)
  /// Thrun's odometry noise for modules that propagate covariance. Empty: fitted to the
  /// file's own per-step covariances (datasets/odometry_noise_fit.hpp), as the landmark
  /// noise is taken from the file's observation covariances.
  std::optional<std::array<double, 4>> odometry_alpha;
};

Stream ParseVictoriaPark(const std::string& text, const std::string& name, const VictoriaParkImportOptions& options = {});
Stream ReadVictoriaPark(const std::string& path, const VictoriaParkImportOptions& options = {});

}  // namespace slambox
