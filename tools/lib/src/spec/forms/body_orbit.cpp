// "NAME moves on a Keplerian orbit about the Sun with a = Q, e = N, i = Q, node = Q, argument of
// perihelion = Q and mean anomaly = Q at MJD N.": a body given by its elements (true anomaly may
// replace the mean one; the epoch may be MJD2000; Omega or Ω the node, omega, ω or w the argument, M
// the mean anomaly, nu or ν the true one; angles in deg, rad or °).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& m) {
  const std::string name = body_name(m[1].str());
  if (!m[4].matched)
    throw sentence_error("the elements of " + name +
                         " need their epoch: end the sentence with 'at MJD N' or "
                         "'at MJD2000 N'");
  static const std::regex clause = re(R"((.+?)\s*=\s*()" + kNum + R"()(?:\s*()" + kUnit + "|\xC2\xB0))?");
  std::map<std::string, double> v;
  for (const auto& part : clauses_of(m[3].str())) {
    std::smatch c;
    const std::string field = std::regex_match(part, c, clause) ? element_field(c[1].str()) : "";
    if (field.empty())
      throw sentence_error("cannot read '" + part +
                           "': expected 'a = Q', 'e = N', 'i = Q', 'node = Q', 'argument of perihelion = Q' and "
                           "'mean anomaly = Q' or 'true anomaly = Q'");
    if (v.count(field) || (field == "mean" && v.count("true")) || (field == "true" && v.count("mean")))
      throw sentence_error("'" + part + "' repeats an element of " + name);
    v[field] = number(c[2].str()) * Builder::element_unit(field, c[3].matched ? c[3].str() : "");
  }
  for (const char* f : {"a", "e", "i", "raan", "argp"})
    if (!v.count(f)) throw sentence_error("the orbit of " + name + " lacks its " + Builder::element_label(f));
  if (!v.count("mean") && !v.count("true"))
    throw sentence_error("the orbit of " + name + " lacks its anomaly ('mean anomaly = Q' or 'true anomaly = Q')");
  b.define_orbit(name, m[2].str(), elements_json(mjd2000_of(m[4].str(), m[5].str()), v));
}

}  // namespace

std::vector<Form> body_orbit() {
  return {
      {"a body's orbit",
       230,
       R"((?:the (?:asteroid|comet|planet|moon|body|object) )?(.+?) moves on an? (?:Keplerian )?orbit (?:about|around) (the central body|(?:the )?[A-Za-z][A-Za-z0-9_]*) with (.+?)(?: at (?:the )?(?:epoch )?(MJD2000|MJD) ()" +
           kNum + "))?",
       read,
       {{"Azusa moves on a Keplerian orbit about the Sun with a = 2.6 AU, e = 0.12, i = 3.5 deg, node = 120 deg, "
         "argument of perihelion = 40 deg and true anomaly = 10 deg at MJD2000 400.",
         "planets -arrival +to_azusa",
         R"~({"/arrival/target": {"kind": "orbit", "body": "Azusa", "elements": {"epoch_mjd2000": 400, "a_AU": 2.6,
                 "e": 0.12, "i_deg": 3.5, "raan_deg": 120, "argp_deg": 40, "true_anomaly_deg": 10}}})~"},
        {"Azusa moves on a Keplerian orbit about the Sun with a = 2.6 AU, e = 0.12, i = 3.5\xC2\xB0, Omega = "
         "120\xC2\xB0, "
         "omega = 40\xC2\xB0 and M = 10\xC2\xB0 at MJD2000 400.",
         "planets -arrival +to_azusa",
         R"~({"/arrival/target/elements": {"epoch_mjd2000": 400, "a_AU": 2.6, "e": 0.12, "i_deg": 3.5,
             "raan_deg": 120, "argp_deg": 40, "mean_anomaly_deg": 10}})~"},
        {"Azusa moves on a Keplerian orbit about the Sun with a = 2.6 AU, e = 0.12, i = 3.5 deg, node = 120 deg "
         "and argument of perihelion = 40 deg at MJD2000 400.",
         "planets -arrival +to_azusa", R"~({"error": "the orbit of Azusa lacks its anomaly"})~"}}}};
}

}  // namespace helios::spec::grammar::forms
