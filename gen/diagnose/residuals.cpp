#include "diagnose/residuals.hpp"

#include "diagnose/crossval.hpp"

namespace dyncc::diagnose {

SelectedResiduals selected_residuals(const Dataset& data, const Diagnosis& diagnosis) {
  SelectedResiduals out;
  out.nominal = data.residual;
  out.heldout = data.residual;
  if (diagnosis.selected.empty()) return out;

  // The effects exactly as the selection accepted them, with its weights and fitting rows.
  const CrossValidation cv = fit_together(diagnosis.accepted_effects, data.residual, diagnosis.weight, diagnosis.folds,
                                          diagnosis.away, diagnosis.far, data.n);
  out.heldout = cv.heldout;

  Eigen::Index at = 0;
  for (std::size_t k = 0; k < diagnosis.accepted_effects.size(); ++k) {
    const Effect& e = diagnosis.accepted_effects[k];
    EffectFit fit;
    fit.effect = e.name;
    fit.joints = diagnosis.selected[k].joints;
    fit.parameters = e.parameters;
    fit.joint_of = e.joint_of;
    fit.values = cv.theta.segment(at, e.columns.cols());
    fit.profile = e.profile;
    fit.sign_velocity = friction_sign_velocity(data);
    fit.contribution = e.columns * fit.values;
    out.effects.push_back(std::move(fit));
    at += e.columns.cols();
  }
  return out;
}

}  // namespace dyncc::diagnose
