#include "sinew/material/expression.hpp"

#include <cctype>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

// Second-order forward-mode dual number: a value with its first and second derivative in x.
struct ScalarFunction::Dual {
  double v = 0.0, d = 0.0, dd = 0.0;
};

namespace {

using Dual = ScalarFunction::Dual;

Dual operator+(const Dual& a, const Dual& b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
Dual operator-(const Dual& a, const Dual& b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
Dual operator*(const Dual& a, const Dual& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * a.d * b.d + a.v * b.dd};
}

// Chain rule for phi(u) given phi, phi', phi'' at u.v:
//   (phi(u))' = phi' u',  (phi(u))'' = phi'' u'^2 + phi' u''.
Dual chain(const Dual& u, double f0, double f1, double f2) {
  return {f0, f1 * u.d, f2 * u.d * u.d + f1 * u.dd};
}

Dual reciprocal(const Dual& u) {
  const double r = 1.0 / u.v;
  return chain(u, r, -r * r, 2.0 * r * r * r);
}

// u^c for a constant c. std::pow is exact in sign for integral c and a negative base; the
// derivative terms whose coefficient vanishes are skipped so 0^c stays finite for c = 1, 2.
Dual power_constant(const Dual& u, double c) {
  if (c == 0.0) return {1.0, 0.0, 0.0};
  const double f0 = std::pow(u.v, c);
  const double f1 = c * std::pow(u.v, c - 1.0);
  const double k2 = c * (c - 1.0);
  const double f2 = k2 == 0.0 ? 0.0 : k2 * std::pow(u.v, c - 2.0);
  return chain(u, f0, f1, f2);
}

struct FunctionEntry {
  const char* name;
  int arity;
};
constexpr FunctionEntry kFunctions[] = {{"log", 1},  {"exp", 1},  {"sqrt", 1}, {"sin", 1},
                                        {"cos", 1},  {"tanh", 1}, {"abs", 1},  {"pow", 2}};

const FunctionEntry* find_function(const std::string& name) {
  for (const auto& f : kFunctions) {
    if (name == f.name) return &f;
  }
  return nullptr;
}

bool is_identifier_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_identifier_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

}  // namespace

// Recursive-descent parser building the node tree of a ScalarFunction (see the grammar in
// the header). Sub-trees independent of x are folded to constants as they are built.
class ExpressionParser {
 public:
  ExpressionParser(const std::string& text, const std::map<std::string, double>& constants,
                   ScalarFunction& out)
      : text_(text), constants_(constants), out_(out) {}

  void run() {
    for (const auto& [name, value] : constants_) {
      if (name == "x" || find_function(name)) {
        throw error(fmt::format("constant name '{}' is reserved", name), std::string::npos);
      }
      if (!std::isfinite(value)) {
        throw error(fmt::format("constant '{}' is not finite", name), std::string::npos);
      }
    }
    // Bounds that keep the recursive parser and evaluator far from the stack limit.
    if (text_.size() > kMaxLength) {
      throw error(fmt::format("expression is longer than {} characters", kMaxLength),
                  std::string::npos);
    }
    skip_space();
    if (pos_ == text_.size()) throw error("empty expression", pos_);
    out_.root_ = expr();
    skip_space();
    if (pos_ < text_.size()) {
      if (text_[pos_] == ')') throw error("unbalanced parenthesis: ')' without a matching '('", pos_);
      throw error(fmt::format("trailing input '{}' after a complete expression",
                              text_.substr(pos_)),
                  pos_);
    }
  }

 private:
  using Node = ScalarFunction::Node;
  using Op = ScalarFunction::Op;

  Error error(const std::string& reason, std::size_t at) const {
    const std::string where = fmt::format("expression '{}'", text_);
    if (at == std::string::npos) return Error(reason, where);
    return Error(fmt::format("{} at position {}", reason, at + 1), where);
  }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  char peek() {
    skip_space();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  std::string describe_next() {
    const char c = peek();
    return c == '\0' ? "end of input" : fmt::format("'{}'", c);
  }

  // Adds a node; if none of its operands depends on x it is evaluated now and replaced by a
  // constant. `start` is where its text begins (for the non-finite-constant error).
  int add(Node n, std::size_t start) {
    out_.nodes_.push_back(n);
    const int id = static_cast<int>(out_.nodes_.size()) - 1;
    const bool constant_a = n.a < 0 || out_.nodes_[n.a].op == Op::Constant;
    const bool constant_b = n.b < 0 || out_.nodes_[n.b].op == Op::Constant;
    if (n.op == Op::X || n.op == Op::Constant || !constant_a || !constant_b) return id;
    const double v = out_.eval(id, 0.0).v;
    if (!std::isfinite(v)) {
      throw error(fmt::format("sub-expression '{}' is not finite (it evaluates to {})",
                              text_.substr(start, pos_ - start), v),
                  start);
    }
    // A constant sub-tree always sits at the end of the node list as one node (by this very
    // folding), so the operands occupy [n.a, id) and can be replaced by the folded value.
    out_.nodes_.resize(static_cast<std::size_t>(n.a));
    Node c;
    c.op = Op::Constant;
    c.constant = v;
    out_.nodes_.push_back(c);
    return static_cast<int>(out_.nodes_.size()) - 1;
  }

  int binary(Op op, int a, int b, std::size_t start) {
    Node n;
    n.op = op;
    n.a = a;
    n.b = b;
    return add(n, start);
  }

  // Counts nesting: parentheses and function arguments (expr), exponents, and signs.
  struct Depth {
    explicit Depth(ExpressionParser& p) : parser(p) {
      if (++parser.depth_ > kMaxDepth) {
        throw parser.error(fmt::format("expression is nested deeper than {} levels", kMaxDepth),
                           parser.pos_);
      }
    }
    ~Depth() { --parser.depth_; }
    Depth(const Depth&) = delete;
    Depth& operator=(const Depth&) = delete;
    ExpressionParser& parser;
  };

  int expr() {
    const Depth guard(*this);
    const std::size_t start = (skip_space(), pos_);
    int lhs = term();
    for (char c = peek(); c == '+' || c == '-'; c = peek()) {
      ++pos_;
      const int rhs = term();
      lhs = binary(c == '+' ? Op::Add : Op::Subtract, lhs, rhs, start);
    }
    return lhs;
  }

  int term() {
    const std::size_t start = (skip_space(), pos_);
    int lhs = unary();
    for (char c = peek(); c == '*' || c == '/'; c = peek()) {
      ++pos_;
      const int rhs = unary();
      lhs = binary(c == '*' ? Op::Multiply : Op::Divide, lhs, rhs, start);
    }
    return lhs;
  }

  int unary() {
    const std::size_t start = (skip_space(), pos_);
    const char c = peek();
    if (c == '+') {
      ++pos_;
      const Depth guard(*this);
      return unary();
    }
    if (c == '-') {
      ++pos_;
      const Depth guard(*this);
      Node n;
      n.op = Op::Negate;
      n.a = unary();
      return add(n, start);
    }
    return power();
  }

  int power() {
    const std::size_t start = (skip_space(), pos_);
    const int base = primary();
    if (peek() != '^') return base;
    ++pos_;
    const Depth guard(*this);
    const int exponent = unary();  // right-associative: a^b^c = a^(b^c)
    return make_power(base, exponent, start);
  }

  int make_power(int base, int exponent, std::size_t start) {
    Node n;
    if (out_.nodes_[exponent].op == Op::Constant) {
      n.op = Op::PowerConstant;
      n.constant = out_.nodes_[exponent].constant;
      n.a = base;
      // The exponent node is now unused; it is the newest node, so drop it.
      if (exponent == static_cast<int>(out_.nodes_.size()) - 1) out_.nodes_.pop_back();
      return add(n, start);
    }
    n.op = Op::Power;
    n.a = base;
    n.b = exponent;
    return add(n, start);
  }

  int primary() {
    const std::size_t start = (skip_space(), pos_);
    const char c = peek();
    if (c == '\0') throw error("expected an operand, got end of input", pos_);
    if (is_digit(c) || c == '.') return number();
    if (c == '(') {
      ++pos_;
      const int inner = expr();
      if (peek() != ')') {
        throw error(fmt::format("unbalanced parenthesis: '(' at position {} is never closed "
                                "(expected ')', got {})",
                                start + 1, describe_next()),
                    pos_);
      }
      ++pos_;
      return inner;
    }
    if (is_identifier_start(c)) return identifier();
    throw error(fmt::format("expected an operand, got '{}'", c), pos_);
  }

  int number() {
    const std::size_t start = pos_;
    std::size_t p = pos_;
    while (p < text_.size() && is_digit(text_[p])) ++p;
    if (p < text_.size() && text_[p] == '.') {
      ++p;
      while (p < text_.size() && is_digit(text_[p])) ++p;
    }
    if (p - start == 1 && text_[start] == '.') throw error("malformed number '.'", start);
    if (p < text_.size() && (text_[p] == 'e' || text_[p] == 'E')) {
      std::size_t q = p + 1;
      if (q < text_.size() && (text_[q] == '+' || text_[q] == '-')) ++q;
      if (q >= text_.size() || !is_digit(text_[q])) {
        throw error(fmt::format("malformed number '{}': the exponent has no digits",
                                text_.substr(start, q - start)),
                    start);
      }
      while (q < text_.size() && is_digit(text_[q])) ++q;
      p = q;
    }
    const std::string literal = text_.substr(start, p - start);
    const double v = std::strtod(literal.c_str(), nullptr);
    if (!std::isfinite(v)) throw error(fmt::format("number '{}' is out of range", literal), start);
    pos_ = p;
    Node n;
    n.op = Op::Constant;
    n.constant = v;
    return add(n, start);
  }

  int identifier() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_identifier_char(text_[pos_])) ++pos_;
    const std::string name = text_.substr(start, pos_ - start);
    const bool call = peek() == '(';
    if (const FunctionEntry* f = find_function(name)) {
      if (!call) {
        throw error(fmt::format("'{}' is a function: expected '(' after it", name), start);
      }
      return call_function(*f, start);
    }
    if (call) {
      throw error(fmt::format("unknown function '{}' (known: log, exp, sqrt, sin, cos, tanh, "
                              "abs, pow)",
                              name),
                  start);
    }
    Node n;
    if (name == "x") {
      n.op = Op::X;
      return add(n, start);
    }
    const auto it = constants_.find(name);
    if (it == constants_.end()) {
      std::string known = "x";
      for (const auto& [k, v] : constants_) known += ", " + k;
      throw error(fmt::format("unknown identifier '{}' (known: {})", name, known), start);
    }
    n.op = Op::Constant;
    n.constant = it->second;
    return add(n, start);
  }

  int call_function(const FunctionEntry& f, std::size_t start) {
    const std::size_t open = (skip_space(), pos_);
    ++pos_;  // '('
    std::vector<int> args;
    if (peek() != ')') {
      args.push_back(expr());
      while (peek() == ',') {
        ++pos_;
        args.push_back(expr());
      }
    }
    if (peek() != ')') {
      throw error(fmt::format("unbalanced parenthesis: '(' at position {} is never closed "
                              "(expected ',' or ')', got {})",
                              open + 1, describe_next()),
                  pos_);
    }
    ++pos_;
    if (static_cast<int>(args.size()) != f.arity) {
      throw error(fmt::format("function '{}' expects {} argument{}, got {}", f.name, f.arity,
                              f.arity == 1 ? "" : "s", args.size()),
                  start);
    }
    const std::string name = f.name;
    if (name == "pow") return make_power(args[0], args[1], start);
    Node n;
    n.a = args[0];
    if (name == "log") n.op = Op::Log;
    if (name == "exp") n.op = Op::Exp;
    if (name == "sqrt") n.op = Op::Sqrt;
    if (name == "sin") n.op = Op::Sin;
    if (name == "cos") n.op = Op::Cos;
    if (name == "tanh") n.op = Op::Tanh;
    if (name == "abs") n.op = Op::Abs;
    return add(n, start);
  }

  static constexpr std::size_t kMaxLength = 4096;
  static constexpr int kMaxDepth = 200;

  const std::string& text_;
  const std::map<std::string, double>& constants_;
  ScalarFunction& out_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

// ---------------------------------------------------------------- ScalarFunction

ScalarFunction::ScalarFunction() : text_("0"), nodes_{Node{}}, root_(0) {}

ScalarFunction ScalarFunction::parse(const std::string& text,
                                     const std::map<std::string, double>& constants) {
  ScalarFunction f;
  f.text_ = text;
  f.nodes_.clear();
  ExpressionParser(text, constants, f).run();
  return f;
}

bool ScalarFunction::is_constant() const { return nodes_[root_].op == Op::Constant; }

ScalarFunction::Dual ScalarFunction::eval(int id, double x) const {
  const Node& n = nodes_[id];
  switch (n.op) {
    case Op::Constant: return {n.constant, 0.0, 0.0};
    case Op::X: return {x, 1.0, 0.0};
    case Op::Negate: {
      const Dual a = eval(n.a, x);
      return {-a.v, -a.d, -a.dd};
    }
    case Op::Add: return eval(n.a, x) + eval(n.b, x);
    case Op::Subtract: return eval(n.a, x) - eval(n.b, x);
    case Op::Multiply: return eval(n.a, x) * eval(n.b, x);
    case Op::Divide: return eval(n.a, x) * reciprocal(eval(n.b, x));
    case Op::PowerConstant: return power_constant(eval(n.a, x), n.constant);
    case Op::Power: {
      // a^b = exp(b log a); defined for a > 0 only (non-finite otherwise, reported by the caller).
      const Dual a = eval(n.a, x);
      const Dual la = chain(a, std::log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v));
      const Dual e = eval(n.b, x) * la;
      const double ex = std::exp(e.v);
      return chain(e, ex, ex, ex);
    }
    case Op::Log: {
      const Dual a = eval(n.a, x);
      return chain(a, std::log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v));
    }
    case Op::Exp: {
      const Dual a = eval(n.a, x);
      const double ex = std::exp(a.v);
      return chain(a, ex, ex, ex);
    }
    case Op::Sqrt: {
      const Dual a = eval(n.a, x);
      const double r = std::sqrt(a.v);
      return chain(a, r, 0.5 / r, -0.25 / (r * a.v));
    }
    case Op::Sin: {
      const Dual a = eval(n.a, x);
      const double s = std::sin(a.v);
      return chain(a, s, std::cos(a.v), -s);
    }
    case Op::Cos: {
      const Dual a = eval(n.a, x);
      const double c = std::cos(a.v);
      return chain(a, c, -std::sin(a.v), -c);
    }
    case Op::Tanh: {
      const Dual a = eval(n.a, x);
      const double t = std::tanh(a.v);
      const double s = 1.0 - t * t;  // sech^2
      return chain(a, t, s, -2.0 * t * s);
    }
    case Op::Abs: {
      // |u| is not differentiable at u = 0; there the (one-sided average) slope 0 is used.
      const Dual a = eval(n.a, x);
      const double sign = a.v > 0.0 ? 1.0 : (a.v < 0.0 ? -1.0 : 0.0);
      return chain(a, std::abs(a.v), sign, 0.0);
    }
  }
  return {};
}

double ScalarFunction::value(double x) const {
  const double v = eval(root_, x).v;
  if (!std::isfinite(v)) {
    throw Error(fmt::format("value is not finite at x = {}", x), fmt::format("expression '{}'", text_));
  }
  return v;
}

Vec3 ScalarFunction::derivatives(double x) const {
  const Dual r = eval(root_, x);
  if (!std::isfinite(r.v) || !std::isfinite(r.d) || !std::isfinite(r.dd)) {
    throw Error(fmt::format("value or derivatives not finite at x = {} (f = {}, f' = {}, f'' = {})",
                            x, r.v, r.d, r.dd),
                fmt::format("expression '{}'", text_));
  }
  return {r.v, r.d, r.dd};
}

}  // namespace sinew
