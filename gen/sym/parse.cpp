#include "sym/parse.hpp"

#include <stdexcept>
#include <string>

namespace dyncc::sym {
namespace {

constexpr int kMaxDepth = 200;    // nesting guard: malformed input must not exhaust the stack
constexpr int kMaxExponent = 64;  // larger powers would make expansion explode
constexpr std::size_t kMaxLength = 100000;

struct Failure {
  ParseError error;
};

class Parser {
 public:
  explicit Parser(std::string_view text) : text_(text) {}

  ParseResult run() {
    ParseResult result;
    try {
      if (text_.size() > kMaxLength) fail(1, "expression longer than " + std::to_string(kMaxLength) + " characters");
      skip_space();
      if (pos_ == text_.size()) fail(pos_, "expected an expression, found nothing");
      const Expr e = expression();
      skip_space();
      if (pos_ != text_.size()) {
        if (text_[pos_] == ')') fail(pos_, "unmatched ')'");
        fail(pos_, "expected an operator (+ - * / ^) or the end, found '" + std::string(1, text_[pos_]) + "'");
      }
      result.expr = e;
      result.symbols = std::move(symbols_);
    } catch (const Failure& f) {
      result.error = f.error;
    }
    return result;
  }

 private:
  [[noreturn]] static void fail(std::size_t index0, std::string message) {
    throw Failure{ParseError{index0 + 1, std::move(message)}};
  }

  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }

  bool accept(std::string_view token) {
    skip_space();
    if (text_.substr(pos_, token.size()) == token) {
      pos_ += token.size();
      return true;
    }
    return false;
  }

  char peek() {
    skip_space();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }

  struct DepthGuard {
    explicit DepthGuard(Parser& p) : parser(p) {
      if (++parser.depth_ > kMaxDepth)
        fail(parser.pos_, "expression nested deeper than " + std::to_string(kMaxDepth) + " levels");
    }
    ~DepthGuard() { --parser.depth_; }
    DepthGuard(const DepthGuard&) = delete;
    DepthGuard& operator=(const DepthGuard&) = delete;
    Parser& parser;
  };

  // Wraps engine errors (division by zero, overflow, domain) with the operator's column.
  template <typename F>
  Expr guarded(std::size_t at, F&& f) {
    try {
      return f();
    } catch (const std::domain_error& e) {
      fail(at, e.what());
    } catch (const std::overflow_error& e) {
      fail(at, e.what());
    }
  }

  Expr expression() {
    const DepthGuard guard(*this);
    Expr e = term();
    for (;;) {
      const char c = peek();
      if (c != '+' && c != '-') return e;
      const std::size_t at = pos_++;
      const Expr rhs = term();
      e = guarded(at, [&] { return c == '+' ? e + rhs : e - rhs; });
    }
  }

  Expr term() {
    Expr e = unary();
    for (;;) {
      const char c = peek();
      if (c != '*' && c != '/') return e;
      if (c == '*' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') return e;  // '**' is power
      const std::size_t at = pos_++;
      const Expr rhs = unary();
      if (c == '/' && rhs.is_zero()) fail(at, "division by zero");
      e = guarded(at, [&] { return c == '*' ? e * rhs : e / rhs; });
    }
  }

  Expr unary() {
    const DepthGuard guard(*this);
    const char c = peek();
    if (c == '-' || c == '+') {
      const std::size_t at = pos_++;
      const Expr operand = unary();
      return c == '-' ? guarded(at, [&] { return -operand; }) : operand;
    }
    return power();
  }

  Expr power() {
    const Expr base = primary();
    skip_space();
    const std::size_t at = pos_;
    if (!(accept("**") || accept("^"))) return base;
    skip_space();
    const std::size_t exponent_at = pos_;
    const Expr exponent = unary();
    if (!exponent.is_number()) fail(exponent_at, "exponent must be a number, found an expression with symbols");
    const Rational n = exponent.value();
    // Range first: doubling a huge exponent (x^4^31) would overflow and throw out of parse().
    if (n > Rational(kMaxExponent) || n < Rational(-kMaxExponent)) {
      fail(exponent_at, "exponent " + n.to_string() + " is too large (at most " + std::to_string(kMaxExponent) + ")");
    }
    const Rational twice = n * Rational(2);
    if (!twice.is_integer()) fail(exponent_at, "exponent must be an integer or a half-integer, found " + n.to_string());
    return guarded(at, [&] {
      if (n.is_integer()) return pow(base, static_cast<int>(n.num()));
      return pow(sqrt(base), static_cast<int>(twice.num()));
    });
  }

  static bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
  static bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9'); }
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }

  Expr primary() {
    const char c = peek();
    const std::size_t start = pos_;
    if (c == '\0') fail(pos_, "expected a number, a name or '(', found the end of the expression");
    if (c == '(') {
      ++pos_;
      const Expr e = expression();
      if (!accept(")")) fail(pos_, "expected ')' to close '(' at column " + std::to_string(start + 1));
      return e;
    }
    if (is_digit(c) || c == '.') return number_literal();
    if (is_name_start(c)) {
      while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
      const std::string name(text_.substr(start, pos_ - start));
      if (peek() == '(') return call(name, start);
      if (name == "pi") return sym::pi();
      if (name == "sin" || name == "cos" || name == "sqrt" || name == "atan2") {
        fail(pos_, "expected '(' after function '" + name + "'");
      }
      symbols_.push_back({name, start + 1});
      return symbol(name);
    }
    fail(pos_, "expected a number, a name or '(', found '" + std::string(1, c) + "'");
  }

  Expr number_literal() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && (is_digit(text_[pos_]) || text_[pos_] == '.')) ++pos_;
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) ++p;
      if (p < text_.size() && is_digit(text_[p])) {
        pos_ = p;
        while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
      }
    }
    Rational value;
    const std::string_view literal = text_.substr(start, pos_ - start);
    if (!Rational::parse_decimal(literal, value)) {
      fail(start, "malformed or out-of-range number '" + std::string(literal) + "'");
    }
    if (pos_ < text_.size() && is_name_start(text_[pos_])) {
      fail(pos_,
           "expected an operator after the number, found '" + std::string(1, text_[pos_]) + "' (write 2*x, not 2x)");
    }
    return number(value);
  }

  Expr call(const std::string& name, std::size_t at) {
    ++pos_;  // '('
    const std::size_t open = pos_ - 1;
    std::vector<Expr> args;
    if (peek() != ')') {
      args.push_back(expression());
      while (accept(",")) args.push_back(expression());
    }
    if (!accept(")")) fail(pos_, "expected ',' or ')' to close '(' at column " + std::to_string(open + 1));
    auto arity = [&](std::size_t n) {
      if (args.size() != n) {
        fail(at, "function '" + name + "' takes " + std::to_string(n) + " argument" + (n == 1 ? "" : "s") + ", found " +
                     std::to_string(args.size()));
      }
    };
    if (name == "sin") {
      arity(1);
      return guarded(at, [&] { return sin(args[0]); });
    }
    if (name == "cos") {
      arity(1);
      return guarded(at, [&] { return cos(args[0]); });
    }
    if (name == "sqrt") {
      arity(1);
      return guarded(at, [&] { return sqrt(args[0]); });
    }
    if (name == "atan2") {
      arity(2);
      return atan2(args[0], args[1]);
    }
    fail(at, "unknown function '" + name + "' (known: sin, cos, sqrt, atan2)");
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  std::vector<SymbolUse> symbols_;
};

}  // namespace

ParseResult parse(std::string_view text) { return Parser(text).run(); }

Expr parse_or_throw(std::string_view text) {
  ParseResult r = parse(text);
  if (!r.ok()) {
    throw std::invalid_argument("column " + std::to_string(r.error.column) + ": " + r.error.message);
  }
  return *r.expr;
}

}  // namespace dyncc::sym
