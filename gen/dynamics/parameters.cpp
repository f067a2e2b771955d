#include "dynamics/parameters.hpp"

#include <set>

#include "sym/expand.hpp"

namespace dyncc::dyn {

std::string_view to_string(StandardKind kind) {
  static constexpr std::array<std::string_view, 13> names = {"M",  "MX", "MY", "MZ", "XX", "XY", "XZ",
                                                             "YY", "YZ", "ZZ", "IA", "FC", "FV"};
  return names[static_cast<std::size_t>(kind)];
}

std::vector<sym::Expr> StandardParameters::symbols() const {
  std::vector<sym::Expr> out;
  out.reserve(list.size());
  for (const auto& p : list) out.push_back(p.symbol);
  return out;
}

sym::Substitution StandardParameters::definitions() const {
  sym::Substitution map;
  for (const auto& p : list) map.emplace(p.symbol, p.definition);
  return map;
}

StandardParameters standard_parameters(const robot::RobotDescription& robot) {
  using sym::Expr;
  StandardParameters out;
  std::set<std::string> taken;
  for (const auto& p : robot.parameters) taken.insert(p.name);
  for (const auto& c : robot.constants) taken.insert(c.name);
  for (const Expr q : robot.coordinates) taken.insert(q.name());

  auto add = [&](StandardKind kind, int number, Expr definition, int link, int coordinate) -> int {
    definition = sym::expand(definition);
    if (definition.is_zero()) return -1;
    std::string name = std::string(to_string(kind)) + std::to_string(number);
    while (taken.contains(name)) name += "_";  // never collide with the description's own names
    taken.insert(name);
    out.list.push_back({name, sym::symbol(name), definition, kind, link, coordinate});
    return static_cast<int>(out.list.size() - 1);
  };

  for (std::size_t li = 0; li < robot.links.size(); ++li) {
    const robot::Link& link = robot.links[li];
    const int number = static_cast<int>(li + 1);
    const Expr m = link.mass;
    const auto& c = link.com;
    const auto& I = link.inertia;
    // Parallel-axis theorem, tensor form: I_o = I_c + m (|c|^2 1 - c c^T).
    const Expr cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    std::array<int, 10> idx{};
    const int l = static_cast<int>(li);
    idx[0] = add(StandardKind::M, number, m, l, -1);
    idx[1] = add(StandardKind::MX, number, m * c[0], l, -1);
    idx[2] = add(StandardKind::MY, number, m * c[1], l, -1);
    idx[3] = add(StandardKind::MZ, number, m * c[2], l, -1);
    idx[4] = add(StandardKind::XX, number, I.xx + m * (cc - c[0] * c[0]), l, -1);
    idx[5] = add(StandardKind::XY, number, I.xy - m * c[0] * c[1], l, -1);
    idx[6] = add(StandardKind::XZ, number, I.xz - m * c[0] * c[2], l, -1);
    idx[7] = add(StandardKind::YY, number, I.yy + m * (cc - c[1] * c[1]), l, -1);
    idx[8] = add(StandardKind::YZ, number, I.yz - m * c[1] * c[2], l, -1);
    idx[9] = add(StandardKind::ZZ, number, I.zz + m * (cc - c[2] * c[2]), l, -1);
    out.of_link.push_back(idx);
  }
  const std::size_t n = robot.coordinates.size();
  out.rotor_of.assign(n, -1);
  out.coulomb_of.assign(n, -1);
  out.viscous_of.assign(n, -1);
  for (const robot::Rotor& r : robot.rotors) {
    out.rotor_of[static_cast<std::size_t>(r.coordinate)] =
        add(StandardKind::IA, r.coordinate + 1, r.reflected_inertia(), -1, r.coordinate);
  }
  for (const robot::Friction& f : robot.friction) {
    const auto k = static_cast<std::size_t>(f.coordinate);
    out.coulomb_of[k] = add(StandardKind::FC, f.coordinate + 1, f.coulomb, -1, f.coordinate);
    out.viscous_of[k] = add(StandardKind::FV, f.coordinate + 1, f.viscous, -1, f.coordinate);
  }
  return out;
}

}  // namespace dyncc::dyn
