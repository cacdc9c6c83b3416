// Endpoint conditions. Initial: the states psi(x(t0)) = 0 fixes have free costates (shooting
// variables); free states would get lambda(t0) = -dPhi/dx(t0). Final: lambda(tf) = lambda0
// dphi/dx + nu^T dpsi/dx. A free final time adds H(tf) + dPhi/dtf = 0, a sliding departure
// -H(t0) + dPhi/dt0 to it (tf = t0 + tof moves with t0).
#include <algorithm>
#include <map>
#include <set>
#include <stdexcept>

#include "conditions.hpp"

namespace helios::pmp {
namespace {

using GiNaC::ex;
using GiNaC::symbol;

// What the endpoint constraints add to the condition of a free time: -H(t0) + dPhi/dt0 and
// H(tf) + dPhi/dtf (nu added by the constraints).
struct TimeConditions {
  ex departure = 0;
  ex final_time;
};

// The solution of `rows` for the multipliers `nus` as a substitution; throws `failure` when
// the rows do not determine them.
GiNaC::exmap multiplier_values(const GiNaC::lst& rows, const GiNaC::lst& nus, const std::string& failure) {
  const ex nu = GiNaC::lsolve(rows, nus);
  if (nu.nops() != nus.nops()) throw std::invalid_argument(failure);
  GiNaC::exmap values;
  for (const auto& r : nu) values[r.lhs()] = r.rhs();
  return values;
}

// psi(x(t0)) = 0 solved for the states it fixes gives the initial values. Where t0 slides or psi
// holds free parameters (a departure orbit's anomaly), lambda(t0) = -nu^T dpsi/dx(t0) gives nu;
// then t0 adds -H(t0) + nu^T dpsi/dt0 to the time condition, and each free parameter q is an
// unknown with the stationarity row nu^T dpsi/dq = 0.
void initial_constraint(Derivation& d, EndpointConditions& c, TimeConditions& time) {
  Problem& p = d.problem;
  auto& S = p.symbols;
  const EndpointConstraint& k = c.constraint;
  GiNaC::lst eqs, unknowns;
  for (const auto& e : k.psi) eqs.append(e == 0);
  for (const auto& s : k.fixed_states) unknowns.append(S.get(s));
  const ex solved = GiNaC::lsolve(eqs, unknowns);
  if (solved.nops() != k.fixed_states.size())
    throw std::invalid_argument("constraint '" + k.id + "' does not determine the initial state it fixes");
  for (const auto& r : solved) d.initial_values.push_back({symbolic::to_text(r.lhs()), r.rhs()});
  if (!p.free_departure && k.free_parameters.empty()) return;
  GiNaC::lst rows, nus;
  for (const auto& m : c.multipliers) nus.append(S.get(m));
  for (const auto& s : k.fixed_states) {
    ex row = S.get(names::at_t0(names::costate(s)));
    for (std::size_t j = 0; j < k.psi.size(); ++j) row += S.get(c.multipliers[j]) * k.psi[j].diff(S.get(s));
    rows.append(row == 0);
  }
  const GiNaC::exmap nu_value =
      multiplier_values(rows, nus, "constraint '" + k.id + "': its multipliers are not determined by lambda(t0)");
  const auto nu_dot = [&](const std::vector<ex>& dpsi) {
    ex sum = 0;
    for (std::size_t j = 0; j < k.psi.size(); ++j) sum += S.get(c.multipliers[j]).subs(nu_value) * dpsi[j];
    return sum;
  };
  for (const auto& q : k.free_parameters) {
    std::vector<ex> dpsi;
    for (const auto& e : k.psi) dpsi.push_back(e.diff(S.get(q.name)));
    d.shooting.variables.push_back(
        {q.name, q.meaning + ", a free parameter of psi at t0", "initial_state", "uniform in its range", {q.lo, q.hi}});
    d.shooting.equations.push_back(
        {names::stationarity_row(k.id, q.name), nu_dot(dpsi).expand(),
         "dPhi/d" + q.name + " = nu^T dpsi/d" + q.name + " = 0 with nu = -lambda(t0): " + q.name + " is free", k.id});
  }
  if (!p.free_departure) return;
  time.departure = -S.get(names::hamiltonian("t0")) + nu_dot(k.psi_t);
  c.time_condition = "-H(t0) + nu^T dpsi/dt0, added to the final time's terms (tf = t0 + tof)";
}

// lambda(tf) - lambda0 dphi/dx - nu^T dpsi/dx = 0; the multipliers of the equality rows are
// solved from the rows of the states they fix (dpsi/dx_J invertible), the other rows remain as
// transversality equations. Where psi fixes no state (multipliers_unknown: an orbit) every row is
// an equation and the multipliers are shooting variables. A bound's multiplier is a shooting
// variable (0 while the bound is inactive). Returns the rows that determine the equality
// multipliers, at tf.
GiNaC::lst final_transversality(Derivation& d, EndpointConditions& c, const GiNaC::exmap& at_tf,
                                std::map<std::string, ex>& free_end) {
  Problem& p = d.problem;
  auto& S = p.symbols;
  const EndpointConstraint& k = c.constraint;
  const ex lambda0 = S.get("lambda0");
  GiNaC::lst touched_rows;
  for (std::size_t i = 0; i < p.states.size(); ++i) {
    const std::string& n = p.states[i].name;
    const symbol x = S.get(n);
    ex row = S.get(names::at_tf(names::costate(n))) - lambda0 * p.endpoint_cost.diff(x);
    free_end[n] = row.subs(at_tf);
    bool touched = false, bounded = false;
    for (std::size_t j = 0; j < k.psi.size(); ++j) {
      const ex dpsi = k.psi[j].diff(x);
      if (dpsi.is_zero()) continue;
      (k.psi_inequality[j] ? bounded : touched) = true;
      row -= S.get(c.multipliers[j]) * dpsi;
    }
    c.transversality.push_back(row);
    if (touched && k.multipliers_unknown) {
      d.shooting.equations.push_back({names::transversality_row(n), row.subs(at_tf),
                                      "lambda_" + n + "(tf) = lambda0 dphi/d" + n + " + nu^T dpsi/d" + n + ": " + n +
                                          "(tf) is free on the target orbit",
                                      k.id});
    } else if (touched) {
      c.eliminated.push_back(row);
      touched_rows.append(row.subs(at_tf) == 0);
    } else {
      d.shooting.equations.push_back(
          {names::transversality_row(n), row.subs(at_tf),
           bounded ? "lambda_" + n + "(tf) = nu^T dpsi/d" + n + ": " + n + "(tf) is free but for a bound"
                   : "lambda_" + n + "(tf) = 0: " + n + "(tf) is free",
           k.id});
    }
  }
  return touched_rows;
}

// The final constraint's rows psi(x(tf)) = 0 and, when tf moves, its terms nu^T dpsi/dtf of
// H(tf) + dPhi/dtf = 0 (Phi = lambda0 phi + nu^T psi) through the target's motion, nu taken
// from the rows it was eliminated with.
void final_constraint(Derivation& d, EndpointConditions& c, TimeConditions& time, const GiNaC::exmap& at_tf) {
  Problem& p = d.problem;
  auto& S = p.symbols;
  const EndpointConstraint& k = c.constraint;
  GiNaC::lst nus;
  for (std::size_t j = 0; j < k.psi.size(); ++j) {
    if (!k.psi_inequality[j] && !k.multipliers_unknown) {
      nus.append(S.get(c.multipliers[j]));
      continue;
    }
    d.shooting.variables.push_back(
        multiplier_variable(c.multipliers[j], "multiplier of " + k.id + ": " + k.psi_names[j], k.psi_inequality[j]));
  }
  std::map<std::string, ex> free_end;  // lambda_s(tf) - lambda0 dphi/dx_s: the row without psi
  const GiNaC::lst touched_rows = final_transversality(d, c, at_tf, free_end);
  for (std::size_t j = 0; j < k.psi.size(); ++j) {
    ShootingEquation eq = constraint_equation(names::constraint_row(k.id, j + 1), k.psi[j].subs(at_tf),
                                              k.kind + " at tf with " + k.id + ": " + k.psi_names[j], k.id,
                                              S.get(c.multipliers[j]), k.psi_inequality[j]);
    // A state free at t0 is held at its guess while the last leg is solved alone, so the row
    // fixing it at tf gives way to that leg's free-end condition.
    if (p.free_initial_mass && !k.psi_inequality[j] && k.psi[j].has(S.get("m"))) eq.alone_expression = free_end.at("m");
    d.shooting.equations.push_back(eq);
  }
  if (!p.free_final_time && !p.free_departure) return;
  c.time_condition = "H(tf) + lambda0*dphi/dtf + nu^T dpsi/dtf = 0 (tf free)";
  if (k.multipliers_unknown) {  // nu are shooting variables
    for (std::size_t j = 0; j < k.psi.size(); ++j) time.final_time += S.get(c.multipliers[j]) * k.psi_t[j].subs(at_tf);
    return;
  }
  const GiNaC::exmap nu_value = multiplier_values(
      touched_rows, nus, "constraint '" + k.id + "': its multipliers are not determined by lambda(tf)");
  for (std::size_t j = 0; j < k.psi.size(); ++j)
    time.final_time += S.get(c.multipliers[j]).subs(nu_value) * k.psi_t[j].subs(at_tf);
}

// The shooting variable and equation of a free departure epoch and of a free final time.
void free_times(Derivation& d, const TimeConditions& time, bool has_final_constraint) {
  const Problem& p = d.problem;
  if (p.free_departure) {
    if (!has_final_constraint) throw std::invalid_argument("a sliding departure needs a constraint at tf");
    d.shooting.variables.push_back(
        {names::fraction("t0"), "departure epoch as a fraction of its window: t0 = t0_min + (t0_max - t0_min)*t0_frac",
         "time_fraction", "uniform in (0, 1)"});
    d.shooting.equations.push_back(
        {names::transversality_row("t0"), (time.departure + time.final_time).expand(),
         "-H(t0) + dPhi/dt0 + H(tf) + dPhi/dtf = 0: t0 slides and tf = t0 + tof moves with it", "departure"});
  }
  if (p.free_final_time) {
    if (!has_final_constraint) throw std::invalid_argument("a free final time needs a constraint at tf");
    d.shooting.variables.push_back({names::fraction("tf"),
                                    "final time as a fraction of its window: tf = tf_min + (tf_max - tf_min)*tf_frac",
                                    "time_fraction", "uniform in (0, 1)"});
    d.shooting.equations.push_back({names::transversality_row("tf"), time.final_time.expand(),
                                    "H(tf) + dPhi/dtf = 0: the final time is free", "final_time"});
  }
}

double value_of(const Problem& p, const std::string& parameter) {
  for (const auto& q : p.parameters)
    if (q.name == parameter) return q.value;
  throw std::logic_error("no parameter " + parameter);
}

}  // namespace

void endpoint_conditions(Derivation& d) {
  Problem& p = d.problem;
  auto& S = p.symbols;
  GiNaC::exmap at_tf;
  for (const auto& s : p.states) at_tf[S.get(s.name)] = S.get(names::at_tf(s.name));
  TimeConditions time;
  time.final_time = S.get(names::hamiltonian("tf")) + S.get("lambda0") * p.endpoint_cost.diff(S.get("t"));
  bool has_final_constraint = false;
  for (const auto& k : p.constraints) {
    EndpointConditions c{k, {}, {}, {}, ""};
    for (std::size_t i = 0; i < k.psi.size(); ++i) c.multipliers.push_back(names::multiplier(k.id, i + 1));
    if (k.at == "t0") {
      initial_constraint(d, c, time);
    } else {
      if (has_final_constraint) throw std::invalid_argument("constraint '" + k.id + "': only one constraint at tf");
      has_final_constraint = true;
      final_constraint(d, c, time, at_tf);
    }
    d.constraints.push_back(c);
  }
  free_times(d, time, has_final_constraint);
}

void initial_costates(Derivation& d) {
  Problem& p = d.problem;
  auto& S = p.symbols;
  std::set<std::string> fixed_at_t0;
  for (const auto& c : d.constraints)
    if (c.constraint.at == "t0") fixed_at_t0.insert(c.constraint.fixed_states.begin(), c.constraint.fixed_states.end());
  const ex lambda0 = S.get("lambda0");
  ex norm2 = GiNaC::pow(lambda0, 2);
  std::set<std::string> sphere = {"lambda0"};
  for (const auto& s : p.states) {
    const std::string lam0 = names::at_t0(names::costate(s.name));
    const symbol lambda_t0 = S.get(lam0);
    const ShootingVariable costate{lam0, "costate of " + s.meaning + " at t0", "",
                                   "uniform in (-1, 1), then normalized"};
    if (fixed_at_t0.count(s.name)) {
      d.shooting.variables.push_back(costate);
    } else if (s.name == "m" && p.free_initial_mass) {
      // Minimum initial mass: m(t0) is a shooting variable, and with no cost on it (the running
      // cost is the fuel) its transversality is lambda_m(t0) = -dPhi/dm(t0) = 0.
      const std::string m0 = names::at_t0(s.name);
      const double most = p.final_mass + value_of(p, "Tmax") / value_of(p, "c") * (p.tf - p.t0);
      d.shooting.variables.push_back({m0,
                                      "initial mass (free: minimized)",
                                      "initial_state",
                                      "uniform in (final mass, final mass + Tmax (tf - t0)/c)",
                                      {p.final_mass, most}});
      d.initial_values.push_back({s.name, S.get(m0)});
      d.shooting.variables.push_back(costate);
      d.shooting.equations.push_back({names::transversality_row(names::at_t0(s.name)), lambda_t0,
                                      "lambda_m(t0) = -dPhi/dm(t0) = 0: the initial mass is free", "initial_mass"});
    } else {
      throw std::invalid_argument("state " + s.name + " is free at t0: not supported by the builtin engine yet");
    }
    norm2 += GiNaC::pow(lambda_t0, 2);
    sphere.insert(lam0);
  }
  // lambda0 and lambda(t0) first (the sphere), then the events' variables, then the time fractions.
  const auto rank = [&](const ShootingVariable& v) {
    return sphere.count(v.name) ? 0 : v.role == "time_fraction" ? 2 : 1;
  };
  std::stable_sort(d.shooting.variables.begin(), d.shooting.variables.end(),
                   [&](const ShootingVariable& a, const ShootingVariable& b) { return rank(a) < rank(b); });
  d.shooting.equations.push_back({"normalization", GiNaC::sqrt(norm2) - 1,
                                  "|(lambda0, lambda(t0))| = 1 (lambda0 inside the sphere normalization)",
                                  "normalization"});
}

}  // namespace helios::pmp
