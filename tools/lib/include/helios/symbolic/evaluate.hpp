#pragma once
// A GiNaC expression compiled to a small tree over symbol slots and evaluated in doubles: the
// verifier evaluates each expression at many points, where GiNaC's subs + evalf per point would
// cost ~100x more.
#include <ginac/ginac.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace helios::symbolic {

// Values of the symbols by slot (the slot of each name given at compilation).
using Point = std::vector<double>;

class Compiled {
 public:
  Compiled() = default;
  // Throws std::invalid_argument for a symbol without a slot, a function it cannot evaluate or a
  // constant that is not real.
  Compiled(const GiNaC::ex& e, const std::map<std::string, int>& slots) { root_ = build(e, slots); }
  // The value at `x` (NaN for a default-constructed Compiled).
  double operator()(const Point& x) const { return root_ < 0 ? std::nan("") : eval(x); }

 private:
  enum class Op { Const, Var, Add, Mul, Pow, PowEx, Fn1, Fn2 };
  struct Node {
    Op op = Op::Const;
    double value = 0;
    int slot = 0;
    double (*f1)(double) = nullptr;
    double (*f2)(double, double) = nullptr;
    std::vector<int> args;
  };
  std::vector<Node> nodes_;
  std::vector<std::uint64_t> hashes_;  // structural hash of each node, independent of GiNaC's run-dependent order
  std::map<std::uint64_t, std::vector<int>> by_hash_;  // equal subtrees share one node (a DAG)
  int root_ = -1;

  int push(Node n, std::uint64_t salt = 0);
  int build(const GiNaC::ex& e, const std::map<std::string, int>& slots);
  double eval(const Point& x) const;
};

}  // namespace helios::symbolic
