#include "sim/soft/sparse_ldlt.hpp"

#include <Eigen/SparseCholesky>

namespace gf::sim {

struct SparseLdlt::Impl {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
};

SparseLdlt::SparseLdlt() : impl_(std::make_unique<Impl>()) {}
SparseLdlt::~SparseLdlt() = default;

void SparseLdlt::analyzePattern(const Eigen::SparseMatrix<double>& a) { impl_->ldlt.analyzePattern(a); }
void SparseLdlt::factorize(const Eigen::SparseMatrix<double>& a) { impl_->ldlt.factorize(a); }
void SparseLdlt::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const { x = impl_->ldlt.solve(b); }

}  // namespace gf::sim
