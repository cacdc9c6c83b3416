// The plots of a trajectory, drawn with gnuplot.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "helios/io/json_io.hpp"
#include "helios/io/process.hpp"
#include "helios/solve/solve.hpp"

namespace helios::solve {
namespace {

namespace fs = std::filesystem;
using io::json;

// The trajectory CSV's header and first data row, to pick the plots' units and panels: read from
// its first 64 KiB only (the program wrote the file; a line without an end is not read whole).
std::pair<std::vector<std::string>, std::vector<double>> csv_head(const std::string& csv_path) {
  std::string head(65536, '\0');
  std::ifstream file(csv_path, std::ios::binary);
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  std::istringstream in(head);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::vector<std::string> columns;
  std::vector<double> values;
  std::stringstream hs(header), rs(row);
  for (std::string c; std::getline(hs, c, ',');) columns.push_back(c);
  for (std::string v; std::getline(rs, v, ',');) values.push_back(std::atof(v.c_str()));
  return {columns, values};
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

json plot_trajectory(const std::string& csv_path, const std::string& prefix, const std::string& title) {
  const auto [columns, first] = csv_head(csv_path);
  // A lambda may not capture a structured binding in C++17 (clang refuses it): a reference it may.
  const auto& names = columns;
  const auto has = [&names](const std::string& c) { return std::find(names.begin(), names.end(), c) != names.end(); };
  const bool engine = has("u") && has("m_kg");
  const bool heliocentric = first.size() > 3 && std::hypot(first[1], first[2], first[3]) > 1e7;
  const std::string length = heliocentric ? "AU" : "km", scale = heliocentric ? "149597870.691" : "1.0";
  // Cone angle between the sail normal and the Sun line, in degrees.
  const std::string cone =
      "(acos((column('nx')*$2 + column('ny')*$3 + column('nz')*$4)/sqrt($2**2 + $3**2 + $4**2))*180/pi)";
  const std::string colour = engine ? "(column('u'))" : cone;
  const std::string panel = engine ? "throttle_mass" : "cone_angle";
  const std::string traj_png = prefix + "trajectory.png", panel_png = prefix + panel + ".png";
  // Fresh files gnuplot only fills: nothing planted under a predictable name is followed.
  io::TempFiles temps;
  const std::string tmp1 = temps.create_beside(traj_png), tmp2 = temps.create_beside(panel_png);
  // ARG1 the trajectory CSV, ARG2 the title, ARG3 and ARG4 the two PNGs (run_gnuplot).
  std::string script = "set datafile separator ','\nset terminal pngcairo size 1000,800 noenhanced\n";
  script += "set output ARG3\nset title ARG2.': trajectory (colour = " +
            std::string(engine ? "throttle" : "cone angle") + ")'\n";
  script += "set xlabel 'x [" + length + "]'\nset ylabel 'y [" + length + "]'\nset zlabel 'z [" + length + "]'\n";
  script += "set view equal xy\nset ticslevel 0\nset grid\nset palette defined (0 '#2b6cb0', 1 '#e53e3e')\n";
  script +=
      engine ? "set cbrange [0:1]\nset cblabel 'throttle u'\n" : "set cbrange [0:90]\nset cblabel 'cone angle [deg]'\n";
  script += "L = " + scale + "\nsplot ARG1 every ::1 using ($2/L):($3/L):($4/L):" + colour +
            " with lines lw 2 palette title 'spacecraft', '< echo 0,0,0' using 1:2:3 with points pt 7 ps 2 lc rgb "
            "'#d69e2e' title 'central body'\n";
  script += "set output ARG4\nset xlabel 'time [days]'\nunset zlabel\n";
  if (engine)
    script +=
        "set title ARG2.': throttle and mass'\nset ylabel 'throttle u'\nset y2label 'mass [kg]'\n"
        "set yrange [-0.05:1.05]\nset y2tics\nset ytics nomirror\nplot ARG1 every ::1 using 1:(column('u')) with "
        "lines lw 2 lc rgb '#e53e3e' title 'throttle', "
        "'' every ::1 using 1:(column('m_kg')) axes x1y2 with lines lw 2 lc rgb '#2b6cb0' title 'mass'\n";
  else
    script += "set title ARG2.': sail cone angle'\nset ylabel 'cone angle [deg]'\nset yrange [0:90]\nplot ARG1 "
              "every ::1 using 1:" +
              cone + " with lines lw 2 lc rgb '#e53e3e' title 'cone angle'\n";
  const std::string out = run_gnuplot(script, {csv_path, title, tmp1, tmp2});
  std::error_code ec;
  if (fs::file_size(tmp1, ec) == 0 || fs::file_size(tmp2, ec) == 0)
    throw std::runtime_error("gnuplot did not draw the plots (is gnuplot installed?): " + io::first_line(out));
  io::move_into_place(tmp1, traj_png);
  io::move_into_place(tmp2, panel_png);
  return {{"trajectory_plot", fs::path(traj_png).filename().string()},
          {panel + "_plot", fs::path(panel_png).filename().string()}};
}

}  // namespace helios::solve
