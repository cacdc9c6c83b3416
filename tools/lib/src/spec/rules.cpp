// The rule table of the controlled English: each sentence form, as a pattern, and its handler.
// A sentence no form matches is read as facts in other words (apply_facts.cpp).
#include "grammar.hpp"

namespace helios::spec::grammar {

void Builder::handle(const std::string& s) {
  static const std::vector<SentenceRule> rules = {
      {re(R"(Problem ([A-Za-z0-9_-]+)\s*:\s*(.+))"), &Builder::on_problem},
      {re(R"(The central body is (?:the )?([A-Za-z]+)(?: with (.+))?)"), &Builder::on_central},
      {re(R"(The spacecraft is an ideal (?:flat )?solar sail with (?:a )?characteristic acceleration (?:of )?)" +
          kQuantity + " at " + kQuantity),
       &Builder::on_sail},
      {re(R"(The dynamics include the J2 (?:perturbation|term) of the central body)"), &Builder::on_j2},
      {re(R"(The dynamics include (?:a|an) (?:perturbing|additional) acceleration ([A-Za-z][A-Za-z0-9_]*) of \[(.+)\]\s*()" +
          kUnit + ")"),
       &Builder::on_accel},
      {re(R"((?:The )?([A-Z][A-Za-z0-9]*) perturbs the spacecraft\b(.*))"), &Builder::on_third_body},
      {re(R"(The (?:total )?time of flight is free,? (?:at most )" + kQuantity + "|between " + kQuantity + " and " +
          kQuantity + ")"),
       &Builder::on_free_tof},
      {re(R"(The spacecraft has (.+))"), &Builder::on_has},
      {re(R"(At the initial time the spacecraft is (?:on|in) (.+\borbit\b.*))"), &Builder::on_depart_orbit},
      {re(R"(The spacecraft departs from (.+) at ((?:t\s*=|MJD2000 |MJD ).+))"), &Builder::on_depart_from},
      {re(R"(The spacecraft departs(?: at (.+?))? from (.+))"), &Builder::on_depart},
      {re(R"(The (?:total )?time of flight is (?:fixed at )?)" + kQuantity), &Builder::on_tof},
      {re(R"(At the final time the spacecraft (?:rendezvouses|must rendezvous) with (.+)|The spacecraft (?:rendezvouses|must rendezvous) with (.+) at the final time)"),
       &Builder::on_arrive},
      {re(R"(At the final time the spacecraft is (?:on|in) (.+\borbit\b.*)|The spacecraft (?:transfers|is transferred|is inserted|must transfer|arrives) (?:in)?to (.+\borbit\b.*?)(?: at the final time)?)"),
       &Builder::on_arrive_orbit},
      {re(R"((?:Between (day|MJD2000|MJD) ()" + kNum + R"() and (day|MJD2000|MJD) ()" + kNum +
          R"(),? )?the spacecraft (?:passes through|crosses|reaches|is (?:on|in)|must (?:pass through|cross|reach|be (?:on|in))) (.+\borbit\b.*?)(?: between (day|MJD2000|MJD) ()" +
          kNum + R"() and (day|MJD2000|MJD) ()" + kNum + R"())?)"),
       &Builder::on_orbit_on_the_way},
      {re(R"(At the final time the spacecraft (?:flies|must fly) by (.+?)(?:,? with a relative speed of at most )" +
          kQuantity + ")?"),
       &Builder::on_arrive_flyby},
      {re(R"(At the final time,? (?!the spacecraft\b)(?:the (?:final )?state (?:satisfies|meets) )?(.+=.+))"),
       &Builder::on_final_conditions},
      {re(R"(Minimi[sz]e (?:the )?(?:initial|launch|departure|wet) mass)"), &Builder::on_initial_mass},
      {re(R"(Minimi[sz]e (?:the )?(?:fuel(?: consumption)?|propellant(?: mass)?|fuel use))"), &Builder::on_fuel},
      {re(R"(Minimi[sz]e (?:the )?(?:time of flight|flight time|final time|transfer time))"), &Builder::on_time},
      {re(R"(Maximi[sz]e (?:the )?final (?:orbital |orbit )?(radius|energy)(?: of the orbit)?)"),
       &Builder::on_final_state_objective},
      {re(R"(The (?:engine|thruster) (?:thrusts|runs|burns|fires) at full (?:throttle|thrust) (?:throughout|all the time|at all times|from start to end))"),
       &Builder::on_full_throttle},
      {re(R"((?:the (?:asteroid|comet|planet|moon|body|object) )?(.+?) moves on an? (?:Keplerian )?orbit (?:about|around) (the central body|(?:the )?[A-Za-z][A-Za-z0-9_]*) with (.+?)(?: at (?:the )?(?:epoch )?(MJD2000|MJD) ()" +
          kNum + "))?"),
       &Builder::on_orbit},
      {re(R"(The (?:following )?(?:bodies|asteroids|comets|planets|targets) move on (?:Keplerian )?orbits (?:about|around) (the central body|(?:the )?[A-Za-z][A-Za-z0-9_]*)(?: with (?:these|the following) elements)?\s*:?)"),
       &Builder::on_intro},
      {re(R"(The departure (?:epoch|date) is free,? between )" + kQuantity + " (before|after) and " + kQuantity +
          " (before|after) (MJD2000|MJD) (" + kNum + ")"),
       &Builder::on_free_dep},
      {re(R"(The departure (?:epoch|date) is free,? within )" + kQuantity + " (?:of|around) (MJD2000|MJD) (" + kNum +
          ")"),
       &Builder::on_free_dep_within},
      {re(R"(The spacecraft (rendezvouses with|must rendezvous with|flies by|must fly by|swings by|must swing by) (.+))"),
       &Builder::on_event},
      {re(R"((?:It|The spacecraft) (?:leaves|drops|releases) (?:a|an) (?:lander|probe|payload|package) of )" +
          kQuantity + " at (.+)"),
       &Builder::on_drop},
  };
  std::smatch m;
  for (const auto& rule : rules)
    if (std::regex_match(s, m, rule.pattern)) return (this->*rule.apply)(m);
  if (detail::states_nothing(s, body_names()))
    throw sentence_error("it matches no form of the controlled English (see tools/lib/src/spec/LANGUAGE.md)");
  apply_facts(facts_of(s));
}

}  // namespace helios::spec::grammar
