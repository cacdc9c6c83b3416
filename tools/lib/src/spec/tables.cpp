// Bodies given by their orbital elements: the elements as the spec keeps them, the orbits defined,
// and the elements table (its lines are items of their own, read here).
#include "grammar.hpp"

#include <algorithm>

#include "helios/astro/constants.hpp"

namespace helios::spec::grammar {

// Which element a name in an orbit sentence or a table header stands for: a, e, i, raan, argp,
// mean or true (the anomaly), or "" if none.
std::string element_field(const std::string& name) {
  static const std::map<std::string, std::string> fields = {{"a", "a"},
                                                            {"semi-major axis", "a"},
                                                            {"semimajor axis", "a"},
                                                            {"e", "e"},
                                                            {"eccentricity", "e"},
                                                            {"i", "i"},
                                                            {"inclination", "i"},
                                                            {"node", "raan"},
                                                            {"raan", "raan"},
                                                            {"ascending node", "raan"},
                                                            {"longitude of the ascending node", "raan"},
                                                            {"right ascension of the ascending node", "raan"},
                                                            {"argument of perihelion", "argp"},
                                                            {"argument of periapsis", "argp"},
                                                            {"argument of pericenter", "argp"},
                                                            {"argument of pericentre", "argp"},
                                                            {"mean anomaly", "mean"},
                                                            {"true anomaly", "true"}};
  const auto it = fields.find(lowercase(trimmed(name)));
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
double Builder::element_unit(const std::string& field, const std::string& unit) {
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

bool Builder::is_table_header(const std::string& row) {
  static const std::regex first = re(R"(\|\s*(?:body|name)\s*\|.*)");
  return std::regex_match(row, first);
}

void Builder::table_line(const std::string& row) {
  const std::vector<std::string> cells = cells_of(row);
  if (is_table_header(row)) {
    table = table_header(cells);
    table_separator_allowed = true;
    table_intro.reset();
    return;
  }
  static const std::regex rule(R"(\s*:?-+:?\s*)");
  const bool is_rule =
      std::all_of(cells.begin(), cells.end(), [](const std::string& c) { return std::regex_match(c, rule); });
  if (!table) throw sentence_error("a table row needs its header line just above it: " + std::string(kTableHeader));
  if (is_rule) {
    if (!table_separator_allowed) throw sentence_error("a rule line may only follow the table's header");
    table_separator_allowed = false;
    return;
  }
  table_separator_allowed = false;
  if (cells.size() != 8)
    throw sentence_error("the row has " + std::to_string(cells.size()) + " cells where the header has 8");
  static const std::regex num_re("\\s*" + kNum + "\\s*");
  for (std::size_t k = 1; k < cells.size(); ++k)
    if (!std::regex_match(cells[k], num_re))
      throw sentence_error("cell " + std::to_string(k + 1) + " '" + cells[k] + "' is not a number");
  const TableColumns& t = *table;
  std::map<std::string, double> v = {
      {"a", number(cells[1]) * t.a_factor},           {"e", number(cells[2])},
      {"i", number(cells[3]) * t.angle_factor[0]},    {"raan", number(cells[4]) * t.angle_factor[1]},
      {"argp", number(cells[5]) * t.angle_factor[2]}, {t.anomaly, number(cells[6]) * t.angle_factor[3]}};
  define_orbit(cells[0], table_about, elements_json(mjd2000_of(t.epoch_scale, cells[7]), v));
}

TableColumns Builder::table_header(const std::vector<std::string>& cells) {
  const std::string layout = std::string("the header reads ") + kTableHeader +
                             " (a in AU or km, angles in deg or rad, 'true anomaly' instead of 'mean anomaly', "
                             "epoch in MJD or MJD2000)";
  if (cells.size() != 8)
    throw sentence_error("the header has " + std::to_string(cells.size()) + " columns, not 8: " + layout);
  static const std::regex cell_re(R"(([^\[]*?)\s*(?:\[\s*([^\]]*?)\s*\])?)");
  static const std::array<std::string, 8> expected = {"body", "a", "e", "i", "raan", "argp", "anomaly", "epoch"};
  TableColumns t;
  for (std::size_t k = 1; k < 8; ++k) {
    std::smatch m;
    std::regex_match(cells[k], m, cell_re);
    const std::string key = lowercase(m[1].str()), unit = m[2].str();
    std::string field = key == "epoch" ? "epoch" : element_field(key);
    if (field == "mean" || field == "true") {
      t.anomaly = field;
      field = "anomaly";
    }
    if (field != expected[k])
      throw sentence_error("column " + std::to_string(k + 1) + " is '" + cells[k] + "': " + layout);
    if (field == "epoch") {
      if (lowercase(unit) != "mjd" && lowercase(unit) != "mjd2000")
        throw sentence_error("the epoch column must say [MJD] or [MJD2000], got '" + cells[k] + "'");
      t.epoch_scale = unit;
    } else if (field == "a") {
      t.a_factor = element_unit("a", unit);
    } else if (field == "e") {
      element_unit("e", unit);
    } else {
      t.angle_factor[k - 3] = element_unit(field, unit);
    }
  }
  return t;
}

}  // namespace helios::spec::grammar
