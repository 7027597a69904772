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
  delta->resize(block.rows(), block.cols());
  for (Eigen::Index c = 0; c < block.cols(); ++c) {
    delta->col(c) = block.col(c).array() - m.means(c, i);
    if (c < 32 && ((m.angle_mask >> c) & 1u)) {
      double* v = delta->col(c).data();
      for (Eigen::Index r = 0; r < block.rows(); ++r) v[r] = gmmrrt_wrap_angle(v[r]);
    }
  }
}

void LogTerms(const Mixture& m, const PreparedMixture& p,
              const Eigen::Ref<const Eigen::MatrixXd>& block, Eigen::MatrixXd* terms,
              std::vector<Eigen::MatrixXd>* deltas) {
  const Eigen::Index b = block.rows();
  const int d = p.dim;
  terms->resize(b, static_cast<Eigen::Index>(p.k) * p.images);
  if (deltas) deltas->resize(p.k);
  Eigen::MatrixXd local_delta;
  Eigen::ArrayXXd z(b, d);
  Eigen::ArrayXd maha(b);
  for (int i = 0; i < p.k; ++i) {
    Eigen::MatrixXd& delta = deltas ? (*deltas)[i] : local_delta;
    ComponentDelta(m, i, block, &delta);
    const Eigen::MatrixXd& li = p.inv_chol[i];
    for (int r = 0; r < d; ++r) {  // z = delta L^-T, row by row of L^-1 (lower triangular)
      z.col(r) = li(r, 0) * delta.col(0).array();
      for (int c = 1; c <= r; ++c) z.col(r) += li(r, c) * delta.col(c).array();
    }
    for (int j = 0; j < p.images; ++j) {
      const Eigen::Index col = static_cast<Eigen::Index>(i) * p.images + j;
      if (j == 0) {  // image 0 has a zero offset
        maha = z.col(0).square();
        for (int r = 1; r < d; ++r) maha += z.col(r).square();
      } else {
        const Eigen::MatrixXd& zo = p.inv_chol_offsets[i];
        maha = (z.col(0) + zo(0, j)).square();
        for (int r = 1; r < d; ++r) maha += (z.col(r) + zo(r, j)).square();
      }
      terms->col(col) = (p.log_coef[i] - 0.5 * maha).matrix();
    }
  }
}

void LogSumExpRows(const Eigen::MatrixXd& terms, Eigen::VectorXd* lse) {
  const Eigen::Index b = terms.rows();
  Eigen::ArrayXd row_max = terms.col(0).array();
  for (Eigen::Index c = 1; c < terms.cols(); ++c) row_max = row_max.max(terms.col(c).array());
  Eigen::ArrayXd sums = Eigen::ArrayXd::Zero(b);
  for (Eigen::Index c = 0; c < terms.cols(); ++c) sums += (terms.col(c).array() - row_max).exp();
  lse->resize(b);
  for (Eigen::Index r = 0; r < b; ++r) {
    const double mx = row_max[r];
    (*lse)[r] = std::isfinite(mx) ? mx + std::log(sums[r]) : mx;
  }
}

void LogSumExpToResponsibilities(Eigen::MatrixXd* terms, Eigen::VectorXd* lse) {
  const Eigen::Index b = terms->rows();
  Eigen::ArrayXd row_max = terms->col(0).array();
  for (Eigen::Index c = 1; c < terms->cols(); ++c) row_max = row_max.max(terms->col(c).array());
  Eigen::ArrayXd sums = Eigen::ArrayXd::Zero(b);
  for (Eigen::Index c = 0; c < terms->cols(); ++c) {
    terms->col(c) = (terms->col(c).array() - row_max).exp().matrix();
    sums += terms->col(c).array();
  }
  const Eigen::ArrayXd inv = sums.inverse();
  for (Eigen::Index c = 0; c < terms->cols(); ++c) terms->col(c).array() *= inv;
  lse->resize(b);
  for (Eigen::Index r = 0; r < b; ++r) {
    const double mx = row_max[r];
    (*lse)[r] = std::isfinite(mx) ? mx + std::log(sums[r]) : mx;
  }
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
