// The statistics of an experiment's report, in C++ so that `godfinger experiment report` needs
// nothing beyond the executable: the t, F and normal distributions (from the regularised
// incomplete beta function), means with 95 % confidence intervals, the Wilcoxon signed-rank test
// (as SciPy's default: zero differences dropped; exact up to 50 pairs without ties or zeros, else
// the normal approximation with the tie correction; differences compared to 12 significant
// digits) with the matched-pairs rank-biserial correlation, a one-way repeated-measures
// ANOVA with partial eta squared and the Greenhouse-Geisser correction, and Holm's adjustment.
// The tests check them against SciPy's and statsmodels' values (tests/app/experiment/statistics_test.cpp).
#pragma once

#include <vector>

namespace gf::app::stats {

/// The regularised incomplete beta function I_x(a, b), a, b > 0, x in [0, 1].
double incompleteBeta(double a, double b, double x);

/// Student's t distribution with `df` degrees of freedom: P(T <= t).
double tCdf(double t, double df);
/// Its quantile: the t with P(T <= t) = p, p in (0, 1).
double tQuantile(double p, double df);
/// The F distribution: P(F <= f).
double fCdf(double f, double df1, double df2);
/// The standard normal distribution: P(Z <= z).
double normalCdf(double z);

struct MeanCi {
  int n = 0;
  double mean = 0.0, sd = 0.0;
  double lo = 0.0, hi = 0.0;  ///< 95 % confidence interval of the mean (t); the mean itself when n < 2
};
/// The mean of `values` with its 95 % confidence interval (NaN values are left out).
MeanCi meanCi(const std::vector<double>& values);

struct Wilcoxon {
  int n = 0;              ///< pairs with a non-zero difference
  double w_plus = 0.0;    ///< sum of the ranks of the positive differences (a - b > 0)
  double w_minus = 0.0;
  double p = 1.0;         ///< two-sided
  bool exact = false;     ///< p from the exact distribution (else the normal approximation)
  double rank_biserial = 0.0;  ///< (W+ - W-) / (W+ + W-): +1 every pair a > b, -1 every pair a < b
};
/// The Wilcoxon signed-rank test of paired samples a and b (equal sizes; pairs with a NaN are
/// left out, zero differences dropped as in Wilcoxon's original test, and then the normal
/// approximation used, as SciPy does).
Wilcoxon wilcoxon(const std::vector<double>& a, const std::vector<double>& b);

struct RmAnova {
  int subjects = 0, levels = 0;
  /// F: infinite when every participant scored alike in each level (no error variance) and the
  /// levels differ (p 0 then), NaN when nothing varies at all (p 1)
  double f = 0.0, df1 = 0.0, df2 = 0.0, p = 1.0;
  double partial_eta_squared = 0.0;
  double gg_epsilon = 1.0;  ///< Greenhouse-Geisser's sphericity estimate (1/(k-1) to 1)
  double p_gg = 1.0;        ///< p with both degrees of freedom times gg_epsilon
};
/// One-way repeated-measures ANOVA: `data[s][k]` subject s's value at level k (complete rows
/// only: a row with a NaN is left out). Needs 2 subjects and 2 levels at least.
RmAnova rmAnova(const std::vector<std::vector<double>>& data);

/// Holm's step-down adjustment of `p` (each at most 1, monotone in the sorted order).
std::vector<double> holm(const std::vector<double>& p);

}  // namespace gf::app::stats
