// The checked-in generated models (generated/<robot>/, written by `dyncc generate`) against the
// generator's own numbers: the derivation's compiled tapes (the numbers `dyncc eval` prints, which
// the dynamics tests check against Newton-Euler, textbook closed forms and the paper's
// appendix), and `dyncc eval --json` itself for the Kraft arm. Every function, in double and
// in float, at random states and random parameter values.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "base/base_parameters.hpp"
#include "dynamics_support.hpp"
#include "kraft/model.hpp"
#include "panda/model.hpp"
#include "planar_2link/model.hpp"
#include "puma560/model.hpp"

namespace dyncc::test {
namespace {

using Vec = Eigen::VectorXd;
using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

double relative(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  return (got - want).norm() / std::max(want.norm(), 1e-12);
}

// One model's checks; G is a struct of static forwarding functions (see the instantiations).
template <typename G>
void check_generated_model(const std::string& robot_file) {
  const auto d = derive_file(robots_dir() / robot_file);
  ASSERT_TRUE(d);
  const int n = G::kDof;
  const int r = G::kBaseParameters;
  ASSERT_EQ(static_cast<std::size_t>(n), d->model.q.size());
  ASSERT_EQ(static_cast<std::size_t>(r), d->base.list.size());
  ASSERT_EQ(static_cast<std::size_t>(G::kLinkParameters), d->robot.parameters.size());

  // Base parameters: the nominal ones, and the map from random link parameter values.
  const Vec nominal_std = d->numeric->nominal_standard_values();
  const Vec nominal_base = d->base.values(nominal_std);
  for (int b = 0; b < r; ++b) {
    EXPECT_NEAR(G::kNominalBaseParameters[b], nominal_base[b], 1e-12 * (1 + std::abs(nominal_base[b]))) << b;
  }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0.2, 1.5);
  std::map<std::string, double> link_values;
  std::vector<double> link(static_cast<std::size_t>(G::kLinkParameters));
  for (int k = 0; k < G::kLinkParameters; ++k) {
    link[static_cast<std::size_t>(k)] = uni(rng);
    link_values[G::kLinkParameterNames[k]] = link[static_cast<std::size_t>(k)];
  }
  const Vec std_values = d->numeric->standard_values(link_values);
  const Vec p = d->base.values(std_values);
  Vec p_generated(r);
  G::base_parameters_from_link(link.data(), p_generated.data());
  EXPECT_LT(relative(p_generated, p), 1e-13);

  for (int sample = 0; sample < 25; ++sample) {
    const dyn::State s = dyn::random_state(static_cast<std::size_t>(n), 1000 + static_cast<std::uint64_t>(sample));
    const dyn::Evaluation ev = d->numeric->evaluate(s, std_values);
    const Eigen::MatrixXd Yb = base::base_regressor(d->base, ev.Y);
    Vec e(n);
    for (int i = 0; i < n; ++i) e[i] = uni(rng) - 0.85;

    RowMat H(n, n), C(n, n), Y(n, r), Yid(n, r);
    Vec g(n), f(n), tau(n), tau_fused(n), YTe(r), YTe_fused(r), tau_id(n);
    G::mass_matrix(s.q.data(), p.data(), H.data());
    G::coriolis_matrix(s.q.data(), s.qd.data(), p.data(), C.data());
    G::gravity_torque(s.q.data(), p.data(), g.data());
    G::friction_torque(s.qd.data(), s.v.data(), p.data(), f.data());
    G::regressor(s.q.data(), s.qd.data(), s.v.data(), s.a.data(), Y.data());
    G::slotine_li_torque(s.q.data(), s.qd.data(), s.v.data(), s.a.data(), p.data(), tau.data());
    G::adaptation_term(s.q.data(), s.qd.data(), s.v.data(), s.a.data(), e.data(), YTe.data());
    G::control_step(s.q.data(), s.qd.data(), s.v.data(), s.a.data(), p.data(), e.data(), tau_fused.data(),
                    YTe_fused.data());
    EXPECT_LT(relative(H, ev.H), 1e-12) << sample;
    EXPECT_LT(relative(C, ev.C), 1e-12) << sample;
    EXPECT_LT(relative(g, ev.g), 1e-12) << sample;
    EXPECT_LT(relative(f, ev.friction), 1e-12) << sample;
    EXPECT_LT(relative(Y, Yb), 1e-12) << sample;
    EXPECT_LT(relative(tau, ev.tau), 1e-12) << sample;
    EXPECT_LT(relative(tau_fused, ev.tau), 1e-12) << sample;
    EXPECT_LT(relative(YTe, Yb.transpose() * e), 1e-12) << sample;
    EXPECT_LT(relative(YTe_fused, Yb.transpose() * e), 1e-12) << sample;

    // Identification form and inverse dynamics: v = qd, a = qdd.
    dyn::State id = s;
    id.v = s.qd;
    const dyn::Evaluation ev_id = d->numeric->evaluate(id, std_values);
    G::identification_regressor(s.q.data(), s.qd.data(), s.a.data(), Yid.data());
    G::inverse_dynamics(s.q.data(), s.qd.data(), s.a.data(), p.data(), tau_id.data());
    EXPECT_LT(relative(Yid, base::base_regressor(d->base, ev_id.Y)), 1e-12) << sample;
    EXPECT_LT(relative(tau_id, ev_id.tau), 1e-12) << sample;

    // The float instantiation of the control step: single precision, same computation.
    std::vector<float> qf(s.q.data(), s.q.data() + n), qdf(s.qd.data(), s.qd.data() + n),
        vf(s.v.data(), s.v.data() + n), af(s.a.data(), s.a.data() + n), pf(p.data(), p.data() + r),
        ef(e.data(), e.data() + n), tauf(static_cast<std::size_t>(n)), yf(static_cast<std::size_t>(r));
    G::control_step(qf.data(), qdf.data(), vf.data(), af.data(), pf.data(), ef.data(), tauf.data(), yf.data());
    EXPECT_LT(relative(Eigen::Map<Eigen::VectorXf>(tauf.data(), n).cast<double>(), ev.tau), 1e-4) << sample;
    EXPECT_LT(relative(Eigen::Map<Eigen::VectorXf>(yf.data(), r).cast<double>(), Yb.transpose() * e), 1e-4) << sample;
  }
}

// Forwarders from a generated namespace to a class the template above can take.
#define DYNCC_FORWARD(NS)                                                                                 \
  struct NS##_model {                                                                                     \
    static constexpr int kDof = dyncc::generated::NS::kDof;                                               \
    static constexpr int kBaseParameters = dyncc::generated::NS::kBaseParameters;                         \
    static constexpr int kLinkParameters = dyncc::generated::NS::kLinkParameters;                         \
    static constexpr const double* kNominalBaseParameters = dyncc::generated::NS::kNominalBaseParameters; \
    static constexpr const char* const* kLinkParameterNames = dyncc::generated::NS::kLinkParameterNames;  \
    template <typename... A>                                                                              \
    static void mass_matrix(A... a) {                                                                     \
      dyncc::generated::NS::mass_matrix(a...);                                                            \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void coriolis_matrix(A... a) {                                                                 \
      dyncc::generated::NS::coriolis_matrix(a...);                                                        \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void gravity_torque(A... a) {                                                                  \
      dyncc::generated::NS::gravity_torque(a...);                                                         \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void friction_torque(A... a) {                                                                 \
      dyncc::generated::NS::friction_torque(a...);                                                        \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void regressor(A... a) {                                                                       \
      dyncc::generated::NS::regressor(a...);                                                              \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void identification_regressor(A... a) {                                                        \
      dyncc::generated::NS::identification_regressor(a...);                                               \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void inverse_dynamics(A... a) {                                                                \
      dyncc::generated::NS::inverse_dynamics(a...);                                                       \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void slotine_li_torque(A... a) {                                                               \
      dyncc::generated::NS::slotine_li_torque(a...);                                                      \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void adaptation_term(A... a) {                                                                 \
      dyncc::generated::NS::adaptation_term(a...);                                                        \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void control_step(A... a) {                                                                    \
      dyncc::generated::NS::control_step(a...);                                                           \
    }                                                                                                     \
    template <typename... A>                                                                              \
    static void base_parameters_from_link(A... a) {                                                       \
      dyncc::generated::NS::base_parameters_from_link(a...);                                              \
    }                                                                                                     \
  };

DYNCC_FORWARD(kraft_right)
DYNCC_FORWARD(planar_2link)
DYNCC_FORWARD(puma560)
DYNCC_FORWARD(panda)

TEST(GeneratedModel, KraftAgreesWithTheDerivation) { check_generated_model<kraft_right_model>("kraft.yaml"); }
TEST(GeneratedModel, Planar2LinkAgreesWithTheDerivation) {
  check_generated_model<planar_2link_model>("planar_2link.yaml");
}
TEST(GeneratedModel, Puma560AgreesWithTheDerivation) { check_generated_model<puma560_model>("puma560.yaml"); }
TEST(GeneratedModel, PandaAgreesWithTheDerivation) { check_generated_model<panda_model>("panda.yaml"); }

// The literal promise of the issue: the generated code reproduces what `dyncc eval` prints.
TEST(GeneratedModel, KraftMatchesDynccEvalJson) {
  namespace K = dyncc::generated::kraft_right;
  const double q[3] = {0.3, -0.4, 0.7}, qd[3] = {0.5, -1.1, 0.9}, v[3] = {0.2, 0.3, -0.6}, a[3] = {1.5, -0.7, 2.0};
  const std::string command = std::string("timeout 120 '") + DYNCC_BINARY + "' eval '" + DYNCC_SOURCE_DIR +
                              "/robots/kraft.yaml' --q 0.3,-0.4,0.7 --qd 0.5,-1.1,0.9 --v 0.2,0.3,-0.6 --a 1.5,-0.7,2 "
                              "--json 2>/dev/null";
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  for (std::size_t got = 0; (got = fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, got);
  ASSERT_EQ(pclose(pipe), 0) << out;
  const nlohmann::json j = nlohmann::json::parse(out);
  // eval's base parameter values are the nominal ones; use them as p.
  const auto base_values = j.at("base_parameters").at("values").get<std::vector<double>>();
  ASSERT_EQ(base_values.size(), static_cast<std::size_t>(K::kBaseParameters));
  double H[9], C[9], g[3], tau[3], Y[3 * K::kBaseParameters];
  K::mass_matrix(q, base_values.data(), H);
  K::coriolis_matrix(q, qd, base_values.data(), C);
  K::gravity_torque(q, base_values.data(), g);
  K::slotine_li_torque(q, qd, v, a, base_values.data(), tau);
  K::regressor(q, qd, v, a, Y);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(g[i], j["g"][i].get<double>(), 1e-12);
    EXPECT_NEAR(tau[i], j["tau"][i].get<double>(), 1e-12);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(H[i * 3 + k], j["H"][i][k].get<double>(), 1e-12);
      EXPECT_NEAR(C[i * 3 + k], j["C"][i][k].get<double>(), 1e-12);
    }
    for (int b = 0; b < K::kBaseParameters; ++b) {
      EXPECT_NEAR(Y[i * K::kBaseParameters + b], j["Y"][i][b].get<double>(), 1e-12) << i << "," << b;
    }
  }
}

// `dyncc generate` as a command: deterministic, --check notices any change, bad input exits 2.
struct ShellRun {
  int exit_code = -1;
  std::string out;
};

ShellRun shell(const std::string& command) {
  ShellRun r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return r;
  char buffer[4096];
  for (std::size_t got = 0; (got = fread(buffer, 1, sizeof buffer, pipe)) > 0;) r.out.append(buffer, got);
  const int status = pclose(pipe);
  if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  return r;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(GenerateCommand, CheckedInKraftIsCurrentAndOutputIsDeterministic) {
  const std::string dyncc = std::string("'") + DYNCC_BINARY + "'";
  const std::string in_source = std::string("cd '") + DYNCC_SOURCE_DIR + "' && ";
  const ShellRun check = shell(in_source + dyncc + " generate robots/kraft.yaml -o generated/kraft --check");
  EXPECT_EQ(check.exit_code, 0) << check.out;

  const auto tmp = std::filesystem::temp_directory_path() / ("dyncc_generate_test_" + std::to_string(getpid()));
  std::filesystem::remove_all(tmp);
  // Twice into the same folder (the folder's name is part of the text): byte-identical.
  const std::string out = std::string("'").append((tmp / "a").string()).append("'");
  const ShellRun first = shell(in_source + dyncc + " generate robots/kraft.yaml -o " + out);
  ASSERT_EQ(first.exit_code, 0) << first.out;
  std::map<std::string, std::string> before;
  for (const char* file : {"model.hpp", "model.cpp", "CMakeLists.txt", "REPORT.md", "report.json"}) {
    before[file] = slurp(tmp / "a" / file);
    EXPECT_FALSE(before[file].empty()) << file;
  }
  const ShellRun second = shell(in_source + dyncc + " generate robots/kraft.yaml -o " + out);
  ASSERT_EQ(second.exit_code, 0) << second.out;
  for (const auto& [file, text] : before) EXPECT_EQ(text, slurp(tmp / "a" / file)) << file << " differs between runs";
  // One changed byte is a stale folder.
  {
    std::ofstream out(tmp / "a" / "model.cpp", std::ios::app);
    out << " ";
  }
  const ShellRun stale =
      shell(in_source + dyncc + " generate robots/kraft.yaml -o '" + (tmp / "a").string() + "' --check");
  EXPECT_EQ(stale.exit_code, 1) << stale.out;
  EXPECT_NE(stale.out.find("model.cpp"), std::string::npos) << stale.out;
  std::filesystem::remove_all(tmp);
}

TEST(GenerateCommand, BadInputExitsTwoWithAMessage) {
  const std::string dyncc = std::string("'") + DYNCC_BINARY + "'";
  const ShellRun missing = shell(dyncc + " generate /nonexistent/robot.yaml -o /tmp/dyncc_never_written");
  EXPECT_EQ(missing.exit_code, 2) << missing.out;
  EXPECT_NE(missing.out.find("robot.yaml"), std::string::npos) << missing.out;
  const ShellRun no_out = shell(dyncc + " generate '" + DYNCC_SOURCE_DIR + "/robots/kraft.yaml'");
  EXPECT_EQ(no_out.exit_code, 2) << no_out.out;
  EXPECT_FALSE(std::filesystem::exists("/tmp/dyncc_never_written"));
  // A folder that cannot be created: exit 2 and say which.
  const ShellRun unwritable =
      shell(dyncc + " generate '" + DYNCC_SOURCE_DIR + "/robots/kraft.yaml' -o /proc/dyncc/kraft");
  EXPECT_EQ(unwritable.exit_code, 2) << unwritable.out;
  EXPECT_NE(unwritable.out.find("/proc/dyncc/kraft"), std::string::npos) << unwritable.out;
}

}  // namespace
}  // namespace dyncc::test
