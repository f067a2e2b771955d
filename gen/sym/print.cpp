#include "sym/print.hpp"

#include <algorithm>
#include <unordered_map>
#include <vector>

namespace dyncc::sym {
namespace {

// Precedence levels of the printed forms, to decide on parentheses.
enum Prec : int { kSum = 1, kProduct = 2, kUnary = 3, kPower = 4, kAtom = 5 };

struct Style {
  bool latex = false;
};

class Printer {
 public:
  explicit Printer(Style style) : style_(style) {}

  std::string print(Expr e) {
    const auto it = memo_.find(e.node());
    if (it != memo_.end()) return it->second.first;
    auto result = render(e);
    memo_.emplace(e.node(), result);
    return result.first;
  }

  int precedence(Expr e) {
    print(e);
    return memo_.at(e.node()).second;
  }

 private:
  std::string wrap(Expr e, int min_prec) {
    std::string s = print(e);  // not const: returned by move
    if (precedence(e) < min_prec) return style_.latex ? "\\left(" + s + "\\right)" : "(" + s + ")";
    return s;
  }

  std::string name_text(const std::string& name) const {
    if (!style_.latex) return name;
    if (name == "pi") return "\\pi";
    // Trailing digits become a subscript: q12 -> q_{12}.
    std::size_t cut = name.size();
    while (cut > 0 && name[cut - 1] >= '0' && name[cut - 1] <= '9') --cut;
    std::string head = name.substr(0, cut);
    std::string out = head.size() > 1 ? "\\mathrm{" + head + "}" : head;
    if (cut < name.size()) out += "_{" + name.substr(cut) + "}";
    return out;
  }

  std::string number_text(const Rational& r) const {
    if (style_.latex && !r.is_integer()) {
      const std::string sign = r.is_negative() ? "-" : "";
      const Rational a = r.abs();
      const std::string dec = a.to_string();
      if (dec.find('/') == std::string::npos) return sign + dec;
      return sign + "\\frac{" + std::to_string(a.num()) + "}{" + std::to_string(a.den()) + "}";
    }
    return r.to_string();
  }

  // A coefficient-free product or atom, with its coefficient printed in front.
  std::string term_with_coef(const Rational& coef, Expr term, bool leading) {
    // Returns e.g. " - 2*x" (non-leading) or "-2*x" (leading).
    const bool negative = coef.is_negative();
    const Rational mag = coef.abs();
    std::string body;
    if (term.is_one()) {
      body = number_text(mag);
    } else if (mag.is_one()) {
      body = product_text(Rational(1), term);
    } else {
      body = product_text(mag, term);
    }
    // Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string at -O3.
    std::string out;
    if (leading) {
      out = negative ? std::string("-") : std::string();
    } else {
      out = negative ? std::string(" - ") : std::string(" + ");
    }
    out.append(body);
    return out;
  }

  std::string power_text(Expr base, std::int64_t exponent) {
    std::string b = wrap(base, kAtom);
    if (exponent == 1) return b;
    if (style_.latex) return "{" + b + "}^{" + std::to_string(exponent) + "}";
    return plain_power(b, exponent);
  }

  // b^n for the parser, which accepts exponents up to 64: larger ones (reachable by merging,
  // (x^2)^33 == x^66) are written as nested powers, b^(64q + r) = (b^q)^64*b^r, so the text
  // still reads back to the same node.
  // (Built with append: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string at -O3.)
  static std::string plain_power(const std::string& b, std::int64_t n) {
    constexpr std::int64_t kMaxParsedExponent = 64;
    std::string out;
    if (n <= kMaxParsedExponent) {
      out.append(b);
      if (n != 1) out.append("^").append(std::to_string(n));
      return out;
    }
    out.append("(")
        .append(plain_power(b, n / kMaxParsedExponent))
        .append(")^")
        .append(std::to_string(kMaxParsedExponent));
    if (n % kMaxParsedExponent != 0) out.append("*").append(plain_power(b, n % kMaxParsedExponent));
    return out;
  }

  // coef * term where term is coefficient-free (Mul with coef 1 or an atom); coef >= 0.
  std::string product_text(const Rational& coef, Expr term) {
    std::vector<std::pair<std::string, std::int64_t>> numerator;
    std::vector<std::pair<std::string, std::int64_t>> denominator;
    auto add_factor = [&](Expr base, std::int64_t exp) {
      if (exp > 0) {
        numerator.emplace_back(power_text(base, exp), exp);
      } else {
        denominator.emplace_back(power_text(base, -exp), -exp);
      }
    };
    if (term.kind() == Kind::Mul) {
      for (std::size_t i = 0; i < term.args().size(); ++i) add_factor(term.args()[i], term.weights()[i].num());
    } else {
      add_factor(term, 1);
    }
    // Names before functions (l2*m3*cos(q3)), each group in natural order.
    auto by_name = [](const auto& l, const auto& r) {
      const bool lf = l.first.find('(') != std::string::npos;
      const bool rf = r.first.find('(') != std::string::npos;
      if (lf != rf) return rf;
      return natural_less(l.first, r.first);
    };
    std::sort(numerator.begin(), numerator.end(), by_name);
    std::sort(denominator.begin(), denominator.end(), by_name);
    const std::string times = style_.latex ? " " : "*";
    auto join = [&](const auto& list) {
      std::string s;
      for (const auto& [text, exp] : list) s += (s.empty() ? "" : times) + text;
      return s;
    };
    // Coefficient p/q: p goes in front, q joins the denominator so "x/2" reads naturally.
    std::string num_text = join(numerator);
    std::string den_text = join(denominator);
    const Rational c = coef;
    std::string coef_text;
    if (!c.is_one()) {
      const std::string dec = number_text(c);
      const bool decimal = dec.find('/') == std::string::npos && dec.find("frac") == std::string::npos;
      if (decimal || style_.latex) {
        coef_text = dec;
      } else {
        coef_text = c.num() == 1 ? "" : std::to_string(c.num());
        den_text = den_text.empty() ? std::to_string(c.den()) : std::to_string(c.den()) + "*" + den_text;
      }
    }
    std::string head = coef_text;
    if (!num_text.empty()) head = head.empty() ? num_text : head + times + num_text;
    if (head.empty()) head.assign(1, '1');
    if (den_text.empty()) return head;
    if (style_.latex) return "\\frac{" + head + "}{" + den_text + "}";
    const bool single =
        denominator.size() <= 1 && (c.is_one() || denominator.empty()) && den_text.find('*') == std::string::npos;
    return head + "/" + (single ? den_text : "(" + den_text + ")");
  }

  std::pair<std::string, int> render(Expr e) {
    switch (e.kind()) {
      case Kind::Number:
        return {number_text(e.value()), e.value().is_negative() || !e.value().is_integer() ? kUnary : kAtom};
      case Kind::Constant:
      case Kind::Symbol: return {name_text(e.name()), kAtom};
      case Kind::Add: {
        // Display order: positive terms first, then by text in natural order; constant last.
        struct Item {
          std::string key;
          Rational coef;
          Expr term;
        };
        std::vector<Item> items;
        for (std::size_t i = 0; i < e.args().size(); ++i)
          items.push_back({print(e.args()[i]), e.weights()[i], e.args()[i]});
        std::sort(items.begin(), items.end(), [](const Item& l, const Item& r) {
          if (l.coef.is_negative() != r.coef.is_negative()) return !l.coef.is_negative();
          return natural_less(l.key, r.key);
        });
        std::string s;
        for (const Item& it : items) s += term_with_coef(it.coef, it.term, s.empty());
        if (!e.value().is_zero()) s += term_with_coef(e.value(), Expr(1), false);
        return {s, kSum};
      }
      case Kind::Mul: {
        const Rational c = e.value();
        auto [_, rest] = split_coefficient(e);
        const std::string body = product_text(c.abs(), rest);
        if (c.is_negative()) return {std::string("-").append(body), kUnary};
        // a lone power x^2 binds tighter than a product
        const bool lone_power = e.args().size() == 1 && c.is_one() && e.weights()[0].num() > 0;
        return {body, lone_power ? kPower : kProduct};
      }
      case Kind::Sin:
      case Kind::Cos:
      case Kind::Sqrt: {
        const char* fn = e.kind() == Kind::Sin ? "sin" : (e.kind() == Kind::Cos ? "cos" : "sqrt");
        if (style_.latex) {
          if (e.kind() == Kind::Sqrt) return {"\\sqrt{" + print(e.args()[0]) + "}", kAtom};
          return {std::string("\\") + fn + "\\left(" + print(e.args()[0]) + "\\right)", kAtom};
        }
        return {std::string(fn) + "(" + print(e.args()[0]) + ")", kAtom};
      }
      case Kind::Atan2: {
        const std::string open = style_.latex ? "\\operatorname{atan2}\\left(" : "atan2(";
        const std::string close = style_.latex ? "\\right)" : ")";
        return {open + print(e.args()[0]) + ", " + print(e.args()[1]) + close, kAtom};
      }
    }
    return {"?", kAtom};
  }

  Style style_;
  std::unordered_map<const Node*, std::pair<std::string, int>> memo_;
};

}  // namespace

std::string to_string(Expr e) { return Printer(Style{false}).print(e); }
std::string to_latex(Expr e) { return Printer(Style{true}).print(e); }

}  // namespace dyncc::sym
