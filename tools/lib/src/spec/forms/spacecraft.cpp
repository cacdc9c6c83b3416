// "The spacecraft has a maximum thrust of Q, a specific impulse of Q and an initial mass of Q.": the
// engine and the mass, clauses in any order, any subset; a clause in other words ("an Isp of 2000 s")
// makes the sentence one of facts in other words.
#include "../form.hpp"
#include "../grammar.hpp"

namespace helios::spec::grammar::forms {
namespace {

void read(Builder& b, const std::smatch& match) {
  const std::string list = match[1].str();
  static const std::regex split(R"(\s*(?:,\s*and\s+|,\s*|\s+and\s+)\s*)");
  static const std::regex clause =
      re(R"((?:an? )?(maximum thrust|specific impulse|initial mass|final mass) of )" + kQuantity);
  static const std::map<std::string, detail::Field> fields = {{"maximum thrust", detail::Field::Thrust},
                                                              {"specific impulse", detail::Field::Isp},
                                                              {"initial mass", detail::Field::InitialMass},
                                                              {"final mass", detail::Field::FinalMass}};
  const auto parts = [&] {
    return std::vector<std::string>(std::sregex_token_iterator(list.begin(), list.end(), split, -1), {});
  };
  for (const std::string& part : parts()) {
    std::smatch m;
    if (std::regex_match(part, m, clause)) continue;
    detail::SentenceFacts f;
    try {
      f = b.facts_of(b.sentence);
    } catch (const sentence_error& e) {
      throw sentence_error("cannot read '" + part +
                           "': expected 'a maximum thrust of Q', 'a specific impulse of Q', 'an initial mass of Q' "
                           "or 'a final mass of Q' (read as facts in other words: " +
                           e.what() + ")");
    }
    return b.apply_facts(f);
  }
  for (const std::string& part : parts()) {
    std::smatch m;
    std::regex_match(part, m, clause);
    const detail::Field field = fields.at(lowercase(m[1].str()));
    b.once(field);
    ++b.seen["the spacecraft's engine"];
    const double value = quantity(m, 2, *detail::fact_info(field).dim);
    b.check_value(field, value, m[2].str() + " " + m[3].str());
    b.spacecraft[detail::spec_key(field)] = value;
  }
}

}  // namespace

std::vector<Form> spacecraft() {
  return {{"the spacecraft's engine and mass",
           80,
           R"(The spacecraft has (.+))",
           read,
           {{"The spacecraft has a maximum thrust of 500 mN, a specific impulse of 2000 s and an initial mass of 1 t.",
             "sun -engine", R"~({"/spacecraft": {"thrust_N": 0.5, "isp_s": 2000, "initial_mass_kg": 1000}})~"},
            {"The spacecraft has a maximum thrust of 0.5 N, an Isp of 2000 s and an initial mass of 1000 kg.",
             "sun -engine", R"~({"/spacecraft": {"thrust_N": 0.5, "isp_s": 2000, "initial_mass_kg": 1000}})~"},
            {"The spacecraft has a maximum thrust of -0.5 N, a specific impulse of 2000 s and an initial mass of "
             "1000 kg.",
             "sun -engine", R"~({"error": "the maximum thrust must be positive, got -0.5 N"})~"}}}};
}

}  // namespace helios::spec::grammar::forms
