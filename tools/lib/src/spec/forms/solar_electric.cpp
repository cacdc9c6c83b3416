// "The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the bus uses 0.5 kW, the engine
// takes at most 5 kW with an efficiency of 0.6 and a specific impulse of 3000 s.": a solar-electric
// engine about the Sun (pmp/terms/solar_electric.cpp): the arrays' power at 1 AU
// (array_power_1AU_W), optionally the bus's share (bus_power_W) and the engine's maximum input power
// (max_engine_power_W) or its maximum thrust (max_thrust_N, the cap a data sheet states: the input
// power at which the engine gives it), its efficiency (engine_efficiency) and specific impulse;
// clauses in any order, an initial mass among them too. The thrust follows from the power: a thrust
// is only ever its cap. A thruster given by fits of its thrust and mass flow to its input power
// (forms/thruster_fits.cpp) takes the place of the efficiency and specific impulse: the text states
// one or the other (parse.cpp's check_complete).
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

const std::string kExpected =
    "expected 'its arrays give Q at 1 AU', 'the bus uses Q', 'the engine takes at most Q', 'the engine gives at most "
    "Q' (a thrust), 'an efficiency of N' or 'a specific impulse of Q'";

// The quantity of clause m's group idx (number) and idx + 1 (unit) in SI (W for a power, N for a
// force), positive.
double positive(const std::smatch& m, std::size_t idx, Dimension dim, const std::string& what) {
  const double v = quantity(m, idx, dim);
  if (!(v > 0)) throw sentence_error(what + " must be positive, got " + m[idx].str() + " " + m[idx + 1].str());
  return v;
}

// Sets the engine's `key` to `value`, refusing a second value of it (a clause or a sentence that
// states it again).
void set_once(Builder& b, const char* key, double value, const std::string& what) {
  if (b.spacecraft.contains(key))
    throw sentence_error(what + " is given twice (" + io::short_number(b.spacecraft[key].get<double>()) + " and " +
                         io::short_number(value) + ")");
  b.spacecraft[key] = value;
}

void read(Builder& b, const std::smatch& match) {
  b.once("the solar-electric engine");
  ++b.seen["the spacecraft's engine"];
  const std::string list = match[1].str();
  static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|;\s*|\s+and\s+|\s+with\s+)\s*)");
  static const std::regex array =
      re(R"((?:(?:its|the) )?(?:solar )?(?:arrays?|panels?) (?:(?:that|which) )?(?:give|gives|giving|provide|)"
         R"(provides|providing|deliver|delivers|delivering|produce|produces|producing|generate|generates|)"
         R"(generating|supply|supplies|supplying|of) )" +
         kQuantity + R"( at 1 AU)");
  // "a solar array power of 12 kW at 1 AU", "15 kW of array power at 1 AU"
  static const std::regex array_power =
      re(R"((?:an? )?(?:solar |solar array |array )power of )" + kQuantity + R"( at 1 AU|)" + kQuantity +
         R"( of (?:solar |solar array |array )power at 1 AU)");
  static const std::regex bus = re(R"((?:(?:the|its) )?bus (?:uses|takes|needs|consumes|draws) )" + kQuantity + "|" +
                                   R"((?:an? )?bus (?:power|load|margin) of )" + kQuantity);
  static const std::regex cap =
      re(R"((?:(?:the|its) )?(?:engine|thruster) (?:takes|uses|draws|accepts|consumes) (?:at most|up to) )" +
         kQuantity + "|" + R"((?:an? )?maximum (?:engine |input )?power of )" + kQuantity);
  // "the engine gives at most 0.25 N", "a maximum thrust of 250 mN": the cap stated by its thrust
  static const std::regex thrust_cap =
      re(R"((?:(?:the|its) )?(?:engine|thruster) (?:gives|delivers|produces|provides|gives a thrust of) )"
         R"((?:at most|up to) )" +
         kQuantity + "|" + R"((?:an? |its )?(?:maximum|most) thrust (?:of|is) )" + kQuantity + "|" +
         R"((?:an? )?thrust of at most )" + kQuantity);
  static const std::regex efficiency = re(
      R"((?:an? |the |its )?(?:engine(?:'s)? |thruster(?:'s)? |total )?efficiency (?:of|is) ()" + kNum + R"()\s*(%)?)");
  static const std::regex isp = re(R"((?:an? |the |its )?(?:specific impulse|Isp)(?: of| is)? )" + kQuantity);
  static const std::regex mass = re(R"((?:an? )?initial mass of )" + kQuantity);
  const std::vector<std::string> parts(std::sregex_token_iterator(list.begin(), list.end(), split, -1), {});
  for (const std::string& part : parts) {
    std::smatch m;
    if (part.empty()) continue;
    if (std::regex_match(part, m, array) || std::regex_match(part, m, array_power)) {
      set_once(b, "array_power_1AU_W", positive(m, m[1].matched ? 1 : 3, Dimension::Power, "the arrays' power at 1 AU"),
               "the arrays' power at 1 AU");
    } else if (std::regex_match(part, m, bus)) {
      const std::size_t at = m[1].matched ? 1 : 3;
      const double w = quantity(m, at, Dimension::Power);
      if (!(w >= 0))
        throw sentence_error("the bus power must not be negative, got " + m[at].str() + " " + m[at + 1].str());
      set_once(b, "bus_power_W", w, "the bus power");
    } else if (std::regex_match(part, m, cap)) {
      set_once(b, "max_engine_power_W",
               positive(m, m[1].matched ? 1 : 3, Dimension::Power, "the engine's maximum input power"),
               "the engine's maximum input power");
    } else if (std::regex_match(part, m, thrust_cap)) {
      set_once(b, "max_thrust_N",
               positive(m,
                        m[1].matched   ? 1
                        : m[3].matched ? 3
                                       : 5,
                        Dimension::Force, "the engine's maximum thrust"),
               "the engine's maximum thrust");
    } else if (std::regex_match(part, m, efficiency)) {
      const double eta = number(m[1].str()) / (m[2].matched ? 100.0 : 1.0);
      if (!(eta > 0 && eta <= 1))
        throw sentence_error("the engine efficiency must be in (0, 1] (or (0, 100] %), got " + m[1].str() +
                             (m[2].matched ? " %" : ""));
      set_once(b, "engine_efficiency", eta, "the engine efficiency");
    } else if (std::regex_match(part, m, isp) || std::regex_match(part, m, mass)) {
      const bool is_isp = std::regex_match(part, isp);
      const detail::Field field = is_isp ? detail::Field::Isp : detail::Field::InitialMass;
      b.once(field);
      const double value = quantity(m, 1, *detail::fact_info(field).dim);
      b.check_value(field, value, m[1].str() + " " + m[2].str());
      b.spacecraft[detail::spec_key(field)] = value;
    } else {
      throw sentence_error("cannot read '" + part + "' of the solar-electric engine: " + kExpected);
    }
  }
  if (!b.spacecraft.contains("array_power_1AU_W"))
    throw sentence_error("a solar-electric engine needs its arrays' power at 1 AU ('its arrays give 10 kW at 1 AU')");
  const double p0 = b.spacecraft["array_power_1AU_W"].get<double>();
  if (b.spacecraft.value("bus_power_W", 0.0) >= p0)
    throw sentence_error("the bus power " + io::short_number(b.spacecraft["bus_power_W"].get<double>()) +
                         " W takes all the arrays give at 1 AU (" + io::short_number(p0) + " W)");
}

}  // namespace

std::vector<Form> solar_electric() {
  return {
      {"a solar-electric engine",
       79,
       R"((?:The spacecraft (?:is|has|uses|flies)|The (?:spacecraft's )?(?:engine|propulsion|thruster) is) (?:an? )?)"
       R"(solar[- ]electric(?: propulsion| engine| spacecraft| propulsion system)?(?:\s*[:;,]\s*|\s+with\s+)(.+))",
       read,
       {{"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the bus uses 0.5 kW, the engine takes at "
         "most 5 kW with an efficiency of 0.6 and a specific impulse of 3000 s and an initial mass of 1000 kg.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "bus_power_W": 500, "max_engine_power_W": 5000,
              "engine_efficiency": 0.6, "isp_s": 3000, "initial_mass_kg": 1000}})~"},
        {"The spacecraft uses solar electric propulsion with a solar array power of 12 kW at 1 AU, an efficiency of "
         "65 %, an Isp of 2500 s and an initial mass of 1 t.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 12000, "engine_efficiency": 0.65, "isp_s": 2500,
              "initial_mass_kg": 1000}})~"},
        {"The spacecraft uses solar electric propulsion: 15 kW of array power at 1 AU, an engine efficiency of 65 %, "
         "a specific impulse of 3100 s, a maximum input power of 7 kW and an initial mass of 800 kg.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 15000, "max_engine_power_W": 7000, "engine_efficiency": 0.65,
              "isp_s": 3100, "initial_mass_kg": 800}})~"},
        {"The spacecraft is solar-electric with arrays giving 12 kW at 1 AU, a bus load of 300 W, an efficiency of "
         "0.55, an Isp of 2500 s and an initial mass of 1 t.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 12000, "bus_power_W": 300, "engine_efficiency": 0.55,
              "isp_s": 2500, "initial_mass_kg": 1000}})~"},
        {"The engine is solar electric; the solar arrays produce 10 kW at 1 AU and the thruster's efficiency is 0.6 "
         "with Isp 3000 s and an initial mass of 500 kg.",
         "sun -engine", R"~({"/spacecraft": {"array_power_1AU_W": 10000, "engine_efficiency": 0.6, "isp_s": 3000,
              "initial_mass_kg": 500}})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the engine gives at most 250 mN with an "
         "efficiency of 0.6 and a specific impulse of 3000 s and an initial mass of 1000 kg.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 10000, "max_thrust_N": 0.25, "engine_efficiency": 0.6,
              "isp_s": 3000, "initial_mass_kg": 1000}})~"},
        {"The spacecraft uses solar electric propulsion: 20 kW of array power at 1 AU, a maximum thrust of 0.4 N, a "
         "maximum input power of 8 kW, an efficiency of 60 %, an Isp of 2000 s and an initial mass of 900 kg.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 20000, "max_thrust_N": 0.4, "max_engine_power_W": 8000,
              "engine_efficiency": 0.6, "isp_s": 2000, "initial_mass_kg": 900}})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the engine gives at most 0 N, an "
         "efficiency of 0.6 and a specific impulse of 3000 s.",
         "sun -engine ", R"~({"error": "the engine's maximum thrust must be positive, got 0 N"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, an efficiency of 1.5 and a specific "
         "impulse of 3000 s.",
         "sun -engine ", R"~({"error": "the engine efficiency must be in (0, 1] (or (0, 100] %), got 1.5"})~"},
        {"The spacecraft is solar-electric: its arrays give -10 kW at 1 AU, an efficiency of 0.6 and a specific "
         "impulse of 3000 s.",
         "sun -engine ", R"~({"error": "the arrays' power at 1 AU must be positive, got -10 kW"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kN at 1 AU, an efficiency of 0.6 and a specific "
         "impulse of 3000 s.",
         "sun -engine ", R"~({"error": "kN"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the bus uses 12 kW, an efficiency of 0.6 "
         "and a specific impulse of 3000 s.",
         "sun -engine ", R"~({"error": "takes all the arrays give at 1 AU"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, the engine takes at most 5 kW, a maximum "
         "input power of 6 kW, an efficiency of 0.6 and a specific impulse of 3000 s.",
         "sun -engine ", R"~({"error": "the engine's maximum input power is given twice (5000 and 6000)"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, a tank of 3 kg and an efficiency of 0.6.",
         "sun -engine ", R"~({"error": "cannot read 'a tank of 3 kg' of the solar-electric engine"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU and a specific impulse of 3000 s and an "
         "initial mass of 1000 kg.",
         "sun -engine", R"~({"error": "needs its efficiency"})~"},
        // S15's engine given by fits instead: its thrust and mass flow proportional to its input power
        {"The spacecraft is solar-electric: its arrays give 20 kW at 1 AU, the bus uses 0.5 kW and an initial mass "
         "of 1000 kg.\nThe thruster's thrust is 61.1829727786757 P mN and its mass flow is 3.1194634650301425 P mg/s, "
         "with P its input power in kW up to 10 kW.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 20000, "bus_power_W": 500, "max_engine_power_W": 10000,
              "thrust_polynomial_mN": [0, 61.1829727786757], "mass_flow_polynomial_mg_s": [0, 3.1194634650301425],
              "initial_mass_kg": 1000}})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU and an initial mass of 1000 kg.",
         "sun -engine", R"~({"error": "needs its efficiency and specific impulse"})~"},
        {"The spacecraft is solar-electric: its arrays give 10 kW at 1 AU, an efficiency of 0.6 and a specific "
         "impulse of 3000 s and an initial mass of 1000 kg.",
         "earth -engine", R"~({"error": "needs the Sun as the central body"})~"}}}};
}

}  // namespace helios::spec::grammar::forms
