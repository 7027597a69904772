// component_terms.cpp - log w_i + log N(delta + 2 pi n; 0, Sigma_i) for every component i and
// image n on a block of points, vectorised with Eigen (paper eq. 1; wrapped normal of gmm.h).
// The Mahalanobis term uses z = L_i^-1 delta, so the image shift is a constant column
// L_i^-1 (2 pi n) added to z: the 3^A images cost one extra squared norm each.
#include "component_terms.hpp"

#include <cmath>
#include <limits>

#include "gmmrrt/features.h"

namespace gmmrrt {
namespace learn {
namespace detail {

void Prepare(const Mixture& m, PreparedMixture* p) {
  const int d = m.dim;
  p->dim = d;
  p->k = m.k();
  p->offsets = ImageOffsets(d, m.angle_mask);
  p->images = static_cast<int>(p->offsets.cols());
  p->inv_chol.resize(p->k);
  p->inv_chol_offsets.resize(p->k);
  p->log_coef.resize(p->k);
  const double half_d_log_2pi = 0.5 * d * std::log(2.0 * M_PI);
  for (int i = 0; i < p->k; ++i) {
    const Eigen::MatrixXd& l = m.chol[i];
    p->inv_chol[i] = l.triangularView<Eigen::Lower>().solve(Eigen::MatrixXd::Identity(d, d));
    p->inv_chol_offsets[i] = p->inv_chol[i] * p->offsets;
    p->log_coef[i] = std::log(m.weights[i]) - half_d_log_2pi - l.diagonal().array().log().sum();
  }
}

void ComponentDelta(const Mixture& m, int i, const Eigen::Ref<const Eigen::MatrixXd>& block,
                    Eigen::MatrixXd* delta) {
  *delta = block.colwise() - m.means.col(i);
  WrapAngleRows(m.angle_mask, delta);
}

void LogTerms(const Mixture& m, const PreparedMixture& p,
              const Eigen::Ref<const Eigen::MatrixXd>& block, Eigen::MatrixXd* terms) {
  const Eigen::Index b = block.cols();
  terms->resize(b, static_cast<Eigen::Index>(p.k) * p.images);
  Eigen::MatrixXd delta, z;
  for (int i = 0; i < p.k; ++i) {
    ComponentDelta(m, i, block, &delta);
    z.noalias() = p.inv_chol[i].triangularView<Eigen::Lower>() * delta;
    for (int j = 0; j < p.images; ++j) {
      const Eigen::Index col = static_cast<Eigen::Index>(i) * p.images + j;
      if (p.images == 1) {
        terms->col(col) = (p.log_coef[i] - 0.5 * z.colwise().squaredNorm().array()).transpose();
      } else {
        terms->col(col) =
            (p.log_coef[i] -
             0.5 * (z.colwise() + p.inv_chol_offsets[i].col(j)).colwise().squaredNorm().array())
                .transpose();
      }
    }
  }
}

void LogSumExpRows(const Eigen::MatrixXd& terms, Eigen::VectorXd* lse) {
  const Eigen::VectorXd row_max = terms.rowwise().maxCoeff();
  const Eigen::VectorXd sums = (terms.colwise() - row_max).array().exp().rowwise().sum();
  lse->resize(terms.rows());
  for (Eigen::Index r = 0; r < terms.rows(); ++r) {
    const double mx = row_max[r];
    (*lse)[r] = std::isfinite(mx) ? mx + std::log(sums[r]) : mx;
  }
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
