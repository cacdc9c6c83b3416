// Launch-window sweeps: the grid of a sweep.json, the cells' problem texts and chains, sweep.csv
// and porkchop.png (helios/sweep/sweep.hpp).
#include "helios/sweep/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/astro/calendar.hpp"
#include "helios/io/error.hpp"
#include "helios/io/schema.hpp"
#include "helios/solve/solve.hpp"
#include "helios/spec/parse.hpp"

namespace helios::sweep {

namespace fs = std::filesystem;
using io::json;

namespace {

constexpr std::size_t kMaxAxis = 1000;    // values on one axis
constexpr std::size_t kMaxCells = 10000;  // cells of a grid: each is a folder and a whole chain
// Departure epochs from 1900 to 2200 (the parser's calendar), times of flight up to a century.
constexpr double kFirstEpoch = -36525, kLastEpoch = 73050, kLongestFlightDays = 36525;

[[noreturn]] void bad(const std::string& source, const std::string& field, const std::string& why) {
  throw input_error(source + ": field /" + field + ": " + why);
}

double number_at(const json& j, const std::string& key, const std::string& source, const std::string& field) {
  if (!j.contains(key) || !j.at(key).is_number()) bad(source, field + "/" + key, "missing or not a number");
  const double v = j.at(key).get<double>();
  if (!std::isfinite(v)) bad(source, field + "/" + key, "not finite");
  return v;
}

// A computed grid value to a millionth (a day's, an epoch's), so that 0.1 steps name cells 0.3,
// not 0.30000000000000004.
double micro(double v) {
  return std::round(v * 1e6) / 1e6;
}

// One axis: {start, stop, step}, {start, stop, count} or {values: [...]}, strictly increasing.
std::vector<double> read_axis(const json& j, const std::string& source, const std::string& field, double lowest,
                              double highest) {
  if (!j.is_object()) bad(source, field, "must be an object {start, stop, step}, {start, stop, count} or {values}");
  std::vector<double> out;
  if (j.contains("values")) {
    if (!j.at("values").is_array() || j.at("values").empty()) bad(source, field + "/values", "not a non-empty array");
    for (std::size_t i = 0; i < j.at("values").size(); ++i) {
      const json& v = j.at("values")[i];
      if (!v.is_number() || !std::isfinite(v.get<double>()))
        bad(source, field + "/values/" + std::to_string(i), "not a finite number");
      out.push_back(v.get<double>());
    }
  } else {
    const double start = number_at(j, "start", source, field), stop = number_at(j, "stop", source, field);
    if (stop < start) bad(source, field + "/stop", number_text(stop) + " is below start " + number_text(start));
    if (j.contains("count")) {
      if (!j.at("count").is_number_integer() || j.at("count").get<long long>() < 1 ||
          j.at("count").get<long long>() > static_cast<long long>(kMaxAxis))
        bad(source, field + "/count", "must be a whole number from 1 to " + std::to_string(kMaxAxis));
      const long long n = j.at("count").get<long long>();
      if (n == 1 && stop != start) bad(source, field + "/count", "1 needs start = stop");
      for (long long i = 0; i < n; ++i) out.push_back(micro(n == 1 ? start : start + (stop - start) * i / (n - 1)));
    } else {
      const double step = number_at(j, "step", source, field);
      if (!(step > 0)) bad(source, field + "/step", number_text(step) + " is not positive");
      const double n = std::floor((stop - start) / step + 1e-9) + 1;
      if (n > kMaxAxis) bad(source, field + "/step", "more than " + std::to_string(kMaxAxis) + " values");
      for (int i = 0; i < static_cast<int>(n); ++i) out.push_back(micro(start + step * i));
    }
  }
  if (out.size() > kMaxAxis) bad(source, field, "more than " + std::to_string(kMaxAxis) + " values");
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i] < lowest) bad(source, field, io::short_number(out[i]) + " is below " + io::short_number(lowest));
    if (out[i] > highest) bad(source, field, io::short_number(out[i]) + " is above " + io::short_number(highest));
    if (i > 0 && !(out[i] > out[i - 1])) bad(source, field, "values must increase");
  }
  return out;
}

// "boundary": false, or {tof_min_days, tof_max_days} (either may be left out), which must hold the
// grid's times of flight.
void read_boundary_window(const json& sweep, const std::string& source, SweepGrid& out) {
  out.boundary_tof_min_days = micro(out.tofs_days.front() / 4);
  out.boundary_tof_max_days = std::min(kLongestFlightDays, micro(2 * out.tofs_days.back()));
  if (!sweep.contains("boundary")) return;
  const json& b = sweep.at("boundary");
  if (b == json(false)) {
    out.boundary = false;
    return;
  }
  if (!b.is_object()) bad(source, "boundary", "must be false or an object {tof_min_days, tof_max_days}");
  for (auto it = b.begin(); it != b.end(); ++it)
    if (it.key() != "tof_min_days" && it.key() != "tof_max_days")
      bad(source, "boundary/" + it.key(), "not a boundary field (known: tof_min_days, tof_max_days)");
  if (b.contains("tof_min_days")) out.boundary_tof_min_days = number_at(b, "tof_min_days", source, "boundary");
  if (b.contains("tof_max_days")) out.boundary_tof_max_days = number_at(b, "tof_max_days", source, "boundary");
  if (!(out.boundary_tof_min_days > 0) || out.boundary_tof_min_days > out.tofs_days.front())
    bad(source, "boundary/tof_min_days",
        io::short_number(out.boundary_tof_min_days) + " must be positive and at most the shortest time of flight " +
            io::short_number(out.tofs_days.front()));
  if (out.boundary_tof_max_days < out.tofs_days.back() || out.boundary_tof_max_days > kLongestFlightDays)
    bad(source, "boundary/tof_max_days",
        io::short_number(out.boundary_tof_max_days) + " must be at least the longest time of flight " +
            io::short_number(out.tofs_days.back()) + " and at most " + io::short_number(kLongestFlightDays));
}

// A plot axis over the grid's values: [first:last], or a day either side of a single value.
std::string axis_range(const std::vector<double>& values) {
  const double pad = values.front() == values.back() ? 1 : 0;
  return "[" + number_text(values.front() - pad) + ":" + number_text(values.back() + pad) + "]";
}

// The departure axis' tics as calendar dates (TDB) over their MJD2000 day: about six, on whole
// days, across the grid's departures. The labels are made here (digits and dashes), not taken
// from an input.
std::string departure_tics(const std::vector<double>& values) {
  const double lo = values.front(), hi = values.back();
  const int n = lo == hi ? 1 : 6;
  std::string tics;
  double previous = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < n; ++k) {
    const double at = std::round(n == 1 ? lo : lo + (hi - lo) * k / (n - 1));
    if (at == previous) continue;
    previous = at;
    tics += (tics.empty() ? "" : ", ") + std::string("\"") + astro::iso_date_tdb(at).substr(0, 10) + "\\n" +
            number_text(at) + "\" " + number_text(at);
  }
  return "(" + tics + ")";
}

// What a problem or a solution flies, in words: "departure MJD2000 9700 and a time of flight of 300 d".
std::string flown(std::optional<double> departure_mjd2000, std::optional<double> tof_days) {
  return "departure MJD2000 " + (departure_mjd2000 ? number_text(*departure_mjd2000) : std::string("none")) + " and " +
         (tof_days ? "a time of flight of " + number_text(*tof_days) + " d" : std::string("a free time of flight"));
}

// The same number to rounding (a time of flight through the normalized units).
bool same(std::optional<double> a, std::optional<double> b) {
  return a.has_value() == b.has_value() && (!a || std::fabs(*a - *b) <= 1e-9 * std::max(1.0, std::fabs(*b)));
}

std::optional<double> number_of(const json& j, const char* key) {
  return j.is_object() && j.contains(key) && j.at(key).is_number() ? std::optional<double>(j.at(key).get<double>())
                                                                   : std::nullopt;
}

std::string grid_values(double departure_mjd2000, std::optional<double> tof_days) {
  return "departure MJD2000 " + number_text(departure_mjd2000) +
         (tof_days ? " and " + number_text(*tof_days) + " d" : std::string(" and a free time of flight"));
}

std::string replace_all(std::string text, const std::string& what, const std::string& with) {
  for (std::size_t at = 0; (at = text.find(what, at)) != std::string::npos; at += with.size())
    text.replace(at, what.size(), with);
  return text;
}

}  // namespace

std::string number_text(double value) {
  char buf[400];
  for (int decimals = 0; decimals <= 9; ++decimals) {  // fixed notation: no exponent in a cell's name
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    if (std::stod(buf) == value) return buf;
  }
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return buf;
}

SweepGrid read_sweep(const json& sweep, const std::string& source, const std::string& grid) {
  if (!sweep.is_object()) throw input_error(source + ": a sweep must be a JSON object");
  static const std::vector<std::string> known = {"template", "departure_mjd2000", "tof_days",   "plot",
                                                 "bench",    "boundary",          "description"};
  for (auto it = sweep.begin(); it != sweep.end(); ++it)
    if (std::find(known.begin(), known.end(), it.key()) == known.end())
      bad(source, it.key(), "not a sweep field (known: template, departure_mjd2000, tof_days, plot, bench, boundary)");
  SweepGrid out;
  if (sweep.contains("template")) {
    if (!sweep.at("template").is_string() || sweep.at("template").get<std::string>().empty() ||
        sweep.at("template").get<std::string>().find('/') != std::string::npos)
      bad(source, "template", "must be a file name beside sweep.json");
    out.template_file = sweep.at("template").get<std::string>();
  }
  if (sweep.contains("plot")) {
    const json& p = sweep.at("plot");
    if (!p.is_string() || (p != "propellant_kg" && p != "final_mass_kg" && p != "tof_days"))
      bad(source, "plot", p.dump() + " is not propellant_kg, final_mass_kg or tof_days");
    out.plot = p.get<std::string>();
  }
  const json* axes = &sweep;
  std::string prefix;
  if (!grid.empty()) {
    if (grid != "bench") throw input_error(source + ": no grid '" + grid + "' (the grids: the top level, bench)");
    if (!sweep.contains(grid) || !sweep.at(grid).is_object()) bad(source, grid, "missing or not an object");
    axes = &sweep.at(grid);
    prefix = grid + "/";
  }
  for (const char* key : {"departure_mjd2000", "tof_days"})
    if (!axes->contains(key)) bad(source, prefix + key, "missing");
  out.departures_mjd2000 =
      read_axis(axes->at("departure_mjd2000"), source, prefix + "departure_mjd2000", kFirstEpoch, kLastEpoch);
  out.tofs_days = read_axis(axes->at("tof_days"), source, prefix + "tof_days", 1e-6, kLongestFlightDays);
  const std::size_t cells = out.departures_mjd2000.size() * out.tofs_days.size();
  if (cells > kMaxCells)
    bad(source, prefix.empty() ? "tof_days" : prefix + "tof_days",
        "the grid has " + std::to_string(cells) + " cells; the limit is " + std::to_string(kMaxCells));
  read_boundary_window(sweep, source, out);
  return out;
}

std::string cell_name(double departure_mjd2000, double tof_days) {
  return "d" + number_text(departure_mjd2000) + "_t" + number_text(tof_days);
}

std::string cell_problem(const std::string& template_text, const std::string& template_source, double departure_mjd2000,
                         double tof_days) {
  for (const char* p : {kDeparturePlaceholder, kTofPlaceholder})
    if (template_text.find(p) == std::string::npos)
      throw input_error(template_source + ": the sweep template has no " + p);
  return replace_all(replace_all(template_text, kDeparturePlaceholder, number_text(departure_mjd2000)), kTofPlaceholder,
                     number_text(tof_days));
}

void check_cell_problem(const json& spec, const std::string& template_source, const std::string& name,
                        double departure_mjd2000, std::optional<double> tof_days) {
  const json& time = spec.at("time");
  const std::optional<double> epoch = number_of(time, "epoch_mjd2000");
  const bool fixed = time.value("final_time", "") == "fixed";
  const std::optional<double> tof = number_of(fixed ? time : json(), "tof_days");  // none when free
  if (same(epoch, departure_mjd2000) && same(tof, tof_days)) return;
  throw input_error(template_source + ": the sweep's cell " + name + " states " + flown(epoch, tof) +
                    ", not its grid values, " + grid_values(departure_mjd2000, tof_days) + ": write " +
                    kDeparturePlaceholder + " and " + kTofPlaceholder +
                    " days where the text states the departure epoch and the time of flight");
}

json checked_solution(const std::string& path, const std::string& name, double departure_mjd2000,
                      std::optional<double> tof_days) {
  const json s = io::read_artifact("solution", path);
  if (s.at("status") != "converged") return s;
  // The runtime records the epoch when the problem has one other than MJD2000 0.
  const std::optional<double> epoch = s.contains("departure_mjd2000") || departure_mjd2000 != 0
                                          ? number_of(s, "departure_mjd2000")
                                          : std::optional<double>(0.0);
  const std::optional<double> tof = number_of(s, "tof_days");
  if (same(epoch, departure_mjd2000) && (!tof_days || same(tof, tof_days))) return s;
  throw input_error(path + ": the sweep's cell " + name + " has a solution that flies " + flown(epoch, tof) +
                    ", not its grid values, " + grid_values(departure_mjd2000, tof_days) +
                    ": solve the cell again from its own problem");
}

std::vector<SweepCell> sweep_cells(const SweepGrid& grid) {
  std::vector<SweepCell> cells;
  for (const double d : grid.departures_mjd2000) {
    std::string previous;
    for (const double t : grid.tofs_days) {
      cells.push_back({d, t, cell_name(d, t), previous});
      previous = cells.back().name;
    }
  }
  return cells;
}

std::vector<SweepCell> feasible_cells(const SweepGrid& grid, const std::string& dir) {
  std::vector<SweepCell> cells;
  for (const double d : grid.departures_mjd2000) {
    const Boundary b = read_boundary(grid, dir, d);
    if (b.status == "missing") return {};
    std::string previous;
    for (const double t : grid.tofs_days) {
      if (below_boundary(b, t)) continue;
      cells.push_back({d, t, cell_name(d, t), previous});
      previous = cells.back().name;
    }
  }
  return cells;
}

std::string write_sweep_cells(const SweepGrid& grid, const std::string& template_text,
                              const std::string& template_source, const std::string& dir) {
  const std::vector<SweepCell> cells = feasible_cells(grid, dir);
  std::ostringstream mk;
  mk << "# Written by helios-score --sweep-cells from " << template_source << "'s sweep: do not edit.\n";
  for (const double d : grid.departures_mjd2000)
    if (read_boundary(grid, dir, d).status == "missing") {
      mk << "# No cell yet: the boundaries are not all solved.\n";
      break;
    }
  mk << "SWEEP_CELLS :=";
  for (const auto& c : cells) mk << ' ' << c.name;
  mk << "\n";
  // Every cell's text states its grid values, or no cell is written.
  std::vector<std::string> texts;
  for (const auto& c : cells) {
    texts.push_back(cell_problem(template_text, template_source, c.departure_mjd2000, c.tof_days));
    check_cell_problem(spec::parse_problem_text(texts.back(), template_source + " (the sweep's cell " + c.name + ")"),
                       template_source, c.name, c.departure_mjd2000, c.tof_days);
  }
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const SweepCell& c = cells[k];
    io::write_text_if_changed((fs::path(dir) / c.name / "problem.txt").string(), texts[k]);
    mk << "SWEEP_WARM_" << c.name << " :=" << (c.warm_from.empty() ? "" : " " + c.warm_from) << "\n";
    if (!c.warm_from.empty()) {
      mk << (fs::path(dir) / c.name / "solution.json").string() << ": "
         << (fs::path(dir) / c.warm_from / "solution.json").string() << "\n";
    }
  }
  return mk.str();
}

std::vector<SweepRow> sweep_rows(const SweepGrid& grid, const std::string& dir, const json& crosscheck) {
  std::vector<SweepRow> rows;
  Boundary boundary;
  for (const auto& c : sweep_cells(grid)) {
    if (rows.empty() || rows.back().cell.departure_mjd2000 != c.departure_mjd2000)
      boundary = read_boundary(grid, dir, c.departure_mjd2000);
    SweepRow row{c, "missing", "", NAN, NAN, "", 0, boundary};
    if (below_boundary(boundary, c.tof_days)) {
      row.status = "infeasible";
      rows.push_back(row);
      continue;
    }
    const json* checked =
        crosscheck.is_object() && crosscheck.contains("cells") && crosscheck.at("cells").contains(c.name)
            ? &crosscheck.at("cells").at(c.name)
            : nullptr;
    const fs::path path =
        checked ? fs::path(dir) / checked->at("answer").get<std::string>() : fs::path(dir) / c.name / "solution.json";
    std::error_code ec;
    if (fs::exists(path, ec)) {
      const json s = checked_solution(path.string(), c.name, c.departure_mjd2000, c.tof_days);
      row.status = s.value("status", "unknown");
      row.start = s.value("start", "");
      if (row.status == "converged") {
        if (!s.contains(grid.plot) || !s.at(grid.plot).is_number())
          throw input_error(path.string() + ": field /" + grid.plot + ": missing in a converged solution");
        row.objective = s.at(grid.plot).get<double>();
        row.max_residual = s.value("max_residual", NAN);
        row.answer_from = "own";
        row.extremals_compared = 1;
      }
    }
    if (checked) {
      row.answer_from = checked->value("answer_from", "");
      row.extremals_compared = checked->value("extremals_compared", 0);
    }
    rows.push_back(row);
  }
  return rows;
}

std::string sweep_csv(const SweepGrid& grid, const std::vector<SweepRow>& rows) {
  std::ostringstream csv;
  csv << "departure_mjd2000,tof_days,cell,status," << grid.plot
      << ",max_residual,start,answer_from,extremals_compared,t_min_days,boundary_saturated\n";
  for (const auto& r : rows) {
    std::string objective, residual, t_min, saturated;
    char buf[40];
    if (r.status == "converged") {
      std::snprintf(buf, sizeof buf, "%.12g", r.objective);
      objective = buf;
      std::snprintf(buf, sizeof buf, "%.3e", r.max_residual);
      residual = buf;
    }
    if (r.boundary.status == "converged") {
      std::snprintf(buf, sizeof buf, "%.9g", r.boundary.t_min_days);
      t_min = buf;
      saturated = r.boundary.saturated ? "true" : "false";
    }
    csv << number_text(r.cell.departure_mjd2000) << ',' << number_text(r.cell.tof_days) << ',' << r.cell.name << ','
        << r.status << ',' << objective << ',' << residual << ',' << r.start << ',' << r.answer_from << ','
        << (r.status == "converged" ? std::to_string(r.extremals_compared) : "") << ',' << t_min << ',' << saturated
        << "\n";
  }
  return csv.str();
}

void porkchop_png(const SweepGrid& grid, const std::vector<SweepRow>& rows, const std::string& png_path,
                  const std::string& title) {
  // The grid as gnuplot's blocks (one per departure row, NaN where a cell has no objective), the
  // infeasible cells, the failed ones, the best one and the boundary line.
  std::ostringstream data, infeasible_cells, failed_cells, best_cell, boundary_line;
  const bool maximize = grid.plot == "final_mass_kg";
  int best = -1;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (std::isfinite(rows[i].objective) &&
        (best < 0 || (maximize ? rows[i].objective > rows[best].objective : rows[i].objective < rows[best].objective)))
      best = static_cast<int>(i);
  const double z = best >= 0 ? rows[best].objective : 0.0;
  double last = NAN;
  for (const auto& r : rows) {
    const std::string at = number_text(r.cell.departure_mjd2000) + ' ' + number_text(r.cell.tof_days) + ' ';
    if (!std::isnan(last) && r.cell.departure_mjd2000 != last) data << "\n";
    if (r.cell.departure_mjd2000 != last && r.boundary.status == "converged")
      boundary_line << number_text(r.cell.departure_mjd2000) << ' ' << number_text(r.boundary.t_min_days) << ' '
                    << number_text(z) << "\n";
    last = r.cell.departure_mjd2000;
    data << at << (std::isfinite(r.objective) ? number_text(r.objective) : "NaN") << "\n";
    if (r.status == "infeasible")
      infeasible_cells << at << number_text(z) << "\n";
    else if (!std::isfinite(r.objective))
      failed_cells << at << number_text(z) << "\n";
  }
  if (best >= 0)
    best_cell << number_text(rows[best].cell.departure_mjd2000) << ' ' << number_text(rows[best].cell.tof_days) << ' '
              << number_text(z) << "\n";
  io::TempFiles temps;
  const auto points_file = [&](const std::string& suffix, const std::ostringstream& points) {
    const std::string file = temps.create_beside(png_path + suffix);
    io::write_text_atomic(file, points.str().empty() ? "NaN NaN NaN\n" : points.str());
    return file;
  };
  const std::string grid_file = points_file(".grid", data),
                    infeasible_file = points_file(".infeasible", infeasible_cells),
                    failed_file = points_file(".failed", failed_cells), best_file = points_file(".best", best_cell),
                    boundary_file = points_file(".boundary", boundary_line), tmp_png = temps.create_beside(png_path);
  const std::string unit = grid.plot == "tof_days"        ? "time of flight [days]"
                           : grid.plot == "final_mass_kg" ? "final mass [kg]"
                                                          : "propellant [kg]";
  // The title and the file names reach gnuplot as data (solve::run_gnuplot): ARG1 the PNG, ARG2 the
  // title, ARG3 the grid, ARG4 the infeasible cells, ARG5 the failed ones, ARG6 the best cell, ARG7
  // the boundary.
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,800 noenhanced\nset output ARG1\n"
     << "set title ARG2.': " << unit << "'\n"
     << "set xlabel 'departure [calendar date TDB, MJD2000]' offset 0,-1\nset xtics "
     << departure_tics(grid.departures_mjd2000) << "\nset ylabel 'time of flight [days]'\nset cblabel '" << unit
     << "'\n"
     << "set view map\nset pm3d at b interpolate 8,8\nset contour base\nset cntrparam levels auto 10\nunset clabel\n"
     << "set bmargin 7\nset key at screen 0.5,0.05 center center horizontal maxrows 2 box\n"
     << "set palette defined (0 '#2b6cb0', 0.5 '#f6e05e', 1 '#e53e3e')\nset datafile missing 'NaN'\n"
     << "set xrange " << axis_range(grid.departures_mjd2000) << "\nset yrange " << axis_range(grid.tofs_days) << "\n"
     << "splot ARG3 using 1:2:3 with pm3d notitle, ARG3 using 1:2:3 with lines nosurface lc rgb 'black' notitle, "
     << "ARG7 using 1:2:3 with lines nocontours lw 3 lc rgb '#444444' title 'minimum time', "
     << "ARG4 using 1:2:3 with points nocontours pt 7 ps 1 lc rgb '#888888' title 'infeasible', "
     << "ARG5 using 1:2:3 with points nocontours pt 2 ps 2 lw 2 lc rgb 'black' title 'failed', "
     << "ARG6 using 1:2:3 with points nocontours pt 6 ps 3 lw 2 lc rgb 'black' title 'best', "
     << "ARG6 using 1:2:3 with points nocontours pt 3 ps 3 lw 3 lc rgb 'white' notitle\n";
  const std::string out =
      solve::run_gnuplot(gp.str(), {tmp_png, title, grid_file, infeasible_file, failed_file, best_file, boundary_file});
  std::error_code ec;
  if (fs::file_size(tmp_png, ec) == 0)
    throw std::runtime_error("gnuplot did not draw " + png_path + " (is gnuplot installed?): " + out.substr(0, 300));
  io::move_into_place(tmp_png, png_path);
}

}  // namespace helios::sweep
