#pragma once
// A small expression language for user-supplied scalar functions of one variable x
// (Hill's f, the Valanis-Landel f, g, h of paper 002 Table 1).
//
// Grammar (recursive descent, usual precedence, '^' right-associative and binding tighter
// than unary minus, so -x^2 = -(x^2) and 2^-1 = 0.5):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('-' | '+') unary | power
//   power   := primary ('^' unary)?
//   primary := number | 'x' | constant | function '(' expr (',' expr)* ')' | '(' expr ')'
// Numbers: 2, 2.5, .5, 1e-3, 1.5E+2. Functions: log exp sqrt sin cos tanh abs (one argument),
// pow(a, b) (same as a^b). Constants are the numeric parameters of the family, fixed when
// the expression is parsed; sub-expressions that do not depend on x are folded then.
//
// The expression is compiled to a tree evaluated with second-order forward-mode dual
// numbers, so f, f' and f'' are exact (to rounding), not finite differences.
// Every failure is a sinew::Error naming the expression, the 1-based position and the reason.
// Expressions are limited to 4096 characters and 200 levels of nesting.
#include <map>
#include <string>
#include <vector>

#include "sinew/core/types.hpp"

namespace sinew {

class ScalarFunction {
 public:
  // The constant zero function ("0").
  ScalarFunction();

  // Parses `text`. Identifiers other than x must be keys of `constants` (whose names may not
  // be 'x' or a function name). Throws sinew::Error on any syntax or name error.
  static ScalarFunction parse(const std::string& text,
                              const std::map<std::string, double>& constants = {});

  // f(x). Throws sinew::Error if the result is not finite (e.g. log of a negative number).
  double value(double x) const;
  // (f(x), f'(x), f''(x)), exact. Throws sinew::Error if any of them is not finite.
  Vec3 derivatives(double x) const;

  const std::string& text() const { return text_; }
  // True when the expression does not depend on x (after folding, a single constant).
  bool is_constant() const;

  // Second-order dual number (value, d/dx, d^2/dx^2); defined in expression.cpp.
  struct Dual;

 private:
  friend class ExpressionParser;
  enum class Op {
    Constant, X, Negate, Add, Subtract, Multiply, Divide,
    PowerConstant,  // a ^ c with c independent of x: integer c accepts a negative base
    Power,          // a ^ b = exp(b log a), a > 0
    Log, Exp, Sqrt, Sin, Cos, Tanh, Abs,
  };
  struct Node {
    Op op = Op::Constant;
    double constant = 0.0;  // Constant: the value; PowerConstant: the exponent
    int a = -1, b = -1;     // operands (indices into nodes_)
  };
  Dual eval(int node, double x) const;

  std::string text_;
  std::vector<Node> nodes_;
  int root_ = 0;
};

}  // namespace sinew
