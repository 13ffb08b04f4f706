#include "app/experiment/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace gf::app::stats {
namespace {

// The continued fraction of I_x(a, b) (its even and odd steps), evaluated by Lentz's method.
double betaFraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  constexpr int kSteps = 500;
  double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
  if (std::abs(d) < kTiny) d = kTiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= kSteps; ++m) {
    const double m2 = 2.0 * m;
    for (const double step : {m * (b - m) * x / ((a + m2 - 1.0) * (a + m2)),
                              -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0))}) {
      d = 1.0 + step * d;
      if (std::abs(d) < kTiny) d = kTiny;
      c = 1.0 + step / c;
      if (std::abs(c) < kTiny) c = kTiny;
      d = 1.0 / d;
      h *= d * c;
    }
    if (std::abs(d * c - 1.0) < 1e-15) break;
  }
  return h;
}

}  // namespace

double incompleteBeta(double a, double b, double x) {
  if (!(x > 0.0)) return 0.0;
  if (!(x < 1.0)) return 1.0;
  const double log_front = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
  // The fraction converges fast below the mean of the Beta(a, b) distribution; above it, by symmetry.
  if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(log_front) * betaFraction(a, b, x) / a;
  return 1.0 - std::exp(log_front) * betaFraction(b, a, 1.0 - x) / b;
}

double tCdf(double t, double df) {
  if (std::isinf(t)) return t > 0 ? 1.0 : 0.0;
  const double tail = 0.5 * incompleteBeta(0.5 * df, 0.5, df / (df + t * t));
  return t > 0.0 ? 1.0 - tail : tail;
}

double tQuantile(double p, double df) {
  double lo = -1.0, hi = 1.0;
  while (tCdf(lo, df) > p) lo *= 2.0;
  while (tCdf(hi, df) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (tCdf(mid, df) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double fCdf(double f, double df1, double df2) {
  if (!(f > 0.0)) return 0.0;
  if (std::isinf(f)) return 1.0;
  return incompleteBeta(0.5 * df1, 0.5 * df2, df1 * f / (df1 * f + df2));
}

double normalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

MeanCi meanCi(const std::vector<double>& values) {
  MeanCi m;
  double sum = 0.0;
  for (const double v : values) {
    if (std::isnan(v)) continue;
    ++m.n;
    sum += v;
  }
  if (m.n == 0) {
    m.mean = m.sd = m.lo = m.hi = NAN;
    return m;
  }
  m.mean = sum / m.n;
  double squares = 0.0;
  for (const double v : values) {
    if (!std::isnan(v)) squares += (v - m.mean) * (v - m.mean);
  }
  m.sd = m.n > 1 ? std::sqrt(squares / (m.n - 1)) : 0.0;
  const double half = m.n > 1 ? tQuantile(0.975, m.n - 1) * m.sd / std::sqrt(static_cast<double>(m.n)) : 0.0;
  m.lo = m.mean - half;
  m.hi = m.mean + half;
  return m;
}

Wilcoxon wilcoxon(const std::vector<double>& a, const std::vector<double>& b) {
  // Differences to 12 significant digits of the largest: rates such as 2/3 - 1/3 and 1/3 differ in
  // their last bits, and would otherwise be neither tied nor zero.
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (!std::isnan(a[i] - b[i])) largest = std::max({largest, std::abs(a[i]), std::abs(b[i])});
  }
  const double grain = largest > 0.0 ? largest * 1e-12 : 1.0;
  std::vector<double> d;
  int zeros = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    const double diff = std::round((a[i] - b[i]) / grain) * grain;
    if (std::isnan(diff)) continue;
    if (diff == 0.0) ++zeros;
    else d.push_back(diff);
  }
  Wilcoxon w;
  w.n = static_cast<int>(d.size());
  if (w.n == 0) return w;
  // Ranks of |d|, ties sharing their mean rank.
  std::vector<std::size_t> order(d.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return std::abs(d[i]) < std::abs(d[j]); });
  std::vector<double> rank(d.size());
  double tie_term = 0.0;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && std::abs(d[order[j + 1]]) == std::abs(d[order[i]])) ++j;
    const double shared = 0.5 * static_cast<double>(i + j) + 1.0;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = shared;
    const double t = static_cast<double>(j - i + 1);
    tie_term += t * t * t - t;
    i = j + 1;
  }
  for (std::size_t i = 0; i < d.size(); ++i) (d[i] > 0.0 ? w.w_plus : w.w_minus) += rank[i];
  const double n = w.n;
  w.rank_biserial = (w.w_plus - w.w_minus) / (w.w_plus + w.w_minus);
  const double smaller = std::min(w.w_plus, w.w_minus);
  // Exact without ties and zeros up to 50 pairs, as SciPy's default; else the normal approximation.
  if (tie_term == 0.0 && zeros == 0 && w.n <= 50) {
    // The exact null distribution of W+: the number of subsets of the ranks 1..n with each sum.
    const int top = w.n * (w.n + 1) / 2;
    std::vector<double> count(static_cast<std::size_t>(top) + 1, 0.0);
    count[0] = 1.0;
    for (int r = 1; r <= w.n; ++r) {
      for (int s = top; s >= r; --s) count[static_cast<std::size_t>(s)] += count[static_cast<std::size_t>(s - r)];
    }
    double below = 0.0;
    for (int s = 0; s <= static_cast<int>(std::lround(smaller)); ++s) below += count[static_cast<std::size_t>(s)];
    w.p = std::min(1.0, 2.0 * below / std::ldexp(1.0, w.n));
    w.exact = true;
    return w;
  }
  const double mean = n * (n + 1.0) / 4.0;
  const double sd = std::sqrt(n * (n + 1.0) * (2.0 * n + 1.0) / 24.0 - tie_term / 48.0);
  w.p = sd > 0.0 ? std::min(1.0, 2.0 * normalCdf((smaller - mean) / sd)) : 1.0;
  return w;
}

RmAnova rmAnova(const std::vector<std::vector<double>>& data) {
  std::vector<std::vector<double>> rows;
  for (const std::vector<double>& row : data) {
    if (std::none_of(row.begin(), row.end(), [](double v) { return std::isnan(v); })) rows.push_back(row);
  }
  RmAnova r;
  r.subjects = static_cast<int>(rows.size());
  r.levels = rows.empty() ? 0 : static_cast<int>(rows[0].size());
  if (r.subjects < 2 || r.levels < 2) {
    r.f = r.p = r.p_gg = r.partial_eta_squared = NAN;
    return r;
  }
  const int n = r.subjects, k = r.levels;
  std::vector<double> level_mean(static_cast<std::size_t>(k), 0.0), subject_mean(static_cast<std::size_t>(n), 0.0);
  double grand = 0.0;
  for (int s = 0; s < n; ++s) {
    for (int j = 0; j < k; ++j) {
      const double v = rows[static_cast<std::size_t>(s)][static_cast<std::size_t>(j)];
      level_mean[static_cast<std::size_t>(j)] += v / n;
      subject_mean[static_cast<std::size_t>(s)] += v / k;
      grand += v / (n * k);
    }
  }
  double scale = 0.0;
  for (const auto& row : rows) {
    for (const double v : row) scale = std::max(scale, std::abs(v));
  }
  // Sums of squares below rounding (every value equal, up to the last bits) are none.
  const double rounding = 1e-20 * n * k * std::max(1e-300, scale * scale);
  double ss_levels = 0.0, ss_subjects = 0.0, ss_total = 0.0;
  for (const double m : level_mean) ss_levels += n * (m - grand) * (m - grand);
  for (const double m : subject_mean) ss_subjects += k * (m - grand) * (m - grand);
  for (const auto& row : rows) {
    for (const double v : row) ss_total += (v - grand) * (v - grand);
  }
  // What is left of the total after the levels and the subjects is rounding below 1e-12 of it.
  if (ss_levels < rounding) ss_levels = 0.0;
  double ss_error = std::max(0.0, ss_total - ss_levels - ss_subjects);
  if (ss_error < rounding + 1e-12 * ss_total) ss_error = 0.0;
  r.df1 = k - 1;
  r.df2 = (k - 1.0) * (n - 1.0);
  const bool no_error = ss_error == 0.0;
  r.f = no_error ? (ss_levels > 0.0 ? INFINITY : NAN) : (ss_levels / r.df1) / (ss_error / r.df2);
  r.p = no_error ? (ss_levels > 0.0 ? 0.0 : 1.0) : 1.0 - fCdf(r.f, r.df1, r.df2);
  r.partial_eta_squared = ss_levels + ss_error > 0.0 ? ss_levels / (ss_levels + ss_error) : NAN;
  // Greenhouse-Geisser: from the levels' covariance matrix, double-centred.
  std::vector<std::vector<double>> cov(static_cast<std::size_t>(k), std::vector<double>(static_cast<std::size_t>(k), 0.0));
  for (const auto& row : rows) {
    for (int i = 0; i < k; ++i) {
      for (int j = 0; j < k; ++j) {
        cov[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] +=
            (row[static_cast<std::size_t>(i)] - level_mean[static_cast<std::size_t>(i)]) *
            (row[static_cast<std::size_t>(j)] - level_mean[static_cast<std::size_t>(j)]) / (n - 1);
      }
    }
  }
  std::vector<double> row_mean(static_cast<std::size_t>(k), 0.0);
  double all_mean = 0.0;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) row_mean[static_cast<std::size_t>(i)] += cov[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] / k;
    all_mean += row_mean[static_cast<std::size_t>(i)] / k;
  }
  double trace = 0.0, squares = 0.0;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      const double c = cov[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] - row_mean[static_cast<std::size_t>(i)] -
                       row_mean[static_cast<std::size_t>(j)] + all_mean;
      squares += c * c;
      if (i == j) trace += c;
    }
  }
  r.gg_epsilon = squares > 0.0 ? std::clamp(trace * trace / ((k - 1) * squares), 1.0 / (k - 1), 1.0) : 1.0;
  r.p_gg = no_error ? r.p : 1.0 - fCdf(r.f, r.df1 * r.gg_epsilon, r.df2 * r.gg_epsilon);
  return r;
}

std::vector<double> holm(const std::vector<double>& p) {
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return p[i] < p[j]; });
  std::vector<double> out(p.size());
  double running = 0.0;
  for (std::size_t r = 0; r < order.size(); ++r) {
    running = std::max(running, std::min(1.0, static_cast<double>(p.size() - r) * p[order[r]]));
    out[order[r]] = running;
  }
  return out;
}

}  // namespace gf::app::stats
