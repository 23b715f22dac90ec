#pragma once
// The limits on what an input file can ask for, in one place. Each is checked before
// allocating or looping, with the usual file:line + fix message (README, "Limits").
// They are far above every built-in scenario and every public log slambox reads; they
// exist so that a typo (`beams: 100000000`) or a hostile file is refused in
// milliseconds instead of running for minutes or exhausting memory.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"

namespace slambox::limits {

/// One line of a text format (CARMEN, Victoria Park, TUM, g2o/TORO/iSAM): 1 MiB.
/// The widest public CARMEN laser line (1081 beams) is ~15 kB.
inline constexpr std::size_t kMaxTextLineBytes = std::size_t{1} << 20;
/// A scenario or sweep YAML file: 1 MiB (the built-ins are < 8 kB; yaml-cpp parses
/// about 1 MB per CPU second).
inline constexpr std::size_t kMaxYamlFileBytes = std::size_t{1} << 20;
/// Decompressed size of a .gz/.bz2 log: 4 GiB (the Intel log is 20 MB).
inline constexpr std::uint64_t kMaxDecompressedBytes = std::uint64_t{4} << 30;

/// sensors.lidar.beams (a 2D scanner has <= a few thousand).
inline constexpr int kMaxLidarBeams = 100000;
/// duration_s of a scenario: one simulated day [s].
inline constexpr double kMaxDurationS = 86400.0;
/// world.landmarks, world.walls, world.movers, robot.path, a polyline: items in one list.
inline constexpr std::size_t kMaxListItems = 20000;
/// Points [x, y] in one scenario, YAML aliases counted at each use (an alias can repeat
/// a long list many times from a few bytes).
inline constexpr std::size_t kMaxScenarioPoints = 100000;
/// sensors.landmarks.clutter_per_scan (Poisson mean of false detections per scan).
inline constexpr double kMaxClutterPerScan = 10000.0;
/// Every coordinate of a scenario (walls, posts, waypoints, movers) within +-100 km [m].
inline constexpr double kMaxCoordinateM = 1e5;
/// Geometry check work: (robot legs + mover legs + 3) x (wall edges + posts) <= 1e7
/// (~0.3 CPU s).
inline constexpr std::uint64_t kMaxGeometryPairs = 10'000'000;
/// Angles in files (poses, increments): |angle| <= 1e4 rad. Files hold wrapped angles;
/// beyond ~1e15 rad NormalizeAngle has no precision left (found by fuzz_pose_graph).
inline constexpr double kMaxAngleRad = 1e4;
/// Timestamps in logs: |t| <= 1e10 s (Unix time is 1.7e9 s), so t / dt_s stays exact.
inline constexpr double kMaxTimestampS = 1e10;

/// Estimated memory of one simulated stream (sim/scenario_limits.hpp): 4 GiB.
inline constexpr std::uint64_t kMaxStreamBytes = std::uint64_t{4} << 30;

/// Runs of one sweep (scenarios x grid points x seeds).
inline constexpr std::uint64_t kMaxSweepRuns = 1'000'000;

/// Particles of a particle filter module (mcl, fastslam).
inline constexpr int kMaxParticles = 1'000'000;
/// Cells of one grid (likelihood field, occupancy grid): 2e8 (1.6 GB of doubles).
inline constexpr std::int64_t kMaxGridCells = 200'000'000;

/// Throws InputError when line `line` of `file` is longer than kMaxTextLineBytes.
inline void CheckLineLength(const std::string& file, int line, std::size_t bytes) {
  if (bytes > kMaxTextLineBytes)
    throw InputError(file, line,
                     "a line of " + std::to_string(bytes) + " bytes, over the limit of " +
                         std::to_string(kMaxTextLineBytes) + " bytes per line",
                     "check that this is a text file of the expected format (not binary or a lost newline)");
}

}  // namespace slambox::limits
