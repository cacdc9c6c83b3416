// The plots of a trajectory, drawn with gnuplot: the path with the central body to scale, the
// orbit the spacecraft starts on and the one it ends on, the thrust direction and equal axes (a
// top view for a near-planar transfer), and the control and mass against time in the problem's
// unit (hours for a flight under three days, else days).
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/astro/calendar.hpp"
#include "helios/io/json_io.hpp"
#include "helios/io/process.hpp"
#include "helios/solve/solve.hpp"

namespace helios::solve {
namespace {

namespace fs = std::filesystem;
using io::json;
using Vec = std::array<double, 3>;

constexpr double kAuKm = 149597870.691;
// A transfer whose extent out of the x-y plane is below this share of its extent in it is drawn
// from the top (x-y, equal scales); any other in 3-D with equal scales.
constexpr double kPlanarShare = 0.05;
// Thrust-direction arrows along the thrusting arcs (at most), each this share of the plot's extent.
constexpr int kArrows = 40;
constexpr double kArrowShare = 0.06;
// The parts a step of the trajectory is drawn in (a cubic through its ends' positions and velocities).
constexpr int kHermiteParts = 8;

Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Vec& a) {
  return std::sqrt(dot(a, a));
}

// The trajectory CSV the program wrote (a regular file of at most 64 MiB: io::read_program_file),
// as columns by name.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
  }
};

Table read_table(const std::string& csv_path) {
  std::istringstream in(io::read_program_file(csv_path));
  Table t;
  std::string line;
  std::getline(in, line);
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) t.names.push_back(c);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream rs(line);
    for (std::string v; std::getline(rs, v, ',');) row.push_back(std::strtod(v.c_str(), nullptr));
    if (row.size() == t.names.size()) t.rows.push_back(std::move(row));
  }
  if (t.rows.empty() || t.names.size() < 7) throw std::runtime_error(csv_path + ": no trajectory rows to plot");
  return t;
}

// What the plots take from the spec: the central body, the thrust, the epoch and the endpoints.
struct Context {
  std::string body = "central body";
  double mu_km3_s2 = 0, radius_km = 0, thrust_N = 0;
  double constant_mass_kg = 0;  // an engine of constant mass (no mass column): its mass
  bool has_epoch = false;
  double epoch_mjd2000 = 0;
  std::string start_label = "initial orbit", end_label = "final orbit (osculating)";
};

std::string possessive(const std::string& name) {
  return name + (name.empty() || name.back() == 's' ? "' orbit" : "'s orbit");
}

Context context_of(const json* spec) {
  Context c;
  if (spec == nullptr || !spec->is_object()) return c;
  const json& cb = spec->value("central_body", json::object());
  if (cb.is_object()) {
    c.body = cb.value("name", c.body);
    c.mu_km3_s2 = cb.value("mu_km3_s2", 0.0);
    c.radius_km = cb.value("radius_km", 0.0);
  }
  if (const json& sc = spec->value("spacecraft", json::object()); sc.is_object()) {
    c.thrust_N = sc.value("thrust_N", 0.0);
    if (sc.value("mass_model", "") == "constant") c.constant_mass_kg = sc.value("initial_mass_kg", 0.0);
  }
  if (const json& t = spec->value("time", json::object()); t.is_object() && t.contains("epoch_mjd2000")) {
    c.has_epoch = t.at("epoch_mjd2000").is_number();
    if (c.has_epoch) c.epoch_mjd2000 = t.at("epoch_mjd2000").get<double>();
  }
  for (const json& k : spec->value("constraints", json::array())) {
    if (!k.is_object()) continue;
    const json& target = k.value("target", json::object());
    const std::string at = k.value("at", ""), kind = k.value("kind", "");
    const std::string body = target.is_object() ? target.value("body", "") : "";
    if (at == "t0" && kind == "initial_state" && !body.empty()) c.start_label = possessive(body);
    if (at == "tf" && (kind == "rendezvous" || kind == "orbit_insertion"))
      c.end_label = body.empty() ? "target orbit" : possessive(body);
  }
  return c;
}

// One period of the Keplerian orbit through (r, v) about mu, as points; none for an open orbit.
std::vector<Vec> conic(const Vec& r, const Vec& v, double mu) {
  std::vector<Vec> points;
  const double rn = norm(r);
  if (mu <= 0 || rn <= 0) return points;
  const Vec h = cross(r, v);
  const double hn = norm(h);
  if (hn <= 0) return points;
  const Vec vh = cross(v, h);
  const Vec e = {vh[0] / mu - r[0] / rn, vh[1] / mu - r[1] / rn, vh[2] / mu - r[2] / rn};
  const double en = norm(e);
  if (en >= 0.99) return points;
  const Vec P = en > 1e-9 ? Vec{e[0] / en, e[1] / en, e[2] / en} : Vec{r[0] / rn, r[1] / rn, r[2] / rn};
  const Vec hh = {h[0] / hn, h[1] / hn, h[2] / hn};
  const Vec Q = cross(hh, P);
  const double p = hn * hn / mu;
  for (int k = 0; k <= 360; ++k) {
    const double nu = k * M_PI / 180;
    const double rad = p / (1 + en * std::cos(nu));
    points.push_back({rad * (std::cos(nu) * P[0] + std::sin(nu) * Q[0]),
                      rad * (std::cos(nu) * P[1] + std::sin(nu) * Q[1]),
                      rad * (std::cos(nu) * P[2] + std::sin(nu) * Q[2])});
  }
  return points;
}

// The central body as a wire sphere of its radius: parallels and meridians every 30 degrees.
std::vector<std::vector<Vec>> sphere(double radius) {
  std::vector<std::vector<Vec>> lines;
  for (int lat = -60; lat <= 60; lat += 30) {
    std::vector<Vec> line;
    for (int lon = 0; lon <= 360; lon += 5) {
      const double a = lat * M_PI / 180, b = lon * M_PI / 180;
      line.push_back({radius * std::cos(a) * std::cos(b), radius * std::cos(a) * std::sin(b), radius * std::sin(a)});
    }
    lines.push_back(line);
  }
  for (int lon = 0; lon < 360; lon += 30) {
    std::vector<Vec> line;
    for (int lat = -90; lat <= 90; lat += 5) {
      const double a = lat * M_PI / 180, b = lon * M_PI / 180;
      line.push_back({radius * std::cos(a) * std::cos(b), radius * std::cos(a) * std::sin(b), radius * std::sin(a)});
    }
    lines.push_back(line);
  }
  return lines;
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// A trajectory table read for plotting: its columns by role, positions and velocities by row, the
// mass (its column, or the constant mass the spec states), and the colour along the path (the
// throttle, or a sail's cone angle: its normal against the Sun line).
struct Trajectory {
  Trajectory(const Table& t, double constant_mass) : table(t), constant_mass_kg(constant_mass) {
    const auto col = [&t](const std::string& name, int fallback) {
      const int c = t.column(name);
      return c >= 0 ? c : fallback;
    };
    r = {col("rx_km", 1), col("ry_km", 2), col("rz_km", 3)};
    v = {col("vx_km_s", 4), col("vy_km_s", 5), col("vz_km_s", 6)};
    a = {t.column("ax"), t.column("ay"), t.column("az")};
    n = {t.column("nx"), t.column("ny"), t.column("nz")};
    throttle = t.column("u");
    mass = t.column("m_kg");
    engine = throttle >= 0 && (mass >= 0 || constant_mass_kg > 0);
  }
  Vec pos(const std::vector<double>& row) const { return {row[r[0]], row[r[1]], row[r[2]]}; }
  Vec vel(const std::vector<double>& row) const { return {row[v[0]], row[v[1]], row[v[2]]}; }
  bool has(const std::array<int, 3>& c) const { return c[0] >= 0 && c[1] >= 0 && c[2] >= 0; }
  double mass_kg(const std::vector<double>& row) const { return mass >= 0 ? row[mass] : constant_mass_kg; }
  double colour(const std::vector<double>& row) const {
    if (engine) return row[throttle];
    if (!has(n)) return 0.0;
    const Vec p = pos(row), normal = {row[n[0]], row[n[1]], row[n[2]]};
    const double c = dot(p, normal) / (norm(p) * std::max(norm(normal), 1e-300));
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI;
  }
  const Table& table;
  double constant_mass_kg = 0;
  std::array<int, 3> r{}, v{}, a{}, n{};
  int throttle = -1, mass = -1;
  bool engine = false;
};

// The data gnuplot draws, in blocks by role ("path", "series", "start", "end", "body", "arrows",
// "ends", "centre"), each written only when it has points.
class PlotData {
 public:
  void begin(const std::string& role) {
    if (!roles_.empty()) text_ << "\n\n";
    roles_.push_back(role);
  }
  std::ostream& out() { return text_; }
  // The block's gnuplot index, -1 where there is none.
  int index(const std::string& role) const {
    const auto it = std::find(roles_.begin(), roles_.end(), role);
    return it == roles_.end() ? -1 : static_cast<int>(it - roles_.begin());
  }
  std::string text() const { return text_.str(); }
  void points(const std::string& role, const std::vector<Vec>& points, double unit) {
    if (points.empty()) return;
    begin(role);
    for (const auto& p : points) text_ << p[0] / unit << ' ' << p[1] / unit << ' ' << p[2] / unit << '\n';
  }

 private:
  std::ostringstream text_ = [] {
    std::ostringstream o;
    o.precision(10);
    return o;
  }();
  std::vector<std::string> roles_;
};

// The path, x y z colour: between two rows a cubic Hermite curve through their positions and
// velocities (the program writes a row per integration step, a few per revolution: straight
// lines between them would draw a polygon), the colour of the row it starts from.
void write_path(const Trajectory& t, double unit, PlotData& data) {
  data.begin("path");
  std::ostream& out = data.out();
  const auto& rows = t.table.rows;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& row = rows[i];
    const Vec p0 = t.pos(row);
    out << p0[0] / unit << ' ' << p0[1] / unit << ' ' << p0[2] / unit << ' ' << t.colour(row) << '\n';
    if (i + 1 == rows.size()) break;
    const auto& next = rows[i + 1];
    const double dt = (next[0] - row[0]) * 86400;
    if (!(dt > 0)) continue;  // an event: no time between the rows
    const Vec p1 = t.pos(next), v0 = t.vel(row), v1 = t.vel(next);
    for (int k = 1; k < kHermiteParts; ++k) {
      const double s = static_cast<double>(k) / kHermiteParts, s2 = s * s, s3 = s2 * s;
      const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      for (int j = 0; j < 3; ++j)
        out << (h00 * p0[j] + h10 * dt * v0[j] + h01 * p1[j] + h11 * dt * v1[j]) / unit << ' ';
      out << t.colour(row) << '\n';
    }
  }
}

// The thrust direction where the engine thrusts (throttle above one half), evenly spaced in
// thrusting time (the rows are integration steps, dense where the dynamics are fast), each arrow
// `length` long (plot units) and none over the one before.
void write_arrows(const Trajectory& t, double unit, double length, PlotData& data) {
  if (!t.engine || !t.has(t.a)) return;
  const auto& rows = t.table.rows;
  double thrusting = 0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i)
    if (rows[i][t.throttle] > 0.5) thrusting += rows[i + 1][0] - rows[i][0];
  if (!(thrusting > 0)) return;
  data.begin("arrows");
  const double spacing = thrusting / kArrows;
  double so_far = 0, next_at = spacing / 2;
  Vec last_arrow = {NAN, NAN, NAN};
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const auto& row = rows[i];
    if (row[t.throttle] <= 0.5) continue;
    so_far += rows[i + 1][0] - row[0];
    if (so_far < next_at) continue;
    while (next_at <= so_far) next_at += spacing;
    const Vec p = t.pos(row), a = {row[t.a[0]], row[t.a[1]], row[t.a[2]]};
    // No arrow over the one before (short thrust arcs): at least most of an arrow's length apart.
    const Vec gap = {p[0] / unit - last_arrow[0], p[1] / unit - last_arrow[1], p[2] / unit - last_arrow[2]};
    if (norm(gap) < 0.7 * length) continue;
    last_arrow = {p[0] / unit, p[1] / unit, p[2] / unit};
    const double an = std::max(norm(a), 1e-300);
    data.out() << p[0] / unit << ' ' << p[1] / unit << ' ' << p[2] / unit << ' ' << length * a[0] / an << ' '
               << length * a[1] / an << ' ' << length * a[2] / an << '\n';
  }
}

// The trajectory's gnuplot commands (ARG2 the title, ARG5 the subtitle, ARG6 and ARG7 the orbits'
// names, ARG8 the central body's): seen from +z (`top_view`, the body a filled disc of its radius)
// or in 3-D (a wire sphere), with equal scales.
std::string trajectory_script(const PlotData& data, const Context& ctx, bool engine, bool top_view, bool heliocentric,
                              double unit, const std::string& length) {
  std::string s = "set terminal pngcairo size 1000,900 noenhanced\nset output ARG3\n";
  s +=
      "set title ARG2.': trajectory (colour = " + std::string(engine ? "throttle" : "cone angle") + ")'.\"\\n\".ARG5\n";
  s += "set grid\nset key outside bottom center horizontal\n";
  s += "set palette defined (0 '#2b6cb0', 1 '#e53e3e')\n";
  s +=
      engine ? "set cbrange [0:1]\nset cblabel 'throttle u'\n" : "set cbrange [0:90]\nset cblabel 'cone angle [deg]'\n";
  s += "set xlabel 'x [" + length + "]'\nset ylabel 'y [" + length + "]'\n";
  const bool disc = top_view && ctx.radius_km > 0 && !heliocentric;
  if (top_view) {
    s += "set size ratio -1\n";
    if (disc)
      s += "set object 1 circle at 0,0 size " + number(ctx.radius_km / unit) +
           " front fc rgb '#3182ce' fs solid 0.5 border lc rgb '#2c5282'\n";
  } else {
    s += "set zlabel 'z [" + length + "]' rotate parallel\nset view equal xyz\nset ticslevel 0\nset view 60,30\n";
  }
  // The columns of a point, of a point and a value, of a point and a vector, in this view.
  const std::string point = top_view ? "1:2" : "1:2:3", valued = top_view ? "1:2:4" : "1:2:3:4";
  const std::string vector = top_view ? "1:2:4:5" : "1:2:3:4:5:6";
  const auto block = [&data](const std::string& role) { return "ARG1 index " + std::to_string(data.index(role)); };
  std::vector<std::string> plots;
  // The body's name in the key: a disc (top view) or a wire sphere of its radius (to scale), or the
  // Sun's marker.
  if (disc)
    plots.push_back("keyentry with filledcurves fc rgb '#3182ce' fs solid 0.5 title ARG8");
  else if (data.index("body") >= 0)
    plots.push_back(block("body") + " using 1:2:3 with lines lw 0.5 lc rgb '#3182ce' title ARG8");
  else
    plots.push_back(block("centre") + " using " + point + " with points pt 7 ps 2.5 lc rgb '#d69e2e' title ARG8");
  if (data.index("start") >= 0)
    plots.push_back(block("start") + " using " + point + " with lines lw 1.5 dt 2 lc rgb '#718096' title ARG6");
  if (data.index("end") >= 0)
    plots.push_back(block("end") + " using " + point + " with lines lw 2 dt 4 lc rgb '#2f855a' title ARG7");
  plots.push_back(block("path") + " using " + valued + " with lines lw 2 lc palette title 'spacecraft'");
  if (data.index("arrows") >= 0)
    plots.push_back(block("arrows") + " using " + vector +
                    " with vectors head filled size screen 0.008,25 lw 1 lc rgb '#1a202c' title 'thrust direction'");
  plots.push_back(block("ends") + " every ::0::0 using " + point +
                  " with points pt 5 ps 1.5 lc rgb '#1a202c' title 'departure'");
  plots.push_back(block("ends") + " every ::1::1 using " + point +
                  " with points pt 9 ps 2 lc rgb '#1a202c' title 'arrival'");
  s += top_view ? "plot " : "splot ";
  for (std::size_t i = 0; i < plots.size(); ++i) s += (i ? ", \\\n  " : "") + plots[i];
  return s + "\n";
}

// The control and the mass (or a sail's cone angle) against time (ARG4 the PNG, ARG9 the time
// axis' label), from the block "series".
std::string panel_script(const PlotData& data, const Context& ctx, bool engine) {
  const std::string series = "ARG1 index " + std::to_string(data.index("series"));
  std::string s = "reset\nset terminal pngcairo size 1000,600 noenhanced\nset output ARG4\nset grid\nset xlabel ARG9\n";
  s += "set key outside bottom center horizontal\nset bmargin 6\n";  // room for the time label above the key
  if (!engine)
    return s + "set title ARG2.': sail cone angle'.\"\\n\".ARG5\nset ylabel 'cone angle [deg]'\nset yrange [0:90]\n" +
           "plot " + series + " using 1:2 with lines lw 2 lc rgb '#e53e3e' title 'cone angle'\n";
  const std::string thrust = ctx.thrust_N > 0 ? "thrust [N]" : "throttle u";
  const double top = ctx.thrust_N > 0 ? ctx.thrust_N : 1.0;
  s += "set title ARG2.': " + std::string(ctx.thrust_N > 0 ? "thrust" : "throttle") + " and mass'.\"\\n\".ARG5\n";
  s += "set ylabel '" + thrust + "'\nset y2label 'mass [kg]'\nset yrange [" + number(-0.05 * top) + ":" +
       number(1.05 * top) + "]\nset y2tics\nset ytics nomirror\n";
  return s + "plot " + series + " using 1:2 with lines lw 2 lc rgb '#e53e3e' title '" + thrust + "', '' index " +
         std::to_string(data.index("series")) +
         " using 1:3 axes x1y2 with lines lw 2 lc rgb '#2b6cb0' title 'mass [kg]'\n";
}

}  // namespace

std::string run_gnuplot(const std::string& script, const std::vector<std::string>& args) {
  char script_path[] = "/tmp/helios-plot-XXXXXX";
  const int fd = ::mkstemp(script_path);
  if (fd < 0) throw std::runtime_error("cannot create a gnuplot script file");
  const io::TempFiles guard({script_path});
  const bool written = ::write(fd, script.data(), script.size()) == static_cast<ssize_t>(script.size());
  ::close(fd);
  if (!written) throw std::runtime_error("cannot write the gnuplot script");
  std::vector<std::string> argv = {"gnuplot", "-c", script_path};
  argv.insert(argv.end(), args.begin(), args.end());
  return io::capture(argv);
}

json plot_trajectory(const std::string& csv_path, const std::string& prefix, const std::string& title,
                     const json* spec) {
  const Table table = read_table(csv_path);
  const Context ctx = context_of(spec);
  const Trajectory t(table, ctx.constant_mass_kg);
  const auto& first = table.rows.front();
  const auto& last = table.rows.back();
  const bool heliocentric = norm(t.pos(first)) > 1e7;
  const double unit = heliocentric ? kAuKm : 1.0;

  // Time from departure in the problem's unit.
  const double t0 = first[0], tof_days = last[0] - first[0];
  const bool hours = tof_days < astro::kHoursBelowDays;
  const std::string time_label =
      std::string(hours ? "hours" : "days") + " after departure" +
      (ctx.has_epoch ? " (" + astro::iso_date_tdb(ctx.epoch_mjd2000 + t0).substr(0, 10) + " TDB)" : "");

  const std::vector<Vec> start_orbit = conic(t.pos(first), t.vel(first), ctx.mu_km3_s2);
  const std::vector<Vec> end_orbit = conic(t.pos(last), t.vel(last), ctx.mu_km3_s2);
  // The extents, for the view and the arrows' length.
  double xy_extent = 0, z_lo = 0, z_hi = 0;
  const auto extend = [&](const Vec& p) {
    xy_extent = std::max({xy_extent, std::fabs(p[0]), std::fabs(p[1])});
    z_lo = std::min(z_lo, p[2]);
    z_hi = std::max(z_hi, p[2]);
  };
  for (const auto& row : table.rows) extend(t.pos(row));
  for (const auto* orbit : {&start_orbit, &end_orbit})
    for (const auto& p : *orbit) extend(p);
  const bool top_view = z_hi - z_lo <= kPlanarShare * 2 * xy_extent;

  PlotData data;
  write_path(t, unit, data);
  // The time series: t, thrust (or throttle, or cone angle), mass.
  data.begin("series");
  for (const auto& row : table.rows)
    data.out() << (row[0] - t0) * (hours ? 24.0 : 1.0) << ' '
               << (t.engine ? row[t.throttle] * (ctx.thrust_N > 0 ? ctx.thrust_N : 1.0) : t.colour(row)) << ' '
               << (t.engine ? t.mass_kg(row) : 0.0) << '\n';
  data.points("start", start_orbit, unit);
  data.points("end", end_orbit, unit);
  if (ctx.radius_km > 0 && !top_view) {
    data.begin("body");
    bool first_line = true;
    for (const auto& line : sphere(ctx.radius_km / unit)) {
      if (!first_line) data.out() << '\n';  // one blank line: a new curve in the same block
      first_line = false;
      for (const auto& p : line) data.out() << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
  }
  write_arrows(t, unit, kArrowShare * 2 * xy_extent / unit, data);
  data.points("ends", {t.pos(first), t.pos(last)}, unit);
  data.points("centre", {Vec{0, 0, 0}}, 1.0);

  const std::string panel = t.engine ? "throttle_mass" : "cone_angle";
  const std::string traj_png = prefix + "trajectory.png", panel_png = prefix + panel + ".png";
  // Fresh files gnuplot only fills: nothing planted under a predictable name is followed.
  io::TempFiles temps;
  const std::string tmp1 = temps.create_beside(traj_png), tmp2 = temps.create_beside(panel_png);
  const std::string data_file = temps.create_beside(traj_png);
  {
    std::ofstream out(data_file, std::ios::binary | std::ios::trunc);
    out << data.text();
    if (!out) throw std::runtime_error(data_file + ": cannot write the plot's data");
  }
  // The subtitle: the dates (a problem with an epoch) or the time of flight.
  std::string subtitle = "time of flight " + astro::duration_text(tof_days);
  if (ctx.has_epoch)
    subtitle += ", departure " + astro::iso_date_tdb(ctx.epoch_mjd2000 + t0) + " TDB, arrival " +
                astro::iso_date_tdb(ctx.epoch_mjd2000 + last[0]) + " TDB";
  const std::string body_label = ctx.body + (heliocentric ? " (not to scale)" : " (to scale)");
  // ARG1 the data, ARG2 the title, ARG3 and ARG4 the two PNGs, ARG5 the subtitle, ARG6 and ARG7
  // the orbits' names, ARG8 the central body's, ARG9 the time axis' (run_gnuplot: all as data).
  const std::string script =
      trajectory_script(data, ctx, t.engine, top_view, heliocentric, unit, heliocentric ? "AU" : "km") +
      panel_script(data, ctx, t.engine);
  const std::string out = run_gnuplot(
      script, {data_file, title, tmp1, tmp2, subtitle, ctx.start_label, ctx.end_label, body_label, time_label});
  std::error_code ec;
  if (fs::file_size(tmp1, ec) == 0 || fs::file_size(tmp2, ec) == 0)
    throw std::runtime_error("gnuplot did not draw the plots (is gnuplot installed?): " + io::first_line(out));
  io::move_into_place(tmp1, traj_png);
  io::move_into_place(tmp2, panel_png);
  return {{"trajectory_plot", fs::path(traj_png).filename().string()},
          {panel + "_plot", fs::path(panel_png).filename().string()}};
}

}  // namespace helios::solve
