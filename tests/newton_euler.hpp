// An independent numeric recursive Newton-Euler algorithm (RNEA), written from the textbook
// (Luh, Walker & Paul 1980; Craig ch. 6; Siciliano et al. ch. 7.5), for checking dyncc's
// Lagrangian H, C and gravity torque. Plain Eigen, all vectors in BASE-frame coordinates
// (unlike dyncc's link-frame velocity propagation), so the two share no code and no formulation.
//
//   tau = RNEA(q, qd, qdd)  =  H(q) qdd + C(q, qd) qd + tau_g(q)
//   H e_k = RNEA(q, 0, e_k) - RNEA(q, 0, 0),   tau_g = RNEA(q, 0, 0)
//
// Supported: a tree of rigid links (each after its parent), standard or modified D-H, revolute
// or prismatic joints whose joint variable is an affine function of the coordinates
// (theta = offset + sum_k c_k q_k; a plain open chain has one c_k = 1), gravity as a base-frame
// vector, and reflected rotor inertia G^2 Jm added on its coordinate (the usual simplification:
// no gyroscopic coupling of the rotors). With an affine joint map the generalised force is
// tau_k = sum_links c_{link,k} * (joint force of the link), by virtual work.
//
// `from_description` turns a loaded RobotDescription into a Chain: the D-H entries, the
// inertial entries and the rotor inertias are evaluated numerically for given parameter values.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "robot/description.hpp"
#include "sym/evaluate.hpp"

namespace dyncc::test::ne {

using Eigen::Matrix3d;
using Eigen::Matrix4d;
using Eigen::Vector3d;
using Eigen::VectorXd;

struct Link {
  int parent = -1;          // -1 = base
  bool modified = false;    // Craig's modified D-H (else standard D-H)
  bool prismatic = false;   // the joint variable is d (else theta)
  double a = 0, alpha = 0;  // constant D-H entries
  double d = 0, theta = 0;  // the constant one, and the offset of the joint variable
  VectorXd coefficient;     // joint variable = offset + coefficient . q
  double mass = 0;
  Vector3d com = Vector3d::Zero();      // centre of mass, link frame
  Matrix3d inertia = Matrix3d::Zero();  // about the centre of mass, link axes (tensor)
};

struct Chain {
  std::vector<Link> links;
  Vector3d gravity = Vector3d::Zero();  // base-frame acceleration of gravity
  VectorXd rotor;                       // reflected rotor inertia per coordinate (G^2 Jm)
  [[nodiscard]] Eigen::Index dof() const { return rotor.size(); }
};

inline Matrix4d rot_x(double angle) {
  Matrix4d t = Matrix4d::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(angle, Vector3d::UnitX()).toRotationMatrix();
  return t;
}
inline Matrix4d rot_z(double angle) {
  Matrix4d t = Matrix4d::Identity();
  t.block<3, 3>(0, 0) = Eigen::AngleAxisd(angle, Vector3d::UnitZ()).toRotationMatrix();
  return t;
}
inline Matrix4d translation(double x, double y, double z) {
  Matrix4d t = Matrix4d::Identity();
  t.block<3, 1>(0, 3) = Vector3d(x, y, z);
  return t;
}

/// Link frame relative to its parent: standard RotZ(theta) TransZ(d) TransX(a) RotX(alpha),
/// modified RotX(alpha) TransX(a) RotZ(theta) TransZ(d).
inline Matrix4d dh_transform(bool modified, double a, double alpha, double d, double theta) {
  return modified ? Matrix4d(rot_x(alpha) * translation(a, 0, 0) * rot_z(theta) * translation(0, 0, d))
                  : Matrix4d(rot_z(theta) * translation(0, 0, d) * translation(a, 0, 0) * rot_x(alpha));
}

/// Joint torques (forces for prismatic joints) for coordinates q, rates qd, accelerations qdd.
inline VectorXd rnea(const Chain& chain, const VectorXd& q, const VectorXd& qd, const VectorXd& qdd) {
  const std::size_t count = chain.links.size();
  std::vector<Matrix3d> R(count);
  std::vector<Vector3d> o(count), w(count), wd(count), ao(count), axis(count), pivot(count);
  std::vector<double> rate(count), accel(count);
  // The base: fixed, accelerating "upwards" by -gravity so that gravity loads every link.
  const Matrix3d R0 = Matrix3d::Identity();
  const Vector3d o0 = Vector3d::Zero(), w0 = Vector3d::Zero(), wd0 = Vector3d::Zero(), a0 = -chain.gravity;

  // ---- forward pass: kinematics of every link, parent first
  for (std::size_t i = 0; i < count; ++i) {
    const Link& L = chain.links[i];
    const bool root = L.parent < 0;
    const auto p = static_cast<std::size_t>(root ? 0 : L.parent);
    const Matrix3d& Rp = root ? R0 : R[p];
    const Vector3d& op = root ? o0 : o[p];
    const Vector3d& wp = root ? w0 : w[p];
    const Vector3d& wdp = root ? wd0 : wd[p];
    const Vector3d& ap = root ? a0 : ao[p];

    const double s = L.coefficient.dot(q);
    rate[i] = L.coefficient.dot(qd);
    accel[i] = L.coefficient.dot(qdd);
    const double theta = L.prismatic ? L.theta : L.theta + s;
    const double d = L.prismatic ? L.d + s : L.d;
    Matrix4d Tp = Matrix4d::Identity();
    Tp.block<3, 3>(0, 0) = Rp;
    Tp.block<3, 1>(0, 3) = op;
    const Matrix4d T = Tp * dh_transform(L.modified, L.a, L.alpha, d, theta);
    R[i] = T.block<3, 3>(0, 0);
    o[i] = T.block<3, 1>(0, 3);

    // Joint axis and a point on it fixed in both the parent and the link: standard D-H turns or
    // slides along the PARENT's z axis through the parent's origin, modified D-H along the
    // link's OWN z axis through its own origin.
    axis[i] = L.modified ? Vector3d(R[i].col(2)) : Vector3d(Rp.col(2));
    pivot[i] = L.modified ? o[i] : op;
    const Vector3d& z = axis[i];

    // Acceleration of the pivot as a point of the parent.
    const Vector3d rp = pivot[i] - op;
    const Vector3d a_pivot = ap + wdp.cross(rp) + wp.cross(wp.cross(rp));
    if (L.prismatic) {
      w[i] = wp;
      wd[i] = wdp;
      // A point of the link moving along z relative to the parent: Coriolis 2 w x v_rel.
      const Vector3d r = o[i] - op;
      ao[i] = ap + wdp.cross(r) + wp.cross(wp.cross(r)) + 2.0 * wp.cross(rate[i] * z) + accel[i] * z;
    } else {
      w[i] = wp + rate[i] * z;
      wd[i] = wdp + accel[i] * z + wp.cross(rate[i] * z);
      // The pivot lies on the axis: it is a point of both bodies with the same acceleration.
      const Vector3d r = o[i] - pivot[i];
      ao[i] = a_pivot + wd[i].cross(r) + w[i].cross(w[i].cross(r));
    }
  }

  // ---- backward pass: forces f and moments n (about the link origin) a link's parent exerts on it
  std::vector<Vector3d> f(count, Vector3d::Zero()), n(count, Vector3d::Zero());
  for (std::size_t k = count; k-- > 0;) {
    const Link& L = chain.links[k];
    const Vector3d rc = R[k] * L.com;  // origin -> centre of mass
    const Vector3d ac = ao[k] + wd[k].cross(rc) + w[k].cross(w[k].cross(rc));
    const Matrix3d I = R[k] * L.inertia * R[k].transpose();
    const Vector3d F = L.mass * ac;
    const Vector3d N = I * wd[k] + w[k].cross(I * w[k]);
    f[k] += F;
    n[k] += N + rc.cross(F);
    if (L.parent >= 0) {
      const auto p = static_cast<std::size_t>(L.parent);
      f[p] += f[k];
      n[p] += n[k] + (o[k] - o[p]).cross(f[k]);
    }
  }

  VectorXd tau = chain.rotor.cwiseProduct(qdd);
  for (std::size_t k = 0; k < count; ++k) {
    const Link& L = chain.links[k];
    // Generalised force of the joint: force along the axis, or moment about the axis line.
    const double joint = L.prismatic ? axis[k].dot(f[k]) : axis[k].dot(n[k] + (o[k] - pivot[k]).cross(f[k]));
    tau += joint * L.coefficient;
  }
  return tau;
}

/// H by columns: RNEA(q, 0, e_k) - RNEA(q, 0, 0).
inline Eigen::MatrixXd mass_matrix(const Chain& chain, const VectorXd& q) {
  const Eigen::Index n = chain.dof();
  const VectorXd zero = VectorXd::Zero(n);
  const VectorXd g = rnea(chain, q, zero, zero);
  Eigen::MatrixXd H(n, n);
  for (Eigen::Index k = 0; k < n; ++k) H.col(k) = rnea(chain, q, zero, VectorXd::Unit(n, k)) - g;
  return H;
}

/// The chain of a loaded description for the given parameter values (name -> value).
/// Throws std::invalid_argument when a joint variable is not affine in the coordinates.
inline Chain from_description(const robot::RobotDescription& robot, const std::map<std::string, double>& parameters) {
  std::unordered_map<std::string, double> values;
  for (const auto& [name, value] : robot.constant_doubles()) values[name] = value;
  for (const auto& [name, value] : parameters) values[name] = value;
  const auto n = static_cast<Eigen::Index>(robot.coordinates.size());
  auto at = [&](sym::Expr e, const VectorXd& q) {
    for (Eigen::Index k = 0; k < n; ++k) values[robot.coordinates[static_cast<std::size_t>(k)].name()] = q[k];
    return sym::evaluate(e, values);
  };
  const VectorXd zero = VectorXd::Zero(n);
  Chain chain;
  chain.gravity = Vector3d(robot.gravity_values()[0], robot.gravity_values()[1], robot.gravity_values()[2]);
  chain.rotor = VectorXd::Zero(n);
  for (const auto& rotor : robot.rotors) {
    const double g = rotor.gear_ratio.to_double();
    chain.rotor[rotor.coordinate] += g * g * at(rotor.inertia, zero);
  }
  for (const auto& link : robot.links) {
    Link L;
    L.parent = link.parent;
    L.modified = robot.convention == robot::Convention::Modified;
    L.prismatic = link.joint == robot::JointType::Prismatic;
    L.a = at(link.a, zero);
    L.alpha = at(link.alpha, zero);
    L.d = at(link.d, zero);
    L.theta = at(link.theta, zero);
    const sym::Expr variable = link.joint_expression();
    L.coefficient = VectorXd::Zero(n);
    for (Eigen::Index k = 0; k < n; ++k)
      L.coefficient[k] = at(variable, VectorXd::Unit(n, k)) - (L.prismatic ? L.d : L.theta);
    // Affine check at an arbitrary point.
    VectorXd probe(n);
    for (Eigen::Index k = 0; k < n; ++k) probe[k] = 0.3 + 0.17 * static_cast<double>(k);
    const double offset = L.prismatic ? L.d : L.theta;
    if (std::abs(at(variable, probe) - offset - L.coefficient.dot(probe)) > 1e-12) {
      throw std::invalid_argument("joint variable of link '" + link.name + "' is not affine in the coordinates");
    }
    L.mass = at(link.mass, zero);
    L.com = Vector3d(at(link.com[0], zero), at(link.com[1], zero), at(link.com[2], zero));
    const auto& t = link.inertia;
    L.inertia << at(t.xx, zero), at(t.xy, zero), at(t.xz, zero),  //
        at(t.xy, zero), at(t.yy, zero), at(t.yz, zero),           //
        at(t.xz, zero), at(t.yz, zero), at(t.zz, zero);
    chain.links.push_back(L);
  }
  return chain;
}

}  // namespace dyncc::test::ne
