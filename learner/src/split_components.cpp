// split_components.cpp - split moves for the BIC sweep's starts (contract in
// split_components.hpp).
#include "split_components.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gmmrrt/limits.h"

namespace gmmrrt {
namespace learn {
namespace detail {

std::vector<Mixture> SplitCandidates(const Mixture& m, int max_candidates) {
  std::vector<Mixture> out;
  const int k = m.k(), d = m.dim;
  if (k + 1 > GMMRRT_MAX_K || max_candidates < 1) return out;
  std::vector<double> size(k);
  for (int i = 0; i < k; ++i) size[i] = m.weights[i] * m.chol[i].diagonal().prod();  // w sqrt(det)
  std::vector<int> order(k);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&size](int a, int b) { return size[a] > size[b]; });
  for (int c = 0; c < std::min(k, max_candidates); ++c) {
    const int j = order[c];
    const Eigen::MatrixXd cov = m.chol[j] * m.chol[j].transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
    if (eig.info() != Eigen::Success) continue;
    const double lambda = eig.eigenvalues()[d - 1];  // ascending order
    const Eigen::VectorXd u = eig.eigenvectors().col(d - 1);
    Eigen::MatrixXd half_cov = cov - 0.64 * lambda * u * u.transpose();
    half_cov = 0.5 * (half_cov + half_cov.transpose());
    Eigen::LLT<Eigen::MatrixXd> llt(half_cov);
    if (llt.info() != Eigen::Success) continue;
    Mixture s;
    s.dim = d;
    s.angle_mask = m.angle_mask;
    s.weights.resize(k + 1);
    s.means.resize(d, k + 1);
    s.chol = m.chol;
    s.weights.head(k) = m.weights;
    s.means.leftCols(k) = m.means;
    const Eigen::VectorXd shift = 0.8 * std::sqrt(lambda) * u;
    s.weights[j] = s.weights[k] = 0.5 * m.weights[j];
    s.means.col(j) = m.means.col(j) + shift;
    s.means.col(k) = m.means.col(j) - shift;
    WrapAngleRows(m.angle_mask, &s.means);
    s.chol[j] = llt.matrixL().toDenseMatrix();
    s.chol.push_back(s.chol[j]);
    if (ValidateMixture(s).ok()) out.push_back(std::move(s));
  }
  return out;
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
