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
  const auto col = [&table](const std::string& name, int fallback) {
    const int c = table.column(name);
    return c >= 0 ? c : fallback;
  };
  const int cx = col("rx_km", 1), cy = col("ry_km", 2), cz = col("rz_km", 3);
  const int cvx = col("vx_km_s", 4), cvy = col("vy_km_s", 5), cvz = col("vz_km_s", 6);
  const int cu = table.column("u"), cm = table.column("m_kg");
  const int cax = table.column("ax"), cay = table.column("ay"), caz = table.column("az");
  const int cnx = table.column("nx"), cny = table.column("ny"), cnz = table.column("nz");
  // An engine: a throttle and the mass, its column or the constant mass the spec states.
  const bool engine = cu >= 0 && (cm >= 0 || ctx.constant_mass_kg > 0);
  const auto& first = table.rows.front();
  const auto& last = table.rows.back();
  const auto pos = [&](const std::vector<double>& row) { return Vec{row[cx], row[cy], row[cz]}; };
  const auto vel = [&](const std::vector<double>& row) { return Vec{row[cvx], row[cvy], row[cvz]}; };
  const bool heliocentric = norm(pos(first)) > 1e7;
  const double L = heliocentric ? kAuKm : 1.0;
  const std::string length = heliocentric ? "AU" : "km";

  // Time from departure in the problem's unit.
  const double t0 = first[0], tof_days = last[0] - first[0];
  const bool hours = tof_days < astro::kHoursBelowDays;
  const double time_scale = hours ? 24.0 : 1.0;
  const std::string time_label =
      std::string(hours ? "hours" : "days") + " after departure" +
      (ctx.has_epoch ? " (" + astro::iso_date_tdb(ctx.epoch_mjd2000 + t0).substr(0, 10) + " TDB)" : "");

  // The colour along the path: the throttle, or a sail's cone angle (normal against the Sun line).
  const auto colour = [&](const std::vector<double>& row) {
    if (engine) return row[cu];
    if (cnx < 0 || cny < 0 || cnz < 0) return 0.0;
    const Vec r = pos(row), n = {row[cnx], row[cny], row[cnz]};
    const double c = dot(r, n) / (norm(r) * std::max(norm(n), 1e-300));
    return std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI;
  };

  const std::vector<Vec> start_orbit = conic(pos(first), vel(first), ctx.mu_km3_s2);
  const std::vector<Vec> end_orbit = conic(pos(last), vel(last), ctx.mu_km3_s2);
  // The extents, for the view and the arrows' length.
  double xy_extent = 0, z_lo = 0, z_hi = 0;
  const auto extend = [&](const Vec& p) {
    xy_extent = std::max({xy_extent, std::fabs(p[0]), std::fabs(p[1])});
    z_lo = std::min(z_lo, p[2]);
    z_hi = std::max(z_hi, p[2]);
  };
  for (const auto& row : table.rows) extend(pos(row));
  for (const auto* orbit : {&start_orbit, &end_orbit})
    for (const auto& p : *orbit) extend(p);
  const bool top_view = z_hi - z_lo <= kPlanarShare * 2 * xy_extent;

  // The data gnuplot draws, in blocks (index 0 ... 5), each written only when it has points.
  std::ostringstream data;
  data.precision(10);
  int block = 0;
  std::vector<std::pair<std::string, int>> blocks;  // role, index
  const auto begin_block = [&](const std::string& role) {
    if (block > 0) data << "\n\n";
    blocks.push_back({role, block++});
  };
  // 0: the path, x y z colour: between two rows a cubic Hermite curve through their positions and
  // velocities (the program writes a row per integration step, a few per revolution: straight
  // lines between them would draw a polygon), the colour of the row it starts from.
  begin_block("path");
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const auto& row = table.rows[i];
    const Vec p0 = pos(row);
    data << p0[0] / L << ' ' << p0[1] / L << ' ' << p0[2] / L << ' ' << colour(row) << '\n';
    if (i + 1 == table.rows.size()) break;
    const auto& next = table.rows[i + 1];
    const double dt = (next[0] - row[0]) * 86400;
    if (!(dt > 0)) continue;  // an event: no time between the rows
    const Vec p1 = pos(next), v0 = vel(row), v1 = vel(next);
    for (int k = 1; k < kHermiteParts; ++k) {
      const double s = static_cast<double>(k) / kHermiteParts, s2 = s * s, s3 = s2 * s;
      const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      for (int j = 0; j < 3; ++j) data << (h00 * p0[j] + h10 * dt * v0[j] + h01 * p1[j] + h11 * dt * v1[j]) / L << ' ';
      data << colour(row) << '\n';
    }
  }
  // 1: the time series, t thrust-or-throttle-or-cone mass, one line per row.
  begin_block("series");
  for (const auto& row : table.rows)
    data << (row[0] - t0) * time_scale << ' '
         << (engine ? row[cu] * (ctx.thrust_N > 0 ? ctx.thrust_N : 1.0) : colour(row)) << ' '
         << (engine ? (cm >= 0 ? row[cm] : ctx.constant_mass_kg) : 0.0) << '\n';
  const auto orbit_block = [&](const std::string& role, const std::vector<Vec>& orbit) {
    if (orbit.empty()) return;
    begin_block(role);
    for (const auto& p : orbit) data << p[0] / L << ' ' << p[1] / L << ' ' << p[2] / L << '\n';
  };
  orbit_block("start", start_orbit);
  orbit_block("end", end_orbit);
  if (ctx.radius_km > 0 && !top_view) {
    begin_block("body");
    bool first_line = true;
    for (const auto& line : sphere(ctx.radius_km / L)) {
      if (!first_line) data << '\n';  // one blank line: a new curve in the same block
      first_line = false;
      for (const auto& p : line) data << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    }
  }
  // The thrust direction where the engine thrusts (throttle above one half), evenly spaced in
  // thrusting time (the rows are integration steps, dense where the dynamics are fast).
  if (engine && cax >= 0 && cay >= 0 && caz >= 0) {
    double thrusting = 0;
    for (std::size_t i = 0; i + 1 < table.rows.size(); ++i)
      if (table.rows[i][cu] > 0.5) thrusting += table.rows[i + 1][0] - table.rows[i][0];
    if (thrusting > 0) {
      begin_block("arrows");
      const double len = kArrowShare * 2 * xy_extent / L, spacing = thrusting / kArrows;
      double so_far = 0, next_at = spacing / 2;
      Vec last_arrow = {NAN, NAN, NAN};
      for (std::size_t i = 0; i + 1 < table.rows.size(); ++i) {
        const auto& row = table.rows[i];
        if (row[cu] <= 0.5) continue;
        so_far += table.rows[i + 1][0] - row[0];
        if (so_far < next_at) continue;
        while (next_at <= so_far) next_at += spacing;
        const Vec p = pos(row), a = {row[cax], row[cay], row[caz]};
        // No arrow over the one before (short thrust arcs): at least most of an arrow's length apart.
        const Vec gap = {p[0] / L - last_arrow[0], p[1] / L - last_arrow[1], p[2] / L - last_arrow[2]};
        if (norm(gap) < 0.7 * len) continue;
        last_arrow = {p[0] / L, p[1] / L, p[2] / L};
        const double an = std::max(norm(a), 1e-300);
        data << p[0] / L << ' ' << p[1] / L << ' ' << p[2] / L << ' ' << len * a[0] / an << ' ' << len * a[1] / an
             << ' ' << len * a[2] / an << '\n';
      }
    }
  }
  begin_block("ends");
  for (const auto* row : {&first, &last})
    data << pos(*row)[0] / L << ' ' << pos(*row)[1] / L << ' ' << pos(*row)[2] / L << '\n';
  begin_block("centre");
  data << "0 0 0\n";
  const auto index_of = [&blocks](const std::string& role) {
    for (const auto& [r, i] : blocks)
      if (r == role) return i;
    return -1;
  };

  const std::string panel = engine ? "throttle_mass" : "cone_angle";
  const std::string traj_png = prefix + "trajectory.png", panel_png = prefix + panel + ".png";
  // Fresh files gnuplot only fills: nothing planted under a predictable name is followed.
  io::TempFiles temps;
  const std::string tmp1 = temps.create_beside(traj_png), tmp2 = temps.create_beside(panel_png);
  const std::string data_file = temps.create_beside(traj_png);
  {
    std::ofstream out(data_file, std::ios::binary | std::ios::trunc);
    out << data.str();
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
  std::string s = "set terminal pngcairo size 1000,900 noenhanced\nset output ARG3\n";
  s +=
      "set title ARG2.': trajectory (colour = " + std::string(engine ? "throttle" : "cone angle") + ")'.\"\\n\".ARG5\n";
  s += "set grid\nset key outside bottom center horizontal\n";
  s += "set palette defined (0 '#2b6cb0', 1 '#e53e3e')\n";
  s +=
      engine ? "set cbrange [0:1]\nset cblabel 'throttle u'\n" : "set cbrange [0:90]\nset cblabel 'cone angle [deg]'\n";
  s += "set xlabel 'x [" + length + "]'\nset ylabel 'y [" + length + "]'\n";
  std::vector<std::string> plots;
  const auto idx = [](int i) { return "ARG1 index " + std::to_string(i); };
  if (top_view) {
    // Seen from +z with equal scales: the body a filled disc of its radius.
    s += "set size ratio -1\n";
    if (ctx.radius_km > 0 && !heliocentric)
      s += "set object 1 circle at 0,0 size " + number(ctx.radius_km / L) +
           " front fc rgb '#3182ce' fs solid 0.5 border lc rgb '#2c5282'\n";
    if (index_of("start") >= 0)
      plots.push_back(idx(index_of("start")) + " using 1:2 with lines lw 1.5 dt 2 lc rgb '#718096' title ARG6");
    if (index_of("end") >= 0)
      plots.push_back(idx(index_of("end")) + " using 1:2 with lines lw 2 dt 4 lc rgb '#2f855a' title ARG7");
    plots.push_back(idx(0) + " using 1:2:4 with lines lw 2 lc palette title 'spacecraft'");
    if (index_of("arrows") >= 0)
      plots.push_back(idx(index_of("arrows")) +
                      " using 1:2:4:5 with vectors head filled size screen 0.008,25 lw 1 lc rgb '#1a202c' "
                      "title 'thrust direction'");
    plots.push_back(idx(index_of("ends")) +
                    " every ::0::0 using 1:2 with points pt 5 ps 1.5 lc rgb '#1a202c' title 'departure'");
    plots.push_back(idx(index_of("ends")) +
                    " every ::1::1 using 1:2 with points pt 9 ps 2 lc rgb '#1a202c' title 'arrival'");
    // The body's name in the key: a disc of its radius (to scale), or the Sun's marker.
    if (ctx.radius_km > 0 && !heliocentric)
      plots.push_back("keyentry with filledcurves fc rgb '#3182ce' fs solid 0.5 title ARG8");
    else
      plots.push_back(idx(index_of("centre")) + " using 1:2 with points pt 7 ps 2.5 lc rgb '#d69e2e' title ARG8");
    s += "plot ";
  } else {
    s += "set zlabel 'z [" + length + "]' rotate parallel\nset view equal xyz\nset ticslevel 0\n";
    s += "set view 60,30\n";
    if (index_of("body") >= 0)
      plots.push_back(idx(index_of("body")) + " using 1:2:3 with lines lw 0.5 lc rgb '#3182ce' title ARG8");
    else
      plots.push_back(idx(index_of("centre")) + " using 1:2:3 with points pt 7 ps 2.5 lc rgb '#d69e2e' title ARG8");
    if (index_of("start") >= 0)
      plots.push_back(idx(index_of("start")) + " using 1:2:3 with lines lw 1.5 dt 2 lc rgb '#718096' title ARG6");
    if (index_of("end") >= 0)
      plots.push_back(idx(index_of("end")) + " using 1:2:3 with lines lw 2 dt 4 lc rgb '#2f855a' title ARG7");
    plots.push_back(idx(0) + " using 1:2:3:4 with lines lw 2 lc palette title 'spacecraft'");
    if (index_of("arrows") >= 0)
      plots.push_back(idx(index_of("arrows")) +
                      " using 1:2:3:4:5:6 with vectors head filled size screen 0.008,25 lw 1 lc rgb '#1a202c' "
                      "title 'thrust direction'");
    plots.push_back(idx(index_of("ends")) +
                    " every ::0::0 using 1:2:3 with points pt 5 ps 1.5 lc rgb '#1a202c' title 'departure'");
    plots.push_back(idx(index_of("ends")) +
                    " every ::1::1 using 1:2:3 with points pt 9 ps 2 lc rgb '#1a202c' title 'arrival'");
    s += "splot ";
  }
  for (std::size_t i = 0; i < plots.size(); ++i) s += (i ? ", \\\n  " : "") + plots[i];
  s += "\n";

  // The control and the mass against time.
  s += "reset\nset terminal pngcairo size 1000,600 noenhanced\nset output ARG4\nset grid\nset xlabel ARG9\n";
  s += "set key outside bottom center horizontal\nset bmargin 6\n";  // room for the time label above the key
  if (engine) {
    const std::string thrust = ctx.thrust_N > 0 ? "thrust [N]" : "throttle u";
    const double top = ctx.thrust_N > 0 ? ctx.thrust_N : 1.0;
    s += "set title ARG2.': " + std::string(ctx.thrust_N > 0 ? "thrust" : "throttle") + " and mass'.\"\\n\".ARG5\n";
    s += "set ylabel '" + thrust + "'\nset y2label 'mass [kg]'\nset yrange [" + number(-0.05 * top) + ":" +
         number(1.05 * top) + "]\nset y2tics\nset ytics nomirror\n";
    s += "plot ARG1 index 1 using 1:2 with lines lw 2 lc rgb '#e53e3e' title '" + thrust +
         "', '' index 1 using 1:3 axes x1y2 with lines lw 2 lc rgb '#2b6cb0' title 'mass [kg]'\n";
  } else {
    s += "set title ARG2.': sail cone angle'.\"\\n\".ARG5\nset ylabel 'cone angle [deg]'\nset yrange [0:90]\n";
    s += "plot ARG1 index 1 using 1:2 with lines lw 2 lc rgb '#e53e3e' title 'cone angle'\n";
  }
  const std::string out =
      run_gnuplot(s, {data_file, title, tmp1, tmp2, subtitle, ctx.start_label, ctx.end_label, body_label, time_label});
  std::error_code ec;
  if (fs::file_size(tmp1, ec) == 0 || fs::file_size(tmp2, ec) == 0)
    throw std::runtime_error("gnuplot did not draw the plots (is gnuplot installed?): " + io::first_line(out));
  io::move_into_place(tmp1, traj_png);
  io::move_into_place(tmp2, panel_png);
  return {{"trajectory_plot", fs::path(traj_png).filename().string()},
          {panel + "_plot", fs::path(panel_png).filename().string()}};
}

}  // namespace helios::solve
