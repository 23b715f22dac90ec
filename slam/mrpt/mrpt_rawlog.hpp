#pragma once
// MRPT rawlogs in and out, through MRPT's own serialization (mrpt::obs::CRawlog), for
// `slambox convert rawlog` and `slambox export --format rawlog` (the MRPT plugin's
// slambox_rawlog_format entry, core/laser_log.hpp). MRPT-free header.
//
// Reading (both rawlog layouts): CObservationOdometry (absolute odometry poses) or, in the
// actions/sensory-frames layout, CActionRobotMovement2D (increments, composed into poses
// from the identity); CObservation2DRangeScan (beams right to left from -aperture/2,
// aperture/(N-1) apart, as MRPT defines them; MRPT's validity flags kept; the sensor pose
// of the first scan is the laser's mounting; later scans' positions must be within 1 cm of it);
// CObservationBearingRange (range and yaw from the sensor, moved to the robot origin by
// the sensor pose; landmarkID, -1 = unknown). Other observations are skipped. Times are
// MRPT timestamps as seconds of their clock (time_origin_s of the stream).
//
// Writing (default: the observations-only layout, which RawLogViewer, rawlog-edit, icp-slam
// and CRawlog read; or the frames layout for kf-slam and rbpf-slam, below): first a CObservationOdometry with the start pose at stream time 0, then
// per event: odometry -> CObservationOdometry with the integrated odometry pose; scan ->
// CObservation2DRangeScan (label LIDAR, ranges as MRPT's floats, the sensor yawed so each
// beam is at its stream angle); landmarks -> CObservationBearingRange (label LANDMARKS).
// Timestamps: time_origin_s (0 for a simulated stream) + t_s, in MRPT's 100 ns ticks.
// Not carried: ground truth, the world, gyro events, noise models (the header).
#include <cstdint>
#include <string>

#include "core/laser_log.hpp"
#include "core/stream.hpp"

namespace slambox::mrpt_bridge {

/// Throws InputError naming the file: unreadable, not a rawlog, truncated or corrupt (the
/// object's index), a limit exceeded, a scan whose sensor moves on the robot. The file may be
/// gzip-compressed; more than `max_bytes` of (decompressed) content is refused while reading.
LaserLog ReadRawlog(const std::string& path, std::uint64_t max_bytes);
/// ReadRawlog's parsing of the (decompressed) content; `path` names it in errors.
LaserLog ParseRawlog(const std::string& bytes, const std::string& path);
/// ReadRawlog with limits::kMaxDecompressedBytes: the plugin's entry.
LaserLog ReadRawlog(const std::string& path);

/// Writes `path` atomically (a temporary name beside it, then rename). kFrames: before each
/// scan or landmark event, a CActionCollection with the CActionRobotMovement2D of the odometry
/// since the previous frame (MRPT's default Gaussian motion model), then a CSensoryFrame
/// holding that one observation; no CObservationOdometry.
void WriteRawlog(const Stream& stream, const std::string& path, RawlogLayout layout = RawlogLayout::kObservations);

}  // namespace slambox::mrpt_bridge
