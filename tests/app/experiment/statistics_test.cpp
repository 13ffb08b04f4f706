// The report's statistics (app/experiment/statistics.hpp) against the values SciPy 1.10.1 and
// statsmodels 0.13.5 give for the same inputs (Debian 12's python3-scipy, python3-statsmodels;
// the calls are quoted beside each value), and against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "app/experiment/statistics.hpp"

namespace gf::app::stats {
namespace {

TEST(Statistics, IncompleteBetaMatchesScipy) {
  EXPECT_NEAR(incompleteBeta(2.5, 3.5, 0.3), 0.2967529892956661, 1e-13);   // scipy.special.betainc(2.5, 3.5, 0.3)
  EXPECT_NEAR(incompleteBeta(0.5, 10, 0.01), 0.3420718248432155, 1e-13);   // betainc(0.5, 10, 0.01)
  EXPECT_NEAR(incompleteBeta(30, 40, 0.45), 0.6447480085585666, 1e-12);    // betainc(30, 40, 0.45)
  EXPECT_NEAR(incompleteBeta(1, 1, 0.37), 0.37, 1e-15) << "Beta(1, 1) is uniform";
  EXPECT_NEAR(incompleteBeta(2, 3, 0.6) + incompleteBeta(3, 2, 0.4), 1.0, 1e-14) << "I_x(a, b) = 1 - I_(1-x)(b, a)";
}

TEST(Statistics, TFAndNormalDistributionsMatchScipy) {
  EXPECT_NEAR(tQuantile(0.975, 7), 2.3646242510102993, 1e-9);    // scipy.stats.t.ppf(0.975, 7)
  EXPECT_NEAR(tQuantile(0.975, 1), 12.706204736432095, 1e-7);    // t.ppf(0.975, 1)
  EXPECT_NEAR(tQuantile(0.975, 100), 1.9839715184496334, 1e-9);  // t.ppf(0.975, 100)
  EXPECT_NEAR(tCdf(-1.3, 4), 0.13172579823561206, 1e-13);        // t.cdf(-1.3, 4)
  EXPECT_NEAR(tCdf(std::tan(0.3), 1), 0.5 + 0.3 / M_PI, 1e-14) << "t with 1 degree is Cauchy";
  EXPECT_NEAR(fCdf(3.2, 2, 14), 0.9283056258823762, 1e-13);      // scipy.stats.f.cdf(3.2, 2, 14)
  EXPECT_NEAR(fCdf(0.7, 1.3, 9.1), 0.5384182605228295, 1e-12);   // f.cdf(0.7, 1.3, 9.1)
  EXPECT_NEAR(normalCdf(1.959963984540054), 0.975, 1e-15);
}

TEST(Statistics, MeanWithItsTInterval) {
  const MeanCi m = meanCi({2.1, 2.5, 1.9, 2.8, 2.2, NAN});
  EXPECT_EQ(m.n, 5);
  EXPECT_NEAR(m.mean, 2.3, 1e-14);
  // m -+ t.ppf(0.975, 4) * scipy.stats.sem(x)
  EXPECT_NEAR(m.lo, 1.8610054834574576, 1e-9);
  EXPECT_NEAR(m.hi, 2.738994516542542, 1e-9);
  const MeanCi one = meanCi({4.0});
  EXPECT_EQ(one.lo, 4.0);
  EXPECT_TRUE(std::isnan(meanCi({}).mean));
}

TEST(Statistics, WilcoxonMatchesScipyExactAndApproximate) {
  // scipy.stats.wilcoxon(a, b): statistic 5, p 0.0390625 (exact, 9 pairs)
  const Wilcoxon w = wilcoxon({1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30},
                              {0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29});
  EXPECT_TRUE(w.exact);
  EXPECT_EQ(w.n, 9);
  EXPECT_EQ(std::min(w.w_plus, w.w_minus), 5.0);
  EXPECT_NEAR(w.p, 0.0390625, 1e-15);
  EXPECT_NEAR(w.rank_biserial, (40.0 - 5.0) / 45.0, 1e-15);
  // With ties, the normal approximation with the tie correction:
  // scipy.stats.wilcoxon(a, b, mode='approx'): statistic 2.5, p 0.003920957190711083
  const Wilcoxon tied = wilcoxon({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}, {2, 1, 1, 2, 4, 3, 5, 5, 4, 9, 8, 7});
  EXPECT_FALSE(tied.exact);
  EXPECT_EQ(std::min(tied.w_plus, tied.w_minus), 2.5);
  EXPECT_NEAR(tied.p, 0.003920957190711083, 1e-12);
  // 40 differences without ties, exact as SciPy's default for up to 50: p 0.017157761747512268
  const std::vector<double> x = {0.646,  1.122,  0.63,  -1.003, 1.205,  0.746, -0.237, 0.881,  0.665, 0.594,
                                 0.328,  0.847,  -0.436, 0.137, -0.182, 0.899, 0.34,   0.008,  -0.482, 0.043,
                                 0.308,  0.024,  1.594,  1.307, -2.411, -1.589, 0.125, -0.122, 0.514,  0.517,
                                 2.418,  -0.812, -0.078, 2.343, 0.947,  0.963,  -0.214, -1.348, 0.467, 0.409};
  const Wilcoxon forty = wilcoxon(x, std::vector<double>(x.size(), 0.0));
  EXPECT_TRUE(forty.exact);
  EXPECT_EQ(std::min(forty.w_plus, forty.w_minus), 234.0);
  EXPECT_NEAR(forty.p, 0.017157761747512268, 1e-12);
  // Zero differences are dropped and the normal approximation is used (SciPy switches too):
  // scipy.stats.wilcoxon([4, 2, 4, 3, 4, 1, 4, 2, 5, 6], [2, 2, 1, 0, 2, 2, 4, 0, 4, 1]): statistic
  // 1.5, p 0.019931199293565356; ([3, 5, 2, 8, 6, 7, 9], [1, 5, 1, 4, 3, 2, 3]): 0, p 0.027707849358079864
  const Wilcoxon zeros = wilcoxon({4, 2, 4, 3, 4, 1, 4, 2, 5, 6}, {2, 2, 1, 0, 2, 2, 4, 0, 4, 1});
  EXPECT_FALSE(zeros.exact);
  EXPECT_EQ(zeros.n, 8);
  EXPECT_NEAR(zeros.p, 0.019931199293565356, 1e-12);
  EXPECT_NEAR(wilcoxon({3, 5, 2, 8, 6, 7, 9}, {1, 5, 1, 4, 3, 2, 3}).p, 0.027707849358079864, 1e-12);
  // Rates that differ in their last bits are tied: 2/3 - 1/3 and 1/3.
  const Wilcoxon rates = wilcoxon({2.0 / 3.0, 1.0 / 3.0, 1.0}, {1.0 / 3.0, 0.0, 0.5});
  EXPECT_FALSE(rates.exact) << "a tie";
  EXPECT_EQ(rates.w_plus, 6.0);
  // None left: p 1.
  const Wilcoxon same = wilcoxon({1, 2, 3}, {1, 2, 3});
  EXPECT_EQ(same.n, 0);
  EXPECT_EQ(same.p, 1.0);
}

TEST(Statistics, RepeatedMeasuresAnovaMatchesStatsmodels) {
  const std::vector<std::vector<double>> d = {{0.45, 0.50, 0.62}, {0.38, 0.48, 0.55}, {0.52, 0.55, 0.70},
                                              {0.40, 0.41, 0.52}, {0.47, 0.58, 0.61}, {0.36, 0.45, 0.58}};
  const RmAnova r = rmAnova(d);
  // statsmodels.stats.anova.AnovaRM(df, 'v', 's', within=['k']).fit(): F 52.99721835883168 on
  // (2, 10), p 4.762272021499154e-06
  EXPECT_EQ(r.subjects, 6);
  EXPECT_EQ(r.df1, 2.0);
  EXPECT_EQ(r.df2, 10.0);
  EXPECT_NEAR(r.f, 52.99721835883168, 1e-9);
  EXPECT_NEAR(r.p, 4.762272021499154e-06, 1e-15);
  // Greenhouse-Geisser from the eigenvalues of the orthonormal contrasts' covariance (numpy):
  // epsilon 0.9298093836895173; p with both degrees times it 9.647472441468582e-06.
  EXPECT_NEAR(r.gg_epsilon, 0.9298093836895173, 1e-12);
  EXPECT_NEAR(r.p_gg, 9.647472441468582e-06, 1e-14);
  EXPECT_GT(r.partial_eta_squared, 0.9);
  // Every participant alike in each level, the levels different: F unbounded, p 0; nothing varying: p 1.
  const RmAnova clean = rmAnova({{0, 1, 1}, {0, 1, 1}, {0, 1, 1}});
  EXPECT_TRUE(std::isinf(clean.f));
  EXPECT_EQ(clean.p, 0.0);
  const RmAnova flat = rmAnova({{1, 1}, {1, 1}, {1, 1}});
  EXPECT_TRUE(std::isnan(flat.f));
  EXPECT_EQ(flat.p, 1.0);
  EXPECT_EQ(rmAnova({{1, 2}, {NAN, 3}}).subjects, 1) << "a row with a gap is left out";
}

TEST(Statistics, HolmMatchesStatsmodels) {
  // statsmodels.stats.multitest.multipletests([0.01, 0.04, 0.03, 0.5], method='holm')[1]
  const std::vector<double> adjusted = holm({0.01, 0.04, 0.03, 0.5});
  const std::vector<double> expected = {0.04, 0.09, 0.09, 0.5};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(adjusted[i], expected[i], 1e-15) << i;
}

}  // namespace
}  // namespace gf::app::stats
