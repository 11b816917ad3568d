// The geometry a turntable scan triangulates with, taken from the station's
// calibration file (station_calibration.h) only after the checks that keep a
// scan from using the wrong one:
//   - made for these devices: the station fingerprint matches
//     (check_calibration_matches: camera, image size, lasers, turntable);
//   - complete for the scan: the camera placed in the station frame and a
//     plane for every laser of the station (check_calibration_complete);
//   - not stale: its oldest part used is at most `max_age_days` old. A
//     station drifts (a knocked laser, a refocused lens) without its
//     description changing, so age is the only sign a program can see; the
//     device changes that the description does show are the fingerprint's.
// On the simulator a scan may instead use the simulator's true geometry.
// A replay may reprocess a recorded session with another calibration file
// (a recalibration after the scan), checked alike against the devices the
// session recorded.
#pragma once

#include "acquisition/session.h"
#include "acquisition/station_calibration.h"
#include "acquisition/turntable_geometry.h"

#include <optional>
#include <string>

namespace scanstation::acquisition {

/// The sentinel for "the simulator's true geometry" where a calibration file is named.
inline constexpr const char* kSimulatorTruth = "sim-truth";
/// Oldest calibration part a scan accepts by default (days).
inline constexpr double kCalibrationMaxAgeDays = 30.0;

/// Seconds since the epoch of an ISO 8601 UTC time "YYYY-MM-DDTHH:MM:SSZ"
/// (as calibration_date() writes); throws InvalidInput naming `field` otherwise.
long long seconds_since_epoch(const std::string& iso_time, const std::string& field);

/// The checked geometry of `calibration` for a scan on devices of
/// fingerprint `station` with `laser_count` lasers (need lasers: the camera
/// and the light planes), or with its stereo pair (need stereo_pose: both
/// cameras placed on the turntable, no laser):
/// source = the calibration file, calibration = {"file", "fingerprint",
/// "created", "updated", "dates": {"camera", "turntable", "lasers": [...]}
/// (stereo: {"stereo", "turntable"}), "age_days"} (age of the oldest part at `now`).
/// max_age_days  0 accepts any age
/// now           ISO 8601 UTC time to age the parts against (calibration_date())
/// Throws InvalidInput naming the file, the field and the command that fixes it.
TurntableGeometry calibrated_geometry(const StationCalibration& calibration, const StationFingerprint& station,
                                      int laser_count, double max_age_days, const std::string& now,
                                      CalibrationNeed need = CalibrationNeed::lasers);

/// Which geometry a scan uses.
/// choice           a calibration file, kSimulatorTruth, or "" for the
///                  default: the calibration file the station description
///                  names (calibration = "..."), else the simulator's truth
///                  when simulating, else an error
/// simulator_truth  the simulated rig's geometry; absent on real devices
///                  (where kSimulatorTruth is refused)
/// need             lasers (laser rig) or stereo_pose (stereo rig)
TurntableGeometry scan_geometry(const std::string& choice, const drivers::StationDescription& station,
                                const std::optional<TurntableGeometry>& simulator_truth,
                                double max_age_days = kCalibrationMaxAgeDays,
                                CalibrationNeed need = CalibrationNeed::lasers);

/// The geometry to reprocess a recorded session with instead of the one it
/// recorded: the calibration `file`, checked as a scan checks it
/// (calibrated_geometry, aged against the current time) against the devices
/// the session was scanned with (its manifest's station fingerprint); a
/// stereo session needs the stereo pair placed on the turntable.
/// Throws InvalidInput naming the session and the file: a missing file, a
/// session that records no fingerprint, other devices, an incomplete or a
/// stale calibration.
TurntableGeometry replay_geometry(const std::filesystem::path& file, const SessionContents& session,
                                  double max_age_days = kCalibrationMaxAgeDays);

}  // namespace scanstation::acquisition
