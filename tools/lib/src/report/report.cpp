#include "helios/report/report.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "helios/astro/calendar.hpp"
#include "helios/derivation/reader.hpp"
#include "helios/symbolic/latex.hpp"

namespace helios::report {

namespace {

using io::json;

// Width of a display line of LaTeX before a sum is broken (about a page's width rendered).
constexpr std::size_t kLineWidth = 150;

// A code span of artifact text: pandoc typesets its characters verbatim (no math, no TeX, no
// HTML); a backtick becomes a quote, a cell separator is escaped and a control character a space.
std::string code(const std::string& text) {
  std::string out = "`";
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += ' ';
    else
      out += c == '`' ? std::string("'") : c == '|' ? std::string("\\|") : std::string(1, c);
  }
  return out + "`";
}

// A value of an artifact as report text: numbers formatted, strings escaped, booleans as words.
std::string value(const json& v) {
  if (v.is_string()) return markdown_text(v.get<std::string>());
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return io::short_number(v.get<double>());
  if (v.is_boolean()) return v.get<bool>() ? "yes" : "no";
  if (v.is_null()) return "";
  if (v.is_array() && std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_primitive(); })) {
    std::string out = "[";
    for (const auto& x : v) out += (out.size() > 1 ? ", " : "") + value(x);
    return out + "]";
  }
  return markdown_text(v.dump());
}

// A key the schemas type as a number: its value when it is one, blank when absent, and a marked
// "not a number" otherwise (a hand-edited or hostile artifact), never the text it holds.
std::string numeric(const json& v) {
  if (v.is_null()) return "";
  if (v.is_number() || v.is_boolean()) return value(v);
  if (v.is_array() && std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_number(); })) return value(v);
  return "*(not a number)*";
}

// The unit a key of the spec names by its suffix (thrust_N, mu_km3_s2, tof_days).
std::string unit_of_key(const std::string& key) {
  static const std::vector<std::pair<std::string, std::string>> suffixes = {{"_km3_s2", "km^3/s^2"},
                                                                            {"_km_s", "km/s"},
                                                                            {"_m_s2", "m/s^2"},
                                                                            {"_mm_s2", "mm/s^2"},
                                                                            {"_m_s", "m/s"},
                                                                            {"_mjd2000", "MJD2000"},
                                                                            {"_days", "d"},
                                                                            {"_km", "km"},
                                                                            {"_kg", "kg"},
                                                                            {"_N", "N"},
                                                                            {"_W", "W"},
                                                                            {"_s", "s"},
                                                                            {"_deg", "deg"},
                                                                            {"_rad", "rad"},
                                                                            {"_AU", "AU"},
                                                                            {"_m2", "m^2"},
                                                                            {"_m", "m"}};
  for (const auto& [suffix, unit] : suffixes)
    if (key.size() > suffix.size() && key.compare(key.size() - suffix.size(), suffix.size(), suffix) == 0) return unit;
  return "";
}

// " (YYYY-MM-DDThh:mm:ss TDB)" of an MJD2000 epoch; "" outside the calendar's years.
std::string calendar_note(double mjd2000) {
  try {
    return " (" + astro::iso_date_tdb(mjd2000) + " TDB)";
  } catch (const std::invalid_argument&) {
    return "";
  }
}

void spec_rows(const json& v, const std::string& pointer, const std::string& key, std::ostringstream& out) {
  if (v.is_object()) {
    for (const auto& [k, x] : v.items()) spec_rows(x, pointer + "/" + k, k, out);
    return;
  }
  if (v.is_array() && !std::all_of(v.begin(), v.end(), [](const json& x) { return x.is_primitive(); })) {
    for (std::size_t i = 0; i < v.size(); ++i) spec_rows(v[i], pointer + "/" + std::to_string(i), key, out);
    return;
  }
  // An epoch also as its calendar date (TDB): MJD2000 numbers mean little to most readers.
  const bool epoch = v.is_number() && unit_of_key(key) == "MJD2000";
  out << "| " << code(pointer) << " | " << value(v) << (epoch ? calendar_note(v.get<double>()) : "") << " | "
      << unit_of_key(key) << " |\n";
}

// A fence for a code block holding `text`: longer than any run of backticks in it.
std::string fence_for(const std::string& text) {
  std::size_t longest = 0, run = 0;
  for (char c : text) {
    run = c == '`' ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  return std::string(std::max<std::size_t>(3, longest + 1), '`');
}

// How far the search looked (solution.json's search record): whether its starts saturated, the
// family of the best extremal, and a minimum-time problem's minimum-fuel companion.
void search_coverage(std::ostringstream& o, const json& sr) {
  if (sr.contains("saturated"))
    o << (sr.at("saturated").get<bool>() ? "The starts saturated" : "**The starts did not saturate**") << " ("
      << markdown_text(sr.value("stopped", ""))
      << "; chance that another start finds a new extremal: " << numeric(sr.value("new_extremal_chance", json()))
      << ").\n\n";
  if (sr.contains("family")) {
    o << "| family of extremal | direction | revolutions looked for | how | found |\n|---|---|---|---|---|\n";
    for (const auto& p : sr.at("family"))
      o << "| " << numeric(p.value("from", json())) << " | " << (p.value("direction", 0) < 0 ? "one fewer" : "one more")
        << " | " << numeric(p.value("revolutions", json())) << " | " << markdown_text(p.value("how", "")) << " | "
        << (p.contains("found") ? "extremal " + numeric(p.at("found")) : std::string("none")) << " |\n";
    o << "\n";
  }
  if (sr.contains("minimum_fuel_companion")) {
    const json& c = sr.at("minimum_fuel_companion");
    o << "Minimum-fuel companion: final time held at " << numeric(c.value("held_tf_days", json())) << " d, "
      << numeric(c.value("converged", json())) << " of " << numeric(c.value("starts", json())) << " starts converged, "
      << c.value("solutions", json::array()).size()
      << " distinct solutions, each continued down in the held time and released.\n\n";
  }
}

class Writer {
 public:
  explicit Writer(const ReportInputs& in)
      : in_(in),
        d_(in.derivation),
        reader_(in.derivation, in.derivation_source, false),
        symbols_(with_multipliers(reader_.symbols, in.derivation)),
        tex_(names(), intermediate_names(in.derivation)) {}

  std::string write();

 private:
  // The reader's symbols and the multipliers the conditions name (nu_arrival_1, ...), which the
  // reader does not register: they are no unknown of the shooting.
  static symbolic::SymbolTable with_multipliers(symbolic::SymbolTable table, const json& d) {
    const auto add = [&](const json& owner) {
      for (const auto& m : owner.value("multipliers", json::array()))
        if (m.is_string() && symbolic::is_identifier(m.get<std::string>())) table.get(m.get<std::string>());
    };
    for (const auto& c : d.value("constraints", json::array())) add(c);
    for (const auto& e : d.value("events", json::array())) add(e);
    return table;
  }

  static std::set<std::string> intermediate_names(const json& d) {
    std::set<std::string> out;
    for (const auto& q : d.value("intermediates", json::array())) out.insert(q.value("name", ""));
    return out;
  }

  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& entry : symbols_.symtab()) out.push_back(entry.first);
    return out;
  }

  // An expression of the derivation parsed, or nothing when it is not one the reader can parse.
  std::optional<GiNaC::ex> parsed(const std::string& text, const std::string& where) const {
    try {
      return symbols_.parse(text, where);
    } catch (const std::exception&) {
      return std::nullopt;
    }
  }

  void learn_all(const json& v, const std::string& key);
  std::string display(const std::string& lhs, const std::string& text, const std::string& where,
                      const std::string& rhs = "");
  std::string display_expression(const std::string& lhs, const GiNaC::ex& e, const std::string& rhs = "");
  std::string condition(const std::string& text, const std::string& where);
  std::string inline_symbol(const std::string& name) const { return "$" + tex_.symbol(name) + "$"; }
  std::string findings(const std::function<bool(const json&)>& concerns) const;
  // The conditions g > 0 an owner's rows leave to the runtime (must_be_positive), each with its meaning.
  std::string side_conditions(const json& owner, const std::string& where);

  void header(std::ostringstream& o) const;
  void problem(std::ostringstream& o) const;
  void specification(std::ostringstream& o) const;
  void symbols(std::ostringstream& o);
  void equations(std::ostringstream& o);
  void control(std::ostringstream& o);
  void boundaries(std::ostringstream& o);
  void events(std::ostringstream& o);
  void shooting(std::ostringstream& o);
  void verification(std::ostringstream& o) const;
  void solution(std::ostringstream& o) const;

  const ReportInputs& in_;
  const json& d_;
  derivation::Reader reader_;
  symbolic::SymbolTable symbols_;
  symbolic::Typesetter tex_;
};

// Every expression-valued string of the derivation (by the keys that hold expressions), learned
// first so that a named quantity has one name in the whole document.
void Writer::learn_all(const json& v, const std::string& key) {
  static const std::vector<std::string> keys = {"hamiltonian",
                                                "rhs",
                                                "state_rhs",
                                                "running_cost",
                                                "endpoint_cost",
                                                "law",
                                                "dH_da",
                                                "switching_function",
                                                "dH_du_at_lower",
                                                "dH_du_at_upper",
                                                "d2H_du2",
                                                "interior",
                                                "psi",
                                                "expression",
                                                "cone_angle"};
  if (v.is_object()) {
    for (const auto& [k, x] : v.items()) learn_all(x, k);
  } else if (v.is_array()) {
    for (const auto& x : v) learn_all(x, key);
  } else if (v.is_string() && std::find(keys.begin(), keys.end(), key) != keys.end()) {
    if (auto e = parsed(v.get<std::string>(), key)) tex_.learn(*e);
  }
}

// A display block "lhs = expression", broken between the terms of a long sum; the text itself
// when it is not an expression the reader parses.
std::string Writer::display(const std::string& lhs, const std::string& text, const std::string& where,
                            const std::string& rhs) {
  const auto e = parsed(text, where);
  if (!e) return "\n" + code(text) + " (not an expression this report can typeset)\n\n";
  return display_expression(lhs, *e, rhs);
}

std::string Writer::display_expression(const std::string& lhs, const GiNaC::ex& e, const std::string& rhs) {
  const std::vector<std::string> lines = tex_.latex_lines(e, kLineWidth);
  std::ostringstream o;
  o << "\n$$\n";
  if (lines.size() == 1) {
    o << lhs << (lhs.empty() ? "" : " = ") << lines[0] << rhs << "\n";
  } else {
    o << "\\begin{aligned}\n" << lhs << (lhs.empty() ? "" : " ={}") << " & " << lines[0] << " \\\\\n";
    for (std::size_t i = 1; i < lines.size(); ++i)
      o << " & " << lines[i] << (i + 1 < lines.size() ? " \\\\\n" : rhs + "\n");
    o << "\\end{aligned}\n";
  }
  o << "$$\n\n";
  return o.str();
}

// A condition "a = b" as mathematics when both sides are expressions, else its words.
std::string Writer::condition(const std::string& text, const std::string& where) {
  const auto eq = text.find(" = ");
  if (eq != std::string::npos) {
    const auto lhs = parsed(text.substr(0, eq), where), rhs = parsed(text.substr(eq + 3), where);
    if (lhs && rhs) return display_expression(tex_.latex(*lhs), *rhs);
  }
  return "- " + markdown_text(text) + "\n";
}

std::string Writer::findings(const std::function<bool(const json&)>& concerns) const {
  if (!in_.verify) return "";
  std::ostringstream o;
  int shown = 0;
  for (const auto& c : in_.verify->at("checks")) {
    if (!concerns(c)) continue;
    const bool pass = c.value("verdict", "") == "pass";
    o << (shown++ ? "; " : "> helios-verify: ") << code(c.value("id", "")) << " "
      << (pass ? markdown_text(c.value("verdict", "")) : "**" + markdown_text(c.value("verdict", "")) + "**");
    const std::string feedback = c.value("feedback", "");
    if (!pass && !feedback.empty()) o << ": " << markdown_text(feedback);
  }
  return shown ? o.str() + "\n\n" : "";
}

bool id_starts(const json& check, const std::string& prefix) {
  return check.value("id", "").rfind(prefix, 0) == 0;
}

// A check of event `id`: its id after the colon is the event's or one of its parts.
bool concerns_event(const json& check, const std::string& id) {
  const std::string c = check.value("id", "");
  const auto colon = c.find(':');
  if (colon == std::string::npos) return false;
  const std::string part = c.substr(colon + 1);
  return part == id || part.rfind(id + "_", 0) == 0 || part.find("_" + id + "_") != std::string::npos ||
         (part.size() > id.size() && part.compare(part.size() - id.size() - 1, id.size() + 1, "_" + id) == 0);
}

void Writer::header(std::ostringstream& o) const {
  const json& p = in_.spec.at("problem");
  o << "# " << markdown_text(p.value("id", "")) << ": " << markdown_text(p.value("title", "")) << "\n\n";
  const json& producer = d_.at("producer");
  o << "Derivation by " << markdown_text(producer.value("tool", "")) << " "
    << markdown_text(producer.value("version", "")) << " (" << markdown_text(producer.value("backend", ""))
    << " backend)";
  if (in_.verify) {
    int passed = 0, total = 0;
    for (const auto& c : in_.verify->at("checks")) {
      ++total;
      passed += c.value("verdict", "") == "pass";
    }
    o << "; verification **" << markdown_text(in_.verify->value("verdict", "")) << "** (" << passed << " of " << total
      << " checks pass)";
  } else {
    o << "; not verified (no verify.json given)";
  }
  if (in_.solution)
    o << "; solution **" << markdown_text(in_.solution->value("status", "")) << "**.\n\n";
  else
    o << "; not solved (no solution.json given).\n\n";
  o << "Written by `helios-score --report` from the run's artifacts. Every formula is an exact rewrite of the "
       "expression stored in "
    << markdown_text(in_.derivation_source)
    << ": norms and differences are named (see *Named quantities*), terms collected and factored where "
       "that is shorter.\n\n";
}

void Writer::problem(std::ostringstream& o) const {
  o << "## The problem\n\n";
  const std::string fence = fence_for(in_.problem_text);
  o << fence << "text\n"
    << in_.problem_text << (in_.problem_text.empty() || in_.problem_text.back() == '\n' ? "" : "\n") << fence << "\n\n";
}

void Writer::specification(std::ostringstream& o) const {
  o << "## Specification (spec.json)\n\n| field | value | unit |\n|---|---|---|\n";
  std::ostringstream rows;
  for (const auto& [k, v] : in_.spec.items())
    if (k != "schema" && k != "schema_version" && k != "producer") spec_rows(v, "/" + k, k, rows);
  o << rows.str() << "\n";
}

void Writer::symbols(std::ostringstream& o) {
  const json& u = d_.at("units");
  o << "## The derivation\n\n### Units and symbols\n\nThe solver works in normalized units: length "
    << markdown_text(u.value("length", "")) << " = " << io::short_number(u.value("length_km", 0.0)) << " km, time "
    << markdown_text(u.value("time", "")) << " = " << io::short_number(u.value("time_s", 0.0)) << " s, mass "
    << io::short_number(u.value("mass_kg", 0.0))
    << " kg.\n\n| symbol | name | meaning | unit | value |\n|---|---|---|---|---|\n";
  for (const auto& s : d_.at("states"))
    o << "| " << inline_symbol(s.at("name")) << " | " << code(s.at("name"))
      << " | state: " << markdown_text(s.value("meaning", "")) << " | " << markdown_text(s.value("unit", ""))
      << " | |\n";
  for (const auto& s : d_.at("states"))
    o << "| " << inline_symbol(s.at("costate")) << " | " << code(s.at("costate")) << " | costate of "
      << markdown_text(s.value("meaning", "")) << " | | |\n";
  for (const auto& c : d_.at("controls"))
    o << "| " << inline_symbol(c.at("name")) << " | " << code(c.at("name"))
      << " | control: " << markdown_text(c.value("meaning", "")) << " | | |\n";
  for (const auto& p : d_.at("parameters"))
    o << "| " << inline_symbol(p.at("name")) << " | " << code(p.at("name")) << " | "
      << markdown_text(p.value("meaning", "")) << " | " << markdown_text(p.value("unit", "")) << " | "
      << (p.value("source", "").empty() ? io::short_number(p.value("value", 0.0))
                                        : "evaluated by the program: " + code(p.at("source")))
      << " |\n";
  o << "| " << inline_symbol(reader_.multiplier) << " | " << code(reader_.multiplier) << " | cost multiplier | | |\n";
  if (!reader_.homotopy.empty())
    o << "| " << inline_symbol(reader_.homotopy) << " | " << code(reader_.homotopy) << " | "
      << markdown_text(d_.at("homotopy").value("meaning", "")) << " | | |\n";
  o << "\n";
}

// The time derivative of a symbol: the dot on its letter, not over its subscript.
std::string dotted(const std::string& tex) {
  for (const char* base : {"\\lambda"})
    if (tex.rfind(base, 0) == 0) return "\\dot{" + std::string(base) + "}" + tex.substr(std::string(base).size());
  if (tex.size() > 1 && std::isalpha(static_cast<unsigned char>(tex[0])) && (tex[1] == '_' || tex[1] == '^'))
    return "\\dot{" + tex.substr(0, 1) + "}" + tex.substr(1);
  return "\\dot{" + tex + "}";
}

void Writer::equations(std::ostringstream& o) {
  if (d_.contains("intermediates") && !d_.at("intermediates").empty()) {
    o << "### Intermediates\n\nNamed quantities of the dynamics, evaluated in this order; the equations below use "
         "their names and differentiate through them by the chain rule.\n\n";
    for (const auto& q : d_.at("intermediates"))
      o << markdown_text(q.value("meaning", "")) << " (" << code(q.value("name", "")) << ")"
        << (q.value("unit", "").empty() ? "" : ", " + markdown_text(q.value("unit", ""))) << ":\n"
        << display(tex_.symbol(q.value("name", "")), q.value("expression", ""), "/intermediates");
    o << findings([](const json& c) { return c.value("category", "") == "intermediates"; });
  }
  o << "### Hamiltonian\n"
    << display("H", d_.at("hamiltonian"), "/hamiltonian")
    << findings([](const json& c) { return id_starts(c, "hamiltonian"); });
  const json& dyn = d_.at("dynamics");
  o << "Running cost and endpoint cost:\n"
    << display("L", dyn.at("running_cost"), "/dynamics/running_cost")
    << display("\\phi", dyn.at("endpoint_cost"), "/dynamics/endpoint_cost");
  o << "### State equations\n";
  for (const auto& s : d_.at("state_odes"))
    o << display(dotted(tex_.symbol(s.at("state"))), s.at("rhs"), "/state_odes");
  o << findings([](const json& c) { return id_starts(c, "state_ode:"); });
  o << "### Costate equations\n";
  for (const auto& s : d_.at("costate_odes"))
    o << display(dotted(tex_.symbol(s.at("costate"))), s.at("rhs"), "/costate_odes");
  o << findings([](const json& c) { return id_starts(c, "costate_ode:"); });
}

void Writer::control(std::ostringstream& o) {
  o << "### Optimal control\n\n";
  const json& law = d_.at("control_law");
  if (law.contains("direction")) {
    const json& dir = law.at("direction");
    o << "Thrust direction: " << markdown_text(dir.value("reason", "")) << "\n";
    for (std::size_t i = 0; i < dir.at("controls").size(); ++i)
      o << display(tex_.symbol(dir.at("controls")[i]) + "^{*}", dir.at("law")[i], "/control_law/direction/law");
  }
  if (law.contains("throttle")) {
    const json& th = law.at("throttle");
    const std::string u = tex_.symbol(th.at("control"));
    o << "Throttle " << inline_symbol(th.at("control")) << " in [" << numeric(th.at("bounds")[0]) << ", "
      << numeric(th.at("bounds")[1]) << "], smoothing " << markdown_text(th.value("smoothing", ""))
      << ". Switching function:\n"
      << display("S", th.at("switching_function"), "/control_law/throttle/switching_function")
      << display("\\left.\\frac{\\partial H}{\\partial " + u + "}\\right|_{" + u + "=0}", th.at("dH_du_at_lower"),
                 "/control_law/throttle/dH_du_at_lower")
      << display("\\left.\\frac{\\partial H}{\\partial " + u + "}\\right|_{" + u + "=1}", th.at("dH_du_at_upper"),
                 "/control_law/throttle/dH_du_at_upper")
      << display("\\frac{\\partial^2 H}{\\partial " + u + "^2}", th.at("d2H_du2"), "/control_law/throttle/d2H_du2")
      << "Interior throttle (stationarity of H):\n"
      << display(u + "_{\\mathrm{int}}", th.at("interior"), "/control_law/throttle/interior")
      << "Law: " << markdown_text(th.value("law", "")) << "\n\n";
  }
  if (law.contains("sail")) {
    const json& sail = law.at("sail");
    o << "Sail normal: " << markdown_text(sail.value("reason", "")) << "\n";
    for (const auto& def : sail.value("definitions", json::array()))
      o << display(tex_.symbol(def.at("name")), def.at("expression"), "/control_law/sail/definitions");
    for (std::size_t i = 0; i < sail.at("controls").size(); ++i)
      o << display(tex_.symbol(sail.at("controls")[i]) + "^{*}", sail.at("law")[i], "/control_law/sail/law");
    o << "Stationarity: " << markdown_text(sail.value("stationarity", ""))
      << ". Admissible: " << markdown_text(sail.value("admissible", "")) << ".\n\n";
  }
  o << findings([](const json& c) { return c.value("category", "") == "control"; });
}

void Writer::boundaries(std::ostringstream& o) {
  o << "### Boundary conditions and transversality\n\n";
  const json& times = d_.at("times");
  o << "Times (normalized): t0 = " << numeric(times.at("t0")) << ", final time "
    << markdown_text(times.value("final_time", ""));
  if (times.contains("tf")) o << ", tf = " << numeric(times.at("tf"));
  if (times.contains("tf_window")) o << ", tf in " << numeric(times.at("tf_window"));
  o << ".\n";
  if (times.contains("tf_expression")) o << display("t_f", times.at("tf_expression"), "/times/tf_expression");
  o << "\n";
  for (const auto& c : d_.at("constraints")) {
    const std::string id = c.at("id");
    o << "#### " << markdown_text(id) << " (" << markdown_text(c.value("kind", "")) << " at "
      << markdown_text(c.value("at", "")) << ")\n\n"
      << "Target: " << code(c.at("target").dump()) << "\n";
    const json& psi = c.value("psi", json::array());
    for (std::size_t i = 0; i < psi.size(); ++i)
      o << display("\\psi_{" + std::to_string(i + 1) + "}", psi[i], "/constraints/" + id + "/psi", " = 0");
    o << side_conditions(c, "/constraints/" + id);
    o << "Conditions:\n\n";
    for (const auto& cond : c.value("conditions", json::array())) o << condition(cond, "/constraints/" + id);
    if (c.contains("time_condition")) o << "- " << markdown_text(c.at("time_condition")) << "\n";
    o << "\n"
      << findings([&](const json& check) {
           return c.at("at") != "interior" && check.value("category", "") == "transversality" &&
                  (c.at("at") == "t0" ? id_starts(check, "transversality_t0") : !id_starts(check, "transversality_t0"));
         });
  }
}

std::string Writer::side_conditions(const json& owner, const std::string& where) {
  const json& sides = owner.value("must_be_positive", json::array());
  if (sides.empty()) return "";
  std::string out =
      "The rows also hold on the target's mirror; the solver returns no extremal where one of these fails:\n";
  for (std::size_t i = 0; i < sides.size(); ++i)
    out +=
        display("g_{" + std::to_string(i + 1) + "}", sides[i].at("expression"), where + "/must_be_positive", " > 0") +
        "(" + markdown_text(sides[i].at("meaning")) + ")\n\n";
  return out;
}

void Writer::events(std::ostringstream& o) {
  const json& evs = d_.value("events", json::array());
  if (evs.empty()) return;
  o << "### Interior events\n\n";
  for (const auto& ev : evs) {
    const std::string id = ev.at("id");
    const json& time = ev.at("time");
    o << "#### " << markdown_text(id) << " (" << markdown_text(ev.value("kind", ""))
      << ")\n\nTarget: " << code(ev.at("target").dump()) << ". Epoch " << inline_symbol(time.at("symbol")) << " in "
      << numeric(time.value("window", json::array())) << ", stay " << numeric(time.value("duration", json(0.0)))
      << " (normalized):\n"
      << display(tex_.symbol(time.at("symbol")), time.at("expression"), "/events/" + id + "/time/expression");
    const json& psi = ev.value("psi", json::array());
    for (std::size_t i = 0; i < psi.size(); ++i)
      o << display("\\psi_{" + std::to_string(i + 1) + "}", psi[i], "/events/" + id + "/psi", " = 0");
    o << side_conditions(ev, "/events/" + id);
    o << "Conditions:\n\n";
    for (const auto& cond : ev.value("conditions", json::array())) o << condition(cond, "/events/" + id);
    o << "\nState and costate after the event:\n";
    for (const auto& m : ev.value("state_map", json::array()))
      o << display(tex_.symbol(m.at("state")) + "(t^{+})", m.at("expression"), "/events/" + id + "/state_map");
    // A costate after the event is an expression, or a shooting variable of its own (free).
    for (const auto& m : ev.value("costate_map", json::array()))
      o << display(tex_.symbol(m.at("costate")) + "(t^{+})",
                   m.contains("expression") ? m.at("expression") : m.at("variable"), "/events/" + id + "/costate_map");
    o << findings([&](const json& c) { return concerns_event(c, id); });
  }
}

void Writer::shooting(std::ostringstream& o) {
  const json& sh = d_.at("shooting");
  o << "### Shooting variables and equations\n\n| # | variable | meaning | scale | first guess "
       "|\n|---|---|---|---|---|\n";
  int i = 0;
  for (const auto& v : sh.at("variables"))
    o << "| " << ++i << " | " << inline_symbol(v.at("name")) << " | " << markdown_text(v.value("meaning", "")) << " | "
      << numeric(v.value("scale", json(1.0))) << " | " << markdown_text(v.value("init", "")) << " |\n";
  o << "\n" << sh.at("equations").size() << " equations in " << sh.at("variables").size() << " unknowns:\n\n";
  i = 0;
  for (const auto& e : sh.at("equations")) {
    ++i;
    o << "**F" << i << "** " << code(e.value("name", "")) << ": " << markdown_text(e.value("meaning", "")) << "\n"
      << display("F_{" + std::to_string(i) + "}", e.at("expression"), "/shooting/equations/" + std::to_string(i - 1));
  }
  o << findings([](const json& c) { return c.value("category", "") == "counts"; });
}

void Writer::verification(std::ostringstream& o) const {
  if (!in_.verify) return;
  o << "## Verification (verify.json)\n\nVerdict: **" << markdown_text(in_.verify->value("verdict", ""))
    << "**.\n\n| check | category | verdict | method | max rel. error | finding |\n|---|---|---|---|---|---|\n";
  for (const auto& c : in_.verify->at("checks"))
    o << "| " << code(c.value("id", "")) << " | " << markdown_text(c.value("category", "")) << " | "
      << markdown_text(c.value("verdict", "")) << " | " << markdown_text(c.value("method", "")) << " | "
      << (c.contains("max_rel_error") ? numeric(c.at("max_rel_error")) : "") << " | "
      << markdown_text(c.value("feedback", "")) << " |\n";
  o << "\n";
}

void Writer::solution(std::ostringstream& o) const {
  if (!in_.solution) return;
  const json& s = *in_.solution;
  o << "## Solution (solution.json)\n\n| quantity | value |\n|---|---|\n";
  const auto row = [&](const char* key) {
    if (s.contains(key)) o << "| " << code(key) << " | " << value(s.at(key)) << " |\n";
  };
  for (const char* key : {"status", "status_detail", "tof_days", "tof_hours", "departure_mjd2000", "departure_date_tdb",
                          "arrival_mjd2000", "arrival_date_tdb"})
    row(key);
  for (const char* key : {"initial_mass_kg", "final_mass_kg", "propellant_kg", "delta_v_m_s", "epsilon", "max_residual",
                          "hamiltonian_drift", "iterations", "function_evaluations", "restarts", "seed", "method"})
    row(key);
  if (s.contains("timings"))
    for (const auto& [k, v] : s.at("timings").items())
      o << "| " << code("timings/" + k) << " | " << numeric(v) << " |\n";
  o << "\n";
  if (s.contains("switches") && !s.at("switches").empty()) {
    // In hours beside days for a flight that is counted in hours (solution.json's tof_hours).
    const bool hours = s.contains("tof_hours");
    o << "### Switches\n\n| t (d) |" << (hours ? " t (h) |" : "") << " throttle after |\n|---|" << (hours ? "---|" : "")
      << "---|\n";
    for (const auto& w : s.at("switches")) {
      const json t = w.value("t_days", json());
      o << "| " << numeric(t) << " | ";
      if (hours) o << (t.is_number() ? numeric(json(t.get<double>() * 24)) : numeric(t)) << " | ";
      o << numeric(w.value("throttle_after", json())) << " |\n";
    }
    o << "\n";
  }
  if (s.contains("homotopy")) {
    o << "### Homotopy\n\n| eps | converged | evaluations | max residual |\n|---|---|---|---|\n";
    for (const auto& h : s.at("homotopy"))
      o << "| " << numeric(h.value("eps", json())) << " | " << numeric(h.value("converged", json())) << " | "
        << numeric(h.value("evaluations", json())) << " | " << numeric(h.value("max_residual", json())) << " |\n";
    o << "\n";
  }
  if (s.contains("search")) {
    const json& sr = s.at("search");
    o << "### The search\n\n"
      << markdown_text(sr.value("method", "")) << ": " << numeric(sr.value("starts", json())) << " starts on "
      << numeric(sr.value("threads", json())) << " threads, " << numeric(sr.value("seconds", json())) << " s"
      << (sr.value("cut_by_time", false) ? ", cut by the time limit" : "") << ". "
      << markdown_text(sr.value("reason", ""))
      << ".\n\n| extremal | objective | in named units | revolutions | switches | reached from | max residual "
         "|\n|---|---|---|---|---|---|---|\n";
    // The objective in the unit the extremal's record names: propellant, flight time or final state.
    const auto named = [&](const json& e) {
      for (const auto& [key, unit] : {std::pair<const char*, const char*>{"propellant_kg", " kg"},
                                      {"delta_v_m_s", " m/s"},
                                      {"tof_days", " d"},
                                      {"final_radius_km", " km"},
                                      {"final_energy_km2_s2", " km^2/s^2"}})
        if (e.contains(key)) return numeric(e.at(key)) + unit;
      return std::string();
    };
    for (const auto& e : sr.value("extremals", json::array()))
      o << "| " << numeric(e.value("id", json()))
        << (e.value("id", -1) == sr.value("returned", -2) ? " (returned)" : "") << " | "
        << numeric(e.value("objective", json())) << " | " << named(e) << " | "
        << numeric(e.value("revolutions", json())) << " | " << numeric(e.value("switches", json())) << " | "
        << numeric(e.value("reached", json())) << " starts | " << numeric(e.value("max_residual", json())) << " |\n";
    o << "\n";
    if (sr.contains("minimum_time")) {
      const json& m = sr.at("minimum_time");
      o << "The minimum time found: " << numeric(m.value("tf_days", json())) << " d, against the stated bound of "
        << numeric(m.value("bound_days", json())) << " d (" << markdown_text(m.value("how", "")) << "; "
        << (m.value("settled", false) ? "settled" : "not settled") << ").\n\n";
    }
    if (sr.contains("routes")) {
      o << "| route | ran | what it did, or why not | extremals added | evaluations |\n|---|---|---|---|---|\n";
      for (const auto& r : sr.at("routes"))
        o << "| " << markdown_text(r.value("name", "")) << " | " << (r.value("ran", false) ? "yes" : "no") << " | "
          << markdown_text(r.value("outcome", "")) << " | " << numeric(r.value("extremals_added", json())) << " | "
          << numeric(r.value("evaluations", json())) << " |\n";
      o << "\n";
    }
    search_coverage(o, sr);
  }
  if (s.contains("files")) {
    o << "### Plots\n\n";
    // An image only for a plain file name beside the report; any other name is shown as text.
    static const std::regex png(R"([A-Za-z0-9][A-Za-z0-9._-]*\.png)");
    for (const auto& [k, v] : s.at("files").items()) {
      const std::string file = v.is_string() ? v.get<std::string>() : "";
      if (std::regex_match(file, png))
        o << "![" << markdown_text(k) << "](" << file << ")\n\n";
      else if (file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0)
        o << markdown_text(k) << ": " << code(file) << "\n\n";
    }
  }
}

std::string Writer::write() {
  learn_all(d_, "");
  std::ostringstream o, derivation;
  header(o);
  problem(o);
  specification(o);
  symbols(derivation);
  equations(derivation);
  control(derivation);
  boundaries(derivation);
  events(derivation);
  shooting(derivation);
  o << derivation.str();
  const auto defs = tex_.definitions();
  if (!defs.empty()) {
    o << "### Named quantities\n\n";
    for (const auto& q : defs) o << "$$\n" << q.symbol << " = " << q.definition << "\n$$\n\n";
  }
  verification(o);
  solution(o);
  return o.str();
}

}  // namespace

std::string markdown_text(const std::string& text) {
  static const std::string markup = "\\`*_[]<>|$^~&@#";
  std::string out;
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      out += ' ';
    else if (markup.find(c) != std::string::npos)
      out += std::string("\\") + c;
    else
      out += c;
  }
  return out;
}

std::string report_markdown(const ReportInputs& in) {
  return Writer(in).write();
}

}  // namespace helios::report
