// The contact candidate: a horizontal surface (perpendicular to gravity) pushing up on a point c
// of the payload link while that point is below the surface height h, with a normal force
// N = F + k (h - z_c - D) + d (-dz_c/dt) and a friction force mu N against the point's horizontal
// sliding. D is the mean depth of the rows in contact, so F (`force`) is the push there with the
// point at rest, and F - k D (`surface_push`) the push at the surface (a damped penalty contact
// lets go before the point leaves the surface: that push reads below zero where F does not). The
// force's torque is J_c^T N (-g^), the gradient of the point's height, i.e. the
// gravity part of the link's mass and first-moment regressor columns over |g|; so the force and
// its moments F c are linear columns (the fit re-estimates the point), and only the gate
// (z_c < h), the spring's and the damper's lever and the sliding direction need the point and the
// height. Those are a profile: a coarse grid of points along the link's x and z axes times
// surface heights at quantiles of z_c, and a local search from the grid's best points (run by
// the diagnosis, which judges each point), because a brief hard touch is explained only when the
// gate holds the touch's rows and few others.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "diagnose/contact.hpp"
#include "diagnose/dataset.hpp"
#include "diagnose/effects.hpp"

namespace dyncc::diagnose {

/// A point of the payload link (m, link frame) and the surface at a quantile of its height; and
/// which of the two models of the force it carries:
/// - pressed (held false): the normal force f0 + k (h - z_c) + d (-dz_c/dt) and kinetic friction
///   against sliding, whose linear moment columns re-estimate the point (8 columns);
/// - held (held true): the point rests on the surface, which pushes it up, at the gate's point (1
///   column). A controller holding a hook on a table through a tele-operator's reference pushes
///   with whatever its position error asks, not as a spring: the pressed model read that as a
///   force 15-100 m off the link (implausible), the held model as a push at the hook's searched
///   point (seed 41 case 33, MuJoCo tele-operation). With static friction holds beside the push
///   (two more columns) it also tied with a payload carried in the same task (seed 97 case 57).
struct ContactPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double quantile = 0;
  bool held = false;
  /// As an Effect's profile_point (x, z, quantile, held), and back.
  [[nodiscard]] std::vector<double> coordinates() const { return {point.x(), point.z(), quantile, held ? 1.0 : 0.0}; }
  static ContactPoint of(const Effect& contact);
};

/// The payload link's geometry along a log's evaluation rows, computed once for every point.
class ContactRows {
 public:
  ContactRows(const Dataset& d, const pipeline::Derivation& derivation);
  /// False when the robot has no payload link with mass and first moments, or no gravity.
  [[nodiscard]] bool valid() const { return valid_; }
  /// The arm's length scale (ContactGeometry::scale) over this log.
  [[nodiscard]] double scale() const { return scale_; }
  /// A surface quantile within what a search may try: at least a few rows below the surface.
  [[nodiscard]] double clamped(double quantile) const;
  /// The coarse grid of points and surfaces, for both models of the force.
  [[nodiscard]] std::vector<ContactPoint> grid() const;
  /// The contact effect at a point and surface, conditioned into the analysis rows.
  [[nodiscard]] Effect effect(const ContactPoint& at) const;

 private:
  const Dataset* d_;
  bool valid_ = false;
  double scale_ = 0;
  Eigen::Vector3d down_ = Eigen::Vector3d::Zero();
  Eigen::MatrixXd height_, lever_;  // S x 4 and S*n x 4: the basis per evaluation row
  std::vector<ContactGeometry::Frame> frames_;
};

/// How well a contact point explains the log, as the diagnosis judges it.
struct ContactFit {
  bool plausible = false;
  double shrink = -1e300;  // held out
};
using ContactJudge = std::function<ContactFit(const Effect&)>;

/// A compass search over the point (x, z) and the surface's quantile from `start`, climbing the
/// held-out shrink whether or not a fit is plausible (the way to the contact point may pass
/// points whose fit pulls instead of pushing). Returns where it ends and, when it differs, the
/// best plausible point it judged.
std::vector<ContactPoint> search_contact(const ContactRows& rows, const ContactPoint& start, const ContactFit& fit,
                                         const ContactJudge& judge);

}  // namespace dyncc::diagnose
