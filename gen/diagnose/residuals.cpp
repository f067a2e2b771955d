#include "diagnose/residuals.hpp"

#include "diagnose/crossval.hpp"

namespace dyncc::diagnose {
namespace {

Eigen::MatrixXd beside(const Eigen::MatrixXd& left, const Eigen::MatrixXd& right) {
  Eigen::MatrixXd out(left.rows(), left.cols() + right.cols());
  out << left, right;
  return out;
}

}  // namespace

SelectedResiduals selected_residuals(const Dataset& data, const Diagnosis& diagnosis) {
  SelectedResiduals out;
  out.nominal = data.residual;
  out.heldout = data.residual;
  if (diagnosis.selected.empty()) return out;

  // The effects exactly as the selection accepted them, with its weights.
  std::vector<const Effect*> chosen;
  Eigen::MatrixXd accepted(data.residual.size(), 0);
  for (const Effect& e : diagnosis.accepted_effects) {
    chosen.push_back(&e);
    accepted = beside(accepted, e.columns);
  }
  const CrossValidation cv = cross_validate(data.residual, accepted, data.n, diagnosis.weight);
  out.heldout = cv.heldout;

  Eigen::Index at = 0;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const Effect& e = *chosen[k];
    EffectFit fit;
    fit.effect = e.name;
    fit.joints = diagnosis.selected[k].joints;
    fit.parameters = e.parameters;
    fit.joint_of = e.joint_of;
    fit.values = cv.theta.segment(at, e.columns.cols());
    fit.profile = e.profile;
    fit.contribution = e.columns * fit.values;
    out.effects.push_back(std::move(fit));
    at += e.columns.cols();
  }
  return out;
}

}  // namespace dyncc::diagnose
