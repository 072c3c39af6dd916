#pragma once
// `rtiow accuracy`'s fits: error against cost on log-log axes, the gains at equal time and the
// time to the book's quality, from the sweeps' rows.

#include <utility>
#include <vector>

#include "core/measure/accuracy_options.h"
#include "core/measure/figures.h"

namespace rtiow {

// Least-squares slope and intercept of log(y) against log(x).
std::pair<double, double> log_log_fit(const std::vector<double>& x, const std::vector<double>& y);

// One key's values over rows.
std::vector<double> column(const Figures& rows, const std::string& key);

// The log-log fit of relMSE against a cost ("seconds", or "rays", which unlike seconds is a
// pure function of the settings) over a sweep's rows with spp >= min_spp (below 4 the times
// are too short to trust).
std::pair<double, double> error_cost_fit(const Figures& rows, const char* cost, double min_spp);
std::pair<double, double> error_time_fit(const Figures& rows, double min_spp = 4);

// How much lower a method's relMSE is than a baseline's (independent sampling's, or uniform
// sampling's with the same sampler) at the same time, from the baseline's log-log fit.
Figures equal_time_factors(const Figures& baseline, const Figures& rows);
double median_factor(const Figures& factors, double min_parameter);

// The ratios a reader looks for: convergence slopes, each sampler's gain over independent
// sampling at equal spp and at equal time, adaptive sampling's over uniform sampling with the
// same sampler, and the time to the book's quality.
Figures summarise(const Figures& figures, const AccuracyOptions& o);

}  // namespace rtiow
