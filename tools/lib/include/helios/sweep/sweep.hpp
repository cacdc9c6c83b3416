// Launch-window sweeps (tools/lib/src/sweep/README.md): a sweep description (scenarios/<P>/sweep.json) as
// a grid of cells over departure epoch x time of flight, each departure's feasibility boundary
// (its minimum-time transfer), each feasible cell's problem text from the scenario's template, the
// make fragments that chain the cells for warm starts, the neighbour cross-check, and the sweep's
// outcome (sweep.csv, porkchop.png).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"

namespace helios::sweep {

// What sweep.json's "plot" may name: a key of solution.json in its unit.
struct SweepGrid {
  std::vector<double> departures_mjd2000;
  std::vector<double> tofs_days;
  std::string plot = "propellant_kg";  // propellant_kg, final_mass_kg or tof_days
  std::string template_file = "problem.txt";
  // The feasibility boundary: each departure's minimum-time transfer with the time of flight free
  // in [boundary_tof_min_days, boundary_tof_max_days]. Off with "boundary": false.
  bool boundary = true;
  double boundary_tof_min_days = 0, boundary_tof_max_days = 0;
};

// The placeholders a template holds (each exactly as written).
inline constexpr const char* kDeparturePlaceholder = "@DEPARTURE_MJD2000@";
inline constexpr const char* kTofPlaceholder = "@TOF_DAYS@";

// sweep.json read and checked: "departure_mjd2000" and "tof_days" are each a range {start, stop,
// step} (stop included, step > 0), {start, stop, count} (count >= 1 evenly spaced values) or
// {values: [...]}, increasing; "plot", "template" optional; "boundary" false or {tof_min_days,
// tof_max_days} (default: a quarter of the shortest and twice the longest time of flight; the window
// must hold the grid's times of flight). `grid` "" takes the top level, else the
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

// What a cell (or a boundary, tof_days empty: a free time of flight) must fly: its spec (a cell's
// problem text as parsed) states the departure epoch and the time of flight of its grid values,
// else an input_error "<template_source>: the sweep's cell <name> states ..., not its grid values,
// ..." (a placeholder read in other units, glued to a digit, in a comment or in a bound).
void check_cell_problem(const io::json& spec, const std::string& template_source, const std::string& name,
                        double departure_mjd2000, std::optional<double> tof_days);

// The same for a solution.json of a cell (or a boundary) at `path`: valid against its schema, and
// a converged one at the grid's departure epoch and time of flight, else an input_error naming the
// path, the cell and the values. Returns the solution.
io::json checked_solution(const std::string& path, const std::string& name, double departure_mjd2000,
                          std::optional<double> tof_days);

// ---- The feasibility boundary --------------------------------------------------------------
// A departure's boundary folder: b<epoch> (e.g. b9700).
std::string boundary_name(double departure_mjd2000);

// The boundary's problem text: the template at this departure with the sentence holding the time
// of flight placeholder replaced by a free time of flight in the grid's boundary window and the
// objective sentence by "Minimize the time of flight." Both texts are parsed and must state the same
// problem but for the objective and the time of flight, else an input_error names the template.
// A template whose objective is already minimum time has no boundary: the parser refuses its cells,
// which minimize a fixed time of flight (input_error).
std::string boundary_problem(const SweepGrid& grid, const std::string& template_text,
                             const std::string& template_source, double departure_mjd2000);

// The boundary's solver settings: the sweep's, without its search budget (search_starts,
// max_attempts), so that the search runs until it saturates: a t_min is a proof only as far as
// the search that found it.
io::json boundary_settings(const io::json& sweep_settings);

// Writes <dir>/b<epoch>/problem.txt and settings.json for every departure (only where changed)
// and returns the make fragment naming them (SWEEP_BOUNDARY); empty names when the grid has no
// boundary.
std::string write_sweep_boundary(const SweepGrid& grid, const std::string& template_text,
                                 const std::string& template_source, const io::json& sweep_settings,
                                 const std::string& dir);

// A departure's boundary as its solution.json says: "missing" (not solved yet), "off" (the grid has
// none), "converged" with t_min_days and how sure it is (the search saturated, its extremals and
// starts), or the solver's failure status (the row's cells are then all solved).
struct Boundary {
  std::string status = "off";
  double t_min_days = 0;
  bool saturated = false;
  int extremals = 0, starts = 0;
};
Boundary read_boundary(const SweepGrid& grid, const std::string& dir, double departure_mjd2000);

// A cell below its row's converged boundary (by more than a millionth of a day) is infeasible:
// the stated engine cannot fly that transfer in that time.
bool below_boundary(const Boundary& b, double tof_days);

// One cell of the chains: its name and the neighbour it starts warm from ("" for a cold seed).
struct SweepCell {
  double departure_mjd2000, tof_days;
  std::string name, warm_from;
};

// The cells in chain order: one chain per departure row along increasing tof, its first cell (the
// shortest tof) cold, each next one warm from the cell before it.
std::vector<SweepCell> sweep_cells(const SweepGrid& grid);

// The cells to solve, in chain order: those not below their row's boundary (read from `dir`), each
// row's chain starting cold at its first feasible cell. Empty while a boundary is missing.
std::vector<SweepCell> feasible_cells(const SweepGrid& grid, const std::string& dir);

// Writes <dir>/<cell>/problem.txt for every feasible cell (only where the text changed, so a
// finished cell is not remade) and returns the make fragment: SWEEP_CELLS and each warm cell's
// dependency on its neighbour's solution.json (SWEEP_WARM_<cell>). While a boundary is missing it
// names no cell (make remakes the fragment once the boundaries are solved). Each cell's text is
// parsed first and must state its grid values (check_cell_problem): else nothing is written.
std::string write_sweep_cells(const SweepGrid& grid, const std::string& template_text,
                              const std::string& template_source, const std::string& dir);

// ---- The neighbour cross-check ---------------------------------------------------------------
// How the cross-check runs a cell from a neighbour: helios-solve (`solver`, after the `launch`
// words) on the cell's shoot.cpp with the sweep's settings, --warm-start the neighbour's answer and
// --warm-only, `jobs` at a time.
struct CrosscheckOptions {
  std::string solver, settings, cache_dir;
  std::vector<std::string> launch;
  double time_limit_s = 900;
  int jobs = 1;
};

// After the first pass, every feasible cell is re-solved warm from each converged 4-neighbour's
// answer (<dir>/<cell>/crosscheck/r<round>_from_<neighbour>/), and keeps the best; the cells whose answer
// improved are offered to their neighbours in the next round, until a round improves none. A run
// already on disk from the same neighbour answer is reused (a killed cross-check resumes).
// Returns crosscheck.json: per cell its answer (the file), where it came from ("own" or the
// neighbour), the converged extremals compared, and every try; the rounds and runs.
io::json crosscheck(const SweepGrid& grid, const std::string& dir, const CrosscheckOptions& o);

// One cell's outcome: "infeasible" below its row's boundary, else from its answer (crosscheck.json's
// when there is one, else <dir>/<cell>/solution.json, checked_solution): its status ("missing" without one), how it
// started, where the answer came from and how many extremals were compared, and where it converged
// the plotted objective in its unit and max_residual (else NaN).
struct SweepRow {
  SweepCell cell;
  std::string status, start;
  double objective, max_residual;
  std::string answer_from;
  int extremals_compared = 0;
  Boundary boundary;
};

// The cells' outcomes in chain order; a converged solution without the plotted key is an input_error.
// `crosscheck`: crosscheck.json's document, or null.
std::vector<SweepRow> sweep_rows(const SweepGrid& grid, const std::string& dir, const io::json& crosscheck = nullptr);

// sweep.csv: one row per cell (departure_mjd2000, tof_days, cell, status, the plotted objective in
// its unit, max_residual, start, answer_from, extremals_compared, and the row's boundary:
// t_min_days, boundary_saturated).
std::string sweep_csv(const SweepGrid& grid, const std::vector<SweepRow>& rows);

// porkchop.png: filled contours of the objective over departure x tof; infeasible cells marked
// with dots and the boundary t_min(departure) drawn as a line, failed cells with crosses, the best
// cell with a circle (gnuplot). Written atomically to png_path.
void porkchop_png(const SweepGrid& grid, const std::vector<SweepRow>& rows, const std::string& png_path,
                  const std::string& title);

}  // namespace helios::sweep
