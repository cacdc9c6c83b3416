// The paraphrase corpus (tests/parse-corpus/sentences.tsv) as the measure of the builtin parser:
// each sentence is put into a minimal, otherwise complete problem text, and the
// spec is checked against the facts the corpus expects. Counts per kind: accepted with the right
// values, rejected, misread (accepted with wrong values, or accepted when it must be rejected).
// Misread must be 0 for every kind; a fact the harness cannot check is never counted as read right.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "helios/astro/constants.hpp"
#include "helios/io/error.hpp"
#include "helios/io/json_io.hpp"
#include "helios/spec/parse.hpp"

namespace {

using helios::io::json;

struct Entry {
  std::string id, kind, sentence;
  json expect;
};

std::vector<Entry> corpus() {
  std::ifstream in(std::string(HELIOS_SOURCE_DIR) + "/tests/parse-corpus/sentences.tsv");
  std::vector<Entry> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, '\t');) f.push_back(cell);
    if (f.size() == 4) out.push_back({f[0], f[1], f[2], json::parse(f[3])});
  }
  return out;
}

// The minimal problems, one group of facts per line; a sentence under test replaces the groups
// whose facts it states. kHelio is S01's; kGeo an Earth orbit (S14's), the context of a final orbit
// and of states near the Earth, where S01's would put the spacecraft inside the Sun.
using Base = std::vector<std::pair<std::string, std::string>>;
const Base kHelio = {
    {"name", "Problem T01: corpus sentence."},
    {"central", "The central body is the Sun."},
    {"thrust", "The spacecraft has a maximum thrust of 0.5 N."},
    {"isp", "The spacecraft has a specific impulse of 2000 s."},
    {"mass", "The spacecraft has an initial mass of 1000 kg."},
    {"departure",
     "The spacecraft departs at t = 0 days from position [-140699693, -51614428, 980] km with velocity "
     "[9.774596, -28.07828, 4.337725e-4] km/s."},
    {"tof", "The time of flight is 348.795 days."},
    {"arrival",
     "At the final time the spacecraft rendezvouses with position [-172682023, 176959469, 7948912] km and "
     "velocity [-16.427384, -14.860506, 9.21486e-2] km/s."},
    {"objective", "Minimize the fuel consumption."},
};
const Base kGeo = {
    {"name", "Problem T02: corpus sentence about the Earth."},
    {"central", "The central body is the Earth."},
    {"thrust", "The spacecraft has a maximum thrust of 60 N."},
    {"isp", "The spacecraft has a specific impulse of 2000 s."},
    {"mass", "The spacecraft has an initial mass of 1500 kg."},
    {"departure",
     "The spacecraft departs at t = 0 days from position [-46500, 0, 0] km with velocity [0, -1.4529784332509441, "
     "-0.17851317059960614] km/s."},
    {"tof", "The time of flight is free, at most 2 days."},
    {"arrival", "At the final time the spacecraft is on the circular equatorial orbit of radius 42165 km."},
    {"objective", "Minimize the time of flight."},
};

// Events on the way: bodies move, so the problem gets the calendar epoch MJD2000 400; a body
// that is no planet gets an orbit, stated before the sentence so that it may name the body; a stay
// or lander without its own window belongs to a rendezvous stated before it.
const char* kEpoch = "Launch is on MJD2000 400.\n";

std::string orbit_of(const std::string& body) {
  static const std::set<std::string> planets = {"Earth", "Mars", "Venus", "Jupiter"};
  if (planets.count(body)) return "";
  return body +
         " moves on a Keplerian orbit about the Sun with a = 1.3 AU, e = 0.1, i = 2 deg, node = 80 deg, argument of "
         "perihelion = 30 deg and mean anomaly = 10 deg at MJD2000 400.\n";
}

std::string visit(const std::string& body) {
  return orbit_of(body) + "The spacecraft rendezvouses with " + body + " between day 100 and day 150.\n";
}

std::string text_without(const Base& base, const std::set<std::string>& omit, const std::string& sentence,
                         const std::string& extra = "", const std::string& before = "") {
  std::string text;
  for (const auto& [group, line] : base)
    if (!omit.count(group)) text += line + "\n";
  return text + before + sentence + "\n" + extra;
}

bool close(double got, double want) {
  return std::fabs(got - want) <= 1e-8 * std::fabs(want) + 1e-6;
}

bool close_vec(const json& got, const json& want) {
  if (!got.is_array() || got.size() != want.size()) return false;
  for (std::size_t k = 0; k < want.size(); ++k)
    if (!close(got[k].get<double>(), want[k].get<double>())) return false;
  return true;
}

enum class Result { Right, Rejected, Misread };

// The final constraint is an orbit with exactly the elements expected (orbit_a_km, orbit_e, ...).
bool orbit_matches(const json& arrival, const json& expect) {
  static const std::map<std::string, std::string> keys = {{"orbit_a_km", "semi_major_axis_km"},
                                                          {"orbit_e", "eccentricity"},
                                                          {"orbit_i_deg", "inclination_deg"},
                                                          {"orbit_raan_deg", "raan_deg"},
                                                          {"orbit_argp_deg", "argp_deg"}};
  const json& target = arrival["target"];
  if (arrival["kind"] != "orbit_insertion" || target.value("kind", "") != "orbital_elements") return false;
  std::size_t n = 0;
  for (const auto& [key, field] : keys) {
    if (!expect.contains(key)) continue;
    ++n;
    if (!target.contains(field) || !close(target[field].get<double>(), expect[key].get<double>())) return false;
  }
  return target.size() == n + 1;  // the kind and the elements expected, no other
}

// Checks the spec's fields against `expect`; `why` says what differs. `on_the_way`: the sentence
// states an event on the way, the one interior constraint, and `body` is its body.
bool matches(const json& spec, const json& expect, bool on_the_way, std::string& why) {
  const json& sc = spec["spacecraft"];
  const json& dep = spec["constraints"].front()["target"];
  const json& arr = spec["constraints"].back()["target"];
  // Numbers the spec holds at a place: of the whole spec, or of the event on the way ("/..." of ev).
  static const std::map<std::string, std::string> numbers = {
      {"thrust_N", "/spacecraft/thrust_N"},
      {"isp_s", "/spacecraft/isp_s"},
      {"mass_kg", "/spacecraft/initial_mass_kg"},
      {"tof_days", "/time/tof_days"},
      {"mu_km3_s2", "/central_body/mu_km3_s2"},
      {"j2_value", "/central_body/j2"},
      {"r_eq_km", "/central_body/radius_km"},
      {"char_accel_mm_s2", "/spacecraft/sail_characteristic_acceleration_mm_s2"}};
  static const std::map<std::string, std::string> event_numbers = {{"min_periapsis_km", "/min_periapsis_radius_km"},
                                                                   {"stay_days", "/stay_days"},
                                                                   {"mass_drop_kg", "/mass_drop_kg"},
                                                                   {"a_au", "/target/elements/a_AU"},
                                                                   {"e", "/target/elements/e"},
                                                                   {"i_deg", "/target/elements/i_deg"},
                                                                   {"raan_deg", "/target/elements/raan_deg"},
                                                                   {"argp_deg", "/target/elements/argp_deg"},
                                                                   {"M_deg", "/target/elements/mean_anomaly_deg"},
                                                                   {"nu_deg", "/target/elements/true_anomaly_deg"},
                                                                   {"epoch_mjd2000", "/target/elements/epoch_mjd2000"}};
  const auto number_at = [](const json& doc, const std::string& where) {
    const json::json_pointer p(where);
    return doc.contains(p) ? doc[p].get<double>() : -1.0;
  };
  json ev = json::object();
  for (const auto& c : spec["constraints"])
    if (c["at"] == "interior") ev = c;
  if (on_the_way && spec["constraints"].size() != 3) why += "events ";
  for (const auto& [key, want] : expect.items()) {
    bool ok = true;
    if (on_the_way && (key == "flyby_body" || key == "body"))
      ok = ev.value("target", json::object()).value("body", "") == want;
    else if (key == "flyby_kind")
      ok = ev.value("kind", "") == want;
    else if (key == "window_days")
      ok = close_vec(ev.value("window_days", json()), want);
    else if (key == "window_mjd2000")
      ok = ev.contains("window_days") &&
           close_vec(json{ev["window_days"][0].get<double>() + spec["time"].value("epoch_mjd2000", 0.0),
                          ev["window_days"][1].get<double>() + spec["time"].value("epoch_mjd2000", 0.0)},
                     want);
    else if (numbers.count(key))
      ok = close(number_at(spec, numbers.at(key)), want);
    else if (event_numbers.count(key))
      ok = close(number_at(ev, event_numbers.at(key)), want);
    else if (key == "a_km")
      ok = close(number_at(ev, event_numbers.at("a_au")) * helios::astro::AU_KM, want);
    else if (key == "epoch_text")  // the text as written: the epoch is checked by its value
      ok = expect.contains("epoch_mjd2000");
    else if (key == "j2")
      ok = spec["dynamics"].value("perturbations", json::array()) == json::array({{{"kind", "j2"}}});
    else if (key == "solar_sail")
      ok = spec["dynamics"]["propulsion"] == "solar_sail" && sc.value("sail_reference_distance_AU", -1.0) == 1.0;
    else if (key == "sail_lightness")  // the Sun's gravity at 1 AU times the lightness number
      ok = close(
          sc.value("sail_characteristic_acceleration_mm_s2", -1.0),
          want.get<double>() * helios::astro::MU_SUN_KM3_S2 / (helios::astro::AU_KM * helios::astro::AU_KM) * 1e6);
    else if (key == "central_body")
      ok = spec["central_body"]["name"] == want;
    else if (key == "r0_km")
      ok = close_vec(dep.value("position_km", json()), want);
    else if (key == "v0_km_s")
      ok = close_vec(dep.value("velocity_km_s", json()), want);
    else if (key == "rf_km")
      ok = close_vec(arr.value("position_km", json()), want);
    else if (key == "vf_km_s")
      ok = close_vec(arr.value("velocity_km_s", json()), want);
    else if (key == "t0_text")  // the text as written: an epoch is checked by its value
      ok = expect.contains("t0_mjd2000") || ((want == "t = 0" || want == "0 s") && spec["time"]["t0_days"] == 0.0);
    else if (key == "body")  // the rendezvous body: a planet, or a body the context gave an orbit
      ok = (arr.value("kind", "") == "body" || arr.value("kind", "") == "orbit") && arr.value("body", "") == want;
    else if (key == "departure_body")
      ok = (dep.value("kind", "") == "body" || dep.value("kind", "") == "orbit") && dep.value("body", "") == want;
    else if (key == "t0_mjd2000")
      ok = spec["time"].contains("epoch_mjd2000") && close(spec["time"]["epoch_mjd2000"], want) &&
           spec["time"]["t0_days"] == 0.0;
    else if (key == "orbit_a_km" || key == "orbit_e" || key == "orbit_i_deg" || key == "orbit_raan_deg" ||
             key == "orbit_argp_deg")
      ok = orbit_matches(spec["constraints"].back(), expect);
    else if (key == "t0_window_mjd2000")
      ok =
          spec["time"].value("departure", "") == "free" &&
          close_vec(json{spec["time"]["t0_window_days"][0].get<double>() + spec["time"]["epoch_mjd2000"].get<double>(),
                         spec["time"]["t0_window_days"][1].get<double>() + spec["time"]["epoch_mjd2000"].get<double>()},
                    want);
    else if (key == "tof_min_days" || key == "tof_max_days")
      ok = spec["time"]["final_time"] == "free" && close(spec["time"][key].get<double>(), want);
    else if (key == "tof_free")
      ok = spec["time"]["final_time"] == "free" && spec["time"]["tof_max_days"].get<double>() > 0;
    else if (key == "objective") {
      const std::string kind = spec["objective"]["kind"];
      ok = (want == "min_fuel" || want == "max_final_mass") ? kind == "minimum_fuel" : kind == "minimum_time";
    } else {
      ok = false;  // a fact this harness cannot check is never counted as read right
    }
    if (!ok) {
      why += key + " ";
    }
  }
  return why.empty();
}

// The sentence as a problem text's lines: "\\n" in the corpus is a line break (a table's rows); a
// sentence gets its period, a table row none.
std::string as_text(const std::string& sentence) {
  std::string text;
  for (std::size_t k = 0; k < sentence.size(); ++k) {
    const bool newline = sentence.compare(k, 2, "\\n") == 0;
    text += newline ? '\n' : sentence[k];
    k += newline;
  }
  return text.back() == '|' ? text : text + ".";
}

bool near(const json& x, const char* key, double value) {
  return x.contains(key) && std::fabs(x[key].get<double>() / value - 1) < 0.01;
}

// A position the corpus states in km that lies within 1e6 km of the centre: about the Earth, not the Sun.
bool near_the_earth(const json& x) {
  for (const char* key : {"r0_km", "rf_km"})
    if (x.contains(key) && std::hypot(x[key][0].get<double>(), x[key][1].get<double>(), x[key][2].get<double>()) < 1e6)
      return true;
  return false;
}

Result run(const Entry& e, std::string& detail) {
  const std::string sentence = as_text(e.sentence);
  if (e.expect.contains("reject")) {
    // Rejected only if no context accepts it: the full problem, and the problem without each group,
    // about the Sun and about the Earth. Also with a calendar epoch and a rendezvous with Nikko on the
    // way, for sentences about events.
    std::vector<std::set<std::string>> contexts = {{}};
    for (const auto& [group, _] : kHelio)
      if (group != "name") contexts.push_back({group});
    contexts.push_back({"departure", "arrival"});
    for (const Base* base : {&kHelio, &kGeo})
      for (const auto& omit : contexts)
        for (const bool on_the_way : {false, true}) {
          try {
            helios::spec::parse_problem_text(
                text_without(*base, omit, sentence, on_the_way ? kEpoch : "", on_the_way ? visit("Nikko") : ""),
                "p.txt");
            detail = std::string("accepted") + (base == &kGeo ? " about the Earth" : "") +
                     (on_the_way ? " on the way" : "") + " without";
            for (const auto& g : omit) detail += " " + g;
            return Result::Misread;
          } catch (const helios::input_error& err) {
            detail = err.what();
          }
        }
    return Result::Rejected;
  }
  std::set<std::string> omit;
  std::string extra, before;
  const json& x = e.expect;
  // A final orbit and a state near the Earth are about the Earth.
  const Base& base = e.kind == "final-orbit" || near_the_earth(x) ? kGeo : kHelio;
  // A body's elements: the sentence gives its orbit, a flyby sends the spacecraft there.
  const bool on_the_way = e.kind == "flyby" || e.kind == "stay" || e.kind == "elements";
  if (on_the_way) {
    const std::string body = x.value("flyby_body", x.value("body", "Nikko"));
    before = e.kind == "stay" && !x.contains("window_days") ? visit(body) : e.kind == "elements" ? "" : orbit_of(body);
    if (e.kind == "elements") extra += "The spacecraft flies by " + body + " between day 100 and day 150.\n";
    extra += kEpoch;
  }
  if (x.contains("thrust_N")) omit.insert("thrust");
  if (x.contains("isp_s")) omit.insert("isp");
  if (x.contains("mass_kg")) omit.insert("mass");
  if (x.contains("tof_days") || e.kind == "tof-bound") omit.insert("tof");
  if (x.contains("objective")) omit.insert("objective");
  if (x.contains("central_body")) omit.insert("central");
  if (e.kind == "final-orbit") omit.insert("arrival");
  if (e.kind == "tof-bound" && !x.contains("objective")) {  // a bounded time of flight: a minimum time
    omit.insert("objective");
    extra += "Minimize the time of flight.\n";
  }
  // A gravitational parameter is the central body's: the body whose known value it is.
  if (e.kind == "mu" && !x.contains("central_body") &&
      (near(x, "mu_km3_s2", 398600.4418) || near(x, "mu_km3_s2", 42828.3))) {
    omit.insert("central");
    before += near(x, "mu_km3_s2", 398600.4418) ? "The central body is the Earth.\n" : "The central body is Mars.\n";
  }
  if (x.contains("t0_text") && !x.contains("t0_mjd2000") && !x.contains("r0_km") && !x.contains("v0_km_s")) {
    // the departure time alone: the base departure states it too
    omit.insert("departure");
    extra += "The initial position is [-140699693, -51614428, 980] km.\n";
    extra += "The initial velocity is [9.774596, -28.07828, 4.337725e-4] km/s.\n";
  }
  if (e.kind == "j2") {  // the J2 of an Earth-centred problem (Mars's for its coefficient), known unless given
    omit.insert("central");
    const bool mars = near(x, "j2_value", 1.96045e-3);
    before += x.contains("j2_value") ? (mars ? "The central body is Mars.\n" : "The central body is the Earth.\n")
                                     : "The central body is the Earth with J2 coefficient 1.08262668e-3.\n";
  }
  if (e.kind == "solar-sail") omit.insert({"thrust", "isp", "mass"});  // a sail has no engine and no mass
  if (e.kind == "departure-window") {  // a free departure from the Earth, the sentence giving its window
    omit.insert("departure");
    if (!x.contains("departure_body")) before += "The spacecraft departs from Earth.\n";
  } else if (!on_the_way && (x.contains("body") || x.contains("departure_body"))) {
    // a body moves: the problem needs a calendar epoch, which the sentence may give
    omit.insert(x.contains("body") ? "arrival" : "departure");
    before = orbit_of(x.value("body", x.value("departure_body", "")));
    if (!x.contains("t0_mjd2000")) extra += "Launch is on MJD2000 400.\n";
  }
  if (x.contains("r0_km") || x.contains("v0_km_s")) {
    omit.insert("departure");
    if (!x.contains("r0_km")) extra += "The initial position is [-140699693, -51614428, 980] km.\n";
    if (!x.contains("v0_km_s")) extra += "The initial velocity is [9.774596, -28.07828, 4.337725e-4] km/s.\n";
  }
  if (x.contains("rf_km") || x.contains("vf_km_s")) {
    omit.insert("arrival");
    if (!x.contains("rf_km")) extra += "The final position is [-172682023, 176959469, 7948912] km.\n";
    if (!x.contains("vf_km_s")) extra += "The final velocity is [-16.427384, -14.860506, 9.21486e-2] km/s.\n";
  }
  if (x.value("objective", "") == "min_time" && !omit.count("tof")) {  // a minimum time needs a free final time
    omit.insert("tof");
    extra += "The time of flight is free, at most 1000 days.\n";
  }
  json spec;
  try {
    spec = helios::spec::parse_problem_text(text_without(base, omit, sentence, extra, before), "p.txt");
  } catch (const helios::input_error& err) {
    detail = err.what();
    return Result::Rejected;
  }
  std::string why;
  if (matches(spec, x, on_the_way, why)) return Result::Right;
  detail = "wrong: " + why;
  return Result::Misread;
}

TEST(ParseCorpus, NoCoveredKindIsMisread) {
  const auto entries = corpus();
  ASSERT_GT(entries.size(), 200u);
  std::map<std::string, std::array<int, 3>> counts;
  int rejects = 0, suggested = 0;
  for (const auto& e : entries) {
    std::string detail;
    const Result r = run(e, detail);
    ++counts[e.kind][static_cast<int>(r)];
    rejects += e.expect.contains("reject");
    suggested += r == Result::Rejected && detail.find("did you mean") != std::string::npos;
    if (std::getenv("HELIOS_CORPUS_VERBOSE"))
      std::printf("%-22s %-9s %s | %s\n", e.id.c_str(),
                  r == Result::Right      ? "right"
                  : r == Result::Rejected ? "rejected"
                                          : "MISREAD",
                  e.sentence.c_str(), detail.c_str());
    // No sentence of any kind is misread: what the reader cannot place is refused, never guessed.
    EXPECT_NE(r, Result::Misread) << e.id << ": " << e.sentence << " -> " << detail;
  }
  std::printf("%-18s %7s %9s %8s\n", "kind", "right", "rejected", "misread");
  for (const auto& [kind, c] : counts) std::printf("%-18s %7d %9d %8d\n", kind.c_str(), c[0], c[1], c[2]);
  // What the covered kinds read right when the reader learned the orbits, windows and bounds of issue 47 (a floor: the
  // reader may only get better), and every sentence that must be rejected is.
  int right = 0;
  for (const auto& [kind, c] : counts) right += c[0];
  std::printf("read right %d, refused %d (of which with a suggested form %d), misread 0 required\n", right,
              static_cast<int>(entries.size()) - right, suggested);
  EXPECT_GE(right, 335);
  EXPECT_EQ(counts["reject"][1], rejects);
  EXPECT_GE(rejects, 117);
}

}  // namespace
