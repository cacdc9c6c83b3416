#pragma once
// helios-solve: compile a shooting program (cached by content hash), run it under resource
// limits, and collect solution.json, trajectory.csv and the plots.
#include <functional>
#include <string>

#include "helios/io/json_io.hpp"

namespace helios::solve {

struct SolveOptions {
  std::string source_path;      // shoot.cpp
  std::string settings_path;    // solver settings JSON (seed, tolerances, limits); may be empty
  std::string cache_dir;        // compiled programs, by content hash
  std::string trajectory_path;  // trajectory.csv to write; empty: none kept (the run's folder is a temporary one)
  std::string spec_path;        // the problem's spec.json (optional): the plots' central body, orbits and
                                // thrust, and the progress lines' dates
  std::string plot_prefix;      // writes <prefix>trajectory.png and <prefix>throttle_mass.png (engine) or
                                // <prefix>cone_angle.png (sail); empty: no plots
  std::string backend = "builtin";
  // A neighbour's solution.json (a sweep's cell): when it converged, its shooting variables are
  // the program's first guess (Settings::warm_start), else the solve starts cold; empty: cold.
  std::string warm_start_path;
  // With warm_start_path: no search when the warm solve fails (the result is the warm solve's, not
  // converged); a sweep's neighbour cross-check.
  bool warm_only = false;
  std::string compiler = "g++";
  double time_limit_s = 600;  // wall clock for the run (the program also stops itself)
  double memory_limit_mb = 4096;
  // Run the program inside bubblewrap (no network, a read-only /usr, the run folder the only
  // writable place); false only when the user says so (--no-sandbox), and recorded.
  bool sandbox = true;
  // Receives each line the program writes on stderr as it comes (its search progress), and the
  // stage's own progress lines; empty: quiet.
  std::function<void(const std::string&)> progress;
};

// The CPUs a scheduler gave this task: SLURM_CPUS_PER_TASK (set by srun -c N / sbatch
// --cpus-per-task), or 0 when it is unset. A value that is not a whole number from 1 to 64 is an
// input_error naming the variable and the value.
int scheduler_cpus_per_task();

// The settings the program runs with: o.settings_path's (validated against
// schemas/settings.schema.json; none: {}), the time limit a little under o.time_limit_s, and
// `threads` set to scheduler_cpus_per_task() where the settings leave it 0 (every core), so that
// the cells of a sweep under `srun -c1` do not each take the whole machine.
io::json run_settings(const SolveOptions& o);

// A neighbour's solution.json as the program's warm start: {"variables": [names], "x": [values]}
// when it converged, else null. `record` receives solution.json's "warm_start" (the file, the
// neighbour's status, whether it is used). A file that is not a solution (no status, a converged
// one without x) is an input_error naming the file and field.
io::json warm_start_of(const std::string& path, io::json& record);

// A program's numbers: its HELIOS_PARAMETER and HELIOS_PARAMETER_ARRAY lines (the PROBLEM block,
// templates/runtime/helios_runtime.hpp), each at the start of its line, outside comments, as
// `HELIOS_PARAMETER(name, number);` or `HELIOS_PARAMETER_ARRAY(name, number, ...);` with an
// optional `  // comment`. `structure` is the source with each of their numbers replaced by `#`
// (nothing else), `values` the parameters file's values ({name: number or [numbers]}, each the
// double its literal denotes). The numbers are not readable (`readable` false, `structure` the whole
// source, `values` empty: the program runs on its literals, compiled on its own) when the source
// names HELIOS_PARAMETER in code outside a parameter line, has a parameter line of another form, a
// preprocessor line other than an #include of the runtime's or a system header or a #pragma, text
// the reader cannot read for sure (a line splice, a universal character name), or a declaration at
// namespace or class scope that could run code before main, where it could read a parameter before
// the parameters file replaces it; `whole_source_because` says which (tools/lib/src/solve/README.md,
// "The compile cache").
struct ProgramParameters {
  bool readable = false;
  std::string structure;
  io::json values = io::json::object();
  std::string whole_source_because;
};
ProgramParameters program_parameters(const std::string& source);

// {"schema": "helios/parameters", "values": values}: the file the program reads with --parameters.
io::json parameters_document(const io::json& values);

struct CompileResult {
  bool ok = false, cached = false;
  // sha256: the key of the source itself (solution.json's source_sha256); structure_sha256: the
  // key the program is cached under, its structure's (ProgramParameters) when its numbers are
  // readable, else the source's own. binary: the cached program; program: its bytes, which match
  // binary_sha256, the SHA-256 stored beside it.
  std::string binary, sha256, structure_sha256, command, diagnostics, program, binary_sha256;
  ProgramParameters parameters;
  int warnings = 0;
  double seconds = 0;
};

// Compiles `source` with o.compiler -O2 into o.cache_dir/<structure_sha256>/shoot unless already
// there (a program of the same structure, compiled from another problem's numbers, which the
// parameters file replaces at run time). The cache entry is used only when its folder and files
// are this user's, not links, and writable by nobody else, and the program's bytes match their
// stored SHA-256; a folder that is not private is an error (std::runtime_error), an entry that is
// not whole is compiled anew (tools/lib/src/solve/README.md, "The compile cache"). The
// compiler runs under the run's limits (run_limited: o.time_limit_s wall clock, o.memory_limit_mb
// of address space, CPU, file size, processes): a source that makes it loop or grow fails the
// compile, with the reason last in its diagnostics.
CompileResult compile_cached(const std::string& source, const SolveOptions& o);
// What a key hashes: the whole source, or its structure (its numbers masked). Apart, so that a
// source can never be served a program cached under another source's structure.
enum class KeyKind { Source, Structure };
// The cache key of a compile: the SHA-256 of the kind, then the text, the command, the compiler's
// --version line and the runtime's SHA-256 (runtime_files), each after its length, so a rebuilt
// runtime invalidates cached programs.
std::string compile_key(KeyKind kind, const std::string& text, const std::string& command,
                        const std::string& compiler_version, const std::string& runtime_sha256);
// `compute()`, the value of `files`, kept in `memo_path` with the files' stamps (device, inode, size,
// modification time) and read from there while they match: the compiler's --version line and the
// runtime's SHA-256 are asked on every solve and change only with the files (ccache identifies a
// compiler by the same stamps). A file modified in the last two seconds is not trusted to its stamp:
// the value is then computed and not kept; nor is it when a file changed while it was computed.
std::string memo_by_stamps(const std::string& memo_path, const std::vector<std::string>& files,
                           const std::function<std::string()>& compute);
// Writes the checked program of `c` to `path` (a new file of mode 0700 in the run's private folder),
// which is what runs: the cache may change after the check, the private copy not.
void install_program(const CompileResult& c, const std::string& path);
// The compile record's cache fields: cache_key ("structure" or "source"), why the whole source
// (cache_key_detail), and the program's binary_sha256.
io::json cache_record(const CompileResult& c);

struct RunResult {
  int exit_code = -1;
  int signal = 0;
  bool timed_out = false;
  std::string output_text;  // the first 64 KiB the program printed (stderr and stdout)
  std::string error_line;   // the last line naming an error, else the last line
  double seconds = 0;
  int leftover_processes = 0;  // processes the program left running, killed after it ended
};

// argv run inside bubblewrap: new user, pid, network, ipc, uts and cgroup namespaces, a new
// session, an empty environment, dying with helios-solve; it sees /usr (and the /lib, /bin links
// into it) read-only, fresh /proc, /dev and /tmp, its binary argv[0] read-only, and `workdir` as
// the only writable folder and its working directory. Nothing else of the host (no /etc, no home,
// no project folders), and the folders of `read_only` read-only. Throws std::runtime_error when
// bwrap is not installed.
std::vector<std::string> sandboxed(const std::vector<std::string>& argv, const std::string& workdir,
                                   const std::vector<std::string>& read_only = {});

// Runs argv (argv[0] a path) in a child with CPU, address-space, file-size, core and process-count
// limits and a wall-clock limit, in its own process group with `workdir` (if not empty) as its
// working directory. On return nothing it started is left running: the group and any orphan
// (helios-solve is a child subreaper) are killed. Each line of the program's stderr goes to
// `on_line` (if set) as it is written, its control bytes replaced by '?', at most 300 bytes.
RunResult run_limited(const std::vector<std::string>& argv, double wall_limit_s, double memory_limit_mb,
                      const std::string& workdir = "",
                      const std::function<void(const std::string&)>& on_line = nullptr);

// Runs gnuplot on `script`; the strings that come from outside it (titles, file names) reach it as
// data, gnuplot's ARG1, ARG2, ... (gnuplot -c), never as its language, whatever quotes, backquotes
// or macros they hold. Returns what gnuplot printed.
std::string run_gnuplot(const std::string& script, const std::vector<std::string>& args);

// Draws the trajectory coloured by the control, with equal axes (seen from +z where the transfer is
// near the x-y plane, else in 3-D), the central body to scale, the osculating orbits at departure
// and arrival (the target's where the spec says the arrival is on it), the thrust direction along
// the thrusting arcs; and the control panel versus time from departure in hours (a flight under
// three days) or days: thrust + mass (throttle_mass.png) for an engine, the cone angle
// (cone_angle.png) for a sail. `spec` (may be null) names the body, its radius and mu, the thrust,
// the epoch and the endpoints. Returns the file names by role ({"trajectory_plot": .., "<panel>_plot": ..}).
io::json plot_trajectory(const std::string& csv_path, const std::string& prefix, const std::string& title,
                         const io::json* spec = nullptr);

// Adds the user's units beside the solution's SI/named keys: tof_hours for a flight under
// astro::kHoursBelowDays, and with departure_mjd2000 the departure's and the arrival's calendar
// dates (departure_date_tdb, arrival_mjd2000, arrival_date_tdb). Returns the line that says them,
// and what the flight cost: the final mass and the propellant, at a constant mass the delta-v.
std::string add_user_units(io::json& solution);

// Removes the private run folders (.run.<pid>.<6 characters>) in `dir` left by runs whose process
// has ended (killed before its folder went), a zombie counted as ended; a running one's stay.
void remove_stale_run_folders(const std::string& dir);

// Compiles only (into the cache) and returns the compile artifact: ok, diagnostics, error count.
io::json compile_report(const SolveOptions& options);

// The whole stage; returns the solution artifact (status "compile_failed" etc. are data, not throws).
io::json solve(const SolveOptions& options);

// Checks a settings document: an object whose keys are those of schemas/settings.schema.json,
// valid against it. Throws input_error "<source>: ..." naming the field.
void check_settings(const io::json& settings, const std::string& source);

}  // namespace helios::solve
