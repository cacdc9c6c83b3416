// ---------------------------------------------------------------------------------------------
// HELIOS shooting runtime, entry point (templates/runtime/main.hpp), the one part of the runtime
// pasted into every program: main calls the library's run (report.hpp), which reads the settings,
// calls the SOLVE module's solve_problem and writes the outcome and the trajectory.
// usage: shoot [--parameters PARAMETERS.json] --settings SETTINGS.json --outcome OUTCOME.json
//              --trajectory TRAJECTORY.csv
// ---------------------------------------------------------------------------------------------
int main(int argc, char** argv) {
  try {
    return helios_rt::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shoot: error: %s\n", e.what());
    return 1;
  }
}
