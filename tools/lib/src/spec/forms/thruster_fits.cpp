// "The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, with P its input power in
// kW up to 7 kW.": a solar-electric thruster given by fits of its thrust and its mass flow to its input
// power P, as flown missions model NSTAR and NEXT (polynomials of degree 4 at most): the coefficients
// c0..ck of P^0..P^k with P in kW, the thrust in mN (thrust_polynomial_mN) and the mass flow in mg/s
// (mass_flow_polynomial_mg_s), over a power range whose top is the engine's maximum input power
// (max_engine_power_W) and whose bottom, when stated, the power below which it is off
// (min_engine_power_W). The arrays that power it are the solar-electric sentence's
// (forms/solar_electric.cpp), which then states no efficiency, specific impulse or maximum thrust: the
// fits give the engine's performance (parse.cpp's check_complete holds the two together).
#include <cmath>
#include <map>
#include <tuple>

#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

constexpr int kMaxDegree = 4;
// The fits are checked at this many powers across their range: neither may be negative there.
constexpr int kRangeSamples = 200;

const std::string kSentence =
    "'The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, with P its input power in kW "
    "up to 7 kW.'";
const std::string kRangeForms = "'up to 7 kW', 'between 0.5 and 2.6 kW' or 'from 500 W to 2.6 kW'";

// A fit as written: its polynomial, its unit and what follows the unit.
struct Written {
  std::string polynomial, unit, rest;
};

bool letter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) != 0;
}
bool digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

// "20 + 30 P mN, with ...": the unit is the first word that is neither the variable P nor the exponent
// of a number ("1.5e-3").
Written split_unit(const std::string& text, const std::string& what, const std::string& units) {
  std::size_t at = 0;
  for (; at < text.size(); ++at) {
    const char c = text[at];
    if (!letter(c)) continue;
    const bool word = at + 1 < text.size() && letter(text[at + 1]);
    if ((c == 'P' || c == 'p') && !word) continue;
    if ((c == 'e' || c == 'E') && at > 0 && (digit(text[at - 1]) || text[at - 1] == '.') && at + 1 < text.size() &&
        (digit(text[at + 1]) || text[at + 1] == '-' || text[at + 1] == '+'))
      continue;
    break;
  }
  if (at == text.size())
    throw sentence_error("the " + what + " fit '" + trimmed(text) + "' needs its unit (" + units + ")");
  std::size_t end = at;
  while (end < text.size() && (letter(text[end]) || digit(text[end]) || text[end] == '/' || text[end] == '^')) ++end;
  return {trimmed(text.substr(0, at)), text.substr(at, end - at), text.substr(end)};
}

// The coefficients c0..ck of a polynomial in P written "20 + 30 P - 1.5e-3 P^2" (terms in any order,
// "30P", "30*P", "P^2", "P**2" and "P²" alike, a lone "P" of coefficient 1), missing ones 0.
std::vector<double> coefficients(std::string text, const std::string& what) {
  text = trimmed(text);
  if (text.size() >= 2 && text.front() == '(' && text.back() == ')') text = trimmed(text.substr(1, text.size() - 2));
  static const std::regex term(
      R"(\s*([-+])?\s*((?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)?\s*(?:(?:\*|\xC2\xB7|\xC3\x97)\s*)?)"
      R"((?:([Pp])\s*(?:(?:\^|\*\*)\s*(\d+)|(\xC2\xB9|\xC2\xB2|\xC2\xB3|\xE2\x81\xB0|\xE2\x81\xB4|\xE2\x81\xB5|)"
      R"(\xE2\x81\xB6|\xE2\x81\xB7|\xE2\x81\xB8|\xE2\x81\xB9))?)?\s*(?=[-+]|$))");
  static const std::map<std::string, int> superscripts = {
      {"\xC2\xB9", 1},     {"\xC2\xB2", 2},     {"\xC2\xB3", 3},     {"\xE2\x81\xB0", 0}, {"\xE2\x81\xB4", 4},
      {"\xE2\x81\xB5", 5}, {"\xE2\x81\xB6", 6}, {"\xE2\x81\xB7", 7}, {"\xE2\x81\xB8", 8}, {"\xE2\x81\xB9", 9}};
  const std::string expected =
      "terms N P^k with k up to " + std::to_string(kMaxDegree) + ", e.g. '20 + 30 P - 0.5 P^2'";
  if (text.empty()) throw sentence_error("the " + what + " fit has no terms: " + expected);
  std::map<int, std::pair<double, std::string>> terms;  // by the power of P: the coefficient, as written
  auto from = text.cbegin();
  while (from != text.cend()) {
    std::smatch m;
    const bool first = terms.empty();
    if (!std::regex_search(from, text.cend(), m, term, std::regex_constants::match_continuous) || m.length(0) == 0 ||
        (!m[2].matched && !m[3].matched) || (!first && !m[1].matched))
      throw sentence_error("cannot read '" + trimmed(std::string(from, text.cend())) + "' of the " + what +
                           " fit: " + expected);
    const std::string written = trimmed(m[0].str());
    int power = 0;
    if (m[3].matched) {
      power = 1;
      if (m[4].matched) power = m[4].length() > 2 ? 99 : std::stoi(m[4].str());
      if (m[5].matched) power = superscripts.at(m[5].str());
    }
    if (power > kMaxDegree)
      throw sentence_error("the " + what + " fit has a term in P^" +
                           (power == 99 ? m[4].str() : std::to_string(power)) + " ('" + written +
                           "'): a fit goes up to P^" + std::to_string(kMaxDegree));
    double c = m[2].matched ? number(m[2].str()) : 1.0;
    if (m[1].matched && m[1].str() == "-") c = -c;
    if (!std::isfinite(c)) throw sentence_error("the " + what + " fit's coefficient '" + written + "' is not finite");
    if (const auto it = terms.find(power); it != terms.end())
      throw sentence_error("the " + what + " fit has two terms in P^" + std::to_string(power) + " ('" +
                           it->second.second + "' and '" + written + "'): write each power of P once");
    terms[power] = {c, written};
    from = m[0].second;
  }
  std::vector<double> c(static_cast<std::size_t>(terms.rbegin()->first) + 1, 0.0);
  for (const auto& [power, term] : terms) c[static_cast<std::size_t>(power)] = term.first;
  return c;
}

double value_at(const std::vector<double>& c, double p) {
  double v = 0;
  for (auto k = c.size(); k-- > 0;) v = v * p + c[k];
  return v;
}

// The clause after the mass flow's unit: P's unit ("with P its input power in kW", "for an input power
// P") and its range ("up to 7 kW", "between 0.5 and 2.6 kW", "from 500 W to 2.6 kW"). P is in the unit
// it is given, else in the unit of the range's top.
struct Range {
  std::optional<double> bottom_W;
  double top_W = 0;
  std::string p_unit, top;  // as written
  bool p_unit_stated = false;
};

// A pattern read at the start of a text, without case (re() matches a text whole).
std::regex start(const std::string& pattern) {
  return std::regex(pattern, std::regex::icase);
}

Range read_range(const std::string& tail) {
  std::string t = tail;
  const auto eat = [&t](const std::regex& r) {
    std::smatch m;
    if (!std::regex_search(t, m, r, std::regex_constants::match_continuous)) return std::vector<std::string>{};
    std::vector<std::string> groups(m.begin(), m.end());
    t = m.suffix().str();
    return groups;
  };
  static const std::regex lead = start(R"(\s*,?\s*(?:(?:with|where|for|over|when|valid(?: for| over)?)\s+)?)");
  static const std::regex p_intro =
      start(R"((?:(?:(?:an?|the|its|their) )?(?:(?:engine|thruster)(?:'s)? )?input power P|)"
            R"(P(?: is| being| as|,)? (?:its|the|their) (?:(?:engine|thruster)(?:'s)? )?input power|P)(?![A-Za-z]))"
            R"((?:\s*,?\s*(?:in|\(in)\s+(?!the\b)([A-Za-z]+)\s*\)?|\s*\[\s*([A-Za-z]+)\s*\])?)");
  static const std::regex sep = start(R"(\s*,?\s*(?:and\s+)?(?:(?:valid|defined)\s+)?(?:(?:for|over)\s+)?)");
  static const std::regex both = re(R"((?:between|from|(?:(?:in|over) )?the range(?: of)?) ()" + kNum + R"()\s*(?:()" +
                                    kUnit + R"()\s+)?(?:and|to|up to|-) ()" + kNum + R"()\s*()" + kUnit + R"()\s*)");
  static const std::regex top_only = re(R"((?:up to|at most|to|below|under|of at most|no more than|not above) ()" +
                                        kNum + R"()\s*()" + kUnit + R"()\s*)");
  static const std::regex bottom_only =
      re(R"((?:from|above|over|of at least|at least|down to) ()" + kNum + R"()\s*()" + kUnit + R"()\s*)");
  eat(lead);
  Range r;
  if (const auto g = eat(p_intro); !g.empty()) r.p_unit = !g[1].empty() ? g[1] : g[2];
  eat(sep);
  std::smatch m;
  const auto power = [](const std::string& value, const std::string& unit, const std::string& what) {
    const double w = number(value) * unit_factor(Dimension::Power, unit);
    if (!(w >= 0)) throw sentence_error(what + " must not be negative, got " + value + " " + unit);
    return w;
  };
  if (std::regex_match(t, m, both)) {
    const std::string bottom_unit = m[2].matched ? m[2].str() : m[4].str();
    r.bottom_W = power(m[1].str(), bottom_unit, "the bottom of the fits' power range");
    r.top_W = power(m[3].str(), m[4].str(), "the top of the fits' power range");
    r.top = m[3].str() + " " + m[4].str();
    if (!(*r.bottom_W < r.top_W))
      throw sentence_error("the bottom of the fits' power range (" + m[1].str() + " " + bottom_unit +
                           ") must be below its top (" + r.top + ")");
  } else if (std::regex_match(t, m, top_only)) {
    r.top_W = power(m[1].str(), m[2].str(), "the top of the fits' power range");
    r.top = m[1].str() + " " + m[2].str();
  } else if (t.empty() || std::regex_match(t, bottom_only)) {
    throw sentence_error("the thruster's fits need the top of their power range, the engine's maximum input power (" +
                         kRangeForms + ")");
  } else {
    throw sentence_error(
        "cannot read '" + trimmed(t) +
        "' of the thruster's fits: expected P's unit ('with P its input power in kW') and its range (" + kRangeForms +
        ")");
  }
  if (!(r.top_W > 0)) throw sentence_error("the top of the fits' power range must be positive, got " + r.top);
  if (r.bottom_W && *r.bottom_W == 0) r.bottom_W.reset();  // the engine is off at no power anyway
  r.p_unit_stated = !r.p_unit.empty();
  if (!r.p_unit_stated) r.p_unit = r.top.substr(r.top.find(' ') + 1);
  return r;
}

void read(Builder& b, const std::smatch& match) {
  if (b.spacecraft.contains("thrust_polynomial_mN")) throw sentence_error("the thruster's fits are given twice");
  if (b.seen.count("the thruster's table"))
    throw sentence_error("the thruster is given by a table already: state its table or its fits, not both");
  ++b.seen["the spacecraft's engine"];
  static const std::regex split =
      re(R"((.*?)\s*,?\s+and (?:its|the) (?:(?:thruster|engine)(?:'s|\xE2\x80\x99s)? )?mass flow(?: rate)? )"
         R"((?:is|fit is|is given by) (.*))");
  std::smatch parts;
  const std::string all = match[1].str();
  if (!std::regex_match(all, parts, split))
    throw sentence_error("the thruster's fits need its mass flow too (" + kSentence + ")");
  const Written thrust = split_unit(parts[1].str(), "thrust", "mN or N");
  if (!trimmed(thrust.rest).empty())
    throw sentence_error("cannot read '" + trimmed(thrust.rest) + "' after the thrust fit's unit " + thrust.unit);
  const Written flow = split_unit(parts[2].str(), "mass flow", "mg/s or kg/s");
  const auto factor = [](Dimension d, const std::string& unit, const std::string& what) {
    try {
      return unit_factor(d, unit);
    } catch (const sentence_error& e) {
      throw sentence_error("the " + what + " fit's " + e.what());
    }
  };
  const double to_mN = factor(Dimension::Force, thrust.unit, "thrust") * 1e3,
               to_mg_s = factor(Dimension::MassFlow, flow.unit, "mass flow") * 1e6;
  std::vector<double> t = coefficients(thrust.polynomial, "thrust"), f = coefficients(flow.polynomial, "mass flow");
  const Range range = read_range(flow.rest);
  double p_kW = 0;  // one P of the fits' unit in kW
  try {
    p_kW = unit_factor(Dimension::Power, range.p_unit) / 1e3;
  } catch (const sentence_error& e) {
    throw sentence_error(std::string("the fits' input power P: ") + e.what());
  }
  for (auto* c : {&t, &f})
    for (std::size_t k = 0; k < c->size(); ++k) (*c)[k] *= (c == &t ? to_mN : to_mg_s) / std::pow(p_kW, k);
  // Neither fit may be negative where the engine runs: from the range's bottom (else from no power)
  // up to its top.
  const double lo = range.bottom_W.value_or(0) / 1e3, hi = range.top_W / 1e3;
  for (int k = 0; k <= kRangeSamples; ++k) {
    const double p = lo + (hi - lo) * k / kRangeSamples;
    for (const auto& [c, what, unit] : {std::tuple{&t, "thrust", "mN"}, std::tuple{&f, "mass flow", "mg/s"}}) {
      const double v = value_at(*c, p);
      if (v < 0 || (k == kRangeSamples && !(v > 0)))
        throw sentence_error(std::string("the ") + what + " fit gives " + io::significant(v, 3) + " " + unit + " at " +
                             io::significant(p, 3) + " kW, inside its power range" +
                             (range.bottom_W ? ""
                                             : " (from no power: state the range's bottom, below which the engine is "
                                               "off, 'between 0.5 and 2.6 kW')"));
    }
    // The jet power T^2 / (2 mdot) cannot exceed the input power: where the engine surely runs (over a
    // stated range, else at its top), which catches fits read in the wrong units.
    if (k < kRangeSamples && !range.bottom_W) continue;
    const double thrust_N = value_at(t, p) * 1e-3, flow_kg_s = value_at(f, p) * 1e-6;
    const double efficiency = flow_kg_s > 0 ? thrust_N * thrust_N / (2 * flow_kg_s) / (p * 1e3) : 0;
    if (efficiency > 1)
      throw sentence_error(
          "the fits give a jet power T^2/(2 mdot) of " + io::significant(efficiency * p * 1e3, 3) +
          " W at an input power of " + io::significant(p, 3) + " kW, " + io::significant(efficiency, 3) +
          " times what the engine takes: check the fits' units (thrust in " + thrust.unit + ", mass flow in " +
          flow.unit + ", P in " + range.p_unit +
          (range.p_unit_stated ? "" : ", the unit of the range's top: say 'with P its input power in kW' otherwise") +
          ")");
  }
  if (b.spacecraft.contains("max_engine_power_W"))
    throw sentence_error("the engine's maximum input power is given twice (" +
                         io::short_number(b.spacecraft["max_engine_power_W"].get<double>()) + " and " +
                         io::short_number(range.top_W) + "): the top of the fits' power range is the engine's maximum");
  b.spacecraft["thrust_polynomial_mN"] = t;
  b.spacecraft["mass_flow_polynomial_mg_s"] = f;
  b.spacecraft["max_engine_power_W"] = range.top_W;
  if (range.bottom_W) b.spacecraft["min_engine_power_W"] = *range.bottom_W;
}

}  // namespace

std::vector<Form> thruster_fits() {
  const std::string sep =
      "\nThe spacecraft is solar-electric: its arrays give 10 kW at 1 AU and an initial mass of 1000 kg.";
  const std::string fits =
      "The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, with P its input "
      "power in kW up to 7 kW.";
  return {
      {"a thruster given by fits",
       78,
       R"((?:The|Its) (?:(?:spacecraft(?:'s|\xE2\x80\x99s) )?(?:thruster|engine)(?:'s|\xE2\x80\x99s)? )?thrust )"
       R"((?:is|fit is|is given by) (?=.*[^A-Za-z]P(?![A-Za-z]))(.+))",
       read,
       {{fits + sep, "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "max_engine_power_W": 7000, "thrust_polynomial_mN": [20, 30],
              "mass_flow_polynomial_mg_s": [1, 0.6], "initial_mass_kg": 1000}})~"},
        // a linear fit of an NSTAR-like engine over its throttle range, off below 0.5 kW
        {"The thruster's thrust is -1.9137 + 36.242 P mN and its mass flow is 0.47556 + 0.90209 P mg/s for an input "
         "power P between 0.5 and 2.6 kW." +
             sep,
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "min_engine_power_W": 500, "max_engine_power_W": 2600,
              "thrust_polynomial_mN": [-1.9137, 36.242], "mass_flow_polynomial_mg_s": [0.47556, 0.90209],
              "initial_mass_kg": 1000}})~"},
        {"The engine's thrust is 1.5e-3 P^4 - 0.0012 P\xC2\xB3 + 2.5 P**2 + 30*P + 10 mN and its mass flow is 0.9P + "
         "0.5 - 0.01 P\xC2\xB2 + P^3 mg/s, from 500 W to 2.6 kW." +
             sep,
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "min_engine_power_W": 500, "max_engine_power_W": 2600,
              "thrust_polynomial_mN": [10, 30, 2.5, -0.0012, 0.0015],
              "mass_flow_polynomial_mg_s": [0.5, 0.9, -0.01, 1], "initial_mass_kg": 1000}})~"},
        // in N and kg/s with P in W: converted to mN and mg/s with P in kW
        {"The thruster's thrust is (0.02 + 3e-5 P) N and its mass flow is 1e-6 + 6e-10 P kg/s, where P is its input "
         "power in W, between 500 W and 7 kW." +
             sep,
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "min_engine_power_W": 500, "max_engine_power_W": 7000,
              "thrust_polynomial_mN": [20, 30], "mass_flow_polynomial_mg_s": [1, 0.6], "initial_mass_kg": 1000}})~"},
        {"Its thrust is 61.1829727786757 P mN and its mass flow is 3.1194634650301425 P mg/s, with P [kW] up to 10 "
         "kW." +
             sep,
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "max_engine_power_W": 10000,
              "thrust_polynomial_mN": [0, 61.1829727786757], "mass_flow_polynomial_mg_s": [0, 3.1194634650301425],
              "initial_mass_kg": 1000}})~"},
        {"The thruster's thrust is 20 + 30 P + 1e-6 P^5 mN and its mass flow is 1 + 0.6 P mg/s, with P its input "
         "power in kW up to 7 kW." +
             sep,
         "sun -engine", R"~({"error": "the thrust fit has a term in P^5 ('+ 1e-6 P^5'): a fit goes up to P^4"})~"},
        {"The thruster's thrust is 20 + 30 P + 5P mN and its mass flow is 1 + 0.6 P mg/s, with P its input power in "
         "kW up to 7 kW." +
             sep,
         "sun -engine", R"~({"error": "the thrust fit has two terms in P^1 ('+ 30 P' and '+ 5P')"})~"},
        {"The thruster's thrust is 20 + 30 P + 0.5 P^-1 mN and its mass flow is 1 + 0.6 P mg/s, with P its input power "
         "in "
         "kW up to 7 kW." +
             sep,
         "sun -engine", R"~({"error": "cannot read '+ 0.5 P^-1' of the thrust fit: terms N P^k with k up to 4"})~"},
        {"The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, with P its input power in kW." +
             sep,
         "sun -engine", R"~({"error": "the thruster's fits need the top of their power range"})~"},
        {"The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s from 0.5 kW." + sep, "sun -engine",
         R"~({"error": "the thruster's fits need the top of their power range"})~"},
        {"The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s for an input power P between 2.6 "
         "and 0.5 kW." +
             sep,
         "sun -engine",
         R"~({"error": "the bottom of the fits' power range (2.6 kW) must be below its top (0.5 kW)"})~"},
        {"The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P sccm, with P its input power in kW up "
         "to 7 kW." +
             sep,
         "sun -engine", R"~({"error": "the mass flow fit's unit 'sccm' is not a mass flow unit"})~"},
        {"The thruster's thrust is 4.5 + 6.7 P lbf and its mass flow is 1 + 0.6 P mg/s, with P its input power in kW "
         "up to 7 kW." +
             sep,
         "sun -engine", R"~({"error": "the thrust fit's unit 'lbf' is not a force unit"})~"},
        {"The thruster's thrust is 20 + 30 P and its mass flow is 1 + 0.6 P mg/s, with P its input power in kW up to "
         "7 kW." +
             sep,
         "sun -engine", R"~({"error": "the thrust fit '20 + 30 P' needs its unit (mN or N)"})~"},
        {"The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, with P its input power in kN up "
         "to 7 kW." +
             sep,
         "sun -engine", R"~({"error": "the fits' input power P: unit 'kN' is not a power unit"})~"},
        {"The thruster's thrust is 20 + 30 P mN, with P its input power in kW up to 7 kW." + sep, "sun -engine",
         R"~({"error": "the thruster's fits need its mass flow too"})~"},
        // the NSTAR-like fit is negative below 53 W: without a bottom the engine would run there
        {"The thruster's thrust is -1.9137 + 36.242 P mN and its mass flow is 0.47556 + 0.90209 P mg/s for an input "
         "power P up to 2.6 kW." +
             sep,
         "sun -engine",
         R"~({"error": "the thrust fit gives -1.91 mN at 0 kW, inside its power range (from no power: state the range's bottom"})~"},
        // P read in W (the unit of the range's top) where the coefficients are per kW
        {"The thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, for P between 500 and 7000 W." +
             sep,
         "sun -engine",
         R"~({"error": "the fits give a jet power T^2/(2 mdot) of 3.75e+05 W at an input power of 0.5 kW, 750 times what the engine takes: check the fits' units (thrust in mN, mass flow in mg/s, P in W, the unit of the range's top"})~"},
        {fits + "\n" + fits + sep, "sun -engine", R"~({"error": "the thruster's fits are given twice"})~"},
        {fits + "\nThe spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the engine takes at most 5 kW and "
                "an initial mass of 1000 kg.",
         "sun -engine", R"~({"error": "the engine's maximum input power is given twice (7000 and 5000)"})~"},
        {fits + "\nThe spacecraft has an initial mass of 1000 kg.", "sun -engine",
         R"~({"error": "the problem text never states the solar arrays that power the thruster's fits"})~"},
        {fits + "\nThe spacecraft is solar-electric: its arrays give 10 kW at 1 AU, an efficiency of 0.6 and an "
                "initial mass of 1000 kg.",
         "sun -engine",
         R"~({"error": "the spacecraft's engine_efficiency (0.6) is stated, but the thruster's fits give its performance"})~"},
        {fits + sep + "\nThe spacecraft has a specific impulse of 3000 s.", "sun -engine",
         R"~({"error": "the spacecraft's isp_s (3000) is stated, but the thruster's fits give its performance"})~"},
        {fits + "\nThe spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the engine gives at most 250 mN "
                "and an initial mass of 1000 kg.",
         "sun -engine",
         R"~({"error": "the spacecraft's max_thrust_N (0.25) is stated, but the thruster's fits give its performance"})~"}}}};
}

}  // namespace helios::spec::grammar::forms
