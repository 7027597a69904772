// mixture.cpp - validation, log-density, BIC and model.h conversion of an Eigen mixture
// (paper eq. 1; the seam-safe wrapped normal of gmm.h). See mixture.hpp.
#include "gmmrrt_learner/mixture.hpp"

#include <cmath>
#include <sstream>

#include "component_terms.hpp"
#include "gmmrrt/features.h"

namespace gmmrrt {
namespace learn {

namespace {
int CountAngleDims(int dim, uint32_t mask) {
  int a = 0;
  for (int j = 0; j < dim; ++j) a += (mask >> j) & 1u;
  return a;
}
}  // namespace

Status ValidateMixture(const Mixture& m) {
  auto bad = [](const std::string& why) { return Status::Error(StatusCode::kBadModel, why); };
  if (m.dim < 1 || m.dim > GMMRRT_MAX_DIM)
    return bad("dimension " + std::to_string(m.dim) + " outside 1.." + std::to_string(GMMRRT_MAX_DIM));
  const int k = m.k();
  if (k < 1 || k > GMMRRT_MAX_K)
    return bad("component count " + std::to_string(k) + " outside 1.." + std::to_string(GMMRRT_MAX_K));
  if (m.dim < 32 && (m.angle_mask >> m.dim) != 0u) return bad("angle flag set on a dimension >= D");
  if (CountAngleDims(m.dim, m.angle_mask) > kMaxAngleDims)
    return bad("more than " + std::to_string(kMaxAngleDims) + " angle dimensions");
  if (m.means.rows() != m.dim || m.means.cols() != k || static_cast<int>(m.chol.size()) != k)
    return bad("means or factors do not match D and K");
  double sum = 0.0;
  for (int i = 0; i < k; ++i) {
    const std::string comp = "component " + std::to_string(i);
    if (!std::isfinite(m.weights[i]) || m.weights[i] <= 0.0 || m.weights[i] > 1.0)
      return bad(comp + ": weight outside (0, 1]");
    sum += m.weights[i];
    if (!m.means.col(i).allFinite()) return bad(comp + ": mean is not finite");
    const Eigen::MatrixXd& l = m.chol[i];
    if (l.rows() != m.dim || l.cols() != m.dim) return bad(comp + ": factor is not D x D");
    if (!l.allFinite()) return bad(comp + ": factor is not finite");
    for (int j = 0; j < m.dim; ++j)
      if (!(l(j, j) > 0.0)) return bad(comp + ": covariance is not positive definite");
  }
  if (std::fabs(sum - 1.0) > 1e-9) return bad("weights do not sum to 1");
  return Status::Ok();
}

Eigen::MatrixXd ImageOffsets(int dim, uint32_t angle_mask) {
  const int a = CountAngleDims(dim, angle_mask);
  int images = 1;
  for (int t = 0; t < a; ++t) images *= 3;
  Eigen::MatrixXd off = Eigen::MatrixXd::Zero(dim, images);
  for (int c = 0; c < images; ++c) {
    int code = c;
    for (int j = 0; j < dim; ++j) {
      if (!((angle_mask >> j) & 1u)) continue;
      // Image 0 is the unshifted one; digits 0, 1, 2 mean n = 0, +1, -1.
      const int digit = code % 3;
      code /= 3;
      off(j, c) = (digit == 0 ? 0.0 : (digit == 1 ? 2.0 * M_PI : -2.0 * M_PI));
    }
  }
  return off;
}

void WrapAngleRows(uint32_t angle_mask, Eigen::MatrixXd* x) {
  if (angle_mask == 0u) return;
  for (Eigen::Index j = 0; j < x->rows() && j < 32; ++j) {
    if (!((angle_mask >> j) & 1u)) continue;
    for (Eigen::Index c = 0; c < x->cols(); ++c) (*x)(j, c) = gmmrrt_wrap_angle((*x)(j, c));
  }
}

void LogDensity(const Mixture& m, const Eigen::MatrixXd& points, Eigen::VectorXd* out) {
  detail::PreparedMixture p;
  detail::Prepare(m, &p);
  const Eigen::Index n = points.cols();
  out->resize(n);
  const Eigen::MatrixXd rows = points.transpose();  // points as rows: see component_terms.hpp
  Eigen::MatrixXd terms;
  Eigen::VectorXd lse;
  for (Eigen::Index start = 0; start < n; start += detail::kBlockPoints) {
    const Eigen::Index b = std::min<Eigen::Index>(detail::kBlockPoints, n - start);
    detail::LogTerms(m, p, rows.middleRows(start, b), &terms);
    detail::LogSumExpRows(terms, &lse);
    out->segment(start, b) = lse;
  }
}

double MeanLogLikelihood(const Mixture& m, const Eigen::MatrixXd& points) {
  Eigen::VectorXd ll;
  LogDensity(m, points, &ll);
  return ll.mean();
}

int FreeParameters(int k, int dim) { return (k - 1) + k * dim + k * dim * (dim + 1) / 2; }

double Bic(double mean_log_likelihood, int64_t n_points, int k, int dim) {
  const double n = static_cast<double>(n_points);
  return -2.0 * n * mean_log_likelihood + FreeParameters(k, dim) * std::log(n);
}

Status MixtureToModel(const Mixture& m, int kind, int task, int homotopy, double delta,
                      gmmrrt_model_t* out) {
  Status s = ValidateMixture(m);
  if (!s.ok()) return s;
  *out = gmmrrt_model_t{};
  out->kind = kind;
  out->task = task;
  out->homotopy = homotopy;
  out->dim = m.dim;
  out->k = m.k();
  out->angle_mask = m.angle_mask;
  out->delta = delta;
  for (int i = 0; i < m.k(); ++i) {
    out->weight[i] = m.weights[i];
    int t = 0;
    for (int r = 0; r < m.dim; ++r) {
      out->mean[i][r] = m.means(r, i);
      for (int c = 0; c <= r; ++c) out->chol[i][t++] = m.chol[i](r, c);
    }
  }
  return Status::Ok();
}

Mixture MixtureFromModel(const gmmrrt_model_t& model) {
  Mixture m;
  m.dim = model.dim;
  m.angle_mask = model.angle_mask;
  m.weights.resize(model.k);
  m.means.resize(model.dim, model.k);
  m.chol.assign(model.k, Eigen::MatrixXd::Zero(model.dim, model.dim));
  for (int i = 0; i < model.k; ++i) {
    m.weights[i] = model.weight[i];
    int t = 0;
    for (int r = 0; r < model.dim; ++r) {
      m.means(r, i) = model.mean[i][r];
      for (int c = 0; c <= r; ++c) m.chol[i](r, c) = model.chol[i][t++];
    }
  }
  return m;
}

}  // namespace learn
}  // namespace gmmrrt
