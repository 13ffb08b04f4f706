// The sparse LDLᵀ factorisation the soft solid solves its steps with: Eigen's SimplicialLDLT,
// behind a class of its own so its translation unit is the only one that instantiates it. The
// sanitizer builds compile that unit without UndefinedBehaviorSanitizer (sim/CMakeLists.txt), as
// Bullet, a library from Debian, is not instrumented at all: its checks in Eigen's inner loops
// were 40 % of a 1.5 mm pad's step there (300 steps on a spinning plate, 17.3 s with them, 10.5 s
// without). AddressSanitizer still covers it.
#pragma once

#include <Eigen/SparseCore>

#include <memory>

namespace gf::sim {

class SparseLdlt {
 public:
  SparseLdlt();
  ~SparseLdlt();
  SparseLdlt(const SparseLdlt&) = delete;
  SparseLdlt& operator=(const SparseLdlt&) = delete;

  /// The ordering and the factor's pattern of `a` (symmetric, its lower triangle read).
  void analyzePattern(const Eigen::SparseMatrix<double>& a);
  /// The factors of `a`, whose pattern analyzePattern() saw. Allocates a work copy.
  void factorize(const Eigen::SparseMatrix<double>& a);
  /// x with a x = b, by the last factorize().
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gf::sim
