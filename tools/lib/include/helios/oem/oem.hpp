#pragma once
// trajectory.oem: a converged run's trajectory.csv as a CCSDS Orbit Ephemeris Message, OEM 2.0 in
// KVN form (CCSDS 502.0-B-3): one segment per arc between interior events, positions in km and
// velocities in km/s at the trajectory's own samples, TIME_SYSTEM TDB, and COMMENT lines for the
// frame, the epoch, the mass and the throttle (tools/lib/src/oem/README.md).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::oem {

// The epoch of t = 0 when the problem states no calendar epoch: J2000.0 = 2000-01-01T12:00:00 TDB,
// MJD2000 0.5 (MJD2000 = MJD - 51544: day 0 starts at 2000-01-01T00:00). The OEM then says so in a COMMENT.
constexpr double kOemDefaultEpochMjd2000 = 0.5;

// CREATION_DATE of every OEM: fixed, not the wall clock, so that the same run gives the same bytes.
inline constexpr const char* kOemCreationDate = "2000-01-01T00:00:00";

// A TDB epoch given in MJD2000 (days since 2000-01-01T00:00:00) as YYYY-MM-DDThh:mm:ss.ffffff,
// rounded to the microsecond. Throws std::invalid_argument outside the years 0001-9999.
std::string oem_epoch(double mjd2000);

// The same epoch as a whole number of microseconds since 2000-01-01T00:00:00 (what oem_epoch prints).
long long oem_epoch_microseconds(double mjd2000);

// One row of trajectory.csv as the OEM uses it.
struct TrajectorySample {
  double t_days = 0;     // days after the spec's epoch_mjd2000 (or after t = 0 without one)
  double state[6] = {};  // rx, ry, rz [km], vx, vy, vz [km/s]
  double mass_kg = -1;   // < 0: the problem has no mass state (a sail)
  double throttle = -1;  // < 0: no throttle column
  std::size_t line = 0;  // line number in the CSV (for errors)
};

// Parses trajectory.csv (header t_days, rx_km, ry_km, rz_km, vx_km_s, vy_km_s, vz_km_s, and
// optionally m_kg and u, among other columns). Throws input_error "SOURCE:LINE: ..." on a missing
// column, a short row or a field that is not a finite number.
std::vector<TrajectorySample> read_trajectory(const std::string& csv_text, const std::string& source);

// Splits the samples into the arcs between interior events. `stays_days` has one entry per interior
// event of the spec, in order: its stay in days (0 for an instantaneous event). trajectory.csv
// marks an instantaneous event (flyby, rendezvous without a stay, swing-by, a dropped lander) by
// two samples at the same time (the arc's end and the next arc's start), and a stay by a step of
// exactly the stay's length (no samples during it). Returns the index of each segment's first
// sample (the first is 0). Throws input_error naming SOURCE and the line where times go back, a
// repeated time comes where a stay is due, or where the events found do not match the spec's.
std::vector<std::size_t> oem_segment_starts(const std::vector<TrajectorySample>& samples,
                                            const std::vector<double>& stays_days, const std::string& source);

// File names used in errors and in the OEM's comments.
struct OemSources {
  std::string spec = "spec.json";
  std::string solution = "solution.json";
  std::string trajectory = "trajectory.csv";
};

// The OEM of a run: the already-read (schema-valid) spec and solution artifacts and the text of
// trajectory.csv. std::nullopt when the solution did not converge (there is no trajectory to
// export). Throws input_error "FILE: field X: ..." for an input the OEM cannot be made from (a
// central body other than the Sun or Earth, a solution of another problem, a malformed CSV).
std::optional<std::string> oem_from_run(const io::json& spec, const io::json& solution,
                                        const std::string& trajectory_csv, const OemSources& sources = {});

}  // namespace helios::oem
