// Bodies given by their orbital elements: the elements as the spec keeps them, the orbits defined,
// and the elements table (its lines are items of their own, read here); the lines of a thruster's
// table are read here too, its header and rows by forms/thruster_table.cpp.
#include "grammar.hpp"

#include <algorithm>

#include "helios/astro/constants.hpp"

namespace helios::spec::grammar {

// Which element a name in an orbit sentence or a table header stands for: a, e, i, raan, argp,
// mean or true (the anomaly), or "" if none. Omega (Ω) is the node, omega (ω, w) the argument.
std::string element_field(const std::string& written) {
  const std::string name = trimmed(written);
  static const std::map<std::string, std::string> symbols = {
      {"Omega", "raan"}, {"\xCE\xA9", "raan"}, {"omega", "argp"}, {"\xCF\x89", "argp"}, {"\xCE\xBD", "true"}};
  if (symbols.count(name)) return symbols.at(name);
  static const std::map<std::string, std::string> fields = {{"a", "a"},
                                                            {"semi-major axis", "a"},
                                                            {"semimajor axis", "a"},
                                                            {"e", "e"},
                                                            {"eccentricity", "e"},
                                                            {"i", "i"},
                                                            {"inclination", "i"},
                                                            {"node", "raan"},
                                                            {"raan", "raan"},
                                                            {"om", "raan"},
                                                            {"ascending node", "raan"},
                                                            {"longitude of the ascending node", "raan"},
                                                            {"right ascension of the ascending node", "raan"},
                                                            {"w", "argp"},
                                                            {"argp", "argp"},
                                                            {"argument of perihelion", "argp"},
                                                            {"argument of periapsis", "argp"},
                                                            {"argument of pericenter", "argp"},
                                                            {"argument of pericentre", "argp"},
                                                            {"m", "mean"},
                                                            {"mean anomaly", "mean"},
                                                            {"nu", "true"},
                                                            {"true anomaly", "true"}};
  const auto it = fields.find(lowercase(name));
  return it == fields.end() ? "" : it->second;
}

// Classical elements in the spec's units, checked for an ellipse.
json elements_json(double epoch_mjd2000, const std::map<std::string, double>& v) {
  const double a = v.at("a"), e = v.at("e");
  if (!(a > 0)) throw sentence_error("the semi-major axis must be positive, got " + io::short_number(a) + " AU");
  if (!(e >= 0 && e < 1)) throw sentence_error("the eccentricity must satisfy 0 <= e < 1, got " + io::short_number(e));
  const bool mean = v.count("mean") != 0;
  return {{"epoch_mjd2000", epoch_mjd2000},
          {"a_AU", a},
          {"e", e},
          {"i_deg", v.at("i")},
          {"raan_deg", v.at("raan")},
          {"argp_deg", v.at("argp")},
          {mean ? "mean_anomaly_deg" : "true_anomaly_deg", mean ? v.at("mean") : v.at("true")}};
}

void Builder::define_orbit(const std::string& written, const std::string& about, json elements) {
  const std::string name = body_name(written);
  for (const auto& o : orbits)
    if (lowercase(o.name) == lowercase(name))
      throw sentence_error("the orbit of " + name + " is given twice (first on line " + std::to_string(o.where.line) +
                           ")");
  orbits.push_back({name, about, std::move(elements), here});
}

std::string Builder::element_label(const std::string& field) {
  static const std::map<std::string, std::string> labels = {{"a", "semi-major axis ('a = Q')"},
                                                            {"e", "eccentricity ('e = N')"},
                                                            {"i", "inclination ('i = Q')"},
                                                            {"raan", "ascending node ('node = Q')"},
                                                            {"argp", "argument of perihelion"}};
  return labels.at(field);
}

// Factor to the spec unit of an element: a in AU, angles in deg, e a pure number.
double Builder::element_unit(const std::string& field, const std::string& written) {
  const std::string unit = written == "\xC2\xB0" ? "deg" : written;  // °
  if (field == "e") {
    if (!unit.empty()) throw sentence_error("the eccentricity is a pure number, not in '" + unit + "'");
    return 1.0;
  }
  if (unit.empty())
    throw sentence_error("the " + std::string(field == "a" ? "semi-major axis needs a length unit (AU, km)"
                                                           : "angles need a unit (deg or rad)"));
  if (field == "a") return unit_factor(Dimension::Length, unit) / helios::astro::AU_KM;
  return unit_factor(Dimension::Angle, unit);
}

std::vector<std::string> Builder::cells_of(const std::string& row) {
  if (row.size() < 2 || row.back() != '|') throw sentence_error("a table line starts and ends with '|'");
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '|') {
      cells.push_back(trimmed(cell));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return cells;
}

std::pair<std::string, std::string> name_and_unit(const std::string& cell) {
  static const std::regex cell_re(R"(([^\[(]*?)\s*(?:[\[(]\s*([^\])]*?)\s*[\])])?)");
  std::smatch m;
  if (!std::regex_match(cell, m, cell_re)) return {cell, ""};
  return {trimmed(m[1].str()), m[2].str()};
}

namespace {

bool is_body_column(const std::string& cell) {
  const std::string name = lowercase(name_and_unit(cell).first);
  return name == "body" || name == "name" || name == "asteroid" || name == "object" || name == "target";
}

}  // namespace

bool Builder::is_table_header(const std::string& row) {
  if (row.empty() || row.front() != '|') return false;
  try {
    const auto cells = cells_of(row);
    return std::any_of(cells.begin(), cells.end(), is_body_column);
  } catch (const sentence_error&) {
    return false;
  }
}

bool Builder::may_be_header(const Sentence& item) const {
  return item.table_row && (table_kind == TableKind::Thruster || is_table_header(item.text));
}

const char* Builder::header_example() const {
  return table_kind == TableKind::Thruster ? kThrusterTableHeader : kTableHeader;
}

void Builder::end_table() {
  if (table && table->kind == TableKind::Thruster) finish_thruster_table(*this);
  table.reset();
}

void Builder::table_line(const std::string& row) {
  const std::vector<std::string> cells = cells_of(row);
  const bool thruster_header = table_intro && table_kind == TableKind::Thruster;
  if (thruster_header || is_table_header(row)) {
    end_table();
    table = thruster_header ? thruster_table_header(cells) : table_header(cells);
    table_separator_allowed = true;
    table_intro.reset();
    return;
  }
  static const std::regex rule(R"(\s*:?-+:?\s*)");
  const bool is_rule =
      std::all_of(cells.begin(), cells.end(), [](const std::string& c) { return std::regex_match(c, rule); });
  if (!table) {
    bool thruster = false;  // a thruster's header with no sentence announcing it
    try {
      thruster_table_header(cells);
      thruster = true;
    } catch (const sentence_error&) {
    }
    if (thruster)
      throw sentence_error(
          "a thruster's table needs the sentence that announces it just above its header ('The thruster's table "
          "gives its thrust and mass flow at these input powers:')");
    throw sentence_error("a table row needs its header line just above it: " + std::string(kTableHeader));
  }
  if (is_rule) {
    if (!table_separator_allowed) throw sentence_error("a rule line may only follow the table's header");
    table_separator_allowed = false;
    return;
  }
  table_separator_allowed = false;
  const TableColumns& t = *table;
  if (cells.size() != t.fields.size())
    throw sentence_error("the row has " + std::to_string(cells.size()) + " cells where the header has " +
                         std::to_string(t.fields.size()));
  if (t.kind == TableKind::Thruster) return thruster_table_row(*this, t, cells);
  static const std::regex num_re("\\s*" + kNum + "\\s*");
  std::map<std::string, double> v;
  std::string body, epoch;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (t.fields[k] == "body") {
      body = cells[k];
      continue;
    }
    if (!std::regex_match(cells[k], num_re))
      throw sentence_error("cell " + std::to_string(k + 1) + " '" + cells[k] + "' is not a number");
    if (t.fields[k] == "epoch")
      epoch = cells[k];
    else
      v[t.fields[k]] = number(cells[k]) * t.factors[k];
  }
  define_orbit(body, table_about, elements_json(mjd2000_of(t.epoch_scale, epoch), v));
}

// The columns by name, in any order: the body, the six elements (one anomaly, mean or true) with their
// units in brackets or parentheses, and the epoch in MJD or MJD2000.
TableColumns Builder::table_header(const std::vector<std::string>& cells) {
  const std::string layout = std::string("the header reads e.g. ") + kTableHeader +
                             " (columns in any order; a in AU or km, angles in deg or rad, 'true anomaly' instead of "
                             "'mean anomaly', epoch in MJD or MJD2000; units in [ ] or ( ))";
  TableColumns t;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const auto [name, unit] = name_and_unit(cells[k]);
    const std::string key = lowercase(name);
    std::string field = is_body_column(cells[k]) ? "body" : element_field(name);
    double factor = 1;
    if (key == "epoch" || key == "mjd" || key == "mjd2000") {
      field = "epoch";
      t.epoch_scale = key == "epoch" ? unit : name;
      if (lowercase(t.epoch_scale) != "mjd" && lowercase(t.epoch_scale) != "mjd2000")
        throw sentence_error("the epoch column must say [MJD] or [MJD2000], got '" + cells[k] + "'");
    } else if (field.empty()) {
      throw sentence_error("column " + std::to_string(k + 1) + " is '" + cells[k] + "': " + layout);
    } else if (field != "body") {
      factor = element_unit(field, unit);
    }
    const auto anomaly = [](const std::string& f) { return f == "mean" || f == "true"; };
    for (const auto& seen : t.fields)
      if (seen == field || (anomaly(seen) && anomaly(field)))
        throw sentence_error("the header gives " + (anomaly(field) ? std::string("the anomaly") : "'" + field + "'") +
                             " twice: " + layout);
    t.fields.push_back(field);
    t.factors.push_back(factor);
  }
  std::string missing;
  for (const char* f : {"body", "a", "e", "i", "raan", "argp", "epoch"})
    if (std::find(t.fields.begin(), t.fields.end(), f) == t.fields.end())
      missing += std::string(missing.empty() ? "" : ", ") + f;
  if (std::none_of(t.fields.begin(), t.fields.end(), [](const std::string& f) { return f == "mean" || f == "true"; }))
    missing += std::string(missing.empty() ? "" : ", ") + "an anomaly";
  if (!missing.empty()) throw sentence_error("the header lacks " + missing + ": " + layout);
  return t;
}

}  // namespace helios::spec::grammar
