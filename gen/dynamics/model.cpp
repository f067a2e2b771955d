#include "dynamics/model.hpp"

#include <set>

#include "sym/diff.hpp"

namespace dyncc::dyn {
namespace {

// Vec3/Mat3 arithmetic lives in kin; the operators are not found by ADL on std::array.
using namespace dyncc::kin;  // NOLINT(google-build-using-namespace)
using kin::Vec3;
using sym::Expr;

// q1 -> qd1, theta2 -> thetad2: the rate symbol sits next to its coordinate when printed.
std::string rate_name(const std::string& coordinate, const std::string& mark, std::set<std::string>& taken) {
  std::size_t cut = coordinate.size();
  while (cut > 0 && coordinate[cut - 1] >= '0' && coordinate[cut - 1] <= '9') --cut;
  std::string name = coordinate.substr(0, cut) + mark + coordinate.substr(cut);
  while (taken.contains(name)) name += "_";
  taken.insert(name);
  return name;
}

std::vector<Expr> make_symbols(const robot::RobotDescription& robot, const std::string& mark,
                               std::set<std::string>& taken, bool prefix_style) {
  std::vector<Expr> out;
  for (std::size_t i = 0; i < robot.coordinates.size(); ++i) {
    std::string name =
        prefix_style ? mark + std::to_string(i + 1) : rate_name(robot.coordinates[i].name(), mark, taken);
    if (prefix_style) {
      while (taken.contains(name)) name += "_";
      taken.insert(name);
    }
    out.push_back(sym::symbol(name));
  }
  return out;
}

}  // namespace

DynamicModel derive_model(const robot::RobotDescription& robot, const kin::Kinematics& kin) {
  DynamicModel m;
  m.params = standard_parameters(robot);
  std::set<std::string> taken;
  for (const auto& p : robot.parameters) taken.insert(p.name);
  for (const auto& c : robot.constants) taken.insert(c.name);
  for (const Expr q : robot.coordinates) taken.insert(q.name());
  for (const auto& p : m.params.list) taken.insert(p.name);
  m.q = robot.coordinates;
  m.qd = make_symbols(robot, "d", taken, false);
  m.v = make_symbols(robot, "v", taken, true);
  m.a = make_symbols(robot, "a", taken, true);
  const std::size_t n = m.q.size();

  // ---- mass matrix: H_jk = sum_links M Jv_j.Jv_k + h.(Jv_j x Jw_k + Jv_k x Jw_j) + Jw_j^T I_o Jw_k
  m.H.assign(n, std::vector<Expr>(n));
  Expr potential;
  for (std::size_t li = 0; li < robot.links.size(); ++li) {
    const kin::LinkKinematics& lk = kin.links[li];
    const auto& idx = m.params.of_link[li];
    auto P = [&](int k) { return m.params.symbol_or_zero(idx[static_cast<std::size_t>(k)]); };
    const Expr mass = P(0);
    const Vec3 h = {P(1), P(2), P(3)};
    const kin::Mat3 inertia = {Vec3{P(4), P(5), P(6)}, Vec3{P(5), P(7), P(8)}, Vec3{P(6), P(8), P(9)}};
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3 iw_j = inertia * lk.angular[j];
      for (std::size_t k = j; k < n; ++k) {
        Expr term = mass * kin::dot(lk.linear[j], lk.linear[k]) +
                    kin::dot(h, kin::cross(lk.linear[j], lk.angular[k]) + kin::cross(lk.linear[k], lk.angular[j])) +
                    kin::dot(iw_j, lk.angular[k]);
        m.H[j][k] = m.H[j][k] + term;
      }
    }
    // ---- potential energy: V = -g . (M p + R h)
    const Vec3 first_moment_base = mass * lk.origin + lk.rotation * h;
    for (int c = 0; c < 3; ++c)
      potential -= robot.gravity[static_cast<std::size_t>(c)] * first_moment_base[static_cast<std::size_t>(c)];
  }
  for (std::size_t k = 0; k < n; ++k) {
    const int ia = m.params.rotor_of[k];
    if (ia >= 0) m.H[k][k] = m.H[k][k] + m.params.symbol_or_zero(ia);
  }
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < j; ++k) m.H[j][k] = m.H[k][j];
  }
  m.potential_energy = potential;
  Expr kinetic;
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t k = 0; k < n; ++k) kinetic += m.H[j][k] * m.qd[j] * m.qd[k];
  }
  m.kinetic_energy = Expr(1) / Expr(2) * kinetic;

  // ---- gravity torque and Christoffel symbols
  std::vector<sym::Differentiator> d_dq;
  d_dq.reserve(n);
  for (const Expr q : m.q) d_dq.emplace_back(q);
  m.g.resize(n);
  for (std::size_t k = 0; k < n; ++k) m.g[k] = d_dq[k](potential);
  // dH[k][i][j] = dH_ij/dq_k, computed once for i <= j and shared.
  std::vector<Matrix> dH(n, Matrix(n, std::vector<Expr>(n)));
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = i; j < n; ++j) dH[k][i][j] = dH[k][j][i] = d_dq[k](m.H[i][j]);
    }
  }
  const Expr half = Expr(1) / Expr(2);
  m.christoffel.assign(n, Matrix(n, std::vector<Expr>(n)));
  m.C.assign(n, std::vector<Expr>(n));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      Expr cij;
      for (std::size_t k = 0; k < n; ++k) {
        const Expr c = half * (dH[k][i][j] + dH[j][i][k] - dH[i][j][k]);
        m.christoffel[k][i][j] = c;
        cij += c * m.qd[k];
      }
      m.C[i][j] = cij;
    }
  }
  return m;
}

Matrix mass_matrix_rate(const DynamicModel& model) {
  const std::size_t n = model.q.size();
  Matrix out(n, std::vector<Expr>(n));
  std::vector<sym::Differentiator> d_dq;
  for (const Expr q : model.q) d_dq.emplace_back(q);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i; j < n; ++j) {
      Expr s;
      for (std::size_t k = 0; k < n; ++k) s += d_dq[k](model.H[i][j]) * model.qd[k];
      out[i][j] = out[j][i] = s;
    }
  }
  return out;
}

}  // namespace dyncc::dyn
