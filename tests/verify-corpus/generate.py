#!/usr/bin/env python3
"""Generates the helios-verify accuracy corpus (issue 4, item 4).

Seeds (tests/verify-corpus/seed/):
  S01.json         builtin derivation (helios-parse scenarios/S01/problem.txt | helios-derive -);
                   refreshed with --bin build/bin, else the committed copy is used
Bases (tests/verify-corpus/base/, committed with the engine): builtin S05, S06, S11, S12, and the
  builtin derivations E-flyby, E-stay, E-ga, E-slide of the specs base/E-*.spec.json (interior events:
  a flyby, a stay with a mass drop, a gravity assist; a sliding departure); refreshed with --bin.
  S05h.json        Earth J2 orbit transfer, fixed tf, minimum fuel        (written here)
  S06h.json        S05h with a coasting target under J2 (coast_dynamics)   (written here)
  S11h.json        solar sail, minimum time, free tf, Mars ephemeris       (written here)
  S01f.json        S01 with a free final time against a moving Mars       (written here)
The hand-written seeds take their derivatives from SymPy, a different CAS from the verifier's
GiNaC, and follow the derivation format of schemas/derivation.schema.json.

Cases are seeds and bases rewritten in equivalent algebraic forms (must pass) or deliberately broken
(must fail exactly the listed checks). Each is stored as an RFC 6902 JSON Patch against its seed or
base (tests/verify-corpus/cases/<name>.patch.json, see diff()); a case that is its base unchanged has
no patch. manifest.json lists them: name, base, patch, expected verdict and failing checks.
Run from anywhere: python3 tests/verify-corpus/generate.py [--bin build/bin]. Needs sympy.
"""
import copy
import json
import pathlib
import re
import subprocess
import sys

import sympy as sp

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def g(e):
    """GiNaC parser syntax for a SymPy expression."""
    return str(e).replace("**", "^")


def write(path, doc):
    path.write_text(json.dumps(doc, indent=2) + "\n")


def pointer(path):
    """RFC 6901 JSON Pointer of a path of keys and indices."""
    return "".join("/" + str(k).replace("~", "~0").replace("/", "~1") for k in path)


def diff(a, b, path=()):
    """RFC 6902 JSON Patch that turns `a` into `b`: the leaves that differ are replaced, object keys
    removed or added, an array is replaced whole only when its length changed, an object only when
    its keys' order could not be kept (added keys are appended)."""
    if isinstance(a, dict) and isinstance(b, dict):
        common = [k for k in a if k in b]
        if list(b) != common + [k for k in b if k not in a]:
            return [{"op": "replace", "path": pointer(path), "value": b}]
        ops = [{"op": "remove", "path": pointer(path + (k,))} for k in a if k not in b]
        for k in b:
            if k in a:
                ops += diff(a[k], b[k], path + (k,))
            else:
                ops.append({"op": "add", "path": pointer(path + (k,)), "value": b[k]})
        return ops
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        return [op for i, (x, y) in enumerate(zip(a, b)) for op in diff(x, y, path + (i,))]
    if type(a) is type(b) and a == b:
        return []
    return [{"op": "replace", "path": pointer(path), "value": b}]


def write_patch(path, ops):
    """A patch with one operation a line."""
    path.write_text("[\n" + ",\n".join("  " + json.dumps(op) for op in ops) + "\n]\n")


# --------------------------------------------------------------------------------------------
# Shared symbols

RX, RY, RZ, VX, VY, VZ, M = sp.symbols("rx ry rz vx vy vz m")
LRX, LRY, LRZ, LVX, LVY, LVZ, LM = sp.symbols("l_rx l_ry l_rz l_vx l_vy l_vz l_m")
L0, EPS, U, AX, AY, AZ = sp.symbols("lambda0 eps u ax ay az")
MU, TMAX, C = sp.symbols("mu Tmax c")
R2 = RX**2 + RY**2 + RZ**2
POS, VEL = [RX, RY, RZ], [VX, VY, VZ]
LPOS, LVEL = [LRX, LRY, LRZ], [LVX, LVY, LVZ]
AXES = "xyz"


def fixed_state_target(state, units):
    """The spec's target of a state given in normalized units (km, km/s)."""
    speed = units["length_km"] / units["time_s"]
    return {"kind": "fixed_state", "position_km": [x * units["length_km"] for x in state[:3]],
            "velocity_km_s": [x * speed for x in state[3:]]}


def named_states(with_mass, length, time):
    out = []
    for k in AXES:
        out.append({"name": f"r{k}", "meaning": f"position {k}", "unit": length, "costate": f"l_r{k}"})
    for k in AXES:
        out.append({"name": f"v{k}", "meaning": f"velocity {k}", "unit": f"{length}/{time}", "costate": f"l_v{k}"})
    if with_mass:
        out.append({"name": "m", "meaning": "mass", "unit": "initial mass", "costate": "l_m"})
    return out


def odes(states, rhs_state, rhs_costate):
    return ([{"state": s["name"], "rhs": r} for s, r in zip(states, rhs_state)],
            [{"costate": s["costate"], "rhs": r} for s, r in zip(states, rhs_costate)])


def variable(name, meaning):
    return {"name": name, "meaning": meaning, "scale": 1, "init": "uniform in (-1, 1), then normalized"}


def equation(name, expression, meaning, source):
    return {"name": name, "expression": expression, "meaning": meaning, "scale": 1, "source": source}


# --------------------------------------------------------------------------------------------
# S05h / S06h: Earth-centred two-body + J2 (R_E = 1, mu = 1), minimum fuel, fixed tf.

J2, RE = sp.symbols("J2 R_E")


def j2_gravity(x, y, z):
    """-mu r/r^3 + a_J2, a_J2 = -(3/2) J2 mu R_E^2 / r^5 ((1 - 5 z^2/r^2) x, (1 - 5 z^2/r^2) y, (3 - 5 z^2/r^2) z)."""
    r2 = x**2 + y**2 + z**2
    k = -sp.Rational(3, 2) * J2 * MU * RE**2
    return [sp.expand_mul(-MU * q * r2 ** sp.Rational(-3, 2) + k * q * r2 ** sp.Rational(-5, 2) * (w - 5 * z**2 / r2))
            for q, w in ((x, 1), (y, 1), (z, 3))]


def s05h(s01):
    d = copy.deepcopy(s01)
    d["problem"] = {"id": "S05h", "dynamics_model": "two_body_j2_cartesian_low_thrust", "objective": "minimum_fuel"}
    d["producer"] = {"tool": "tests/verify-corpus/generate.py", "version": "1", "backend": "llm", "model": "hand"}
    d["units"] = {"length": "Earth radius", "length_km": 6378.137, "time": "TU", "time_s": 806.8109913067327,
                  "mass_kg": 1000.0}
    d["times"] = {"t0": 0.0, "tf": 60.0, "final_time": "fixed"}
    values = {"mu": 1.0, "Tmax": 0.0020, "c": 2.5, "J2": 1.08262668e-3, "R_E": 1.0}
    dep = [1.1, 0.0, 0.0, 0.0, 0.95346259, 0.0]
    arr = [-1.3, 0.5, 0.35, -0.35, -0.72, 0.18]
    params = []
    for name, value, meaning in [("mu", 1.0, "gravitational parameter of the Earth"),
                                 ("J2", values["J2"], "J2 zonal coefficient of the Earth"),
                                 ("R_E", 1.0, "equatorial radius of the Earth"),
                                 ("Tmax", values["Tmax"], "maximum thrust"),
                                 ("c", values["c"], "exhaust velocity Isp*g0")]:
        params.append({"name": name, "meaning": meaning, "unit": "normalized", "value": value})
    for prefix, vals in (("departure", dep), ("arrival", arr)):
        for k, v in zip(["rx", "ry", "rz", "vx", "vy", "vz"], vals):
            params.append({"name": f"{prefix}_{k}", "meaning": f"{k} of the {prefix} state", "unit": "normalized",
                           "value": v})
    d["parameters"] = params
    for c, vals in zip(d["constraints"], (dep, arr)):
        c["target"] = fixed_state_target(vals, d["units"])
    d["terms"] = [{"name": "two_body", "kind": "force", "parameters": ["mu"]},
                  {"name": "j2", "kind": "force", "parameters": ["J2", "R_E"]},
                  {"name": "thrust", "kind": "force", "parameters": ["Tmax", "c"]},
                  {"name": "fuel", "kind": "cost", "parameters": ["Tmax", "c"]}]
    grav = j2_gravity(RX, RY, RZ)
    thrust = [TMAX * U * a / M for a in (AX, AY, AZ)]
    f = VEL + [grav[k] + thrust[k] for k in range(3)] + [-TMAX * U / C]
    L = TMAX / C * (U - EPS * U + EPS * U**2)
    xs = POS + VEL + [M]
    ls = LPOS + LVEL + [LM]
    H = L0 * L + sum(l * fi for l, fi in zip(ls, f))
    d["dynamics"]["state_rhs"] = [g(e) for e in f]
    d["hamiltonian"] = g(sp.expand_mul(H))
    costates = [sp.expand_mul(-sp.diff(H, x)) for x in xs]
    d["state_odes"], d["costate_odes"] = odes(d["states"], [g(e) for e in f], [g(e) for e in costates])
    return d, (H, f, xs, ls)


def s06h(s05):
    d = copy.deepcopy(s05)
    d["problem"]["id"] = "S06h"
    d["problem"]["dynamics_model"] = "two_body_j2_cartesian_low_thrust_coasting_target"
    for p in d["parameters"]:
        if p["name"].startswith("arrival_"):
            p["source"] = "coast:arrival:tf"
            p["meaning"] = p["meaning"].replace("arrival state", "coasting target at tf")
    target0 = [-1.2, 0.6, 0.3, -0.4, -0.7, 0.2]
    for k, v in zip(["rx", "ry", "rz", "vx", "vy", "vz"], target0):
        d["parameters"].append({"name": f"target0_{k}", "meaning": f"{k} of the coasting target at t0",
                                "unit": "normalized", "value": v})
    d["constraints"][1]["target"] = fixed_state_target(target0, d["units"]) | {"kind": "coasting"}
    tx, ty, tz, tvx, tvy, tvz = sp.symbols("tgt_rx tgt_ry tgt_rz tgt_vx tgt_vy tgt_vz")
    d["coast_dynamics"] = {"states": ["tgt_rx", "tgt_ry", "tgt_rz", "tgt_vx", "tgt_vy", "tgt_vz"],
                           "rhs": [g(e) for e in [tvx, tvy, tvz] + j2_gravity(tx, ty, tz)]}
    return d


# --------------------------------------------------------------------------------------------
# S11h: ideal flat sail, minimum time, free tf (AU, TU = year/2pi, mu = 1).

NX, NY, NZ = sp.symbols("nx ny nz")
AC, RREF = sp.symbols("a_c r_ref")
RS = "(rx^2+ry^2+rz^2)"
RN = f"sqrt({RS})"
A_TXT = f"((l_vx*rx+l_vy*ry+l_vz*rz)/{RN})"
B_TXT = f"sqrt(l_vx^2+l_vy^2+l_vz^2-{A_TXT}^2)"
S_TXT = f"sqrt(9*{A_TXT}^2+8*{B_TXT}^2)"


def perp(k):
    return f"(l_v{k}-{A_TXT}*r{k}/{RN})"


def sail_law(alpha):
    return [f"cos({alpha})*r{k}/{RN}-sin({alpha})*{perp(k)}/{B_TXT}" for k in AXES]


ALPHA = f"atan2(2*{B_TXT},{S_TXT}-3*{A_TXT})"
MARS = [-1.1543080272625081, 1.182900987712027, 0.05313519479444179, -0.5515465, -0.4989226, 0.0030937]
MARS_RATE = MARS[3:] + [0.3971, -0.4070, -0.0183]


def free_tf_parts(d, body, window, tf_var):
    """Free final time against ephemeris parameters arrival_* of `body` at tf (with rates)."""
    lo, hi = window
    d["times"] = {"t0": 0.0, "final_time": "free", "tf_window": [lo, hi],
                  "tf_expression": f"{lo}+{hi - lo}*{tf_var}"}
    d["event_values"] = [{"name": "H_tf", "kind": "hamiltonian", "at": "tf", "meaning": "H at tf under the optimal control"}]
    rates = []
    find(d["constraints"], "id", "arrival")["target"] = {"kind": "body", "body": body, "ephemeris": "jpl_lp"}
    for p in d["parameters"]:
        if p["name"].startswith("arrival_"):
            p["source"] = f"ephemeris:{body}:tf"
            p["meaning"] = p["meaning"].replace("target arrival", body + " at tf")
    for k, v in zip(["rx", "ry", "rz", "vx", "vy", "vz"], MARS_RATE):
        rates.append({"name": f"arrival_{k}_rate", "meaning": f"time derivative of {body}'s {k} at tf",
                      "unit": "normalized", "value": v, "source": f"ephemeris_rate:{body}:tf"})
    d["parameters"] += rates
    d["shooting"]["variables"].append({"name": tf_var, "meaning": f"final time tf = {lo} + {hi - lo}*{tf_var}",
                                       "scale": 1, "init": "uniform in (0, 1)"})
    eqs = d["shooting"]["equations"]
    eqs.insert(len(eqs) - 1, equation(
        "transversality_tf", "H_tf-(" + "+".join(f"l_{k}_tf*arrival_{k}_rate" for k in
                                                  ["rx", "ry", "rz", "vx", "vy", "vz"]) + ")",
        "H(tf) + dPhi/dtf = 0 with psi = x(tf) - x_Mars(tf)", "arrival"))


def s11h():
    states = named_states(False, "AU", "TU")
    xs, ls = POS + VEL, LPOS + LVEL
    sn = NX * RX + NY * RY + NZ * RZ
    sail = [AC * RREF**2 * sn**2 / R2**2 * n for n in (NX, NY, NZ)]
    f = VEL + [-MU * q / R2 ** sp.Rational(3, 2) + a for q, a in zip(POS, sail)]
    H = L0 + sum(l * fi for l, fi in zip(ls, f))
    costates = [sp.expand_mul(-sp.diff(H, x)) for x in xs]
    params = [{"name": "mu", "meaning": "gravitational parameter of the Sun", "unit": "AU^3/TU^2", "value": 1.0},
              {"name": "a_c", "meaning": "characteristic acceleration of the sail at r_ref", "unit": "AU/TU^2",
               "value": 0.1686},
              {"name": "r_ref", "meaning": "reference distance of a_c", "unit": "AU", "value": 1.0}]
    dep = [-0.9405193559915065, -0.34502114075280876, 6.550895380217186e-06, 0.3281733, -0.9427007, 0.0000146]
    for prefix, vals, src in (("departure", dep, "ephemeris:Earth:t0"), ("arrival", MARS, None)):
        for k, v in zip(["rx", "ry", "rz", "vx", "vy", "vz"], vals):
            p = {"name": f"{prefix}_{k}", "meaning": f"{k} of target {prefix}", "unit": "normalized", "value": v}
            if src:
                p["source"] = src
            params.append(p)
    d = {
        "schema": "helios/derivation", "schema_version": 1,
        "producer": {"tool": "tests/verify-corpus/generate.py", "version": "1", "backend": "llm", "model": "hand"},
        "problem": {"id": "S11h", "dynamics_model": "two_body_ideal_solar_sail", "objective": "minimum_time"},
        "units": {"length": "AU", "length_km": 149597870.691, "time": "TU (year/2pi)", "time_s": 5022642.890912,
                  "mass_kg": 100.0},
        "times": {},
        "states": states,
        "controls": [{"name": f"n{k}", "meaning": f"sail normal {k} (unit, n.r_hat >= 0)", "kind": "sail_normal"}
                     for k in AXES],
        "parameters": params,
        "terms": [{"name": "two_body", "kind": "force", "parameters": ["mu"]},
                  {"name": "solar_sail", "kind": "force", "parameters": ["a_c", "r_ref"]},
                  {"name": "time", "kind": "cost", "parameters": []}],
        "homotopy": {"symbol": "eps", "start": 0.0, "end": 0.0, "meaning": "unused: the sail law is continuous"},
        "multiplier": "lambda0",
        "dynamics": {"state_rhs": [g(e) for e in f], "running_cost": "1", "endpoint_cost": "0"},
        "hamiltonian": g(sp.expand_mul(H)),
        "state_odes": [], "costate_odes": [],
        "control_law": {"sail": {
            "controls": ["nx", "ny", "nz"],
            "cone_angle": ALPHA,
            "law": sail_law(ALPHA),
            "stationarity": "dH/dalpha = 0: 2B tan^2(alpha) - 3A tan(alpha) - B = 0, A = l_v.r_hat, B = |l_v_perp|",
            "reason": "n* = cos(alpha) r_hat - sin(alpha) l_v_perp/B with the root of smallest H"}},
        "initial_values": [{"state": s["name"], "value": f"departure_{s['name']}"} for s in states],
        "constraints": [
            {"id": "departure", "kind": "initial_state", "at": "t0",
             "target": {"kind": "body", "body": "Earth", "ephemeris": "jpl_lp"},
             "psi": [f"{s['name']}-departure_{s['name']}" for s in states],
             "multipliers": [f"nu_departure_{i + 1}" for i in range(6)]},
            {"id": "arrival", "kind": "rendezvous", "at": "tf",
             "target": {"kind": "body", "body": "Mars", "ephemeris": "jpl_lp"},
             "psi": [f"{s['name']}-arrival_{s['name']}" for s in states],
             "multipliers": [f"nu_arrival_{i + 1}" for i in range(6)]}],
        "shooting": {
            "variables": [{"name": "lambda0", "meaning": "cost multiplier", "scale": 1, "init": "uniform in (0, 1)"}] +
                         [variable(s["costate"] + "_t0", "costate of " + s["meaning"] + " at t0") for s in states],
            "equations": [equation(f"psi_arrival_{i + 1}", f"{s['name']}_tf-arrival_{s['name']}",
                                   f"rendezvous with Mars: {s['name']} at tf", "arrival")
                          for i, s in enumerate(states)] +
                         [equation("normalization",
                                   "-1+sqrt(lambda0^2+" + "+".join(s["costate"] + "_t0^2" for s in states) + ")",
                                   "|(lambda0, lambda(t0))| = 1", "normalization")]},
    }
    d["state_odes"], d["costate_odes"] = odes(states, [g(e) for e in f], [g(e) for e in costates])
    free_tf_parts(d, "Mars", (2.0, 8.0), "tf_frac")
    return d, (H, f, xs, ls)


def s01f(s01):
    d = copy.deepcopy(s01)
    d["problem"]["id"] = "S01f"
    d["producer"] = {"tool": "tests/verify-corpus/generate.py", "version": "1", "backend": "llm", "model": "hand"}
    free_tf_parts(d, "Mars", (0.6, 1.4), "tf_frac")
    return d


# --------------------------------------------------------------------------------------------
# Case helpers

def find(lst, key, name):
    for e in lst:
        if e[key] == name:
            return e
    raise KeyError(name)


def costate(d, name):
    return find(d["costate_odes"], "costate", name)


def eq(d, name):
    return find(d["shooting"]["equations"], "name", name)


def drop_eq(d, name):
    d["shooting"]["equations"] = [e for e in d["shooting"]["equations"] if e["name"] != name]


def flip(d, name):
    costate(d, name)["rhs"] = "-(" + costate(d, name)["rhs"] + ")"


def set_costates(d, model, form):
    """Costate ODEs recomputed by SymPy and written in another form (`form`: expression -> text)."""
    H, f, xs, ls = model
    for x, l in zip(xs, ls):
        costate(d, str(l))["rhs"] = form(-sp.diff(H, x))


# --------------------------------------------------------------------------------------------
# psi against the constraints' targets (builtin derivations in base/: S14's orbit, the same orbit
# as equations of the state, a departure anywhere on an orbit)

TARGET_BASES = {"S14": "scenarios/S14/problem.txt", "GEOX": "tests/fixtures/problems/geo_by_equations.txt",
                "OR2OR": "tests/fixtures/problems/gto_anywhere_to_geo.txt"}


def replace_everywhere(d, old, new, where=("constraints", "initial_values", "shooting")):
    """Replaces `old` by `new` in every string of the sections `where`."""
    def walk(x):
        if isinstance(x, dict):
            return {k: walk(v) for k, v in x.items()}
        if isinstance(x, list):
            return [walk(v) for v in x]
        return x.replace(old, new) if isinstance(x, str) else x
    for key in where:
        d[key] = walk(d[key])


def target_cases(case):
    case("S14-builtin", "S14", "builtin: a fixed departure, the GEO orbit as a target (its mirror told apart)")
    case("GEOX-builtin", "GEOX", "builtin: GEO written as five equations of the final state")
    case("OR2OR-builtin", "OR2OR", "builtin: a departure anywhere on the GTO, the GEO orbit as a target")

    def orbit_rows_equivalent(d):
        """|r| - a as |r|^2 - a^2, |v|^2 - mu/a as a |v|^2 - mu, h.(n x N) negated, the side condition over |r|."""
        arrival = find(d["constraints"], "id", "arrival")
        arrival["psi"][0] = "rx^2+ry^2+rz^2-a_arrival^2"
        arrival["psi"][2] = "a_arrival*(vx^2+vy^2+vz^2)-mu"
        arrival["psi"][4] = "rx*vz-rz*vx"
        arrival["must_be_positive"][0]["expression"] = "(rx*vy-ry*vx)/sqrt(rx^2+ry^2+rz^2)"
        eq(d, "psi_arrival_1")["expression"] = "rx_tf^2+ry_tf^2+rz_tf^2-a_arrival^2"
        eq(d, "psi_arrival_3")["expression"] = "a_arrival*(vx_tf^2+vy_tf^2+vz_tf^2)-mu"
        eq(d, "psi_arrival_5")["expression"] = "rx_tf*vz_tf-rz_tf*vx_tf"
        for e in d["shooting"]["equations"]:
            e["expression"] = (e["expression"].replace("(rx_tf^2+ry_tf^2+rz_tf^2)^(-1/2)*nu_arrival_1", "2*nu_arrival_1")
                               .replace("2*nu_arrival_3", "2*a_arrival*nu_arrival_3")
                               .replace("nu_arrival_5", "(-nu_arrival_5)"))
    case("S14-orbit-rows-equivalent", "S14", "GEO's rows squared, scaled and negated; h.n over |r|",
         edit=orbit_rows_equivalent)

    def departure_literal(d):
        """The departure's rows and initial values with the numbers written out."""
        for p in d["parameters"]:
            if p["name"].startswith("departure_"):
                replace_everywhere(d, p["name"], "(" + repr(p["value"]) + ")")
    case("S14-departure-literal", "S14", "the departure state written as numbers, not parameters",
         edit=departure_literal)

    def radius_times(d):
        """The LLM's S14 (issue 46): psi asks for |r| = 1.1 a; the shooting row follows it."""
        find(d["constraints"], "id", "arrival")["psi"][0] = "-1.1*a_arrival+sqrt(rx^2+ry^2+rz^2)"
        eq(d, "psi_arrival_1")["expression"] = "-1.1*a_arrival+sqrt(rx_tf^2+ry_tf^2+rz_tf^2)"
    case("S14-orbit-radius-shifted", "S14", "psi asks for |r| = 1.1 a (46,381.5 km), the target 42,165 km",
         ["target:arrival"], radius_times)

    def departure_shifted(d):
        """rx(t0) 0.1 Earth radius (638 km) off the stated departure, in psi and the initial value alike."""
        find(d["constraints"], "id", "departure")["psi"][0] = "-departure_rx-0.1+rx"
        find(d["initial_values"], "state", "rx")["value"] = "departure_rx+0.1"
    case("S14-departure-shifted", "S14", "the departure row and its initial value 638 km off the stated position",
         ["target:departure"], departure_shifted)
    case("S14-initial-value-shifted", "S14", "the initial value of rx 638 km off what psi fixes",
         ["initial_values"], lambda d: find(d["initial_values"], "state", "rx").update(value="departure_rx+0.1"))

    def side_flipped(d):
        side = find(d["constraints"], "id", "arrival")["must_be_positive"][0]
        side["expression"] = "-(" + side["expression"] + ")"
    case("S14-side-condition-flipped", "S14", "h.n > 0 written h.n < 0: the retrograde GEO",
         ["target:arrival"], side_flipped)
    case("S14-side-condition-dropped", "S14", "no side condition: the rows hold on the retrograde GEO too",
         ["target:arrival"], lambda d: find(d["constraints"], "id", "arrival").pop("must_be_positive"))
    def plane_row_dropped(d):
        """h_y = 0 dropped with its multiplier: the rest of the shooting system consistent without it."""
        arrival = find(d["constraints"], "id", "arrival")
        arrival["psi"].pop(4)
        arrival["multipliers"].pop(4)
        drop_eq(d, "psi_arrival_5")
        d["shooting"]["variables"] = [v for v in d["shooting"]["variables"] if v["name"] != "nu_arrival_5"]
        for e in d["shooting"]["equations"]:
            e["expression"] = re.sub(r"[+-]nu_arrival_5\*[a-z]+_tf", "", e["expression"])
    case("S14-plane-row-dropped", "S14", "h_y = 0 dropped (with its multiplier): an inclined circle would pass",
         ["target:arrival"], plane_row_dropped)

    def equation_value(d):
        """|r| = 42165 km met at 44,652 km (7 Earth radii) in psi and the shooting row."""
        arrival = find(d["constraints"], "id", "arrival")
        arrival["psi"][0] = arrival["psi"][0].replace("-6.6108645831847141494", "-7")
        e = eq(d, "psi_arrival_1")
        e["expression"] = e["expression"].replace("-6.6108645831847141494", "-7")
    case("GEOX-equation-value-changed", "GEOX", "the row of |r| = 42165 km asks for 7 Earth radii (44,652 km)",
         ["target:arrival"], equation_value)

    def departure_orbit_shifted(d):
        """The departure orbit's semi-latus rectum 1% off, in psi, the initial values and the shooting."""
        replace_everywhere(d, "p_departure", "(1.01*p_departure)")
    case("OR2OR-departure-orbit-shifted", "OR2OR", "the departure orbit's p 1% larger than the stated GTO's",
         ["target:departure"], departure_orbit_shifted)


# --------------------------------------------------------------------------------------------
# Interior events and a sliding departure (builtin derivations in base/E-*.json)

EVENT_BASES = ["E-flyby", "E-stay", "E-ga", "E-slide"]


def event(d, eid):
    return find(d["events"], "id", eid)


def cmap(d, eid, costate_name):
    return find(event(d, eid)["costate_map"], "costate", costate_name)


def sym(text):
    return sp.sympify(text.replace("^", "**"))


def event_cases(case):
    """Cases of the event checks: each broken one fails exactly the check of the condition it breaks."""
    for name, note in (("E-flyby", "a flyby of an asteroid (position matched, free epoch)"),
                       ("E-stay", "rendezvous with a 20-day stay and a 100 kg mass drop"),
                       ("E-ga", "unpowered gravity assist (delta, phi free parameters of psi)"),
                       ("E-slide", "sliding departure from Earth with a flyby")):
        case(f"{name}-builtin", name, "builtin: " + note)

    def flyby_forms(d):
        ev = event(d, "rock")
        for k in "xyz":
            cmap(d, "rock", f"l_r{k}")["expression"] = f"l_r{k}_rock_m-nu_rock_{'xyz'.index(k) + 1}"
        first_map = len(ev["multipliers"]) - len(d["states"])  # after c's rows (position, window bounds)
        ev["multipliers"][first_map:] = [f"-1*{m[1:]}" for m in ev["multipliers"][first_map:]]
        t = eq(d, "time_rock")
        t["expression"] = f"-2*({t['expression']})"
        for j in (1, 2, 3):
            e = eq(d, f"psi_rock_{j}")
            e["expression"] = g(-3 * sym(e["expression"]))
    case("E-flyby-forms", "E-flyby", "flyby: costate jumps reordered, time condition and psi rows scaled/negated",
         edit=flyby_forms)

    def stay_forms(d):
        for k in ["rx", "ry", "rz", "vx", "vy", "vz"]:
            e = eq(d, f"jump_rock_{k}")
            e["expression"] = g(-sym(e["expression"]))
        cmap(d, "rock", "l_m")["expression"] = "(l_m_rock_m*m_rock_m)/m_rock_m"
        t = eq(d, "time_rock")
        t["expression"] = g(sp.factor_terms(sym(t["expression"])))
    case("E-stay-forms", "E-stay", "stay: jump rows negated, l_m(t+) in another form, time condition regrouped",
         edit=stay_forms)

    # ---- broken
    case("E-flyby-jump-sign", "E-flyby", "flyby: lambda(t+) = lambda(t-) + nu (the jump's sign flipped)",
         ["costate_jump:rock_rx"], lambda d: cmap(d, "rock", "l_rx").update(expression="l_rx_rock_m+nu_rock_1"))

    def time_without_h(d):
        t = eq(d, "time_rock")
        t["expression"] = g(sym(t["expression"]).subs({sp.Symbol("H_rock_m"): 0, sp.Symbol("H_rock_p"): 0}))
    case("E-flyby-time-without-H", "E-flyby", "flyby: free-epoch condition without H(t-) - H(t+)",
         ["event_time:rock"], time_without_h)

    def time_h_sign(d):
        t = eq(d, "time_rock")
        hm, hp = sp.symbols("H_rock_m H_rock_p")
        t["expression"] = g(sym(t["expression"]).subs({hm: hp, hp: hm}, simultaneous=True))
    case("E-flyby-time-H-sign", "E-flyby", "flyby: free-epoch condition with H(t+) - H(t-)", ["event_time:rock"],
         time_h_sign)
    case("E-flyby-time-without-rates", "E-flyby", "flyby: free-epoch condition H(t-) - H(t+) = 0 without nu^T dpsi/dt",
         ["event_time:rock"], lambda d: eq(d, "time_rock").update(expression="H_rock_m-H_rock_p"))
    case("E-stay-time-without-rates", "E-stay",
         "stay: free-epoch condition without nu^T dc/dt and lambda(t+)^T dg/dt (the body moves)",
         ["event_time:rock"], lambda d: eq(d, "time_rock").update(expression="H_rock_m-H_rock_p"))

    def time_without_window(d):
        t = eq(d, "time_rock")
        t["expression"] = g(sym(t["expression"]).subs({sp.Symbol("nu_rock_4"): 0, sp.Symbol("nu_rock_5"): 0}))
    case("E-flyby-time-without-window-bounds", "E-flyby",
         "flyby: free-epoch condition without the window bounds' -nu_4 + nu_5 (d(window start - t)/dt = -1)",
         ["event_time:rock"], time_without_window)
    case("E-flyby-bound-inactive-form", "E-flyby", "flyby: the window bound's inactive equation nu_4 - 1 = 0",
         ["bound:psi_rock_4"], lambda d: eq(d, "psi_rock_4")["inequality"].update(inactive_expression="nu_rock_4-1"))
    case("E-flyby-bound-multiplier", "E-flyby", "flyby: the window end's bound names the window start's multiplier",
         ["bound:psi_rock_5"], lambda d: eq(d, "psi_rock_5")["inequality"].update(multiplier="nu_rock_4"))

    def multiplier_sign(d):
        ev = event(d, "rock")
        ev["multipliers"][len(ev["multipliers"]) - len(d["states"]) + 1] = "l_ry_rock_p"
    case("E-flyby-multiplier-sign", "E-flyby", "flyby: multiplier of ry+ - ry- written +lambda(t+)",
         ["event_multipliers:rock"], multiplier_sign)

    def drop_constraint(d):
        drop_eq(d, "psi_rock_2")
    case("E-flyby-dropped-constraint", "E-flyby", "flyby: the constraint ry(t-) = ry_Rock dropped",
         ["count", "event_constraint:rock_2"], drop_constraint)

    def continuous_v(d):
        cmap(d, "rock", "l_vx").pop("variable")
        cmap(d, "rock", "l_vx")["expression"] = "l_vx_rock_m"
        d["shooting"]["variables"] = [v for v in d["shooting"]["variables"] if v["name"] != "l_vx_rock_p"]
        drop_eq(d, "jump_rock_vx")
    case("E-stay-continuous-costate", "E-stay",
         "stay: lambda_vx treated as continuous although the stay maps vx to the body's (no variable, no jump row)",
         ["costate_jump:rock_vx", "event_unknowns:rock"], continuous_v)
    case("E-stay-mass-drop-jump", "E-stay", "stay: lambda_m jumping at the mass drop (scaled by the mass ratio)",
         ["costate_jump:rock_m"],
         lambda d: cmap(d, "rock", "l_m").update(expression="l_m_rock_m*m_rock_m/(m_rock_m-drop_rock)"))

    def jump_row_sign(d):
        e = eq(d, "jump_rock_vy")
        e["expression"] = e["expression"].replace("-nu_rock_5", "+nu_rock_5")
    case("E-stay-jump-row-sign", "E-stay", "stay: jump row of vy with +nu", ["costate_jump:rock_vy"], jump_row_sign)

    def map_without_drop(d):
        find(event(d, "rock")["state_map"], "state", "m")["expression"] = "m_rock_m"
    case("E-stay-state-map-without-drop", "E-stay", "stay: state_map keeps the mass although psi drops it",
         ["event_psi:rock"], map_without_drop)

    def stationarity_sign(d):
        e = eq(d, "stationarity_rock_delta_rock")
        expr = sym(e["expression"])
        lvx = sp.Symbol("l_vx_rock_p")
        e["expression"] = g(expr - 2 * lvx * sp.diff(expr, lvx))
    case("E-ga-stationarity-sign", "E-ga", "gravity assist: dPhi/ddelta with the l_vx(t+) term's sign flipped",
         ["event_stationarity:rock_delta_rock"], stationarity_sign)

    case("E-slide-H0-only", "E-slide", "sliding departure: H(t0) = 0 alone (the paper's condition)",
         ["transversality_t0"], lambda d: eq(d, "transversality_t0").update(expression="H_t0"))

    def slide_without_tf(d):
        e = eq(d, "transversality_t0")
        keep = [t for t in sp.Add.make_args(sym(e["expression"])) if not str(t).count("_tf")]
        e["expression"] = g(sp.Add(*keep))
    case("E-slide-without-tf", "E-slide", "sliding departure: -H(t0) + dPhi/dt0 without the tf terms",
         ["transversality_t0"], slide_without_tf)


def main():
    bin_dir = None
    if "--bin" in sys.argv:
        bin_dir = pathlib.Path(sys.argv[sys.argv.index("--bin") + 1])
    seed_dir, case_dir = HERE / "seed", HERE / "cases"
    seed_dir.mkdir(exist_ok=True)
    case_dir.mkdir(exist_ok=True)
    builtin = ["S05", "S06", "S11", "S12"]  # base/: committed with the engine (see base/README.md)
    if bin_dir:
        spec = subprocess.run([str(bin_dir / "helios-parse"), str(ROOT / "scenarios/S01/problem.txt")],
                              check=True, capture_output=True, text=True).stdout
        out = subprocess.run([str(bin_dir / "helios-derive"), "-"], input=spec, check=True, capture_output=True,
                             text=True).stdout
        (seed_dir / "S01.json").write_text(out)
    s01 = json.loads((seed_dir / "S01.json").read_text())
    S05, j2model = s05h(s01)
    S06 = s06h(S05)
    S11, sailmodel = s11h()
    S01F = s01f(s01)
    for name, doc in (("S05h", S05), ("S06h", S06), ("S11h", S11), ("S01f", S01F)):
        write(seed_dir / f"{name}.json", doc)
    for name, problem in TARGET_BASES.items():
        if bin_dir:
            spec = subprocess.run([str(bin_dir / "helios-parse"), str(ROOT / problem)], check=True,
                                  capture_output=True, text=True).stdout
            subprocess.run([str(bin_dir / "helios-derive"), "-", "-o", str(HERE / "base" / f"{name}.json")],
                           input=spec, check=True, text=True)
    for name in EVENT_BASES:
        if bin_dir:
            subprocess.run([str(bin_dir / "helios-derive"), str(HERE / "base" / f"{name}.spec.json"), "-o",
                            str(HERE / "base" / f"{name}.json")], check=True)
    # Every case is a patch against one of these files, as committed.
    bases = {name: f"seed/{name}.json" for name in ("S01", "S05h", "S06h", "S11h", "S01f")}
    bases.update({name: f"base/{name}.json" for name in builtin + EVENT_BASES + list(TARGET_BASES)})
    seeds = {name: json.loads((HERE / path).read_text()) for name, path in bases.items()}

    cases = []

    def case(name, seed, note, fails=(), edit=None):
        entry = {"name": name, "base": bases[seed]}
        if edit:
            d = copy.deepcopy(seeds[seed])
            edit(d)
            ops = diff(seeds[seed], d)
            assert ops, name
            write_patch(case_dir / f"{name}.patch.json", ops)
            entry["patch"] = f"cases/{name}.patch.json"
        cases.append(entry | {"verdict": "fail" if fails else "pass", "fails": sorted(fails), "note": note})

    # ---- correct derivations, in different but equivalent forms
    case("S01-builtin", "S01", "builtin derivation as produced")

    def s01_factored(d):
        for k, q in zip(AXES, ["rx", "ry", "rz"]):
            others = [o for o in "xyz" if o != k]
            costate(d, f"l_r{k}")["rhs"] = (
                f"mu*{RS}^(-5/2)*(l_v{k}*(r{others[0]}^2+r{others[1]}^2-2*{q}^2)"
                f"-3*{q}*(l_v{others[0]}*r{others[0]}+l_v{others[1]}*r{others[1]}))")
    case("S01-costates-factored", "S01", "lambda_r' factored over (r^2)^(5/2)", edit=s01_factored)

    def s01_r_cubed(d):
        r3 = f"(sqrt{RS}*{RS})"
        for k in AXES:
            costate(d, f"l_r{k}")["rhs"] = (
                f"mu*l_v{k}/{r3}-3*mu*r{k}*(l_vx*rx+l_vy*ry+l_vz*rz)/({r3}*{RS})")
        d["hamiltonian"] = ("l_rx*vx+l_ry*vy+l_rz*vz-mu*(l_vx*rx+l_vy*ry+l_vz*rz)/" + r3 +
                            "+Tmax*u/m*(ax*l_vx+ay*l_vy+az*l_vz)+Tmax/c*u*(lambda0*(1-eps+eps*u)-l_m)")
    case("S01-r-times-r2", "S01", "r^3 written as sqrt(r^2)*r^2, H grouped with lambda0 inside", edit=s01_r_cubed)

    def s01_primer_norm(d):
        n = "sqrt(l_vx^2+l_vy^2+l_vz^2)"
        d["control_law"]["direction"]["law"] = [f"-l_v{k}/{n}" for k in AXES]
        t = d["control_law"]["throttle"]
        t["switching_function"] = f"Tmax/c*(lambda0-l_m)-Tmax*{n}/m"
        t["dH_du_at_lower"] = f"Tmax*((lambda0*(1-eps)-l_m)/c-{n}/m)"
        t["dH_du_at_upper"] = f"Tmax*((lambda0*(1+eps)-l_m)/c-{n}/m)"
        t["interior"] = f"(1+(c*{n}/m+l_m-lambda0)/(eps*lambda0))/2"
    case("S01-primer-norms", "S01", "primer law and switching function written with norms", edit=s01_primer_norm)

    def s01_envelope(d):
        costate(d, "l_m")["rhs"] = "-Tmax*u*sqrt(l_vx^2+l_vy^2+l_vz^2)/m^2"
    case("S01-lm-with-primer", "S01", "lambda_m' with the primer direction substituted (envelope form)",
         edit=s01_envelope)

    def s01_reordered(d):
        eqs = d["shooting"]["equations"]
        for e in eqs:
            if e["name"].startswith("psi_arrival"):
                a, b = e["expression"].split("+")
                e["expression"] = f"2*({b}{a})"
        eq(d, "normalization")["expression"] = ("l_m_t0^2+l_vz_t0^2+l_vy_t0^2+l_vx_t0^2+l_rz_t0^2+l_ry_t0^2+"
                                                "l_rx_t0^2+lambda0^2-1")
        d["shooting"]["equations"] = list(reversed(eqs))
        d["state_odes"][3]["rhs"] = "Tmax*u*ax/m-mu*rx/(rx^2+ry^2+rz^2)^(3/2)"
    case("S01-reordered", "S01", "equations reordered and scaled, squared normalization, reordered sums",
         edit=s01_reordered)

    case("S05h-expanded", "S05h", "J2: costates as SymPy expand_mul writes them")
    case("S05h-together", "S05h", "J2: costates as single fractions (SymPy together)",
         edit=lambda d: set_costates(d, j2model, lambda e: g(sp.together(e))))
    case("S05h-expanded-denominators", "S05h", "J2: costates with every denominator multiplied out (SymPy expand)",
         edit=lambda d: set_costates(d, j2model, lambda e: g(sp.expand(e))))
    case("S06h-coast", "S06h", "J2 rendezvous with a coasting target")
    case("S11h-atan2", "S11h", "sail: cone angle with atan2, law with cos/sin")

    def sail_algebraic(d):
        X = f"({S_TXT}-3*{A_TXT})"
        d["control_law"]["sail"]["law"] = [f"({X}*r{k}/{RN}-2*{perp(k)})/sqrt({X}^2+4*{B_TXT}^2)" for k in AXES]
        d["control_law"]["sail"]["cone_angle"] = f"atan((3*{A_TXT}+{S_TXT})/(4*{B_TXT}))"
    case("S11h-algebraic-law", "S11h", "sail: algebraic law (X r_hat - 2 l_perp)/sqrt(X^2+4B^2), tan form",
         edit=sail_algebraic)
    case("S11h-factored", "S11h", "sail: costates factored (SymPy factor per term)",
         edit=lambda d: set_costates(d, sailmodel, lambda e: g(sp.collect(sp.factor_terms(e), [LVX, LVY, LVZ]))))

    def sail_tf_forms(d):
        eq(d, "transversality_tf")["expression"] = (
            "2*(l_vz_tf*arrival_vz_rate+l_vy_tf*arrival_vy_rate+l_vx_tf*arrival_vx_rate+l_rz_tf*arrival_rz_rate"
            "+l_ry_tf*arrival_ry_rate+l_rx_tf*arrival_rx_rate-H_tf)")
        d["times"]["tf_expression"] = "2*(1+3*tf_frac)"
        d["hamiltonian"] = ("lambda0+l_rx*vx+l_ry*vy+l_rz*vz+(l_vx*nx+l_vy*ny+l_vz*nz)*a_c*r_ref^2*"
                            "(nx*rx+ny*ry+nz*rz)^2/(rx^2+ry^2+rz^2)^2-mu*(l_vx*rx+l_vy*ry+l_vz*rz)/"
                            "(rx^2+ry^2+rz^2)^(3/2)")
    case("S11h-tf-forms", "S11h", "sail: transversality negated and scaled, tf_expression and H regrouped",
         edit=sail_tf_forms)
    case("S01f-free-tf", "S01f", "S01 with a free final time against moving Mars")

    # ---- broken derivations
    for seed, names in (("S01", ["l_rx", "l_vy", "l_m"]), ("S05h", ["l_ry", "l_vz", "l_m"]),
                        ("S11h", ["l_rz", "l_vx"])):
        for n in names:
            case(f"{seed}-flip-{n}", seed, f"sign of the {n} costate equation flipped", [f"costate_ode:{n}"],
                 lambda d, n=n: flip(d, n))

    def drop_sail_g3(d):  # lambda_r' without the d[(n.r_hat)^2/r^2]/dr terms of the sail
        H, f, xs, ls = sailmodel
        H0 = H.subs(AC, 0)
        costate(d, "l_rx")["rhs"] = g(sp.expand_mul(-sp.diff(H0, RX)))
    case("S11h-missing-G3", "S11h", "sail: l_rx' without the geometric terms of the sail acceleration (G3)",
         ["costate_ode:l_rx"], drop_sail_g3)

    def drop_sail_g3_part(d):  # only the d(n.r)^2/dr part kept, the d(1/r^4)/dr part dropped
        H, f, xs, ls = sailmodel
        sn = NX * RX + NY * RY + NZ * RZ
        lv_n = LVX * NX + LVY * NY + LVZ * NZ
        twobody = -sp.diff(H.subs(AC, 0), RY)
        costate(d, "l_ry")["rhs"] = g(sp.expand_mul(twobody - AC * RREF**2 * lv_n * 2 * sn * NY / R2**2))
    case("S11h-missing-G3-part", "S11h", "sail: l_ry' misses the d(1/r^4)/dry part of the sail terms (G3)",
         ["costate_ode:l_ry"], drop_sail_g3_part)

    def drop_j2_entry(d):  # l_rz' without the l_vx * d(a_J2,x)/dz entry
        H, f, xs, ls = j2model
        j2x = j2_gravity(RX, RY, RZ)[0] - j2_gravity(RX, RY, RZ)[0].subs(J2, 0)
        costate(d, "l_rz")["rhs"] = g(sp.expand_mul(-sp.diff(H, RZ) + LVX * sp.diff(j2x, RZ)))
    case("S05h-missing-J2-entry", "S05h", "J2: l_rz' misses the d(a_J2,x)/dz Jacobian entry (G6)",
         ["costate_ode:l_rz"], drop_j2_entry)

    def drop_j2_all(d):  # l_rx' with the two-body Jacobian only
        H, f, xs, ls = j2model
        costate(d, "l_rx")["rhs"] = g(sp.expand_mul(-sp.diff(H.subs(J2, 0), RX)))
    case("S05h-missing-J2-jacobian", "S05h", "J2: l_rx' with the two-body Jacobian only (G6)",
         ["costate_ode:l_rx"], drop_j2_all)

    def coast_without_j2(d):
        tx, ty, tz = sp.symbols("tgt_rx tgt_ry tgt_rz")
        d["coast_dynamics"]["rhs"][3:] = [g(sp.expand_mul(e.subs(J2, 0))) for e in j2_gravity(tx, ty, tz)]
    case("S06h-coast-without-J2", "S06h", "J2: the coasting target moves without J2", ["coast_dynamics"],
         coast_without_j2)

    def sail_with_mass(d):
        d["states"].append({"name": "m", "meaning": "mass", "unit": "kg", "costate": "l_m"})
        d["dynamics"]["state_rhs"].append("0")
        d["state_odes"].append({"state": "m", "rhs": "0"})
        d["costate_odes"].append({"costate": "l_m", "rhs": "0"})
        d["initial_values"].append({"state": "m", "value": "1"})
        dep = find(d["constraints"], "id", "departure")
        dep["psi"].append("m-1")
        dep["multipliers"].append("nu_departure_7")
        d["shooting"]["variables"].insert(7, variable("l_m_t0", "costate of mass at t0"))
        d["shooting"]["equations"].insert(6, equation("transversality_m", "l_m_tf", "m(tf) free", "arrival"))
        eq(d, "normalization")["expression"] = eq(d, "normalization")["expression"].replace("lambda0^2",
                                                                                           "lambda0^2+l_m_t0^2")
    case("S11h-mass-state", "S11h", "sail: a mass state with zero dynamics left in (G4)", ["state_usage"],
         sail_with_mass)

    for seed in ("S01", "S05h", "S11h"):
        def no_l0(d):
            e = eq(d, "normalization")
            e["expression"] = re.sub(r"\+?lambda0\^2\+?", lambda m: "+" if m.group(0) == "+lambda0^2+" else "",
                                     e["expression"])
            assert "lambda0" not in e["expression"]
        case(f"{seed}-normalization-without-lambda0", seed, "lambda0 dropped from the normalization (G1)",
             ["normalization"], no_l0)

    def minus_root(d):
        alpha = f"atan((3*{A_TXT}-{S_TXT})/(4*{B_TXT}))"
        d["control_law"]["sail"]["law"] = sail_law(alpha)
        d["control_law"]["sail"]["cone_angle"] = alpha
    case("S11h-wrong-root", "S11h", "sail: minus sign in front of the square root (other root of dH/dalpha = 0)",
         ["control_sail", "control_sail_cone_angle"], minus_root)

    def minus_root_law_only(d):
        d["control_law"]["sail"]["law"] = sail_law(f"atan((3*{A_TXT}-{S_TXT})/(4*{B_TXT}))")
    case("S11h-wrong-root-law-only", "S11h", "sail: wrong root in the law, right cone angle", ["control_sail"],
         minus_root_law_only)

    def perp_sign(d):
        d["control_law"]["sail"]["law"] = [f"cos({ALPHA})*r{k}/{RN}+sin({ALPHA})*{perp(k)}/{B_TXT}" for k in AXES]
    case("S11h-law-maximizes", "S11h", "sail: + sin(alpha) l_perp/B (tilts toward the costate: a maximizer side)",
         ["control_sail"], perp_sign)

    def cone_complement(d):
        d["control_law"]["sail"]["cone_angle"] = f"Pi/2-{ALPHA}"
    case("S11h-cone-angle-complement", "S11h", "sail: cone angle written as pi/2 - alpha*",
         ["control_sail_cone_angle"], cone_complement)

    def extra_eq(d):
        d["shooting"]["equations"].insert(0, equation("psi_extra", "rx_tf-arrival_rx", "duplicate", "arrival"))
    case("S01-count-extra-equation", "S01", "one equation more than variables (Rule 0)", ["count"], extra_eq)

    def no_tf_var(d):
        d["shooting"]["variables"] = [v for v in d["shooting"]["variables"] if v["name"] != "tf_frac"]
    case("S11h-count-no-tf-variable", "S11h", "free tf without its shooting variable (Rule 0)",
         ["count", "tf_expression"], no_tf_var)

    case("S01-dropped-transversality-m", "S01", "lambda_m(tf) = 0 dropped", ["count", "transversality:m"],
         lambda d: drop_eq(d, "transversality_m"))
    case("S05h-dropped-endpoint", "S05h", "psi_arrival_3 dropped", ["count", "endpoint:arrival_3"],
         lambda d: drop_eq(d, "psi_arrival_3"))
    case("S11h-dropped-transversality-tf", "S11h", "free-tf condition dropped", ["count", "transversality_tf"],
         lambda d: drop_eq(d, "transversality_tf"))

    def tf_sign(d):
        e = eq(d, "transversality_tf")
        e["expression"] = e["expression"].replace("H_tf-(", "H_tf+(")
    case("S11h-transversality-tf-sign", "S11h", "free-tf condition with + lambda.rate", ["transversality_tf"],
         tf_sign)

    def tf_drop_rate(d):
        e = eq(d, "transversality_tf")
        e["expression"] = e["expression"].replace("+l_vz_tf*arrival_vz_rate", "")
    case("S11h-transversality-tf-dropped-rate", "S11h", "free-tf condition without the l_vz*vz_rate term",
         ["transversality_tf"], tf_drop_rate)

    def tf_no_h(d):
        e = eq(d, "transversality_tf")
        e["expression"] = e["expression"].replace("H_tf-(", "-(")
    case("S01f-transversality-tf-without-H", "S01f", "free-tf condition without H(tf)", ["transversality_tf"],
         tf_no_h)

    def tf_as_fixed_target(d):
        eq(d, "transversality_tf")["expression"] = "H_tf"
    case("S01f-transversality-tf-fixed-target", "S01f", "free-tf condition H(tf) = 0 ignoring the moving target",
         ["transversality_tf"], tf_as_fixed_target)

    def maximizing_direction(d):
        d["control_law"]["direction"]["law"] = [f"-({x})" for x in d["control_law"]["direction"]["law"]]
    case("S05h-direction-maximizes", "S05h", "primer law with the wrong sign (G2)", ["control_direction"],
         maximizing_direction)

    def h_without_l0(d):
        d["hamiltonian"] = g(sp.expand_mul(sailmodel[0].subs(L0, 0)))
    case("S11h-hamiltonian-without-lambda0", "S11h", "H without lambda0*L", ["hamiltonian"], h_without_l0)

    def switching_sign(d):
        t = d["control_law"]["throttle"]
        t["switching_function"] = t["switching_function"].replace("-Tmax*m^(-1)*sqrt", "+Tmax*m^(-1)*sqrt")
    case("S01-switching-sign", "S01", "primer term of the switching function with the wrong sign",
         ["throttle_switching"], switching_sign)

    def j2_state(d):
        H, f, xs, ls = j2model
        d["state_odes"][5]["rhs"] = g(f[5].subs(J2, 0))
    case("S05h-state-ode-without-J2", "S05h", "vz' without the J2 acceleration", ["state_ode:vz"], j2_state)

    # ---- the builtin engine's S05, S06, S11, S12 (tests/verify-corpus/base/)
    for scenario in builtin:
        case(f"{scenario}-builtin", scenario, "builtin derivation as produced")
    case("S05-flip-l_vx", "S05", "builtin J2: sign of l_vx' flipped", ["costate_ode:l_vx"], lambda d: flip(d, "l_vx"))
    case("S11-flip-l_ry", "S11", "builtin sail: sign of l_ry' flipped", ["costate_ode:l_ry"],
         lambda d: flip(d, "l_ry"))

    def without_terms(d, name, *factors):
        """Drops from costate `name` every term that contains all `factors` (symbol names)."""
        e = sp.sympify(costate(d, name)["rhs"].replace("^", "**"))
        keep = [t for t in sp.Add.make_args(sp.expand_mul(e)) if not all(sp.Symbol(f) in t.free_symbols
                                                                          for f in factors)]
        assert len(keep) < len(sp.Add.make_args(sp.expand_mul(e)))
        costate(d, name)["rhs"] = g(sp.Add(*keep))
    case("S05-missing-J2-entry", "S05", "builtin J2: l_ry' misses the l_vz d(a_J2,z)/dry entry (G6)",
         ["costate_ode:l_ry"], lambda d: without_terms(d, "l_ry", "J2", "l_vz"))
    case("S06-missing-J2-entry", "S06", "builtin J2 rendezvous: l_rx' misses the l_vy d(a_J2,y)/drx entry (G6)",
         ["costate_ode:l_rx"], lambda d: without_terms(d, "l_rx", "J2", "l_vy"))
    case("S11-missing-G3", "S11", "builtin sail: l_rz' misses the sail terms in nx (G3)", ["costate_ode:l_rz"],
         lambda d: without_terms(d, "l_rz", "ac", "nx"))

    def coast_two_body(d):
        rhs = d["coast_dynamics"]["rhs"]
        for k in range(3, 6):
            e = sp.sympify(rhs[k].replace("^", "**"))
            rhs[k] = g(e.subs(sp.Symbol("J2"), 0))
    case("S06-coast-without-J2", "S06", "builtin J2 rendezvous: the coasting target moves without J2",
         ["coast_dynamics"], coast_two_body)

    def builtin_minus_root(d):
        sail = d["control_law"]["sail"]
        for df in sail["definitions"]:
            if df["name"] == "sail_alpha":
                df["expression"] = "atan((3*sail_A-sqrt(8*sail_B^2+9*sail_A^2))/(4*sail_B))"
    case("S11-wrong-root", "S11", "builtin sail: minus sign in front of the square root in sail_alpha",
         ["control_sail"], builtin_minus_root)
    case("S11-mass-state", "S11", "builtin sail with a mass state left in (G4)", ["state_usage"], sail_with_mass)
    case("S11-transversality-tf-sign", "S11", "builtin sail: + lambda.rate in the free-tf condition",
         ["transversality_tf"], lambda d: eq(d, "transversality_tf").update(
             expression=eq(d, "transversality_tf")["expression"].replace("-arrival", "+arrival")))
    case("S06-count-missing-transversality-m", "S06", "builtin J2 rendezvous: lambda_m(tf) = 0 dropped",
         ["count", "transversality:m"], lambda d: drop_eq(d, "transversality_m"))

    def without_float_terms(d, name):
        """Drops from costate `name` the terms with a floating-point coefficient (S12's SRP constant)."""
        e = sp.expand_mul(sp.sympify(costate(d, name)["rhs"].replace("^", "**")))
        keep = [t for t in sp.Add.make_args(e) if not t.atoms(sp.Float)]
        assert len(keep) < len(sp.Add.make_args(e))
        costate(d, name)["rhs"] = g(sp.Add(*keep))
    case("S12-missing-SRP-jacobian", "S12", "S01 + SRP: l_rx' without the Jacobian of the SRP acceleration",
         ["costate_ode:l_rx"], lambda d: without_float_terms(d, "l_rx"))
    case("S12-missing-SRP-mass-term", "S12", "S01 + SRP: l_m' without d(a_SRP)/dm (the plate's a = k/m)",
         ["costate_ode:l_m"], lambda d: without_float_terms(d, "l_m"))
    case("S12-flip-l_vz", "S12", "S01 + SRP: sign of l_vz' flipped", ["costate_ode:l_vz"], lambda d: flip(d, "l_vz"))

    event_cases(case)
    target_cases(case)

    write(HERE / "manifest.json", {"description": "helios-verify accuracy corpus: expected verdict and the exact "
                                                  "set of failing checks of every case (generate.py)",
                                   "cases": cases})
    print(f"{len(cases)} cases: {sum(c['verdict'] == 'pass' for c in cases)} correct, "
          f"{sum(c['verdict'] == 'fail' for c in cases)} broken")


if __name__ == "__main__":
    main()
