// em.cpp - EM for a (wrapped) Gaussian mixture in log space (paper Sect. 3, eq. 1), seeded by
// k-means++ with restarts; degenerate components re-seeded or dropped. Contract in em.hpp.
//
// Sufficient statistics are accumulated per block of points relative to the previous mean
// (y - mu_old = delta + 2 pi n, delta the wrapped difference), which keeps the one-pass
// covariance free of the cancellation that raw second moments would suffer far from the origin.
#include "gmmrrt_learner/em.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>

#include "component_terms.hpp"
#include "gmmrrt/features.h"
#include "gmmrrt_learner/kmeans.hpp"

namespace gmmrrt {
namespace learn {

bool FitOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& why) {
    *error = why;
    return false;
  };
  if (k < 1 || k > GMMRRT_MAX_K)
    return fail("k = " + std::to_string(k) + " outside 1.." + std::to_string(GMMRRT_MAX_K));
  if (restarts < 1) return fail("restarts must be >= 1");
  if (kmeans_max_iterations < 1) return fail("kmeans_max_iterations must be >= 1");
  if (max_iterations < 0) return fail("max_iterations must be >= 0");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) return fail("tolerance must be finite and > 0");
  if (!(reg_relative >= 0.0) || !std::isfinite(reg_relative)) return fail("reg_relative must be finite and >= 0");
  if (!(reg_floor > 0.0) || !std::isfinite(reg_floor)) return fail("reg_floor must be finite and > 0");
  if (max_reseeds < -1) return fail("max_reseeds must be >= 0 (or -1 for 3 K)");
  return true;
}

std::string FitSummary::BriefReport() const {
  std::ostringstream o;
  o.precision(10);
  o << "N=" << n_points << " D=" << dim << " K=" << k_final;
  if (k_final != k_requested) o << " (of " << k_requested << " requested)";
  o << " iterations=" << iterations << (converged ? " converged" : " NOT converged (iteration cap)")
    << " mean_log_likelihood=" << final_mean_log_likelihood << " BIC=" << bic
    << " reseeds=" << reseeds << " dropped=" << dropped;
  return o.str();
}

namespace {

struct Stats {
  Eigen::VectorXd nk;               // K: sum of responsibilities
  Eigen::MatrixXd s1;               // D x K: sum r (y - mu_old)
  std::vector<Eigen::MatrixXd> s2;  // K of D x D: sum r (y - mu_old)(y - mu_old)^T

  void Reset(int d, int k) {
    nk.setZero(k);
    s1.setZero(d, k);
    s2.assign(k, Eigen::MatrixXd::Zero(d, d));
  }
};

// Data-wide quantities the fit needs more than once.
struct DataInfo {
  Eigen::VectorXd mean;       // D (angle rows: circular mean)
  Eigen::MatrixXd cov;        // D x D (angle rows: of wrapped differences to the mean)
  double reg = 0.0;           // added to each covariance diagonal
};

void ComputeDataInfo(const Eigen::MatrixXd& x, uint32_t mask, const FitOptions& o, DataInfo* info) {
  const Eigen::Index d = x.rows();
  info->mean = x.rowwise().mean();
  for (Eigen::Index j = 0; j < d; ++j) {
    if (!((mask >> j) & 1u)) continue;
    const double s = x.row(j).array().sin().mean(), c = x.row(j).array().cos().mean();
    info->mean[j] = std::atan2(s, c);
  }
  Eigen::MatrixXd delta = x.colwise() - info->mean;
  WrapAngleRows(mask, &delta);
  const Eigen::VectorXd dmean = delta.rowwise().mean();
  delta.colwise() -= dmean;
  info->cov = delta * delta.transpose() / static_cast<double>(x.cols());
  info->reg = std::max(o.reg_relative * info->cov.diagonal().mean(), o.reg_floor);
}

// One E-step: mean log-likelihood per point; statistics and per-point log-likelihood out.
double EStep(const Mixture& m, const Eigen::MatrixXd& x, Stats* st, Eigen::VectorXd* point_ll) {
  detail::PreparedMixture p;
  detail::Prepare(m, &p);
  const Eigen::Index n = x.cols();
  st->Reset(m.dim, m.k());
  point_ll->resize(n);
  Eigen::MatrixXd terms, resp, delta;
  Eigen::VectorXd lse, rsum;
  for (Eigen::Index start = 0; start < n; start += detail::kBlockPoints) {
    const Eigen::Index b = std::min<Eigen::Index>(detail::kBlockPoints, n - start);
    const auto block = x.middleCols(start, b);
    detail::LogTerms(m, p, block, &terms);
    detail::LogSumExpRows(terms, &lse);
    point_ll->segment(start, b) = lse;
    resp = (terms.colwise() - lse).array().exp().matrix();
    for (int i = 0; i < p.k; ++i) {
      detail::ComponentDelta(m, i, block, &delta);
      rsum = resp.middleCols(static_cast<Eigen::Index>(i) * p.images, p.images).rowwise().sum();
      st->nk[i] += rsum.sum();
      const Eigen::VectorXd dr = delta * rsum;
      st->s1.col(i) += dr;
      st->s2[i].noalias() += (delta.array().rowwise() * rsum.transpose().array()).matrix() *
                             delta.transpose();
      for (int j = 1; j < p.images; ++j) {  // image 0 has a zero offset
        const Eigen::VectorXd r = resp.col(static_cast<Eigen::Index>(i) * p.images + j);
        const double sr = r.sum();
        if (sr == 0.0) continue;
        const Eigen::VectorXd o = p.offsets.col(j);
        const Eigen::VectorXd drj = delta * r;
        st->s1.col(i) += o * sr;
        st->s2[i] += o * drj.transpose() + drj * o.transpose() + (o * o.transpose()) * sr;
      }
    }
  }
  return point_ll->mean();
}

// Candidates for re-seeding: point indices from the lowest score upward.
std::vector<Eigen::Index> WorstPoints(const Eigen::VectorXd& score, int count) {
  std::vector<Eigen::Index> idx(score.size());
  std::iota(idx.begin(), idx.end(), 0);
  count = std::min<int>(count, static_cast<int>(idx.size()));
  std::partial_sort(idx.begin(), idx.begin() + count, idx.end(), [&score](Eigen::Index a, Eigen::Index b) {
    return score[a] < score[b] || (score[a] == score[b] && a < b);
  });
  idx.resize(count);
  return idx;
}

struct FitState {
  const Eigen::MatrixXd* x = nullptr;
  uint32_t mask = 0;
  const FitOptions* options = nullptr;
  DataInfo info;
  Eigen::MatrixXd reseed_chol;  // Cholesky of the data covariance shrunk by K^(-2/D)
  int max_reseeds = 0;
  FitSummary* summary = nullptr;

  void Warn(const std::string& w) const {
    summary->warnings.push_back(w);
    if (options->warn) options->warn(w);
  }
};

// M-step from statistics taken around old_means. Returns true when a component was re-seeded or
// dropped. score ranks points for re-seeding (lowest first).
bool MStep(const FitState& s, const Stats& st, const Eigen::MatrixXd& old_means,
           const Eigen::VectorXd& score, int iteration, Mixture* m) {
  const int d = m->dim;
  const int k = static_cast<int>(st.nk.size());
  const double n = static_cast<double>(s.x->cols());
  Mixture next;
  next.dim = d;
  next.angle_mask = s.mask;
  std::vector<double> w;
  std::vector<Eigen::VectorXd> mu;
  std::vector<Eigen::MatrixXd> chol;
  std::vector<int> degenerate;
  for (int i = 0; i < k; ++i) {
    bool ok = st.nk[i] >= d + 1.0;
    if (ok) {
      const Eigen::VectorXd c = st.s1.col(i) / st.nk[i];
      Eigen::MatrixXd cov = st.s2[i] / st.nk[i] - c * c.transpose();
      cov = 0.5 * (cov + cov.transpose());
      ok = (cov.diagonal().array() > s.info.reg).all();
      cov.diagonal().array() += s.info.reg;
      Eigen::LLT<Eigen::MatrixXd> llt(cov);
      ok = ok && llt.info() == Eigen::Success && llt.matrixL().toDenseMatrix().allFinite();
      if (ok) {
        w.push_back(st.nk[i] / n);
        mu.push_back(old_means.col(i) + c);
        chol.push_back(llt.matrixL().toDenseMatrix());
      }
    }
    if (!ok) degenerate.push_back(i);
  }
  bool changed = false;
  if (!degenerate.empty()) {
    changed = true;
    s.summary->reseed_iterations.push_back(iteration);
    const std::vector<Eigen::Index> worst = WorstPoints(score, static_cast<int>(degenerate.size()));
    size_t next_worst = 0;
    for (int i : degenerate) {
      std::ostringstream msg;
      msg << "component " << i << " degenerate at iteration " << iteration << " (" << st.nk[i]
          << " effective points)";
      if (s.summary->reseeds < s.max_reseeds && next_worst < worst.size()) {
        const Eigen::Index p = worst[next_worst++];
        ++s.summary->reseeds;
        w.push_back(1.0 / k);
        mu.push_back(s.x->col(p));
        chol.push_back(s.reseed_chol);
        msg << ": re-seeded at point " << p;
      } else {
        ++s.summary->dropped;
        msg << ": dropped (re-seed budget of " << s.max_reseeds << " spent)";
      }
      s.Warn(msg.str());
    }
  }
  const int k_next = static_cast<int>(w.size());
  next.weights.resize(k_next);
  next.means.resize(d, k_next);
  next.chol = chol;
  for (int i = 0; i < k_next; ++i) {
    next.weights[i] = w[i];
    next.means.col(i) = mu[i];
  }
  if (k_next > 0) next.weights /= next.weights.sum();
  WrapAngleRows(s.mask, &next.means);
  *m = std::move(next);
  return changed;
}

}  // namespace

Status FitMixture(const Eigen::MatrixXd& points, uint32_t angle_mask, const FitOptions& options,
                  Mixture* mixture, FitSummary* summary) {
  std::string why;
  if (!options.IsValid(&why)) return Status::Error(StatusCode::kInvalidArgument, why);
  const int d = static_cast<int>(points.rows());
  const Eigen::Index n = points.cols();
  if (d < 1 || d > GMMRRT_MAX_DIM)
    return Status::Error(StatusCode::kInvalidArgument,
                         "dimension " + std::to_string(d) + " outside 1.." + std::to_string(GMMRRT_MAX_DIM));
  if ((d < 32 && (angle_mask >> d) != 0u))
    return Status::Error(StatusCode::kInvalidArgument, "angle flag set on a dimension >= D");
  if (ImageOffsets(d, angle_mask).cols() > 81)
    return Status::Error(StatusCode::kInvalidArgument,
                         "more than " + std::to_string(kMaxAngleDims) + " angle dimensions");
  if (n == 0) return Status::Error(StatusCode::kNotEnoughData, "no data points");
  const int64_t needed = static_cast<int64_t>(options.k) * (d + 1);
  if (n < needed)
    return Status::Error(StatusCode::kNotEnoughData,
                         std::to_string(n) + " points, but K = " + std::to_string(options.k) +
                             " components in D = " + std::to_string(d) + " need at least K (D + 1) = " +
                             std::to_string(needed));
  for (Eigen::Index c = 0; c < n; ++c)
    for (int j = 0; j < d; ++j)
      if (!std::isfinite(points(j, c)))
        return Status::Error(StatusCode::kBadInput, "point " + std::to_string(c) + ", dimension " +
                                                        std::to_string(j) + " is not finite");

  *summary = FitSummary();
  summary->n_points = n;
  summary->dim = d;
  summary->k_requested = options.k;
  Eigen::MatrixXd x = points;
  WrapAngleRows(angle_mask, &x);

  FitState s;
  s.x = &x;
  s.mask = angle_mask;
  s.options = &options;
  s.summary = summary;
  s.max_reseeds = options.max_reseeds < 0 ? 3 * options.k : options.max_reseeds;
  ComputeDataInfo(x, angle_mask, options, &s.info);
  for (int j = 0; j < d; ++j)
    if (!(s.info.cov(j, j) > options.reg_floor))
      return Status::Error(StatusCode::kBadInput,
                           "dimension " + std::to_string(j) + " is (nearly) constant: variance " +
                               std::to_string(s.info.cov(j, j)) + " <= reg_floor");
  {
    Eigen::MatrixXd shrunk = s.info.cov * std::pow(static_cast<double>(options.k), -2.0 / d);
    shrunk.diagonal().array() += s.info.reg;
    Eigen::LLT<Eigen::MatrixXd> llt(shrunk);
    if (llt.info() != Eigen::Success)
      return Status::Error(StatusCode::kBadInput, "the data covariance is not positive definite");
    s.reseed_chol = llt.matrixL().toDenseMatrix();
  }

  // Seed: k-means++ with restarts, then one M-step from the hard assignment.
  std::mt19937_64 rng(options.seed);
  KMeansOptions ko;
  ko.k = options.k;
  ko.restarts = options.restarts;
  ko.max_iterations = options.kmeans_max_iterations;
  KMeansResult km;
  Status st = KMeans(x, angle_mask, ko, &rng, &km);
  if (!st.ok()) return st;
  summary->kmeans_inertia = km.inertia;

  Mixture m;
  m.dim = d;
  m.angle_mask = angle_mask;
  Stats stats;
  stats.Reset(d, options.k);
  Eigen::VectorXd score(n);
  {
    Eigen::VectorXd delta(d);
    for (Eigen::Index c = 0; c < n; ++c) {
      const int l = km.labels[c];
      delta = x.col(c) - km.centers.col(l);
      for (int j = 0; j < d; ++j)
        if ((angle_mask >> j) & 1u) delta[j] = gmmrrt_wrap_angle(delta[j]);
      stats.nk[l] += 1.0;
      stats.s1.col(l) += delta;
      stats.s2[l] += delta * delta.transpose();
      score[c] = -delta.squaredNorm();
    }
  }
  MStep(s, stats, km.centers, score, 0, &m);
  if (m.k() == 0) return Status::Error(StatusCode::kNumericalFailure, "every component degenerate at the seed");

  double previous = 0.0;
  bool last_changed = true;
  for (int t = 0;; ++t) {
    const double ll = EStep(m, x, &stats, &score);
    summary->log_likelihood.push_back(ll);
    if (options.progress) options.progress(t, ll);
    if (t >= 1 && !last_changed && std::fabs(ll - previous) < options.tolerance) {
      summary->converged = true;
      break;
    }
    if (t == options.max_iterations) break;
    previous = ll;
    const Eigen::MatrixXd old_means = m.means;
    last_changed = MStep(s, stats, old_means, score, t + 1, &m);
    summary->iterations = t + 1;
    if (m.k() == 0)
      return Status::Error(StatusCode::kNumericalFailure, "every component degenerate (all dropped)");
  }
  summary->k_final = m.k();
  summary->final_mean_log_likelihood = summary->log_likelihood.back();
  summary->bic = Bic(summary->final_mean_log_likelihood, n, m.k(), d);
  st = ValidateMixture(m);
  if (!st.ok()) return Status::Error(StatusCode::kNumericalFailure, "fit produced an invalid mixture: " + st.message);
  *mixture = std::move(m);
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
