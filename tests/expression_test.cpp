// The expression language of user-supplied functions: values, exact first and second
// derivatives (checked against finite differences), precedence, and every error path.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sinew/core/error.hpp"
#include "sinew/core/finite_difference.hpp"
#include "sinew/material/expression.hpp"

namespace sinew {
namespace {

const std::map<std::string, double> kConstants{{"lambda", 4.0}, {"mu", 1.5}, {"E", 3.0}};

double value_of(const std::string& text, double x = 0.0) {
  return ScalarFunction::parse(text, kConstants).value(x);
}

// Central differences with one Richardson step (error O(h^4)), from the library's core.
template <class Fn>
double central(Fn&& fn, double x, double h) {
  return richardson_difference(fn, x, 1.0, h);
}

struct Case {
  const char* text;
  double x;
};

TEST(Expression, DerivativesMatchFiniteDifferences) {
  const Case cases[] = {
      {"x", 0.7},
      {"2*x+1", -1.3},
      {"x^2", 1.7},
      {"x^3 - 2*x", -0.8},
      {"-x^2 + 3", 0.4},
      {"x^x", 1.4},
      {"pow(x, 2.5)", 0.9},
      {"2^x", 0.3},
      {"x^-1.5", 2.2},
      {"log(x)", 0.6},
      {"exp(-x)*x", 1.1},
      {"sqrt(x)", 3.0},
      {"sin(x)*cos(x)", 0.5},
      {"tanh(2*x)", -0.3},
      {"abs(x-2)", 1.0},
      {"abs(x-2)", 3.0},
      {"1e-3*x^4 + .5*x", 1.9},
      {"mu*(x-1)^2", 1.4},
      {"lambda/2*log(x)^2", 0.7},
      {"(x+1)/(x-3)", 1.2},
      {"E*(x - 1 - log(x) - log(x)^2/6 + log(x)^3/18 - log(x)^4/216)", 2.5},
      {"exp(sin(x)^2)/sqrt(1 + x^2)", 0.8},
      {"(x^0.5 - x^-0.5)^2", 1.6},
  };
  for (const Case& c : cases) {
    const ScalarFunction f = ScalarFunction::parse(c.text, kConstants);
    const Vec3 d = f.derivatives(c.x);
    EXPECT_DOUBLE_EQ(d(0), f.value(c.x)) << c.text;
    const double h = 1e-3 * std::max(1.0, std::abs(c.x));
    const double fd1 = central([&](double t) { return f.value(t); }, c.x, h);
    const double fd2 = central([&](double t) { return f.derivatives(t)(1); }, c.x, h);
    EXPECT_NEAR(d(1), fd1, 1e-8 * std::max(1.0, std::abs(fd1))) << c.text << " at x = " << c.x;
    EXPECT_NEAR(d(2), fd2, 1e-8 * std::max(1.0, std::abs(fd2))) << c.text << " at x = " << c.x;
  }
}

TEST(Expression, ExactValuesAndDerivatives) {
  // x^3 - 2x at 2: 4, 10, 12.
  Vec3 d = ScalarFunction::parse("x^3 - 2*x").derivatives(2.0);
  EXPECT_EQ(d, Vec3(4.0, 10.0, 12.0));
  // Integral powers of a negative base.
  d = ScalarFunction::parse("x^3").derivatives(-2.0);
  EXPECT_EQ(d, Vec3(-8.0, 12.0, -12.0));
  // x^2 and x^1 at 0 stay finite.
  EXPECT_EQ(ScalarFunction::parse("x^2").derivatives(0.0), Vec3(0.0, 0.0, 2.0));
  EXPECT_EQ(ScalarFunction::parse("pow(x, 1)").derivatives(0.0), Vec3(0.0, 1.0, 0.0));
  // log at 1: 0, 1, -1; parameters by name.
  EXPECT_EQ(ScalarFunction::parse("log(x)").derivatives(1.0), Vec3(0.0, 1.0, -1.0));
  d = ScalarFunction::parse("mu*(x-1)^2", kConstants).derivatives(1.0);
  EXPECT_EQ(d, Vec3(0.0, 0.0, 3.0));
  // Division: 1/x at 2 = 0.5, -0.25, 0.25.
  EXPECT_EQ(ScalarFunction::parse("1/x").derivatives(2.0), Vec3(0.5, -0.25, 0.25));
}

TEST(Expression, PrecedenceAndNumbers) {
  EXPECT_EQ(value_of("2+3*4"), 14.0);
  EXPECT_EQ(value_of("(2+3)*4"), 20.0);
  EXPECT_EQ(value_of("-2^2"), -4.0);  // '^' binds tighter than unary minus
  EXPECT_EQ(value_of("2^3^2"), 512.0);  // right-associative
  EXPECT_EQ(value_of("2^-1"), 0.5);
  EXPECT_EQ(value_of("8/2/2"), 2.0);  // left-associative
  EXPECT_EQ(value_of("2-3-4"), -5.0);
  EXPECT_EQ(value_of("x - -x", 1.5), 3.0);
  EXPECT_EQ(value_of("+x", 1.5), 1.5);
  EXPECT_EQ(value_of("1e-3"), 1e-3);
  EXPECT_EQ(value_of("1.5E+2"), 150.0);
  EXPECT_EQ(value_of(".25"), 0.25);
  EXPECT_EQ(value_of("  lambda *  mu "), 6.0);
  EXPECT_EQ(value_of("E"), 3.0);  // a parameter named like an exponent letter
  EXPECT_EQ(value_of("pow(2, 10)"), 1024.0);
  EXPECT_NEAR(value_of("exp(log(7))"), 7.0, 1e-14);
  std::string sum = "x";
  for (int i = 0; i < 1000; ++i) sum += "+x";
  EXPECT_EQ(value_of(sum, 0.5), 500.5);
  EXPECT_EQ(value_of(std::string(100, '(') + "x" + std::string(100, ')'), 2.0), 2.0);
}

TEST(Expression, ConstantsAreFolded) {
  EXPECT_TRUE(ScalarFunction::parse("lambda/2*log(2)^2", kConstants).is_constant());
  EXPECT_FALSE(ScalarFunction::parse("lambda*x", kConstants).is_constant());
  const ScalarFunction zero;
  EXPECT_TRUE(zero.is_constant());
  EXPECT_EQ(zero.derivatives(3.0), Vec3::Zero());
  EXPECT_EQ(zero.text(), "0");
}

// Expects an Error whose text names the expression and contains every fragment.
void expect_error(const std::string& text, std::initializer_list<std::string> fragments,
                  const std::map<std::string, double>& constants = kConstants) {
  try {
    ScalarFunction::parse(text, constants);
    ADD_FAILURE() << "no error for '" << text << "'";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("expression '" + text + "'"), std::string::npos) << what;
    for (const auto& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << what;
  }
}

TEST(Expression, ParseErrorsNameExpressionPositionAndReason) {
  expect_error("", {"empty expression"});
  expect_error("   ", {"empty expression"});
  expect_error("log(y)", {"unknown identifier 'y'", "position 5", "known: x, E, lambda, mu"});
  expect_error("foo(x)", {"unknown function 'foo'", "position 1"});
  expect_error("log x", {"'log' is a function", "position 1"});
  expect_error("2*exp", {"'exp' is a function", "position 3"});
  expect_error("(x+1", {"unbalanced parenthesis", "'(' at position 1 is never closed", "end of input"});
  expect_error("log(x", {"unbalanced parenthesis", "'(' at position 4 is never closed"});
  expect_error("x+1)", {"unbalanced parenthesis", "')' without a matching '('", "position 4"});
  expect_error("x 2", {"trailing input '2'", "position 3"});
  expect_error("x*", {"expected an operand, got end of input", "position 3"});
  expect_error("*x", {"expected an operand, got '*'", "position 1"});
  expect_error("x + #", {"expected an operand, got '#'", "position 5"});
  expect_error("2*()", {"expected an operand, got ')'", "position 4"});
  expect_error("1e", {"malformed number '1e'", "position 1"});
  expect_error("x*2e+", {"malformed number '2e+'", "position 3"});
  expect_error(".", {"malformed number '.'", "position 1"});
  expect_error("1e999", {"number '1e999' is out of range"});
  expect_error("pow(x)", {"function 'pow' expects 2 arguments, got 1", "position 1"});
  expect_error("log(x, 2)", {"function 'log' expects 1 argument, got 2"});
  expect_error("sin()", {"function 'sin' expects 1 argument, got 0"});
  expect_error("x + 1/0", {"sub-expression '1/0' is not finite", "position 5"});
  expect_error("log(-1) * x", {"is not finite", "position 1"});
  expect_error(std::string(300, '(') + "x" + std::string(300, ')'), {"nested deeper than 200 levels"});
  expect_error(std::string(300, '-') + "x", {"nested deeper than 200 levels"});
  std::string long_sum = "x";
  while (long_sum.size() <= 4096) long_sum += "+x";
  expect_error(long_sum, {"longer than 4096 characters"});
  expect_error("x", {"constant name 'x' is reserved"}, {{"x", 1.0}});
  expect_error("x", {"constant name 'log' is reserved"}, {{"log", 1.0}});
  expect_error("x", {"constant 'a' is not finite"}, {{"a", std::nan("")}});
}

TEST(Expression, EvaluationErrorsAreReported) {
  const ScalarFunction f = ScalarFunction::parse("log(x)");
  EXPECT_THROW(f.value(-1.0), Error);
  EXPECT_THROW(f.derivatives(0.0), Error);
  const ScalarFunction s = ScalarFunction::parse("sqrt(x)");
  EXPECT_EQ(s.value(0.0), 0.0);
  EXPECT_THROW(s.derivatives(0.0), Error);  // infinite slope
  try {
    ScalarFunction::parse("x^x").value(-1.5);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("expression 'x^x'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not finite at x = -1.5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sinew
