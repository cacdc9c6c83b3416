#include "helios/oem/oem.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>

#include "helios/astro/calendar.hpp"
#include "helios/io/error.hpp"

namespace helios::oem {
namespace {

using io::json;

constexpr long long kMicrosecondsPerDay = 86400LL * 1000000LL;
// A stay is the step of trajectory.csv that equals its length to within this many days (1 ms):
// an ordinary step is at most a 500th of the flight.
constexpr double kStayToleranceDays = 1e-8;

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

long long floor_div(long long a, long long b) {
  return a / b - ((a % b != 0) && ((a < 0) != (b < 0)) ? 1 : 0);
}

// KVN values and comments are printable ASCII on one line: anything else becomes '_' (values) or
// is dropped (comments), and a comment is cut at 200 characters.
std::string kvn_value(const std::string& s) {
  std::string out;
  for (const char c : s) {
    const bool ok =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    out += ok ? c : '_';
  }
  return out.empty() ? "UNNAMED" : out;
}

std::string kvn_comment_text(const std::string& s) {
  std::string out;
  for (const char c : s)
    if (c >= 0x20 && c < 0x7f) out += c;
  return out.size() > 200 ? out.substr(0, 200) : out;
}

// A file's name without its folder (the OEM's bytes do not depend on where the run is).
std::string base_name(const std::string& path) {
  const std::string name = path == "-" ? "<stdin>" : std::filesystem::path(path).filename().string();
  return kvn_comment_text(name);
}

std::string upper(std::string s) {
  for (char& c : s)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return s;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

struct Event {
  std::string id, kind;
  double stay_days = 0;
  double mass_drop_kg = 0;
};

std::string describe(const Event& e) {
  std::string s = e.id + " (" + e.kind;
  if (e.stay_days > 0) s += ", stay of " + fmt("%.10g", e.stay_days) + " d";
  if (e.mass_drop_kg > 0) s += ", lander of " + fmt("%.10g", e.mass_drop_kg) + " kg left";
  return s + ")";
}

// The frame of the spec's states and the comments that say why, by the central body.
struct Frame {
  std::string center, ref_frame;
  std::vector<std::string> comments;
};

bool uses_ephemeris(const json& spec) {
  for (const json& c : spec.at("constraints")) {
    const std::string kind = c.at("target").value("kind", "");
    if (kind == "body" || kind == "orbit") return true;
  }
  return false;
}

Frame frame_of(const json& spec, const std::string& source) {
  const std::string body = spec.at("central_body").at("name").get<std::string>();
  Frame f;
  f.center = upper(kvn_value(body));
  if (f.center == "SUN") {
    f.ref_frame = "ECLIPJ2000";
    f.comments = {"REF_FRAME ECLIPJ2000 is the mean ecliptic and equinox of J2000 (its NAIF/SPICE name);",
                  "it is not one of the OEM's listed frames (EME2000, ICRF, ...): a reader may need it mapped"};
    if (uses_ephemeris(spec))
      f.comments.push_back("It is the frame of the JPL low-precision ephemerides and the orbits the problem uses");
    else
      f.comments.insert(f.comments.end(),
                        {"The problem gives its states in km without naming a frame: written as given,",
                         "taken as ecliptic J2000 like the heliocentric ephemerides of HELIOS"});
  } else if (f.center == "EARTH") {
    f.ref_frame = "EME2000";
    f.comments = {"REF_FRAME EME2000: the problem gives its states in km without naming a frame;",
                  "its z axis is the Earth's pole (the J2 axis), taken as the mean equator of J2000"};
  } else {
    throw input_error(source + ": field /central_body/name: no OEM reference frame is known for a problem centred on " +
                      body + " (the OEM export knows the Sun and the Earth)");
  }
  return f;
}

// Throttle runs of one segment: the throttle at its start, then each change, one comment each.
void throttle_comments(std::ostringstream& o, const std::vector<TrajectorySample>& s, std::size_t begin,
                       std::size_t end, double epoch0) {
  if (s[begin].throttle < 0) {
    o << "COMMENT No throttle: a solar sail (its normal is in trajectory.csv)\n";
    return;
  }
  std::size_t changes = 0;
  for (std::size_t i = begin + 1; i < end; ++i) changes += s[i].throttle != s[i - 1].throttle;
  if (changes > 40) {
    double lo = s[begin].throttle, hi = lo;
    for (std::size_t i = begin; i < end; ++i) lo = std::min(lo, s[i].throttle), hi = std::max(hi, s[i].throttle);
    o << "COMMENT Throttle varies between " << fmt("%.6f", lo) << " and " << fmt("%.6f", hi) << " (" << changes
      << " changes; see trajectory.csv)\n";
    return;
  }
  o << "COMMENT Throttle " << fmt("%.6g", s[begin].throttle) << " from START_TIME\n";
  for (std::size_t i = begin + 1; i < end; ++i)
    if (s[i].throttle != s[i - 1].throttle)
      o << "COMMENT Throttle " << fmt("%.6g", s[i].throttle) << " from " << oem_epoch(epoch0 + s[i].t_days) << '\n';
}

}  // namespace

long long oem_epoch_microseconds(double mjd2000) {
  // Years 0001-9999: -730119 and +2921940 days from MJD2000 0.
  if (!std::isfinite(mjd2000) || mjd2000 < -730119.0 || mjd2000 >= 2921940.0)
    throw std::invalid_argument("epoch MJD2000 " + fmt("%.17g", mjd2000) + " is outside the years 0001-9999");
  return std::llround(static_cast<long double>(mjd2000) * static_cast<long double>(kMicrosecondsPerDay));
}

std::string oem_epoch(double mjd2000) {
  // Microseconds since 2000-01-01T00:00:00, MJD2000 0 (MJD 51544).
  const long long us = oem_epoch_microseconds(mjd2000);
  const long long days = floor_div(us, kMicrosecondsPerDay);
  long long rest = us - days * kMicrosecondsPerDay;
  long long year = 0;
  int month = 0, day = 0;
  astro::civil_from_days_since_2000(days, year, month, day);
  if (year < 1 || year > 9999)
    throw std::invalid_argument("epoch MJD2000 " + fmt("%.17g", mjd2000) + " is outside the years 0001-9999");
  const long long hour = rest / 3600000000LL;
  rest -= hour * 3600000000LL;
  const long long minute = rest / 60000000LL;
  rest -= minute * 60000000LL;
  const long long second = rest / 1000000LL;
  const long long micro = rest - second * 1000000LL;
  char buf[96];  // room for any long long, though the checks above bound every field
  std::snprintf(buf, sizeof buf, "%04lld-%02d-%02dT%02lld:%02lld:%02lld.%06lld", year, month, day, hour, minute, second,
                micro);
  return buf;
}

std::vector<TrajectorySample> read_trajectory(const std::string& csv_text, const std::string& source) {
  std::istringstream in(csv_text);
  std::string line;
  if (std::getline(in, line) && !line.empty() && line.back() == '\r') line.pop_back();
  if (line.empty()) throw input_error(source + ":1: no header line");
  const std::vector<std::string> header = split_csv_line(line);
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column.emplace(header[i], i);
  const char* const state_names[6] = {"rx_km", "ry_km", "rz_km", "vx_km_s", "vy_km_s", "vz_km_s"};
  std::size_t state_col[6];
  for (int k = 0; k < 6; ++k) {
    if (!column.count(state_names[k]))
      throw input_error(source + ":1: no column " + state_names[k] +
                        " (the OEM needs positions in km and velocities in km/s)");
    state_col[k] = column.at(state_names[k]);
  }
  if (!column.count("t_days")) throw input_error(source + ":1: no column t_days");
  const std::size_t t_col = column.at("t_days");
  const bool has_mass = column.count("m_kg") > 0, has_throttle = column.count("u") > 0;
  std::vector<TrajectorySample> out;
  std::size_t line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a CSV saved with CRLF line ends
    if (line.empty()) continue;
    const std::vector<std::string> f = split_csv_line(line);
    if (f.size() != header.size())
      throw input_error(source + ":" + std::to_string(line_no) + ": " + std::to_string(f.size()) +
                        " fields, the header has " + std::to_string(header.size()));
    const auto number = [&](std::size_t col) {
      const std::string& text = f[col];
      char* end = nullptr;
      errno = 0;
      const double v = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(v))
        throw input_error(source + ":" + std::to_string(line_no) + ": field " + header[col] + ": '" +
                          kvn_comment_text(text.substr(0, 40)) + "' is not a finite number");
      return v;
    };
    TrajectorySample s;
    s.line = line_no;
    s.t_days = number(t_col);
    for (int k = 0; k < 6; ++k) s.state[k] = number(state_col[k]);
    if (has_mass) s.mass_kg = number(column.at("m_kg"));
    if (has_throttle) s.throttle = number(column.at("u"));
    out.push_back(s);
  }
  if (out.empty()) throw input_error(source + ": no samples after the header");
  return out;
}

std::vector<std::size_t> oem_segment_starts(const std::vector<TrajectorySample>& samples,
                                            const std::vector<double>& stays_days, const std::string& source) {
  std::vector<std::size_t> starts{0};
  std::size_t next_event = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const double dt = samples[i].t_days - samples[i - 1].t_days;
    const std::string where = source + ":" + std::to_string(samples[i].line) + ": ";
    const bool stay_due = next_event < stays_days.size() && stays_days[next_event] > 0;
    if (dt < 0)
      throw input_error(where + "field t_days: " + fmt("%.15g", samples[i].t_days) +
                        " is before the previous sample's " + fmt("%.15g", samples[i - 1].t_days));
    if (dt == 0) {
      if (next_event >= stays_days.size())
        throw input_error(where + "field t_days: a repeated time (an event) after all " +
                          std::to_string(stays_days.size()) + " interior events of the spec");
      if (stay_due)
        throw input_error(where + "field t_days: a repeated time where the spec's next event stays " +
                          fmt("%.10g", stays_days[next_event]) + " d");
      starts.push_back(i);
      ++next_event;
    } else if (stay_due && std::fabs(dt - stays_days[next_event]) <= kStayToleranceDays) {
      starts.push_back(i);
      ++next_event;
    }
  }
  if (next_event != stays_days.size())
    throw input_error(source + ": field t_days: " + std::to_string(next_event) + " of the spec's " +
                      std::to_string(stays_days.size()) +
                      " interior events found (an event is a repeated time, a stay a step of its length)");
  return starts;
}

std::optional<std::string> oem_from_run(const json& spec, const json& solution, const std::string& trajectory_csv,
                                        const OemSources& sources) {
  if (solution.at("status").get<std::string>() != "converged") return std::nullopt;
  const std::string id = spec.at("problem").at("id").get<std::string>();
  const std::string solution_id = solution.at("problem").at("id").get<std::string>();
  if (solution_id != id)
    throw input_error(sources.solution + ": field /problem/id: " + solution_id + " is not the problem of " +
                      sources.spec + " (" + id + ")");
  const Frame frame = frame_of(spec, sources.spec);
  const json& time = spec.at("time");
  const bool has_epoch = time.contains("epoch_mjd2000");
  const double epoch0 = has_epoch ? time.at("epoch_mjd2000").get<double>() : kOemDefaultEpochMjd2000;

  std::vector<Event> events;
  for (const json& c : spec.at("constraints")) {
    if (c.at("at") != "interior") continue;
    events.push_back({c.at("id").get<std::string>(), c.at("kind").get<std::string>(), c.value("stay_days", 0.0),
                      c.value("mass_drop_kg", 0.0)});
  }
  std::vector<double> stays;
  for (const Event& e : events) stays.push_back(e.stay_days);

  const std::vector<TrajectorySample> samples = read_trajectory(trajectory_csv, sources.trajectory);
  const std::vector<std::size_t> starts = oem_segment_starts(samples, stays, sources.trajectory);
  std::vector<std::string> epochs;
  for (const TrajectorySample& s : samples) {
    try {
      epochs.push_back(oem_epoch(epoch0 + s.t_days));
    } catch (const std::invalid_argument& e) {
      throw input_error(sources.trajectory + ":" + std::to_string(s.line) + ": field t_days: " + e.what());
    }
  }

  std::ostringstream o;
  o << "CCSDS_OEM_VERS = 2.0\n"
    << "COMMENT HELIOS trajectory of " << kvn_comment_text(id) << ": "
    << kvn_comment_text(spec.at("problem").value("title", "")) << '\n'
    << "COMMENT Written by helios-score --oem from " << base_name(sources.spec) << ", " << base_name(sources.solution)
    << " and " << base_name(sources.trajectory) << ":\n"
    << "COMMENT positions in km, velocities in km/s, at the trajectory's own samples\n";
  for (const std::string& c : frame.comments) o << "COMMENT " << c << '\n';
  if (has_epoch)
    o << "COMMENT Epochs: t = 0 of the problem is MJD2000 " << fmt("%.10g", epoch0) << " = " << oem_epoch(epoch0)
      << " TDB\n";
  else
    o << "COMMENT The problem states no calendar epoch: t = 0 is put at the default epoch\n"
      << "COMMENT " << oem_epoch(epoch0) << " TDB (J2000.0); only times relative to it mean anything\n";
  o << "COMMENT One segment per arc between interior events; a stay or a state jump starts a new one\n"
    << "COMMENT CREATION_DATE is fixed, not the wall clock: the same run gives the same bytes\n"
    << "CREATION_DATE = " << kOemCreationDate << '\n'
    << "ORIGINATOR = HELIOS\n";

  const std::size_t n_segments = starts.size();
  for (std::size_t k = 0; k < n_segments; ++k) {
    const std::size_t begin = starts[k];
    const std::size_t end = k + 1 < n_segments ? starts[k + 1] : samples.size();
    for (std::size_t i = begin + 1; i < end; ++i)
      if (oem_epoch_microseconds(epoch0 + samples[i].t_days) <= oem_epoch_microseconds(epoch0 + samples[i - 1].t_days))
        throw input_error(sources.trajectory + ":" + std::to_string(samples[i].line) +
                          ": field t_days: less than a microsecond after the previous sample (the OEM's epochs would "
                          "not increase)");
    o << "\nMETA_START\n"
      << "OBJECT_NAME = " << kvn_value(id) << '\n'
      << "OBJECT_ID = HELIOS-" << kvn_value(id) << '\n'
      << "CENTER_NAME = " << frame.center << '\n'
      << "REF_FRAME = " << frame.ref_frame << '\n'
      << "TIME_SYSTEM = TDB\n"
      << "START_TIME = " << epochs[begin] << '\n'
      << "STOP_TIME = " << epochs[end - 1] << '\n'
      << "META_STOP\n\n";
    o << "COMMENT Segment " << k + 1 << " of " << n_segments << ": from "
      << (k == 0 ? std::string("the departure") : "event " + describe(events[k - 1])) << " to "
      << (k + 1 < n_segments ? "event " + describe(events[k]) : std::string("the arrival")) << '\n';
    if (samples[begin].mass_kg >= 0)
      o << "COMMENT Mass " << fmt("%.6f", samples[begin].mass_kg) << " kg at START_TIME, "
        << fmt("%.6f", samples[end - 1].mass_kg) << " kg at STOP_TIME\n";
    throttle_comments(o, samples, begin, end, epoch0);
    for (std::size_t i = begin; i < end; ++i) {
      o << epochs[i];
      for (const double v : samples[i].state) o << ' ' << fmt("%.15e", v);
      o << '\n';
    }
  }
  return o.str();
}

}  // namespace helios::oem
