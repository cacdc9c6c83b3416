// "The following asteroids move on Keplerian orbits about the Sun with these elements:": announces an
// elements table (tables.cpp), whose header must follow.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  b.table_intro = b.here;
  b.table_kind = TableKind::Elements;
  b.table_about = m[1].str();
}

}  // namespace

std::vector<Form> table_intro() {
  return {
      {"an elements table's introduction",
       240,
       R"(The (?:following )?(?:bodies|asteroids|comets|planets|targets) move on (?:Keplerian )?orbits (?:about|around) (the central body|(?:the )?[A-Za-z][A-Za-z0-9_]*)(?: with (?:these|the following) elements)?\s*:?)",
       read,
       {{"The following asteroids move on Keplerian orbits about the Sun with these elements:\n"
         "| body | a [AU] | e | i [deg] | node [deg] | argument of perihelion [deg] | mean anomaly [deg] | epoch "
         "[MJD] |\n|---|---|---|---|---|---|---|---|\n"
         "| Nikko | 2.2375176 | 0.1052183 | 5.70117 | 71.94548 | 2.08462 | 287.3844555 | 56800 |",
         "planets +visit", R"~({"/constraints/1/target/elements/a_AU": 2.2375176})~"},
        {"The following asteroids move on Keplerian orbits about the Sun with these elements:\n"
         "| Body | a (AU) | e | i (deg) | \xCE\xA9 (deg) | \xCF\x89 (deg) | M (deg) | Epoch (MJD) |\n"
         "| Nikko | 2.2375176 | 0.1052183 | 5.70117 | 71.94548 | 2.08462 | 287.3844555 | 56800 |",
         "planets +visit", R"~({"/constraints/1/target/elements/raan_deg": 71.94548})~"},
        {"The following asteroids move on Keplerian orbits about the Sun with these elements:\n"
         "| name | epoch [MJD2000] | a [km] | e | i [rad] | RAAN [deg] | argp [deg] | true anomaly [deg] |\n"
         "| Nikko | 5256 | 334723000 | 0.1 | 0.1 | 71.9 | 2.1 | 287.4 |",
         "planets +visit",
         R"~({"/constraints/1/target/elements": {"epoch_mjd2000": 5256, "a_AU": 2.2374850554616708, "e": 0.1,
             "i_deg": 5.729577951308232, "raan_deg": 71.9, "argp_deg": 2.1, "true_anomaly_deg": 287.4}})~"},
        {"The following asteroids move on Keplerian orbits about the Sun with these elements:\n"
         "| body | a [AU] | e | i [deg] | node [deg] | mean anomaly [deg] | epoch [MJD] |",
         "planets +visit", R"~({"error": "the header lacks argp"})~"},
        {"The following asteroids move on Keplerian orbits about the Sun with these elements:", "planets",
         R"~({"error": "no table follows it"})~"}}}};
}

}  // namespace helios::spec::grammar::forms
