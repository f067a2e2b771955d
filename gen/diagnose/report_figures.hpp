// The report's figures as data (plot::Figure; diagnosis_report.cpp writes them and the page
// around them), built from the dataset, the diagnosis and the selected effects refitted. Each
// figure has one panel per joint unless said otherwise; the tests read the series back.
#pragma once

#include "diagnose/dataset.hpp"
#include "diagnose/diagnosis.hpp"
#include "diagnose/residuals.hpp"
#include "plot.hpp"

namespace dyncc::diagnose {

/// Lags shown either way in the cross-correlation figure, s: a sensor delay is tens of ms.
inline constexpr double kCorrelationLag = 0.5;

/// The residual against the joint's velocity (a scatter, "residual") with the fitted curve of the
/// selected friction effects acting on that joint (a line, "fitted " and their names). The
/// residual is the nominal one less the fitted parts of the selected effects that are not
/// friction, so that what is left is what the curve claims to explain.
plot::Figure velocity_figure(const Dataset& data, const SelectedResiduals& residuals);

/// The residual's amplitude spectrum before ("nominal") and, when effects are selected, after
/// them ("after selected", held out), per log, up to twice the filter's cut-off (beyond it the
/// zero-phase filter has left nothing).
plot::Figure spectrum_figure(const Dataset& data, const SelectedResiduals& residuals);

/// Normalised cross-correlation by lag, on the evaluation rows of each log: of the logged torque
/// with the model's ("logged vs model torque": the peak is the lag by which the model, computed
/// from the logged positions, is late, so a sensor delay shows as a peak off zero) and of the
/// residual with the logged torque ("residual vs logged torque").
plot::Figure correlation_figure(const Dataset& data);

/// The residual of log `log` (0-based) over its clock, before ("nominal") and after the selected
/// effects ("after selected", held out), the flagged windows of that log shaded.
plot::Figure residual_figure(const Dataset& data, const Diagnosis& diagnosis, const SelectedResiduals& residuals,
                             int log);

/// The held-out gap stage by stage, as a step line over the stages named by x_ticks ("nominal",
/// then "+ effect" for each selected effect in order). First panel: the torque-weighted held-out
/// RMS over all joints, % of the nominal's ("all joints"), with the inertial parameters
/// re-identified alone as a dashed reference; second panel: each joint's held-out RMS, % of its
/// torque RMS ("joint k").
plot::Figure waterfall_figure(const Dataset& data, const Diagnosis& diagnosis);

}  // namespace dyncc::diagnose
