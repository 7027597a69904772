// squarem.cpp - SQUAREM's extrapolation for mixtures (contract in squarem.hpp).
#include "squarem.hpp"

#include <algorithm>
#include <cmath>

#include "gmmrrt/features.h"

namespace gmmrrt {
namespace learn {
namespace detail {

namespace {

// Parameters in unconstrained coordinates: K log weights, D x K means, then per component the
// D log diagonal entries and the D (D - 1) / 2 entries below the diagonal of L.
Eigen::VectorXd Pack(const Mixture& m) {
  const int k = m.k(), d = m.dim;
  Eigen::VectorXd p(k + d * k + k * (d + d * (d - 1) / 2));
  Eigen::Index q = 0;
  for (int i = 0; i < k; ++i) p[q++] = std::log(m.weights[i]);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < d; ++j) p[q++] = m.means(j, i);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < d; ++j) p[q++] = std::log(m.chol[i](j, j));
    for (int j = 0; j < d; ++j)
      for (int c = 0; c < j; ++c) p[q++] = m.chol[i](j, c);
  }
  return p;
}

// Differences b - a, with the mean entries of angle dimensions wrapped into (-pi, pi].
Eigen::VectorXd Difference(const Mixture& m, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  Eigen::VectorXd diff = b - a;
  if (m.angle_mask != 0u) {
    const int k = m.k(), d = m.dim;
    for (int i = 0; i < k; ++i)
      for (int j = 0; j < d; ++j)
        if ((m.angle_mask >> j) & 1u) diff[k + i * d + j] = gmmrrt_wrap_angle(diff[k + i * d + j]);
  }
  return diff;
}

}  // namespace

bool SquaremExtrapolate(const Mixture& m0, const Mixture& m1, const Mixture& m2, double step_max,
                        const Eigen::VectorXd& min_var, Mixture* out, double* step, double* wanted) {
  const int k = m0.k(), d = m0.dim;
  if (m1.k() != k || m2.k() != k) return false;
  const Eigen::VectorXd p0 = Pack(m0), p1 = Pack(m1), p2 = Pack(m2);
  const Eigen::VectorXd r = Difference(m0, p0, p1);
  const Eigen::VectorXd v = Difference(m0, p1, p2) - r;
  const double rr = r.squaredNorm(), vv = v.squaredNorm();
  if (!(rr > 0.0) || !std::isfinite(rr) || !std::isfinite(vv)) return false;
  *wanted = vv > 0.0 ? std::sqrt(rr / vv) : HUGE_VAL;
  const double s = std::min(std::max(*wanted, 1.0), step_max);
  const Eigen::VectorXd p = p0 + (2.0 * s) * r + (s * s) * v;
  if (!p.allFinite()) return false;

  Mixture m;
  m.dim = d;
  m.angle_mask = m0.angle_mask;
  m.weights.resize(k);
  m.means.resize(d, k);
  m.chol.assign(k, Eigen::MatrixXd::Zero(d, d));
  Eigen::Index q = 0;
  const double log_w_max = p.head(k).maxCoeff();
  for (int i = 0; i < k; ++i) m.weights[i] = std::exp(p[q++] - log_w_max);
  m.weights /= m.weights.sum();
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < d; ++j) {
      const double mu = p[q++];
      m.means(j, i) = ((m.angle_mask >> j) & 1u) ? gmmrrt_wrap_angle(mu) : mu;
    }
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < d; ++j) {
      const double l = std::exp(p[q++]);
      if (!(l * l >= min_var[j]) || !std::isfinite(l)) return false;
      m.chol[i](j, j) = l;
    }
    for (int j = 0; j < d; ++j)
      for (int c = 0; c < j; ++c) m.chol[i](j, c) = p[q++];
  }
  if (!(m.weights.array() > 0.0).all() || !ValidateMixture(m).ok()) return false;
  *out = std::move(m);
  *step = s;
  return true;
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
