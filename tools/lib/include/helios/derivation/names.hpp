#pragma once
// The grammar of the names in a derivation artifact (schemas/derivation.schema.json), stated once:
// helios-derive makes these names, helios-verify and helios-gen read them, and nothing else spells
// them. x is a state (or a costate, or a target's component), id an interior event's or a
// constraint's id, j a row's number from 1, q a free parameter, label where a value is taken.
//
//   name                      meaning                                        function
//   l_<x>                     the costate of state x                         costate(x), costate_state
//   <x>_t0, <x>_tf            x at the initial / final time                  at_t0(x), at_tf(x)
//   <x>_<id>_m, <x>_<id>_p    x just before / just after event id            before(x, id), after(x, id)
//   <x>_<label>               x at label (t0, tf, <id>_m, <id>_p)            at(x, label)
//   <id>_m, <id>_p            the labels of before / after event id          before_label, after_label
//   <id>_dep                  the label of the departure after id's stay     departure_label(id)
//   t_<id>                    event id's time                                event_time(id)
//   t_<id>_dep                its departure after a stay                     event_departure_time(id)
//   <t>_frac                  the free fraction variable of a time t         fraction(t), event_fraction(id)
//   nu_<id>_<j>               the multiplier of constraint id's row j        multiplier(id, j), is_multiplier_of
//   H_<label>                 H at label (t0, tf, <id>_m, <id>_p)            hamiltonian(label), _label, _before/_after
//   psi_<id>_<j>              row j of constraint id                         constraint_row(id, j)
//   jump_<id>_<x>             the costate jump row of state x at event id    jump_row(id, x)
//   time_<id>                 the row of event id's free time                time_row(id)
//   stationarity_<id>_<q>     the row of event id's free parameter q         stationarity_row(id, q)
//   transversality_<what>     the transversality row of x (at tf), of        transversality_row(what)
//                             <x>_t0, or of a free time t0 / tf
//   <id>_<c>                  component c (rx..vz) of id's target, at id     target_component(id, c)
//                             (<id>_dep_<c>: at the departure after a stay)
//   <name>_rate               the time derivative of a target's component    rate(name)
//   <name>_0                  a coasting target's component at t0            initial_value(name)
//   <x>_<id>_rel              x just before event id relative to its target  relative(x, id)
#include <cstddef>
#include <string>

namespace helios::derivation::names {

// The words of the grammar, for a reader that splits a name at '_' (the LaTeX typesetter).
inline constexpr char kCostate[] = "l", kT0[] = "t0", kTf[] = "tf", kBefore[] = "m", kAfter[] = "p";

inline std::string at(const std::string& name, const std::string& label) {
  return name + "_" + label;
}
inline std::string at_t0(const std::string& name) {
  return at(name, kT0);
}
inline std::string at_tf(const std::string& name) {
  return at(name, kTf);
}

inline std::string before_label(const std::string& id) {
  return at(id, kBefore);
}
inline std::string after_label(const std::string& id) {
  return at(id, kAfter);
}
inline std::string departure_label(const std::string& id) {
  return at(id, "dep");
}
inline std::string before(const std::string& name, const std::string& id) {
  return at(name, before_label(id));
}
inline std::string after(const std::string& name, const std::string& id) {
  return at(name, after_label(id));
}
// True when `name` ends as a value just before or just after an event (..._m, ..._p).
inline bool is_before_or_after(const std::string& name) {
  const auto ends_with = [&](const std::string& end) {
    return name.size() > end.size() && name.compare(name.size() - end.size(), end.size(), end) == 0;
  };
  return ends_with(before_label("")) || ends_with(after_label(""));
}

// The intermediate that holds intermediate q's own partial derivative in state x (dP_in_drx).
inline std::string partial(const std::string& q, const std::string& x) {
  return "d" + q + "_d" + x;
}

inline std::string costate(const std::string& state) {
  return at(kCostate, state);
}
// True when `name` is a costate's (l_<x>, or the bare prefix l_).
inline bool is_costate(const std::string& name) {
  return name.rfind(costate(""), 0) == 0;
}
// The state of costate `name` (the x of l_x); "" when `name` is not a costate's.
inline std::string costate_state(const std::string& name) {
  return is_costate(name) ? name.substr(costate("").size()) : "";
}

inline std::string event_time(const std::string& id) {
  return at("t", id);
}
inline std::string event_departure_time(const std::string& id) {
  return event_time(departure_label(id));
}
inline std::string fraction(const std::string& time) {
  return at(time, "frac");
}
inline std::string event_fraction(const std::string& id) {
  return fraction(event_time(id));
}

inline std::string multiplier_prefix(const std::string& id) {
  return at("nu", id) + "_";
}
inline std::string multiplier(const std::string& id, std::size_t row) {
  return multiplier_prefix(id) + std::to_string(row);
}
// True when `name` is nu_<id>_<j> exactly (an id may itself end in _<n>, as a second visit's does).
inline bool is_multiplier_of(const std::string& name, const std::string& id) {
  const std::string prefix = multiplier_prefix(id);
  return name.size() > prefix.size() && name.rfind(prefix, 0) == 0 &&
         name.find_first_not_of("0123456789", prefix.size()) == std::string::npos;
}

inline std::string hamiltonian(const std::string& label) {
  return at("H", label);
}
// The label of H_<label> ("" for a name that is not a Hamiltonian's value).
inline std::string hamiltonian_label(const std::string& name) {
  const std::string prefix = hamiltonian("");
  return name.size() > prefix.size() && name.rfind(prefix, 0) == 0 ? name.substr(prefix.size()) : "";
}
inline std::string hamiltonian_before(const std::string& id) {
  return hamiltonian(before_label(id));
}
inline std::string hamiltonian_after(const std::string& id) {
  return hamiltonian(after_label(id));
}

inline std::string constraint_row(const std::string& id, std::size_t row) {
  return at(at("psi", id), std::to_string(row));
}
inline bool is_constraint_row(const std::string& name) {
  return name.rfind("psi_", 0) == 0;
}
inline std::string jump_row(const std::string& id, const std::string& state) {
  return at(at("jump", id), state);
}
inline std::string time_row(const std::string& id) {
  return at("time", id);
}
inline std::string stationarity_row(const std::string& id, const std::string& parameter) {
  return at(at("stationarity", id), parameter);
}
inline std::string transversality_row(const std::string& what) {
  return at("transversality", what);
}

inline std::string target_component(const std::string& owner, const std::string& component) {
  return at(owner, component);
}
inline std::string rate(const std::string& name) {
  return at(name, "rate");
}
inline std::string initial_value(const std::string& name) {
  return at(name, "0");
}
inline std::string relative(const std::string& state, const std::string& id) {
  return at(at(state, id), "rel");
}

}  // namespace helios::derivation::names
