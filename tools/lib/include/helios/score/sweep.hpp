// Launch-window sweeps (issue 17): a sweep description (scenarios/<P>/sweep.json) as a grid of
// cells over departure epoch x time of flight, each cell's problem text from the scenario's
// template, the make fragment that chains the cells for warm starts, and the sweep's outcome
// (sweep.csv, porkchop.png) from the cells' solution.json files.
#pragma once

#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::score {

// What sweep.json's "plot" may name: a key of solution.json in its unit.
struct SweepGrid {
  std::vector<double> departures_mjd2000;
  std::vector<double> tofs_days;
  std::string plot = "propellant_kg";  // propellant_kg, final_mass_kg or tof_days
  std::string template_file = "problem.txt";
};

// The placeholders a template holds (each exactly as written).
inline constexpr const char* kDeparturePlaceholder = "@DEPARTURE_MJD2000@";
inline constexpr const char* kTofPlaceholder = "@TOF_DAYS@";

// sweep.json read and checked: "departure_mjd2000" and "tof_days" are each a range {start, stop,
// step} (stop included, step > 0), {start, stop, count} (count >= 1 evenly spaced values) or
// {values: [...]}, increasing; "plot", "template" optional. `grid` "" takes the top level, else the
// object of that name (e.g. "bench") whose ranges replace the top level's. Bad input is an
// input_error naming `source`, the field and the value.
SweepGrid read_sweep(const io::json& sweep, const std::string& source, const std::string& grid = "");

// A cell's folder name: d<epoch>_t<tof> (shortest exact decimal form, e.g. d9700_t300, d9700.5_t300).
std::string cell_name(double departure_mjd2000, double tof_days);

// A number in a problem text and a cell name: the shortest fixed form (at most 9 decimals) that reads
// back equal, else %.17g.
std::string number_text(double value);

// A cell's problem text: the template with both placeholders replaced (each must occur).
std::string cell_problem(const std::string& template_text, const std::string& template_source, double departure_mjd2000,
                         double tof_days);

// One cell of the chains: its name and the neighbour it starts warm from ("" for a cold seed).
struct SweepCell {
  double departure_mjd2000, tof_days;
  std::string name, warm_from;
};

// The cells in chain order: one chain per departure row along increasing tof, its first cell (the
// shortest tof) cold, each next one warm from the cell before it.
std::vector<SweepCell> sweep_cells(const SweepGrid& grid);

// Writes <dir>/<cell>/problem.txt for every cell (only where the text changed, so a finished cell
// is not remade) and returns the make fragment: SWEEP_CELLS and each warm cell's dependency on
// its neighbour's solution.json (SWEEP_WARM_<cell>).
std::string write_sweep_cells(const SweepGrid& grid, const std::string& template_text,
                              const std::string& template_source, const std::string& dir);

// One cell's outcome, from <dir>/<cell>/solution.json: its status ("missing" without one), how it
// started, and where it converged the plotted objective in its unit and max_residual (else NaN).
struct SweepRow {
  SweepCell cell;
  std::string status, start;
  double objective, max_residual;
};

// The cells' outcomes in chain order; a converged solution without the plotted key is an input_error.
std::vector<SweepRow> sweep_rows(const SweepGrid& grid, const std::string& dir);

// sweep.csv: one row per cell (departure_mjd2000, tof_days, cell, status, the plotted objective in
// its unit, max_residual, start).
std::string sweep_csv(const SweepGrid& grid, const std::vector<SweepRow>& rows);

// porkchop.png: filled contours of the objective over departure x tof, unconverged cells marked
// with crosses and the best cell with a circle (gnuplot). Written atomically to png_path.
void porkchop_png(const SweepGrid& grid, const std::vector<SweepRow>& rows, const std::string& png_path,
                  const std::string& title);

}  // namespace helios::score
