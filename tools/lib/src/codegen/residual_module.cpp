// The RESIDUAL module: the shooting function (by legs with events); the legs' plans are plans.cpp.
#include "body.hpp"
#include "context.hpp"
#include "plans.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace helios::codegen::detail {
namespace {

// Runtime-evaluated parameters grouped by source "<kind>:<what>:<event>", names in order.
std::map<std::string, std::vector<std::string>> runtime_parameters(const Context& c, const std::string& kind) {
  std::map<std::string, std::vector<std::string>> groups;
  for (const auto& p : c.parameter_quantities)
    if (p.source.rfind(kind + ":", 0) == 0) groups[p.source.substr(kind.size() + 1)].push_back(p.name);
  for (const auto& [key, names] : groups)
    if (names.size() != 6)
      throw std::invalid_argument("field /parameters: " + kind + " target " + key + " needs 6 components, got " +
                                  std::to_string(names.size()));
  return groups;
}

// The C++ local holding the time of `event`: t0, tf, an interior event's epoch t_<id> or the end
// of its stay t_<id>_dep.
std::string event_time(const Context& c, const std::string& event) {
  if (event == "t0" || event == "tf") return event;
  for (const auto& id : c.events)
    if (event == id || event == names::departure_label(id)) return names::event_time(event);
  throw std::invalid_argument("field /parameters: unknown event '" + event + "' (t0, tf or an interior event)");
}

// coast_dynamics: the right-hand side of a coasting target's two-body motion.
std::string coast_dynamics_function(Context& c) {
  const derivation::CoastDynamics& coast = *c.coast_dynamics;
  const auto& names = coast.states;
  if (names.size() != 6 || coast.rhs.size() != 6)
    throw std::invalid_argument("field /coast_dynamics: a coasting target has 6 states and 6 right-hand sides");
  Body body(c);
  for (std::size_t i = 0; i < names.size(); ++i) body.unpack(names[i], "y[" + std::to_string(i) + "]");
  for (std::size_t i = 0; i < names.size(); ++i)
    body.code() << "  dy[" << i << "] = " << body.cpp(c.parsed(coast.rhs[i])) << ";\n";
  return "void coast_dynamics(const double* y, double* dy) {\n" + body.str() + "}\n\n";
}

// The expression of event k's costate map entry i that is not a shooting variable.
const derivation::Expression& costate_expression(const derivation::CostateMapEntry& m, std::size_t k, std::size_t i) {
  if (!m.expression)
    throw std::invalid_argument("field /events/" + std::to_string(k) + "/costate_map/" + std::to_string(i) +
                                ": neither a variable nor an expression");
  return *m.expression;
}

// The shooting function's body, written step by step (variables, epochs, targets, the start,
// each event, the end), and the number of equations of each leg solved alone.
class ShootingFunction {
 public:
  explicit ShootingFunction(Context& c)
      : c_(c), eqs_(c.shooting.equations), vars_(c.shooting.variables), events_(c.interior_events), body_(c, "T") {}

  // The function template shooting_residual on the scalar T (with `legs` when the problem has
  // events), shooting_function (or shooting_legs) on double, and with `jacobian` shooting_jacobian
  // on dual numbers.
  std::string text(bool jacobian);
  // The equations of each leg alone (known after text()).
  const std::vector<int>& leg_sizes() const { return leg_sizes_; }

 private:
  void unpack_variables();
  void epochs();
  bool window_map(const derivation::Times& times) const;
  void targets();
  void start();
  void event(std::size_t k);
  void relative_to_target(const std::string& id);
  void leg_alone_at_event(std::size_t k);
  void jump(std::size_t k);
  void end();

  // Equation i's code from its expression (`alone`: its alone_expression); a bound's row goes
  // through bound_row (its multiplier while inactive).
  std::string equation_code(std::size_t i, bool alone);
  // The row F[row++] of a leg alone: the equation called `name`, from its alone_expression when
  // `alone` and it has one.
  void alone_row(int& row, const std::string& name, bool alone = false);
  // H just before or after an event (`at`), at `time`, if the derivation asks for it.
  void evaluate_h(const std::string& at, const std::string& time);
  // Locals for y[] named <state>_<label>, <costate>_<label> (names::at).
  void unpack_y(const std::string& label);
  // The conditions g > 0 the rows leave to the runtime, recorded on the propagator in order
  // (side_condition; the runtime's Shape reads them).
  // `at` renames their symbols to the locals of where they are evaluated.
  void side_conditions(const std::vector<derivation::SideCondition>& sides, const GiNaC::exmap& at = {});

  Context& c_;
  const std::vector<derivation::ShootingEquation>& eqs_;
  const std::vector<derivation::ShootingVariable>& vars_;
  const std::vector<derivation::Event>& events_;
  Body body_;
  std::map<std::string, std::string> hamiltonian_at_;  // event value names by where H is evaluated
  std::vector<int> leg_sizes_;
  int side_condition_count_ = 0;  // recorded so far (each one's index on the propagator)
};

std::string ShootingFunction::text(bool jacobian) {
  unpack_variables();
  epochs();
  targets();
  start();
  for (std::size_t k = 0; k < events_.size(); ++k) event(k);
  end();
  const bool legs = !events_.empty();
  // NOTE: -O2 on the module's Dual instantiation costs g++ 20 s for S10's long expressions, -O0
  // about 4 s; the module runs once per Newton iteration, outside the integration, so its
  // optimization buys little.
  std::string o =
      std::string(jacobian ? "// The module on Dual compiles at -O0 (it runs outside the integration's loop).\n"
                             "#pragma GCC push_options\n#pragma GCC optimize(\"O0\")\n"
                           : "") +
      "// The shooting function on its scalar T: double, or Dual for the exact Jacobian.\n" +
      std::string(
          legs ? "// With `legs`: multiple shooting (the costates after each event are legs->starts, their mismatch\n"
                 "// with the jump conditions goes to legs->continuity), or one leg alone (legs->stop_at).\n"
               : "") +
      "template <class T>\nvoid shooting_residual(const T* x, double eps, Propagator& prop, T* F" +
      (legs ? ", const LegsOf<T>* legs" : "") +
      ") {\n"
      "  using std::abs, std::acos, std::asin, std::atan, std::atan2, std::cos, std::exp, std::log, std::pow, "
      "std::sin,\n"
      "      std::sqrt, std::tan;\n" +
      body_.str() + "}\n\n";
  if (legs)
    o += "void shooting_legs(const double* x, double eps, Propagator& prop, double* F, const Legs* legs) {\n"
         "  shooting_residual(x, eps, prop, F, legs);\n}\n\n";
  else
    o += "void shooting_function(const double* x, double eps, Propagator& prop, double* F) {\n"
         "  shooting_residual(x, eps, prop, F);\n}\n\n";
  if (jacobian) {
    o += "// The exact Jacobian: the shooting function on dual numbers (its propagations by the variational\n"
         "// equations of the JACOBIAN module).\n"
         "void shooting_jacobian(const double* x, double eps, Propagator& prop, double* F, double* J) {\n"
         "  dual_jacobian(problem::kNumVars, x, F, J, [&](const Dual* xd, Dual* Fd) {\n"
         "    shooting_residual(xd, eps, prop, Fd" +
         std::string(legs ? ", static_cast<const LegsOf<Dual>*>(nullptr)" : "") + ");\n  });\n}\n\n";
    if (legs)
      o += "void shooting_legs_dual(const Dual* x, double eps, Propagator& prop, Dual* F, const LegsOf<Dual>* legs) {\n"
           "  shooting_residual(x, eps, prop, F, legs);\n}\n\n";
    else
      o += "void shooting_function_dual(const Dual* x, double eps, Propagator& prop, Dual* F) {\n"
           "  shooting_residual(x, eps, prop, F);\n}\n\n";
    o += "#pragma GCC pop_options\n\n";
  }
  return o;
}

std::string ShootingFunction::equation_code(std::size_t i, bool alone) {
  const std::string code = body_.cpp(c_.parsed(alone ? *eqs_[i].alone_expression : eqs_[i].expression));
  // A time window's transversality row, which the runtime may hold at the window's edge.
  for (const char* time : {"t0", "tf"})
    for (std::size_t k = 0; k < vars_.size(); ++k)
      if (eqs_[i].name == names::transversality_row(time) && vars_[k].name == names::fraction(time))
        return "window_row(prop, " + std::to_string(k) + ", " + body_.cpp(c_.symbols.get(vars_[k].name)) + ", " + code +
               ")";
  if (!eqs_[i].inequality) return code;
  int bound = 0;
  for (std::size_t j = 0; j < i; ++j) bound += eqs_[j].inequality ? 1 : 0;
  return "bound_row(prop, " + std::to_string(bound) + ", " + code + ", " +
         body_.cpp(c_.parsed(eqs_[i].inequality->inactive_expression)) + ")";
}

void ShootingFunction::alone_row(int& row, const std::string& name, bool alone_wanted) {
  for (std::size_t i = 0; i < eqs_.size(); ++i) {
    if (eqs_[i].name != name) continue;
    const bool alone = alone_wanted && eqs_[i].alone_expression;
    body_.code() << "    F[" << row++ << "] = " << equation_code(i, alone) << ";  // "
                 << comment_text(eqs_[i].meaning +
                                 (alone ? " (alone: " + eqs_[i].alone_expression->text + " = 0)" : ""))
                 << "\n";
    return;
  }
  throw std::invalid_argument("field /shooting/equations: no equation " + name);
}

void ShootingFunction::evaluate_h(const std::string& at, const std::string& time) {
  const auto it = hamiltonian_at_.find(at);
  if (it == hamiltonian_at_.end()) return;
  body_.code() << "  const T " << it->second << " = optimal_hamiltonian(" << time << ", y, mult);\n";
  hamiltonian_at_.erase(it);
}

void ShootingFunction::unpack_y(const std::string& label) {
  for (std::size_t i = 0; i < c_.states.size(); ++i)
    body_.unpack(names::at(c_.states[i], label), "y[" + std::to_string(i) + "]");
  for (std::size_t i = 0; i < c_.costates.size(); ++i)
    body_.unpack(names::at(c_.costates[i], label), "y[" + std::to_string(c_.states.size() + i) + "]");
}

void ShootingFunction::side_conditions(const std::vector<derivation::SideCondition>& sides, const GiNaC::exmap& at) {
  for (const auto& side : sides)
    body_.code() << "  side_condition(prop, " << side_condition_count_++ << ", "
                 << body_.cpp(c_.parsed(side.expression).subs(at)) << ", " << cpp_string(side.meaning) << ");\n";
}

// The shooting variables x[] as locals, each with its meaning.
void ShootingFunction::unpack_variables() {
  for (std::size_t i = 0; i < vars_.size(); ++i)
    body_.unpack(vars_[i].name, "x[" + std::to_string(i) + "]", vars_[i].meaning);
}

// Whether tf_expression is the map of tf_frac onto the final time's window, tf_min + (tf_max -
// tf_min) tf_frac: then the program writes it with the window's parameters kTfMin and kTf, which
// the runtime's thrust continuation scales (a sliding departure's tf moves with t0 instead).
bool ShootingFunction::window_map(const derivation::Times& times) const {
  if (times.tf_window.size() != 2 || times.t0_expression) return false;
  const GiNaC::symbol frac = c_.symbols.get(names::fraction("tf"));
  const GiNaC::ex tf = c_.parsed(*times.tf_expression);
  const auto free = symbolic::free_symbols(tf);
  if (free.size() > 1 || (free.size() == 1 && *free.begin() != frac.get_name()) || !tf.is_polynomial(frac) ||
      tf.degree(frac) > 1)
    return false;
  for (const double at : {0.0, 1.0}) {
    const GiNaC::ex value = tf.subs(frac == at).evalf();
    const double want = times.tf_window[0] + (times.tf_window[1] - times.tf_window[0]) * at;
    if (!GiNaC::is_a<GiNaC::numeric>(value) ||
        std::fabs(GiNaC::ex_to<GiNaC::numeric>(value).to_double() - want) > 1e-12 * std::max(1.0, std::fabs(want)))
      return false;
  }
  return true;
}

// t0, tf and the epochs of the interior events (a stay ends at t_<id>_dep), checked to be in order.
void ShootingFunction::epochs() {
  const derivation::Times& times = c_.times;
  auto& o = body_.code();
  o << "  const T t0 = "
    << (times.t0_expression ? body_.cpp(c_.parsed(*times.t0_expression)) : std::string("problem::kT0")) << ";\n";
  if (times.tf_expression && window_map(times))
    o << "  const T tf = problem::kTfMin + (problem::kTf - problem::kTfMin) * "
      << body_.cpp(c_.symbols.get(names::fraction("tf"))) << ";  // times.tf_expression\n";
  else if (times.tf_expression)
    o << "  const T tf = " << body_.cpp(c_.parsed(*times.tf_expression)) << ";\n";
  else
    o << "  const T tf = problem::kTf;\n";
  std::string order = "t0";
  for (std::size_t k = 0; k < events_.size(); ++k) {
    const derivation::Event& e = events_[k];
    const std::string t = names::event_time(e.id), departure = names::event_departure_time(e.id);
    o << "  const T " << t << " = " << body_.cpp(c_.parsed(e.time_expression)) << ";\n"
      << "  const T " << departure << " = " << t << " + " << number(e.duration) << ";\n";
    order += ", " + t + ", " + departure;
  }
  order += ", tf";
  o << "  {\n    const T epochs[] = {" << order << "};\n"
    << "    for (std::size_t k = 1; k < sizeof epochs / sizeof epochs[0]; ++k)\n"
    << "      if (!(epochs[k] >= epochs[k - 1]) || (k % 2 == 1 && !(epochs[k] > epochs[k - 1])))\n"
    << "        throw numerical_error(\"the event epochs are out of order\");\n  }\n"
    << "  T y[kNY];\n";
}

// Targets evaluated at the actual event time, in normalized units: a planet's state or rate from
// the ephemeris, a coasting target's state; the call is written if one of its components is used.
void ShootingFunction::targets() {
  int block = 0;
  for (const char* kind : {"ephemeris", "ephemeris_rate", "coast"})
    for (const auto& [key, components] : runtime_parameters(c_, kind)) {
      const std::string what = key.substr(0, key.find(':')), event = key.substr(key.find(':') + 1);
      const std::string var = std::string(kind) + "_" + std::to_string(block++);
      std::string call;
      if (std::string(kind) == "coast") {
        std::string start;
        for (const auto& n : components) {
          const std::string initial = names::initial_value(n);
          if (index_of(c_.parameters, initial) < 0)
            throw std::invalid_argument("field /parameters: coasting target " + what + " has no initial value " +
                                        initial);
          start += (start.empty() ? "" : ", ") + std::string("problem::") + initial;
        }
        call = "coast_state({" + start + "}, problem::kT0, " + event_time(c_, event) + ")";
      } else {
        const std::string function = std::string(kind) == "ephemeris" ? "ephemeris_state" : "ephemeris_rate";
        call = function + "(\"" + what + "\", " + event_time(c_, event) + ")";
      }
      body_.unpack_line("  const auto " + var + " = " + call + ";\n", components);
      for (std::size_t i = 0; i < 6; ++i) body_.unpack(components[i], var + "[" + std::to_string(i) + "]");
    }
}

// Initial states from psi(t0) = 0, initial costates from the shooting variables; the multipliers.
void ShootingFunction::start() {
  auto& o = body_.code();
  for (const auto& iv : c_.initial_values) {
    const int k = index_of(c_.states, iv.state);
    if (k < 0) throw std::invalid_argument("field /initial_values: unknown state " + json(iv.state).dump());
    o << "  y[" << k << "] = " << body_.cpp(c_.symbols.parse(iv.value.text, "field /initial_values/" + iv.state))
      << ";\n";
  }
  for (std::size_t i = 0; i < c_.costates.size(); ++i) {
    const std::string v = names::at_t0(c_.costates[i]);
    bool found = false;
    for (const auto& var : vars_) found = found || var.name == v;
    if (!found) throw std::invalid_argument("field /shooting/variables: no variable " + v + " for the initial costate");
    o << "  y[" << c_.states.size() + i << "] = " << body_.use(v) << ";\n";
  }
  o << "  const auto mult = multipliers(T(" << body_.use(c_.multiplier) << "), eps);\n";
  // Event values: H just before / after an event, under the optimal control.
  for (const auto& e : c_.event_value_list) {
    if (e.kind.value_or("") != "hamiltonian")
      throw std::invalid_argument("field /event_values: the runtime evaluates H only, not " + e.name + " (kind '" +
                                  e.kind.value_or("") + "')");
    hamiltonian_at_[e.at.value_or("tf")] = e.name;
  }
  evaluate_h("t0", "t0");
}

// Event k: the leg up to it, its values just before (<name>_<id>_m), the leg alone's end, the
// jump, its values just after (<name>_<id>_p).
void ShootingFunction::event(std::size_t k) {
  const derivation::Event& e = events_[k];
  const std::string& id = e.id;
  const std::string from = k == 0 ? "t0" : names::event_departure_time(events_[k - 1].id);
  body_.code() << "  propagate(prop, " << from << ", " << names::event_time(id) << ", y, mult);\n";
  unpack_y(names::before_label(id));
  side_conditions(e.must_be_positive);
  relative_to_target(id);
  evaluate_h(names::before_label(id), names::event_time(id));
  leg_alone_at_event(k);
  jump(k);
  const auto& costate_map = e.costate_map;
  for (std::size_t i = 0; i < c_.states.size(); ++i)
    body_.unpack(names::after(c_.states[i], id), "y[" + std::to_string(i) + "]");
  for (std::size_t i = 0; i < c_.costates.size(); ++i)
    if (!costate_map[i].variable || *costate_map[i].variable != names::after(c_.costates[i], id))
      body_.unpack(names::after(c_.costates[i], id), "y[" + std::to_string(c_.states.size() + i) + "]");
  evaluate_h(names::after_label(id), names::event_departure_time(id));
}

// The spacecraft's position and velocity just before event `id` relative to the event's target
// (a planet's or a coasting body's state there), as locals <state>_<id>_rel for the rows that
// print shorter in them. Cartesian states only.
void ShootingFunction::relative_to_target(const std::string& id) {
  static const std::vector<std::string> cartesian = {"rx", "ry", "rz", "vx", "vy", "vz"};
  if (c_.states.size() < cartesian.size() || !std::equal(cartesian.begin(), cartesian.end(), c_.states.begin())) return;
  for (const char* kind : {"ephemeris", "coast"})
    for (const auto& [key, components] : runtime_parameters(c_, kind)) {
      if (key.substr(key.find(':') + 1) != id) continue;
      const auto name = [&](std::size_t i) { return names::relative(cartesian[i], id); };
      for (std::size_t i = 0; i < cartesian.size(); ++i)
        if (c_.symbols.has(name(i))) return;  // a name the derivation has: no relative locals
      for (std::size_t i = 0; i < cartesian.size(); ++i)
        body_.relative(name(i), names::before(cartesian[i], id), components[i]);
      return;
    }
}

// Leg k alone ends at event k as if the trajectory ended: its conditions c = 0 and lambda(t+) = 0
// (the shooting variables of lambda(t+) are 0 in leg mode); leg 0 carries the normalization.
void ShootingFunction::leg_alone_at_event(std::size_t k) {
  const derivation::Event& e = events_[k];
  const std::string& id = e.id;
  body_.code() << "  if (legs && legs->stop_at == " << k << ") {\n";
  int row = 0;
  if (k == 0) alone_row(row, "normalization");
  for (std::size_t j = 0; j < e.psi.size() - c_.states.size(); ++j)
    alone_row(row, names::constraint_row(id, j + 1), true);
  for (std::size_t i = 0; i < c_.costates.size(); ++i) {
    const derivation::CostateMapEntry& m = e.costate_map.at(i);
    if (m.variable)
      alone_row(row, names::jump_row(id, c_.states[i]));
    else
      body_.code() << "    F[" << row++ << "] = " << body_.cpp(c_.parsed(costate_expression(m, k, i))) << ";  // "
                   << "costate " << c_.costates[i] << " just after " << id << " = 0 (the leg alone ends there)\n";
  }
  body_.code() << "    return;\n  }\n";
  leg_sizes_.push_back(row);
}

// x+ = g(x-), lambda+ from the jump rows (or a shooting variable); with `legs`, the costates
// after the event are the leg's starts instead, their mismatch the continuity.
void ShootingFunction::jump(std::size_t k) {
  const derivation::Event& e = events_[k];
  const std::string where = "/events/" + std::to_string(k);
  const auto& state_map = e.state_map;
  const auto& costate_map = e.costate_map;
  if (state_map.size() != c_.states.size() || costate_map.size() != c_.costates.size())
    throw std::invalid_argument("field " + where + ": state_map and costate_map need one entry per state");
  auto& o = body_.code();
  for (std::size_t i = 0; i < c_.states.size(); ++i) {
    if (state_map[i].state != c_.states[i] || costate_map[i].costate != c_.costates[i])
      throw std::invalid_argument("field " + where + ": the maps must follow the state order");
    o << "  y[" << i << "] = " << body_.cpp(c_.parsed(state_map[i].expression)) << ";\n";
  }
  for (std::size_t i = 0; i < c_.costates.size(); ++i) {
    const derivation::CostateMapEntry& m = costate_map[i];
    const std::string value = m.variable ? body_.use(*m.variable) : body_.cpp(c_.parsed(costate_expression(m, k, i)));
    o << "  y[" << c_.states.size() + i << "] = " << value << ";\n";
  }
  o << "  if (legs) {\n"
    << "    for (int i = 0; i < problem::kNumStates; ++i) {\n"
    << "      const T start = legs->starts[" << k << " * problem::kNumStates + i];\n"
    << "      if (legs->continuity) legs->continuity[" << k
    << " * problem::kNumStates + i] = y[problem::kNumStates + i] - start;\n"
    << "      y[problem::kNumStates + i] = start;\n    }\n  }\n";
}

// The last leg to tf, the values there (<name>_tf), the last leg alone's rows (the final
// constraint's own equations, its epoch held at its guess) and the rows of the whole problem.
void ShootingFunction::end() {
  const std::string from = events_.empty() ? "t0" : names::event_departure_time(events_.back().id);
  body_.code() << "  propagate(prop, " << from << ", tf, y, mult);\n";
  unpack_y("tf");
  GiNaC::exmap final_states;  // a constraint's rows at tf are in the states' own symbols
  for (const auto& x : c_.states) final_states[c_.symbols.get(x)] = c_.symbols.get(names::at(x, "tf"));
  for (const auto& k : c_.constraints)
    if (k.at == "tf") side_conditions(k.must_be_positive, final_states);
  evaluate_h("tf", "tf");
  if (!hamiltonian_at_.empty())
    throw std::invalid_argument("field /event_values: no event '" + hamiltonian_at_.begin()->first + "'");
  if (!events_.empty()) {
    std::string final_id;
    for (const auto& k : c_.constraints)
      if (k.at == "tf") final_id = k.id;
    body_.code() << "  if (legs && legs->stop_at == " << events_.size() << ") {\n";
    int row = 0;
    for (std::size_t i = 0; i < eqs_.size(); ++i)
      if (eqs_[i].source == final_id) alone_row(row, eqs_[i].name, true);
    body_.code() << "    return;\n  }\n";
    leg_sizes_.push_back(row);
  }
  for (std::size_t i = 0; i < eqs_.size(); ++i) {
    const double scale = eqs_[i].scale;
    body_.code() << "  F[" << i << "] = (" << equation_code(i, false) << ")";
    if (scale != 1.0) body_.code() << " / " << number(scale);
    body_.code() << ";  // " << comment_text(eqs_[i].meaning) << "\n";
  }
}

}  // namespace

std::string residual_module(Context& c, bool jacobian) {
  const auto& vars = c.shooting.variables;
  const auto& eqs = c.shooting.equations;
  if (vars.size() != eqs.size())
    throw std::invalid_argument("field /shooting: " + std::to_string(vars.size()) + " variables but " +
                                std::to_string(eqs.size()) + " equations");
  std::string o =
      "// ----- module RESIDUAL (generated) -------------------------------------------------------\n"
      "namespace helios_rt {\n\n";
  if (c.coast_dynamics) o += coast_dynamics_function(c);
  ShootingFunction shooting(c);
  o += shooting.text(jacobian);
  if (!c.interior_events.empty()) o += legs_block(c, shooting.leg_sizes());
  return o + "}  // namespace helios_rt\n";
}

}  // namespace helios::codegen::detail
