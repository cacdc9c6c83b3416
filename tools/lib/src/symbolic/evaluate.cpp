#include "helios/symbolic/evaluate.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "helios/symbolic/compare.hpp"

namespace helios::symbolic {
namespace {

using GiNaC::ex;
using GiNaC::numeric;
using GiNaC::symbol;

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9E3779B97F4A7C15ULL + (h << 6) + (h >> 2);
  return h * 0x100000001B3ULL;
}
std::uint64_t text_hash(const std::string& s) {
  std::uint64_t h = 0xCBF29CE484222325ULL;
  for (const char ch : s) h = (h ^ static_cast<unsigned char>(ch)) * 0x100000001B3ULL;
  return h;
}
double (*unary(const std::string& name))(double) {
  static const std::map<std::string, double (*)(double)> table = {
      {"exp", +[](double x) { return std::exp(x); }},   {"log", +[](double x) { return std::log(x); }},
      {"sin", +[](double x) { return std::sin(x); }},   {"cos", +[](double x) { return std::cos(x); }},
      {"tan", +[](double x) { return std::tan(x); }},   {"asin", +[](double x) { return std::asin(x); }},
      {"acos", +[](double x) { return std::acos(x); }}, {"atan", +[](double x) { return std::atan(x); }},
      {"sinh", +[](double x) { return std::sinh(x); }}, {"cosh", +[](double x) { return std::cosh(x); }},
      {"tanh", +[](double x) { return std::tanh(x); }}, {"abs", +[](double x) { return std::fabs(x); }}};
  const auto it = table.find(name);
  return it == table.end() ? nullptr : it->second;
}

}  // namespace

int Compiled::push(Node n, std::uint64_t salt) {
  std::uint64_t h = mix(static_cast<std::uint64_t>(n.op) + 1, salt);
  std::uint64_t bits = 0;
  static_assert(sizeof bits == sizeof n.value, "double is 64 bits");
  std::memcpy(&bits, &n.value, sizeof bits);
  h = mix(h, bits);
  h = mix(h, static_cast<std::uint64_t>(n.slot));
  for (int a : n.args) h = mix(h, hashes_[static_cast<std::size_t>(a)]);
  auto& same = by_hash_[h];
  for (int i : same) {
    const Node& m = nodes_[static_cast<std::size_t>(i)];
    if (m.op == n.op && std::memcmp(&m.value, &n.value, sizeof bits) == 0 && m.slot == n.slot && m.f1 == n.f1 &&
        m.f2 == n.f2 && m.args == n.args)
      return i;
  }
  nodes_.push_back(std::move(n));
  hashes_.push_back(h);
  same.push_back(static_cast<int>(nodes_.size()) - 1);
  return static_cast<int>(nodes_.size()) - 1;
}

int Compiled::build(const ex& e, const std::map<std::string, int>& slots) {
  Node n;
  std::uint64_t salt = 0;
  if (GiNaC::is_a<numeric>(e) || GiNaC::is_a<GiNaC::constant>(e)) {
    const ex v = GiNaC::evalf(e);
    if (!GiNaC::is_a<numeric>(v) || !GiNaC::ex_to<numeric>(v).is_real())
      throw std::invalid_argument("constant " + print(e) + " is not a real number");
    n.value = GiNaC::ex_to<numeric>(v).to_double();
    return push(n);
  }
  if (GiNaC::is_a<symbol>(e)) {
    const std::string name = GiNaC::ex_to<symbol>(e).get_name();
    const auto it = slots.find(name);
    if (it == slots.end()) throw std::invalid_argument("unknown symbol " + name);
    n.op = Op::Var;
    n.slot = it->second;
    return push(n);
  }
  if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
    // GiNaC's operand order follows hash values that vary between runs; a fixed order (by a
    // structural hash of the operands) keeps the rounding, and so every reported number, reproducible.
    n.op = GiNaC::is_a<GiNaC::add>(e) ? Op::Add : Op::Mul;
    for (const auto& op : e) n.args.push_back(build(op, slots));
    std::sort(n.args.begin(), n.args.end(), [this](int a, int b) {
      return hashes_[static_cast<std::size_t>(a)] < hashes_[static_cast<std::size_t>(b)];
    });
    return push(n);
  }
  if (GiNaC::is_a<GiNaC::power>(e)) {
    n.args.push_back(build(e.op(0), slots));
    if (GiNaC::is_a<numeric>(e.op(1)) && GiNaC::ex_to<numeric>(e.op(1)).is_real()) {
      n.op = Op::Pow;
      n.value = GiNaC::ex_to<numeric>(e.op(1)).to_double();
    } else {
      n.op = Op::PowEx;
      n.args.push_back(build(e.op(1), slots));
    }
    return push(n);
  }
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    salt = text_hash(name);
    if (e.nops() == 1 && unary(name)) {
      n.op = Op::Fn1;
      n.f1 = unary(name);
    } else if (e.nops() == 2 && name == "atan2") {
      n.op = Op::Fn2;
      n.f2 = +[](double y, double x) { return std::atan2(y, x); };
    } else {
      throw std::invalid_argument("function " + name + " is not supported by the verifier");
    }
    for (const auto& op : e) n.args.push_back(build(op, slots));
    return push(n, salt);
  }
  throw std::invalid_argument("cannot evaluate " + print(e));
}

// Children precede their parents in nodes_, so one pass in order evaluates every shared node once.
double Compiled::eval(const Point& x) const {
  std::vector<double> v(static_cast<std::size_t>(root_) + 1);
  auto at = [&v](int a) { return v[static_cast<std::size_t>(a)]; };
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Node& n = nodes_[i];
    double r = std::nan("");
    switch (n.op) {
      case Op::Const:
        r = n.value;
        break;
      case Op::Var:
        r = x[static_cast<std::size_t>(n.slot)];
        break;
      case Op::Add:
        r = 0;
        for (int a : n.args) r += at(a);
        break;
      case Op::Mul:
        r = 1;
        for (int a : n.args) r *= at(a);
        break;
      case Op::Pow:
        r = std::pow(at(n.args[0]), n.value);
        break;
      case Op::PowEx:
        r = std::pow(at(n.args[0]), at(n.args[1]));
        break;
      case Op::Fn1:
        r = n.f1(at(n.args[0]));
        break;
      case Op::Fn2:
        r = n.f2(at(n.args[0]), at(n.args[1]));
        break;
    }
    v[i] = r;
  }
  return v.back();
}

}  // namespace helios::symbolic
