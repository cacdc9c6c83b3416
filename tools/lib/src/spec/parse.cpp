// The builtin parser: reads the text item by item into a Builder and assembles the spec.
#include "helios/spec/parse.hpp"

#include "grammar.hpp"
#include "helios/io/schema.hpp"

namespace helios::spec::grammar {

void Builder::once(detail::Field f) {
  once(detail::field_name(f));
}

void Builder::check_value(detail::Field f, double v, const std::string& written) const {
  try {
    detail::check_value(f, v, written);
  } catch (const detail::facts_error& e) {
    throw sentence_error(e.what());
  }
}

void Builder::once(const std::string& what) {
  if (!seen[what]++) return;
  if (what == "the final rendezvous" && windowless_rendezvous)
    throw sentence_error("the final rendezvous is given twice: \"" + windowless_rendezvous->text + "\" (line " +
                         std::to_string(windowless_rendezvous->line) +
                         ") has no window, so it was read as the final one; an event on the way needs its window "
                         "('... between day N and day N')");
  throw sentence_error(what + " is given twice");
}

void Builder::fail(const Where& w, const std::string& why) const {
  throw input_error(source + ":" + std::to_string(w.line) + ": cannot use " + (w.table_row ? "table row" : "sentence") +
                    " \"" + w.text + "\": " + why);
}

// One item of the text; a sentence error is reported at it.
void Builder::read(const Sentence& item) {
  here = {item.line, item.text, item.table_row};
  try {
    if (table_intro && !may_be_header(item))
      throw sentence_error(std::string("it follows a sentence announcing ") +
                           (table_kind == TableKind::Thruster ? "the thruster's table" : "a table") +
                           ", so it must be the table's header " + header_example());
    if (item.table_row) {
      table_line(item.text);
    } else {
      end_table();
      // numbers in words as digits, but for the problem's title, which is kept as written
      static const std::regex title = re("Problem .*");
      sentence = std::regex_match(item.text, title) ? item.text : with_digits(item.text);
      handle(sentence);
    }
  } catch (const sentence_error& e) {
    fail(here, e.what());
  }
}

}  // namespace helios::spec::grammar

namespace helios::spec {

using grammar::json;

namespace {

[[noreturn]] void missing(const std::string& source, const std::string& what, const std::string& example) {
  throw input_error(source + ": the problem text never states " + what + " (add a sentence such as \"" + example +
                    "\")");
}

// A constant mass (no mass state): the mass is the initial one throughout and the specific impulse
// optional (it prices the minimum fuel in kg; without it the cost is the delta-v).
void check_constant_mass(const grammar::Builder& b, const std::string& source) {
  if (b.spacecraft.value("mass_model", "") != "constant") return;
  const std::string where = source + ": the spacecraft's mass is constant";
  if (b.propulsion == "solar_sail")
    throw input_error(where + ", but a solar sail has no engine and no mass: drop the sentence on the mass");
  if (b.spacecraft.contains("final_mass_kg"))
    throw input_error(where + ", so a constant mass has no final mass of its own: state the mass ('The " +
                      "spacecraft's mass is constant at 1500 kg.')");
  if (b.objective.is_object() && b.objective.value("kind", "") == "minimum_initial_mass")
    throw input_error(where + ", so it burns no propellant that a larger initial mass would carry: minimize the " +
                      "fuel (the propellant with a specific impulse, else the delta-v) or the time instead");
}

// A solar-electric engine: the thrust follows from the power, about the Sun; its performance is its
// efficiency and specific impulse, or the fits of its thrust and mass flow to its input power, or
// a table of them (whose lowest and highest powers are the engine's range).
void check_solar_electric(const grammar::Builder& b, const std::string& source) {
  const bool constant_mass = b.spacecraft.value("mass_model", "") == "constant";
  const bool solar_electric = b.spacecraft.contains("array_power_1AU_W");
  const bool fits = b.spacecraft.contains("thrust_polynomial_mN");
  const bool table = b.spacecraft.contains("thruster_table");
  if ((fits || table) && !solar_electric)
    missing(source, std::string("the solar arrays that power the thruster's ") + (fits ? "fits" : "table"),
            "The spacecraft is solar-electric: its arrays give 10 kW at 1 AU.");
  if (solar_electric) {
    const std::string where = source + ": the spacecraft is solar-electric";
    const std::string body = b.central_body.value("name", "");
    if (body != "Sun" && body != "sun")
      throw input_error(where +
                        ", so it needs the Sun as the central body (its power falls as 1/r^2 with r in AU), "
                        "not " +
                        body);
    if (b.spacecraft.contains("thrust_N"))
      throw input_error(where + ", so the thrust follows from the power: drop the maximum thrust (" +
                        io::short_number(b.spacecraft.at("thrust_N").get<double>()) + " N)");
    if (constant_mass) throw input_error(where + ": a solar-electric engine of constant mass is not supported");
    // The fits or the table give the engine's performance: what else would give it is refused.
    const auto given_by = [&](std::initializer_list<const char*> keys, const std::string& what) {
      for (const char* key : keys)
        if (b.spacecraft.contains(key))
          throw input_error(
              source + ": the spacecraft's " + key + " (" + io::short_number(b.spacecraft.at(key).get<double>()) +
              ") is stated, but the thruster's " + what + " give" + (what == "fits" ? "" : "s") +
              " its performance (its thrust and mass flow at each input power" +
              (what == "fits" ? "" : ", from its lowest input power to its highest") + "): drop the " + key);
    };
    if (fits) {
      given_by({"engine_efficiency", "isp_s", "max_thrust_N"}, "fits");
    } else if (table) {
      given_by({"engine_efficiency", "isp_s", "max_thrust_N", "max_engine_power_W"}, "table");
    } else if (!b.spacecraft.contains("engine_efficiency") || !b.spacecraft.contains("isp_s")) {
      const bool eta = b.spacecraft.contains("engine_efficiency"), isp = b.spacecraft.contains("isp_s");
      throw input_error(where + ", so its engine needs its " +
                        (!eta && !isp ? "efficiency and specific impulse"
                         : !eta       ? "efficiency"
                                      : "specific impulse") +
                        " ('with an efficiency of 0.6 and a specific impulse of 3000 s' in its sentence), or fits of "
                        "its thrust and mass flow to its input power ('The thruster's thrust is 20 + 30 P mN and its "
                        "mass flow is 1 + 0.6 P mg/s, with P its input power in kW up to 7 kW.'), or a table of "
                        "them ('The thruster's table gives its thrust and mass flow at these input powers:' above "
                        "the table " +
                        grammar::kThrusterTableHeader + ")");
    }
  }
}

// Every fact a problem needs is stated, once the whole text is read; a minimum time without a time of
// flight has it free.
void check_complete(grammar::Builder& b, const std::string& source) {
  if (b.table_intro)
    b.fail(*b.table_intro, "no table follows it (its header reads " + std::string(b.header_example()) + ")");
  b.end_table();
  b.finish_facts();
  if (b.central_body.is_null() && b.constants_body)  // "The Sun's gravitational parameter is Q." names it
    b.central(b.constants_body->first, "");
  if (b.problem.is_null()) missing(source, "its name", "Problem S01: Earth to Mars.");
  if (b.central_body.is_null()) missing(source, "the central body", "The central body is the Sun.");
  check_constant_mass(b, source);
  check_solar_electric(b, source);
  const bool constant_mass = b.spacecraft.value("mass_model", "") == "constant";
  const bool solar_electric = b.spacecraft.contains("array_power_1AU_W");
  const bool fitted = b.spacecraft.contains("thrust_polynomial_mN") || b.spacecraft.contains("thruster_table");
  if (b.propulsion == "low_thrust") {
    // Minimizing the initial mass needs the final mass instead of the initial one.
    const bool find_m0 = b.objective.is_object() && b.objective.value("kind", "") == "minimum_initial_mass";
    using detail::Field;
    for (const auto& [field, example] : std::vector<std::pair<Field, std::string>>{
             {Field::Thrust, "0.5 N"},
             {Field::Isp, "2000 s"},
             {find_m0 ? Field::FinalMass : Field::InitialMass, find_m0 ? "1500 kg" : "1000 kg"}})
      if (!(constant_mass && field == Field::Isp) && !(solar_electric && field == Field::Thrust) &&
          !(fitted && field == Field::Isp) && !b.spacecraft.contains(detail::spec_key(field)))
        missing(source, "the spacecraft's " + detail::spec_key(field), detail::controlled_form(field, example));
    const std::string extra = find_m0 ? "initial_mass_kg" : "final_mass_kg";
    if (b.spacecraft.contains(extra))
      throw input_error(source + ": the spacecraft's " + extra + " is stated, but the objective " +
                        (find_m0 ? "finds the initial mass from the final one" : "takes the initial mass") +
                        ": state only the " + (find_m0 ? "final" : "initial") + " mass");
  }
  if (b.propulsion == "solar_sail" && b.seen.count("the spacecraft's engine"))
    throw input_error(source + ": the spacecraft is a solar sail, so it has no thrust, specific impulse or mass");
  if (!b.seen.count("the departure"))
    missing(source, "the departure", "The spacecraft departs at MJD2000 400 from Earth.");
  const bool minimum_time = b.objective.is_object() && b.objective.value("kind", "") == "minimum_time";
  if (!b.time.contains("final_time") && !minimum_time)
    missing(source, detail::field_name(detail::Field::Tof),
            detail::controlled_form(detail::Field::Tof, "348.795 days"));
  for (const auto& p : b.perturbations)
    if (p["kind"] == "j2" && (!b.central_body.contains("j2") || !b.central_body.contains("radius_km")))
      throw input_error(source +
                        ": the J2 perturbation needs the central body's J2 coefficient and radius (\"The central "
                        "body is the Earth with J2 coefficient 1.08262668e-3 and equatorial radius 6378.137 km.\")");
  if (!b.seen.count("the final rendezvous"))
    missing(source, "the final condition", "At the final time the spacecraft rendezvouses with Mars.");
  if (b.objective.is_null()) missing(source, "the objective", "Minimize the fuel consumption.");
  if (!b.time.contains("final_time")) b.time["final_time"] = "free";  // a minimum time, its bounds to come
}

}  // namespace

json parse_problem_text(const std::string& text, const std::string& source) {
  detail::check_text(text, source);
  grammar::Builder b(source);
  for (const auto& item : detail::split_sentences(text)) {
    if (item.text.size() > kMaxSentenceChars)
      throw input_error(source + ":" + std::to_string(item.line) + ": the sentence is longer than " +
                        std::to_string(kMaxSentenceChars) + " characters, the limit of a line or sentence");
    b.read(item);
  }
  check_complete(b, source);
  b.finish_departure_window();
  b.resolve_targets();
  b.finish_time();
  b.finish_events();
  b.check_constants();
  b.check_physics();
  b.check_objective();
  if (!b.time.contains("t0_days")) b.time["t0_days"] = 0.0;
  json doc = io::artifact_header("spec", "helios-parse", "builtin");
  b.problem["source_file"] = source;
  doc["problem"] = b.problem;
  doc["central_body"] = b.central_body;
  json spacecraft = json::object();  // in one order, however the text states the facts
  for (const char* k : {"thrust_N", "array_power_1AU_W", "bus_power_W", "min_engine_power_W", "max_engine_power_W",
                        "max_thrust_N", "thrust_polynomial_mN", "mass_flow_polynomial_mg_s", "thruster_table",
                        "engine_efficiency", "isp_s", "initial_mass_kg", "final_mass_kg", "mass_model"})
    if (b.spacecraft.contains(k)) spacecraft[k] = b.spacecraft[k];
  for (const auto& [k, v] : b.spacecraft.items())
    if (!spacecraft.contains(k)) spacecraft[k] = v;
  doc["spacecraft"] = spacecraft;
  doc["dynamics"] = {{"model", "two_body"}, {"coordinates", "cartesian"}, {"propulsion", b.propulsion}};
  if (!b.perturbations.empty()) doc["dynamics"]["perturbations"] = b.perturbations;
  doc["objective"] = b.objective;
  json time = json::object();
  for (const char* k : {"t0_days", "epoch_mjd2000", "departure", "t0_window_days", "final_time", "tof_days",
                        "tof_min_days", "tof_max_days"})
    if (b.time.contains(k)) time[k] = b.time[k];
  doc["time"] = time;
  doc["constraints"] = b.constraints();
  if (!b.notes.empty()) doc["notes"] = b.notes;
  return doc;
}

void check_problem_text(const std::string& text, const std::string& source) {
  detail::check_text(text, source);
}

}  // namespace helios::spec
