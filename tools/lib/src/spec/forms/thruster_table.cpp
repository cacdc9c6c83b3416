// "The thruster's table gives its thrust and mass flow at these input powers:" and the table below it
// (tables.cpp reads its lines): a solar-electric thruster given by its throttle table, as flown
// missions give NSTAR and NEXT, each row its thrust and mass flow at an input power. The header names
// the columns in any order, each with its unit ("| input power [kW] | thrust [mN] | mass flow [mg/s]
// |"; the rule line optional); the rows go by increasing input power, at least 3 of them. The table
// is stored in SI as spacecraft.thruster_table, rows {input_power_W, thrust_N, mass_flow_kg_s} as
// written: its lowest and highest powers are the engine's range, and the derivation fits it. The
// arrays that power it are the solar-electric sentence's (forms/solar_electric.cpp), which then
// states no efficiency, specific impulse, maximum thrust or maximum input power (parse.cpp's
// check_complete); the thruster's fits (forms/thruster_fits.cpp) are the other way to give it.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar {
namespace {

constexpr std::size_t kMinRows = 3;

// A column of the thruster's table: the field it holds, its name in errors, its dimension and an
// example of its header cell.
struct Column {
  const char* field;
  const char* label;
  Dimension dim;
  const char* example;
};

const std::vector<Column>& columns() {
  static const std::vector<Column> c = {{"power", "input power", Dimension::Power, "input power [kW]"},
                                        {"thrust", "thrust", Dimension::Force, "thrust [mN]"},
                                        {"flow", "mass flow", Dimension::MassFlow, "mass flow [mg/s]"}};
  return c;
}

const Column& column(const std::string& field) {
  for (const Column& c : columns())
    if (field == c.field) return c;
  throw std::logic_error("no column " + field);
}

// The field a header's name stands for ("P", "input power", "T", "mdot", "flow rate", ...), or "".
std::string field_of(const std::string& name) {
  static const std::vector<std::pair<std::regex, std::string>> names = {
      {re(R"((?:(?:engine |thruster )?input |engine |thruster )?power(?: P(?:_?in)?)?|P(?:_?in)?)"), "power"},
      {re(R"(thrust(?: T)?|T)"), "thrust"},
      {re(R"((?:(?:propellant )?mass flow(?: rate)?|flow(?: rate)?|mdot|m_dot|\xE1\xB9\x81)(?: (?:mdot|\xE1\xB9\x81))?)"),
       "flow"}};
  for (const auto& [pattern, field] : names)
    if (std::regex_match(name, pattern)) return field;
  return "";
}

const std::regex& number_cell() {
  static const std::regex n("\\s*" + kNum + "\\s*");
  return n;
}

// A cell in its column's unit, in SI. A unit that is a power of ten of the SI one (mN, kW, mg/s)
// shifts the number's decimal exponent, so that 52 mN is 0.052 N as written, not 0.052000000000000005
// N as 52 times 0.001 rounds.
double in_si(const std::string& cell, double factor) {
  const double decades = std::log10(factor);
  const long k = std::lround(decades);
  if (std::fabs(decades - static_cast<double>(k)) > 1e-9) return number(cell) * factor;
  std::string digits = trimmed(cell);
  long exponent = k;
  if (const auto e = digits.find_first_of("eE"); e != std::string::npos) {
    try {
      exponent += std::stol(digits.substr(e + 1));
    } catch (const std::out_of_range&) {
      throw sentence_error("the number " + trimmed(cell) + " is outside the range of a double");
    }
    digits.erase(e);
  }
  return number(digits + "e" + std::to_string(exponent));
}

void read(Builder& b, const std::smatch& m) {
  // Its sentence ends at the table's first line: words after its colon are the next sentence's,
  // run into it for want of the table.
  if (const std::string after = trimmed(m[1].str()); !after.empty())
    throw sentence_error(std::string("the table's header must follow on the next line (") + kThrusterTableHeader +
                         "), not '" + after + "'");
  if (b.spacecraft.contains("thrust_polynomial_mN"))
    throw sentence_error("the thruster is given by fits already: state its fits or its table, not both");
  b.once("the thruster's table");
  ++b.seen["the spacecraft's engine"];
  b.table_intro = b.here;
  b.table_kind = TableKind::Thruster;
  b.thruster_table_where = b.here;
  b.thruster_rows = json::array();
}

}  // namespace

TableColumns thruster_table_header(const std::vector<std::string>& cells) {
  const std::string layout =
      std::string("the header reads e.g. ") + kThrusterTableHeader +
      " (columns in any order: the input power, 'P' or 'power', in W or kW; the thrust, 'T', in "
      "N or mN; the mass flow, 'mdot' or 'flow rate', in mg/s, g/s or kg/s; units in [ ] or ( ))";
  TableColumns t;
  t.kind = TableKind::Thruster;
  static const std::regex rule(R"(\s*:?-+:?\s*)");
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (std::regex_match(cells[k], number_cell()) || std::regex_match(cells[k], rule))
      throw sentence_error("the thruster's table starts with its header line: " + layout);
    const auto [name, unit] = name_and_unit(cells[k]);
    const std::string field = field_of(name);
    if (field.empty()) throw sentence_error("column " + std::to_string(k + 1) + " is '" + cells[k] + "': " + layout);
    const Column& c = column(field);
    for (std::size_t j = 0; j < t.fields.size(); ++j)
      if (t.fields[j] == field)
        throw sentence_error("the header gives the " + std::string(c.label) + " twice (columns " +
                             std::to_string(j + 1) + " and " + std::to_string(k + 1) + "): " + layout);
    if (unit.empty())
      throw sentence_error("the " + std::string(c.label) + " column '" + cells[k] + "' needs its unit ('" + c.example +
                           "')");
    double factor = 0;
    try {
      factor = unit_factor(c.dim, unit);
    } catch (const sentence_error& e) {
      throw sentence_error("the " + std::string(c.label) + " column's " + e.what());
    }
    t.fields.push_back(field);
    t.factors.push_back(factor);
    t.units.push_back(unit);
  }
  std::string missing;
  for (const Column& c : columns())
    if (std::find(t.fields.begin(), t.fields.end(), c.field) == t.fields.end())
      missing += std::string(missing.empty() ? "" : " and ") + c.label;
  if (!missing.empty()) throw sentence_error("the header lacks the " + missing + ": " + layout);
  return t;
}

void thruster_table_row(Builder& b, const TableColumns& t, const std::vector<std::string>& cells) {
  std::map<std::string, double> si;            // by field, in W, N and kg/s
  std::map<std::string, std::string> written;  // by field, with its unit
  std::map<std::string, std::size_t> at;       // by field, its column
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (!std::regex_match(cells[k], number_cell()))
      throw sentence_error("cell " + std::to_string(k + 1) + " '" + cells[k] +
                           "' is not a number (a unit goes in the header)");
    const double v = in_si(cells[k], t.factors[k]);
    if (!std::isfinite(v)) throw sentence_error("cell " + std::to_string(k + 1) + " '" + cells[k] + "' is not finite");
    si[t.fields[k]] = v;
    written[t.fields[k]] = trimmed(cells[k]) + " " + t.units[k];
    at[t.fields[k]] = k;
  }
  const double p = si.at("power"), thrust = si.at("thrust"), flow = si.at("flow");
  if (!(p > 0)) throw sentence_error("the input power must be positive, got " + written.at("power"));
  if (!(thrust >= 0)) throw sentence_error("the thrust must not be negative, got " + written.at("thrust"));
  if (!(flow > 0)) throw sentence_error("the mass flow must be positive, got " + written.at("flow"));
  if (!b.thruster_rows.empty()) {
    const double before = b.thruster_rows.back()["input_power_W"].get<double>();
    if (!(p > before)) {
      const std::size_t k = at.at("power");
      throw sentence_error("the input power " + written.at("power") + " is not above the row before's (" +
                           io::short_number(before / t.factors[k]) + " " + t.units[k] +
                           "): the rows go by increasing input power");
    }
  }
  // The jet power T^2 / (2 mdot) cannot exceed the input power, which catches a column in the wrong
  // unit (as the fits' check does, forms/thruster_fits.cpp).
  const double jet = thrust * thrust / (2 * flow);
  if (jet > p)
    throw sentence_error("the row gives a jet power T^2/(2 mdot) of " + io::significant(jet, 3) +
                         " W at an input power of " + written.at("power") + ", " + io::significant(jet / p, 3) +
                         " times what the engine takes: check the table's units (input power in " +
                         t.units[at.at("power")] + ", thrust in " + t.units[at.at("thrust")] + ", mass flow in " +
                         t.units[at.at("flow")] + ")");
  b.thruster_rows.push_back(json{{"input_power_W", p}, {"thrust_N", thrust}, {"mass_flow_kg_s", flow}});
}

void finish_thruster_table(Builder& b) {
  const std::size_t n = b.thruster_rows.size();
  if (n < kMinRows)
    b.fail(b.thruster_table_where,
           "the thruster's table has " +
               (n == 0 ? std::string("no rows") : std::to_string(n) + " row" + (n == 1 ? "" : "s")) +
               ": it needs at least " + std::to_string(kMinRows) +
               ", from the engine's lowest input power to its highest");
  b.spacecraft["thruster_table"] = b.thruster_rows;
}

namespace forms {

std::vector<Form> thruster_table() {
  const std::string sep =
      "\nThe spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the bus uses 0.3 kW and an initial mass of "
      "150 kg.";
  const std::string intro = "The thruster's table gives its thrust and mass flow at these input powers:\n";
  const std::string header = "| input power [kW] | thrust [mN] | mass flow [mg/s] |\n|---|---|---|\n";
  const std::string rows =
      "| 0.525 | 19.0 | 0.91 |\n| 1.0 | 35.0 | 1.32 |\n| 1.5 | 52.0 | 1.73 |\n| 2.0 | 68.0 | 2.13 |\n"
      "| 2.567 | 92.7 | 2.89 |";
  const std::string table = intro + header + rows;
  // the NSTAR-like table's rows in SI
  const std::string si_rows =
      R"~([{"input_power_W": 525, "thrust_N": 0.019, "mass_flow_kg_s": 9.1e-7},
           {"input_power_W": 1000, "thrust_N": 0.035, "mass_flow_kg_s": 1.32e-6},
           {"input_power_W": 1500, "thrust_N": 0.052, "mass_flow_kg_s": 1.73e-6},
           {"input_power_W": 2000, "thrust_N": 0.068, "mass_flow_kg_s": 2.13e-6},
           {"input_power_W": 2567, "thrust_N": 0.0927, "mass_flow_kg_s": 2.89e-6}])~";
  const std::string three =
      R"~([{"input_power_W": 500, "thrust_N": 0.02, "mass_flow_kg_s": 1e-6},
           {"input_power_W": 1500, "thrust_N": 0.05, "mass_flow_kg_s": 1.7e-6},
           {"input_power_W": 2500, "thrust_N": 0.09, "mass_flow_kg_s": 2.9e-6}])~";
  const std::string performance =
      "the thruster's table gives its performance (its thrust and mass flow at each input power";
  return {
      {"a thruster's table",
       77,
       R"((?:(?:The |Its )(?:spacecraft(?:'s|\xE2\x80\x99s) )?(?:thruster|engine)(?:)"
       R"((?:'s|\xE2\x80\x99s) (?:throttle |throttling |performance )?table(?:\s+(?:gives|lists|states|holds|shows|)"
       R"(is|reads|of|with|for)\b.*?)?|)"
       R"( (?:is given by|is described by|follows|has|uses) (?:this|the following|a|its) )"
       R"((?:throttle |throttling |performance )?table(?:\s+(?:of|with|giving|listing|for)\b.*?)?)|)"
       R"((?:thruster|engine) (?:throttle |throttling |performance )?table)\s*(?::\s*(.*))?)",
       read,
       {{table + sep, "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 5000, "bus_power_W": 300, "initial_mass_kg": 150,
              "thruster_table": )~" +
             si_rows + "}}"},
        // in SI, without the rule line
        {"The thruster's throttle table:\n| P (W) | T (N) | mdot (kg/s) |\n| 500 | 0.02 | 1e-6 |\n"
         "| 1500 | 0.05 | 1.7e-6 |\n| 2500 | 0.09 | 2.9e-6 |" +
             sep,
         "sun -engine", R"~({"/spacecraft/thruster_table": )~" + three + "}"},
        // the columns in another order, the mass flow in g/s
        {"The thruster is given by this table of its input power, thrust and mass flow:\n"
         "| thrust [mN] | mass flow rate [g/s] | power [kW] |\n|:---|:---:|---:|\n| 20 | 0.001 | 0.5 |\n"
         "| 50 | 0.0017 | 1.5 |\n| 90 | 0.0029 | 2.5 |" +
             sep,
         "sun -engine", R"~({"/spacecraft/thruster_table": )~" + three + "}"},
        {"The engine's throttle table lists its thrust and flow rate at each input power:\n"
         "| Input power [W] | Flow rate [mg/s] | Thrust [mN] |\n|---|---|---|\n| 500 | 1 | 20 |\n| 1500 | 1.7 | 50 |\n"
         "| 2500 | 2.9 | 90 |\n"
         "The spacecraft is solar-electric: its arrays give 5 kW at 1 AU.\nThe spacecraft has an initial mass of 150 "
         "kg.",
         "sun -engine",
         R"~({"/spacecraft": {"array_power_1AU_W": 5000, "initial_mass_kg": 150, "thruster_table": )~" + three + "}}"},
        {table + "\nThe spacecraft has an initial mass of 150 kg.", "sun -engine",
         R"~({"error": "the problem text never states the solar arrays that power the thruster's table"})~"},
        {table + sep +
             "\nThe thruster's thrust is 20 + 30 P mN and its mass flow is 1 + 0.6 P mg/s, with P its input power in "
             "kW up to 2.6 kW.",
         "sun -engine",
         R"~({"error": "the thruster is given by a table already: state its table or its fits, not both"})~"},
        {table + "\n" + table + sep, "sun -engine", R"~({"error": "the thruster's table is given twice"})~"},
        {intro + header + "| 0.5 | 20 | 1 |\n| 2.5 | 90 | 2.9 |" + sep, "sun -engine",
         R"~({"error": "the thruster's table has 2 rows: it needs at least 3"})~"},
        {intro + "| input power [kW] | thrust [mN] |\n| 0.5 | 20 |" + sep, "sun -engine",
         R"~({"error": "the header lacks the mass flow: the header reads e.g. | input power [kW] | thrust [mN] | mass flow [mg/s] |"})~"},
        {intro + "| input power [kW] | thrust [mN] | voltage [V] | mass flow [mg/s] |\n| 0.5 | 20 | 1100 | 1 |" + sep,
         "sun -engine", R"~({"error": "column 3 is 'voltage [V]': the header reads e.g."})~"},
        {intro + "| P [kW] | thrust [mN] | T [N] | mass flow [mg/s] |" + sep, "sun -engine",
         R"~({"error": "the header gives the thrust twice (columns 2 and 3)"})~"},
        {intro + "| P | thrust [mN] | mass flow [mg/s] |" + sep, "sun -engine",
         R"~({"error": "the input power column 'P' needs its unit ('input power [kW]')"})~"},
        {intro + "| input power [kW] | thrust [lbf] | mass flow [mg/s] |" + sep, "sun -engine",
         R"~({"error": "the thrust column's unit 'lbf' is not a force unit"})~"},
        {intro + header + "| 0.5 | 20 | 1 |\n| 1.0 | 35 mN | 1.32 |" + sep, "sun -engine",
         R"~({"error": "table row \"| 1.0 | 35 mN | 1.32 |\": cell 2 '35 mN' is not a number"})~"},
        {intro + header + "| 0 | 0 | 0.5 |" + sep, "sun -engine",
         R"~({"error": "the input power must be positive, got 0 kW"})~"},
        {intro + header + "| 0.5 | -1 | 0.5 |" + sep, "sun -engine",
         R"~({"error": "the thrust must not be negative, got -1 mN"})~"},
        {intro + header + "| 0.5 | 0 | 0 |" + sep, "sun -engine",
         R"~({"error": "the mass flow must be positive, got 0 mg/s"})~"},
        {intro + header + "| 0.5 | 20 | 1 |\n| 2.0 | 68 | 2.13 |\n| 1.5 | 52 | 1.73 |" + sep, "sun -engine",
         R"~({"error": "table row \"| 1.5 | 52 | 1.73 |\": the input power 1.5 kW is not above the row before's (2 kW): the rows go by increasing input power"})~"},
        // the thrust written in mN under a header in N
        {intro + "| input power [kW] | thrust [N] | mass flow [mg/s] |\n| 0.525 | 19.0 | 0.91 |" + sep, "sun -engine",
         R"~({"error": "the row gives a jet power T^2/(2 mdot) of 1.98e+08 W at an input power of 0.525 kW, 3.78e+05 times what the engine takes: check the table's units (input power in kW, thrust in N, mass flow in mg/s)"})~"},
        {"The thruster's throttle table:" + sep, "sun -engine",
         R"~({"error": "the table's header must follow on the next line (| input power [kW] | thrust [mN] | mass flow [mg/s] |), not 'The spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the bus uses 0.3 kW and an initial mass of 150 kg'"})~"},
        {"The thruster's throttle table." + sep, "sun -engine",
         R"~({"error": "it follows a sentence announcing the thruster's table, so it must be the table's header | input power [kW] | thrust [mN] | mass flow [mg/s] |"})~"},
        {"The spacecraft's thruster has this throttle table:", "sun -engine",
         R"~({"error": "no table follows it (its header reads | input power [kW] | thrust [mN] | mass flow [mg/s] |)"})~"},
        {table +
             "\nThe spacecraft is solar-electric: its arrays give 5 kW at 1 AU, an efficiency of 0.6 and an initial "
             "mass of 150 kg.",
         "sun -engine",
         R"~({"error": "the spacecraft's engine_efficiency (0.6) is stated, but )~" + performance + "\"}"},
        {table +
             "\nThe spacecraft is solar-electric: its arrays give 5 kW at 1 AU, the engine takes at most 2.6 kW and "
             "an initial mass of 150 kg.",
         "sun -engine",
         R"~({"error": "the spacecraft's max_engine_power_W (2600) is stated, but )~" + performance + "\"}"}}}};
}

}  // namespace forms
}  // namespace helios::spec::grammar
