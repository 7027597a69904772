// em.cpp - EM for a (wrapped) Gaussian mixture in log space (paper Sect. 3, eq. 1), seeded by
// k-means++ with restarts; degenerate components re-seeded or dropped. Contract in em.hpp.
//
// Sufficient statistics are accumulated per block of points relative to the previous mean
// (y - mu_old = delta + 2 pi n, delta the wrapped difference), which keeps the one-pass
// covariance free of the cancellation that raw second moments would suffer far from the origin.
#include "gmmrrt_learner/em.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <random>
#include <sstream>

#include "angle_dims.hpp"
#include "component_terms.hpp"
#include "estep_2d.hpp"
#include "gmmrrt/features.h"
#include "gmmrrt_learner/kmeans.hpp"
#include "parallel.hpp"
#include "spatial_order.hpp"
#include "squarem.hpp"

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
  if (screen_iterations < 0) return fail("screen_iterations must be >= 0");
  if (kmeans_max_iterations < 1) return fail("kmeans_max_iterations must be >= 1");
  if (max_iterations < 0) return fail("max_iterations must be >= 0");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) return fail("tolerance must be finite and > 0");
  if (!(reg_relative >= 0.0) || !std::isfinite(reg_relative)) return fail("reg_relative must be finite and >= 0");
  if (!(reg_floor > 0.0) || !std::isfinite(reg_floor)) return fail("reg_floor must be finite and > 0");
  if (max_reseeds < -1) return fail("max_reseeds must be >= 0 (or -1 for 3 K)");
  if (screen_points < 0) return fail("screen_points must be >= 0");
  if (threads < 0) return fail("threads must be >= 0 (0: the available cores)");
  for (size_t e = 0; e < extra_starts.size(); ++e) {
    if (extra_starts[e].k() != k) return fail("extra start " + std::to_string(e) + " has K != k");
    const Status st = ValidateMixture(extra_starts[e]);
    if (!st.ok()) return fail("extra start " + std::to_string(e) + ": " + st.message);
  }
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
  o.precision(3);
  o << " seconds: prepare=" << prepare_seconds << " candidates=" << candidates_seconds
    << " converge=" << converge_seconds;
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
  Eigen::VectorXd reg;        // D: added to each covariance diagonal
};

using detail::PassRange;  // points [first, last) of pass task t (parallel.hpp)

using detail::AsFitValue;  // angle_dims.hpp
using detail::IsAngleDim;

// The data's mean and covariance in three passes on up to `threads` threads (sums per task of
// points, added in task order: the same bits for any thread count): the mean (angle columns:
// the circular mean, from the sums of sine and cosine), the mean of the (wrapped) differences
// to it, and the covariance of those differences about their mean (two-pass, no cancellation).
void ComputeDataInfo(const Eigen::MatrixXd& xt, uint32_t mask, const FitOptions& o, int threads, DataInfo* info) {
  const Eigen::Index d = xt.cols(), n = xt.rows();
  const long tasks = detail::PassTasks(static_cast<long>(n));
  const double inv_n = 1.0 / static_cast<double>(n);
  Eigen::MatrixXd part(2 * d, tasks);  // per task: sums of x (or sin x), of cos x; then of deltas
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    for (Eigen::Index j = 0; j < d; ++j) {
      const double* xj = xt.col(j).data();
      double a = 0.0, b = 0.0;
      if (IsAngleDim(mask, j)) {
        for (Eigen::Index p = first; p < last; ++p) {
          a += std::sin(xj[p]);
          b += std::cos(xj[p]);
        }
      } else {
        for (Eigen::Index p = first; p < last; ++p) a += xj[p];
      }
      part(j, t) = a;
      part(d + j, t) = b;
    }
  });
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(2 * d);
  for (long t = 0; t < tasks; ++t) sum += part.col(t);
  info->mean.resize(d);
  for (Eigen::Index j = 0; j < d; ++j)
    info->mean[j] = IsAngleDim(mask, j) ? std::atan2(sum[j] * inv_n, sum[d + j] * inv_n) : sum[j] * inv_n;
  // Column j's difference to the mean at point p (wrapped for an angle column).
  auto delta = [&](const double* xj, Eigen::Index p, double mj, bool angle) {
    const double v = xj[p] - mj;
    return angle ? gmmrrt_wrap_angle(v) : v;
  };
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    for (Eigen::Index j = 0; j < d; ++j) {
      const double* xj = xt.col(j).data();
      const double mj = info->mean[j];
      const bool angle = IsAngleDim(mask, j);
      double a = 0.0;
      for (Eigen::Index p = first; p < last; ++p) a += delta(xj, p, mj, angle);
      part(j, t) = a;
    }
  });
  Eigen::VectorXd dmean = Eigen::VectorXd::Zero(d);
  for (long t = 0; t < tasks; ++t) dmean += part.col(t).head(d);
  dmean *= inv_n;
  // Lower triangle, one pair of columns at a time (a loop over points that vectorises).
  Eigen::MatrixXd cov_part(d * d, tasks);
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    for (Eigen::Index b = 0; b < d; ++b)
      for (Eigen::Index a = b; a < d; ++a) {
        const double *xa = xt.col(a).data(), *xb = xt.col(b).data();
        const double ma = info->mean[a], mb = info->mean[b], da = dmean[a], db = dmean[b];
        const bool angle_a = IsAngleDim(mask, a), angle_b = IsAngleDim(mask, b);
        double acc = 0.0;
        for (Eigen::Index p = first; p < last; ++p)
          acc += (delta(xa, p, ma, angle_a) - da) * (delta(xb, p, mb, angle_b) - db);
        cov_part(b * d + a, t) = acc;
      }
  });
  info->cov = Eigen::MatrixXd::Zero(d, d);
  for (long t = 0; t < tasks; ++t)
    for (Eigen::Index b = 0; b < d; ++b)
      for (Eigen::Index a = b; a < d; ++a) info->cov(a, b) += cov_part(b * d + a, t);
  info->cov *= inv_n;
  info->cov = info->cov.selfadjointView<Eigen::Lower>();
  info->reg = (o.reg_relative * info->cov.diagonal().array()).max(o.reg_floor).matrix();
}

// One E-step over xt (points as rows, N x D): mean log-likelihood per point; statistics and
// per-point log-likelihood out.
// Points per task of the general E-step on several threads (two of its blocks). The split
// depends on N only and the per-task statistics are added in task order, so the result is the
// same bits for any thread count.
constexpr Eigen::Index kTaskPoints = 2 * detail::kBlockPoints;

// One E-step over xt (points as rows, N x D) on up to `threads` threads: mean log-likelihood per
// point; statistics and per-point log-likelihood out.
double EStep(const Mixture& m, const Eigen::MatrixXd& xt, int threads, Stats* st, Eigen::VectorXd* point_ll) {
  if (detail::EStep2dApplies(m)) {  // the fused kernel of estep_2d.cpp: same quantities
    point_ll->resize(xt.rows());
    detail::Moments2d mo;
    const double ll = detail::EStep2d(m, xt.col(0).data(), xt.col(1).data(), xt.rows(), point_ll->data(), &mo,
                                      detail::Simd::kAuto, threads);
    st->Reset(2, m.k());
    for (int i = 0; i < m.k(); ++i) {
      st->nk[i] = mo.n[i];
      st->s1(0, i) = mo.m0[i];
      st->s1(1, i) = mo.m1[i];
      st->s2[i] << mo.s00[i], mo.s01[i], mo.s01[i], mo.s11[i];
    }
    return ll;
  }
  detail::PreparedMixture p;
  detail::Prepare(m, &p);
  const Eigen::Index n = xt.rows();
  const int d = m.dim;
  point_ll->resize(n);
  const long tasks = static_cast<long>((n + kTaskPoints - 1) / kTaskPoints);
  std::vector<Stats> part(static_cast<size_t>(tasks));
  detail::ParallelFor(threads, tasks, [&](long task) {
    Stats& ts = part[static_cast<size_t>(task)];
    ts.Reset(d, m.k());
    Eigen::MatrixXd terms;
    std::vector<Eigen::MatrixXd> deltas;
    Eigen::VectorXd lse;
    Eigen::ArrayXd rsum, r, weighted;
    const Eigen::Index task_end = std::min<Eigen::Index>(n, (task + 1) * kTaskPoints);
    for (Eigen::Index start = task * kTaskPoints; start < task_end; start += detail::kBlockPoints) {
      const Eigen::Index b = std::min<Eigen::Index>(detail::kBlockPoints, task_end - start);
      detail::LogTerms(m, p, xt.middleRows(start, b), &terms, &deltas);
      detail::LogSumExpToResponsibilities(&terms, &lse);  // terms now hold responsibilities
      point_ll->segment(start, b) = lse;
      for (int i = 0; i < p.k; ++i) {
        const Eigen::MatrixXd& delta = deltas[i];
        const Eigen::Index first = static_cast<Eigen::Index>(i) * p.images;
        rsum = terms.col(first).array();
        for (int j = 1; j < p.images; ++j) {  // image 0 has a zero offset; the others add o_j terms
          r = terms.col(first + j).array();
          rsum += r;
          const double sr = r.sum();
          if (sr == 0.0) continue;
          const Eigen::VectorXd o = p.offsets.col(j);
          Eigen::VectorXd drj(d);
          for (int c = 0; c < d; ++c) drj[c] = (delta.col(c).array() * r).sum();
          ts.s1.col(i) += o * sr;
          ts.s2[i] += o * drj.transpose() + drj * o.transpose() + (o * o.transpose()) * sr;
        }
        ts.nk[i] += rsum.sum();
        for (int c = 0; c < d; ++c) {
          weighted = delta.col(c).array() * rsum;
          ts.s1(c, i) += weighted.sum();
          for (int c2 = 0; c2 <= c; ++c2) {
            const double v = (weighted * delta.col(c2).array()).sum();
            ts.s2[i](c, c2) += v;
            if (c2 != c) ts.s2[i](c2, c) += v;
          }
        }
      }
    }
  });
  st->Reset(d, m.k());
  for (const Stats& ts : part) {
    st->nk += ts.nk;
    st->s1 += ts.s1;
    for (int i = 0; i < m.k(); ++i) st->s2[i] += ts.s2[i];
  }
  return point_ll->mean();
}

// The statistics of k-means' hard assignment (each point's responsibility 1 for its cluster),
// taken around the centres, and each point's score (minus its squared distance to its centre),
// on up to `threads` threads: sums per task of points, added in task order, so the same bits
// for any thread count.
void HardAssignmentStats(const Eigen::MatrixXd& xt, uint32_t mask, const KMeansResult& km, int threads, Stats* st,
                         Eigen::VectorXd* score) {
  const Eigen::Index n = xt.rows();
  const int d = static_cast<int>(xt.cols()), k = static_cast<int>(km.centers.cols());
  const long tasks = detail::PassTasks(static_cast<long>(n));
  score->resize(n);
  // Per task: n_k, then s1 (D per component), then s2 (D x D per component, column-major).
  const size_t stride = static_cast<size_t>(1 + d + d * d);
  std::vector<double> part(static_cast<size_t>(tasks) * k * stride, 0.0);
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    double* ts = part.data() + static_cast<size_t>(t) * k * stride;
    if (d == 2) {
      // Points in spatial order come in runs of one label: a run's sums stay in registers and
      // are added to its cluster's slot when the label changes (instead of a store and a load
      // of the slot per point, a chain of dependent memory round trips).
      const bool angle0 = IsAngleDim(mask, 0), angle1 = IsAngleDim(mask, 1);
      const double* x0 = xt.col(0).data();
      const double* x1 = xt.col(1).data();
      int run = km.labels[first];
      double r[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // count, s1 (2), s2 (00, 10, 11)
      auto flush = [&]() {
        double* cs = ts + static_cast<size_t>(run) * stride;  // layout: n, s1 0..1, s2 col-major
        cs[0] += r[0];
        cs[1] += r[1];
        cs[2] += r[2];
        cs[3] += r[3];
        cs[4] += r[4];
        cs[5] += r[4];
        cs[6] += r[5];
        for (double& v : r) v = 0.0;
      };
      for (Eigen::Index c = first; c < last; ++c) {
        const int l = km.labels[c];
        if (l != run) {
          flush();
          run = l;
        }
        double e0 = x0[c] - km.centers(0, l), e1 = x1[c] - km.centers(1, l);
        if (angle0) e0 = gmmrrt_wrap_angle(e0);
        if (angle1) e1 = gmmrrt_wrap_angle(e1);
        r[0] += 1.0;
        r[1] += e0;
        r[2] += e1;
        r[3] += e0 * e0;
        r[4] += e1 * e0;
        r[5] += e1 * e1;
        (*score)[c] = -(e0 * e0 + e1 * e1);
      }
      flush();
      return;
    }
    double delta[GMMRRT_MAX_DIM];
    for (Eigen::Index c = first; c < last; ++c) {
      const int l = km.labels[c];
      double norm2 = 0.0;
      for (int j = 0; j < d; ++j) {
        const double v = xt(c, j) - km.centers(j, l);
        delta[j] = IsAngleDim(mask, j) ? gmmrrt_wrap_angle(v) : v;
        norm2 += delta[j] * delta[j];
      }
      double* cs = ts + static_cast<size_t>(l) * stride;
      cs[0] += 1.0;
      for (int b = 0; b < d; ++b) {
        cs[1 + b] += delta[b];
        for (int a = 0; a < d; ++a) cs[1 + d + b * d + a] += delta[a] * delta[b];
      }
      (*score)[c] = -norm2;
    }
  });
  st->Reset(d, k);
  for (long t = 0; t < tasks; ++t)
    for (int i = 0; i < k; ++i) {
      const double* cs = part.data() + (static_cast<size_t>(t) * k + i) * stride;
      st->nk[i] += cs[0];
      for (int b = 0; b < d; ++b) {
        st->s1(b, i) += cs[1 + b];
        for (int a = 0; a < d; ++a) st->s2[i](a, b) += cs[1 + d + b * d + a];
      }
    }
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
  const Eigen::MatrixXd* xt = nullptr;  // points as rows (N x D)
  const detail::PointOrder* original_index = nullptr;  // row -> column of the caller's points
  uint32_t mask = 0;
  const FitOptions* options = nullptr;
  DataInfo info;
  Eigen::MatrixXd reseed_chol;  // Cholesky of the data covariance shrunk by K^(-2/D)
  int max_reseeds = 0;
  int threads = 1;  // for the E-step sums
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
  const double n = static_cast<double>(s.xt->rows());
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
      ok = (cov.diagonal().array() > s.info.reg.array()).all();
      cov.diagonal() += s.info.reg;
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
        mu.push_back(s.xt->row(p).transpose());
        chol.push_back(s.reseed_chol);
        msg << ": re-seeded at point " << (s.original_index ? (*s.original_index)[p] : p);
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

// One candidate fit: the mixture and where its EM stands. pending: the last E-step's statistics
// (stats, score) have not been used by an M-step yet.
struct EmRun {
  int restart = 0;
  double kmeans_inertia = 0.0;
  Mixture m;
  Stats stats;
  Eigen::VectorXd score;
  std::vector<double> ll;
  double previous = 0.0;
  bool last_changed = true;
  bool pending = false;
  bool converged = false;
  bool kept = false;  // the candidate chosen to run to convergence: progress after every step
  int iterations = 0;
  int ll_refused = 0;  // SQUAREM extrapolations refused (their E-step was spent)
};

// Runs EM steps until converged, until the E-step index reaches `until`, or max_iterations.
// Leaves the run E-stepped: run->m is the mixture whose mean log-likelihood is run->ll.back().
void AdvancePlain(const FitState& s, EmRun* run, int until) {
  const FitOptions& o = *s.options;
  while (!run->converged) {
    if (run->pending) {
      run->previous = run->ll.back();
      const Eigen::MatrixXd old_means = run->m.means;
      run->last_changed = MStep(s, run->stats, old_means, run->score, run->iterations + 1, &run->m);
      ++run->iterations;
      run->pending = false;
      if (run->m.k() == 0) return;
    }
    const int t = static_cast<int>(run->ll.size());
    const double ll = EStep(run->m, *s.xt, s.threads, &run->stats, &run->score);
    run->ll.push_back(ll);
    run->pending = true;
    if (o.progress && (o.restarts == 1 || run->kept)) o.progress(run->restart, t, ll);
    if (t >= 1 && !run->last_changed && std::fabs(ll - run->previous) < o.tolerance) {
      run->converged = true;
      run->pending = false;
      return;
    }
    if (t >= o.max_iterations || t >= until) return;
  }
}

// SQUAREM's growth factor of the step bound after a full-length step, and the bound's start
// (step.max0 = 1, mstep = 4 in Varadhan and Roland 2008): the first extrapolation is a plain
// double EM step, longer ones are earned.
constexpr double kSquaremStepGrowth = 4.0;

// The same contract as AdvancePlain, with SQUAREM (squarem.hpp). A cycle from an E-stepped
// mixture theta0: an EM step to theta1 (E-stepped: the convergence test |LL1 - LL0| < tolerance
// is that of plain EM), the M-step to theta2, the extrapolation theta', and its E-step. theta' is
// kept when its log-likelihood is at least theta1's, so the recorded log-likelihood never
// decreases; otherwise theta2 is E-stepped and kept (a plain EM step) and the step bound shrinks.
// Its M-step is the next cycle's first step (SQUAREM's stabilising step). A re-seeded or dropped
// component, or an extrapolation that fails (squarem.hpp), gives a plain EM step instead.
// Every E-step counts as an iteration, so max_iterations bounds the work as in plain EM.
void AdvanceSquarem(const FitState& s, EmRun* run, int until) {
  const FitOptions& o = *s.options;
  double step_max = 1.0;
  auto e_step = [&]() {
    const int t = static_cast<int>(run->ll.size());
    const double ll = EStep(run->m, *s.xt, s.threads, &run->stats, &run->score);
    run->ll.push_back(ll);
    run->pending = true;
    if (o.progress && (o.restarts == 1 || run->kept)) o.progress(run->restart, t, ll);
    return t;
  };
  // E-steps of refused extrapolations are not in run->ll but are work: they count towards the
  // cap (all of the run's, from earlier calls too) and towards `until` (this call's).
  int spent = 0;
  auto at_cap = [&](int t) { return t + run->ll_refused >= o.max_iterations || t + spent >= until; };
  auto m_step = [&](Mixture* m) {  // from the pending statistics of run->m
    const bool changed = MStep(s, run->stats, run->m.means, run->score, run->iterations + 1, m);
    ++run->iterations;
    run->pending = false;
    return changed;
  };
  if (!run->pending) {
    if (at_cap(e_step())) return;
  }
  for (;;) {
    // theta0 = run->m, E-stepped. EM step to theta1.
    const Mixture m0 = run->m;
    const double ll0 = run->ll.back();
    const bool changed1 = m_step(&run->m);
    if (run->m.k() == 0) return;
    int t = e_step();
    if (!changed1 && std::fabs(run->ll.back() - ll0) < o.tolerance) {
      run->converged = true;
      run->pending = false;
      return;
    }
    if (at_cap(t) || changed1) {
      if (at_cap(t)) return;
      continue;
    }
    // theta2 = F(theta1) without its E-step yet.
    const Mixture m1 = run->m;
    const double ll1 = run->ll.back();
    Mixture m2 = m1;  // MStep takes D and the angle mask from its output
    const bool changed2 = MStep(s, run->stats, m1.means, run->score, run->iterations + 1, &m2);
    Mixture mx;
    double step = 1.0, wanted = 1.0;
    const bool extrapolated =
        !changed2 && detail::SquaremExtrapolate(m0, m1, m2, step_max, s.info.reg, &mx, &step, &wanted) &&
        step > 1.0;
    if (!extrapolated && !changed2 && wanted > step_max) step_max *= kSquaremStepGrowth;  // bound was binding
    if (extrapolated) {
      // Keep the E-step of theta1 in case theta' is refused.
      const Stats stats1 = run->stats;
      const Eigen::VectorXd score1 = run->score;
      run->m = std::move(mx);
      ++run->iterations;
      const double ll_before = ll1;
      t = static_cast<int>(run->ll.size());
      const double llx = EStep(run->m, *s.xt, s.threads, &run->stats, &run->score);
      if (std::isfinite(llx) && llx >= ll_before) {
        run->ll.push_back(llx);
        run->pending = true;
        if (o.progress && (o.restarts == 1 || run->kept)) o.progress(run->restart, t, llx);
        if (step >= step_max) step_max *= kSquaremStepGrowth;
        if (at_cap(t)) return;
        continue;
      }
      // Refused: that E-step is spent (it counts), theta2 is next.
      ++run->ll_refused;
      ++spent;
      step_max = std::max(1.0, step_max / kSquaremStepGrowth);
      run->stats = stats1;
      run->score = score1;
      if (at_cap(t)) {  // stop at theta1, whose statistics are restored
        run->m = m1;
        run->pending = true;
        return;
      }
      ++run->iterations;  // the E-step of theta2 below
    } else {
      ++run->iterations;
    }
    run->m = std::move(m2);
    run->pending = false;
    if (run->m.k() == 0) return;
    t = e_step();
    if (!changed2 && std::fabs(run->ll.back() - ll1) < o.tolerance) {
      run->converged = true;
      run->pending = false;
      return;
    }
    if (at_cap(t)) return;
  }
}

// Runs the fit's EM variant (FitOptions::accelerate).
void Advance(const FitState& s, EmRun* run, int until) {
  if (s.options->accelerate)
    AdvanceSquarem(s, run, until);
  else
    AdvancePlain(s, run, until);
}

// The screening sample: m of the n rows of xt, drawn by a partial Fisher-Yates shuffle with our
// own draw (Uniform01), kept in the data's order (the chosen rows in ascending row number, by
// marking them and reading the marks in order: the same sample as a sort of the chosen numbers
// gives, in linear time). Only the m swaps are serial; filling the numbers, clearing the marks
// and gathering the marked rows run on the fit's threads, in pass tasks (parallel.hpp), and
// the scratch is made uninitialised so that its first-write page faults are taken there too
// (this was serial time in every default fit on large data: docs/learner.md).
void DrawSample(const Eigen::MatrixXd& xt, Eigen::Index m, int threads, std::mt19937_64* rng, Eigen::MatrixXd* sample) {
  const Eigen::Index n = xt.rows();
  const long tasks = detail::PassTasks(static_cast<long>(n));
  std::unique_ptr<Eigen::Index[]> number(new Eigen::Index[static_cast<size_t>(n)]);
  std::unique_ptr<unsigned char[]> chosen(new unsigned char[static_cast<size_t>(n)]);
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    for (Eigen::Index p = first; p < last; ++p) number[p] = p;
    std::fill(chosen.get() + first, chosen.get() + last, static_cast<unsigned char>(0));
  });
  for (Eigen::Index i = 0; i < m; ++i)
    std::swap(number[i], number[i + static_cast<Eigen::Index>(Uniform01(rng) * static_cast<double>(n - i)) % (n - i)]);
  for (Eigen::Index i = 0; i < m; ++i) chosen[number[i]] = 1;
  // Each task's marked rows go after those of the tasks before it.
  std::vector<Eigen::Index> row_of_task(static_cast<size_t>(tasks) + 1, 0);
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    row_of_task[static_cast<size_t>(t) + 1] = std::count(chosen.get() + first, chosen.get() + last, 1);
  });
  for (long t = 0; t < tasks; ++t) row_of_task[static_cast<size_t>(t) + 1] += row_of_task[static_cast<size_t>(t)];
  sample->resize(m, xt.cols());
  detail::ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    Eigen::Index row = row_of_task[static_cast<size_t>(t)];
    for (Eigen::Index p = first; p < last; ++p)
      if (chosen[p] == 1) sample->row(row++) = xt.row(p);  // as counted above
  });
}

}  // namespace

int DefaultThreadCount() { return detail::AvailableCores(); }

Status FitMixture(const Eigen::MatrixXd& points, uint32_t angle_mask, const FitOptions& options,
                  Mixture* mixture, FitSummary* summary) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
  Clock::time_point stage = Clock::now();
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
  // The checks and copies below run on the fit's threads, in tasks of points (parallel.hpp).
  const int threads = options.threads > 0 ? options.threads : detail::AvailableCores();
  const long tasks = detail::PassTasks(static_cast<long>(n));
  {
    // A value must be finite, and small enough that squared distances between points stay
    // finite: beyond kMaxMagnitude a square overflows to inf, and k-means' nearest centre and
    // the data's variance are then undefined (one point at 1e200 among ordinary ones crashed
    // the hard assignment).
    constexpr double kMaxMagnitude = 1e150;
    std::vector<Eigen::Index> first_bad(static_cast<size_t>(tasks), -1);  // c D + j, or -1
    detail::ParallelFor(threads, tasks, [&](long t) {
      Eigen::Index first, last;
      PassRange(t, n, &first, &last);
      for (Eigen::Index c = first; c < last; ++c)
        for (int j = 0; j < d; ++j)
          if (!(std::fabs(points(j, c)) <= kMaxMagnitude)) {  // NaN fails the comparison too
            first_bad[static_cast<size_t>(t)] = c * d + j;
            return;
          }
    });
    for (Eigen::Index bad : first_bad) {  // the first bad value in the points' order
      if (bad < 0) continue;
      const double v = points(bad % d, bad / d);
      const std::string where = "point " + std::to_string(bad / d) + ", dimension " + std::to_string(bad % d);
      if (!std::isfinite(v)) return Status::Error(StatusCode::kBadInput, where + " is not finite");
      char value[32];
      std::snprintf(value, sizeof value, "%.9g", v);
      return Status::Error(StatusCode::kBadInput, where + " is " + value +
                                                      ": beyond 1e150 squared distances overflow; rescale the data");
    }
  }

  *summary = FitSummary();
  summary->n_points = n;
  summary->dim = d;
  summary->k_requested = options.k;
  // Points as rows (see component_terms.hpp), angle columns wrapped (AsFitValue). For the fused
  // 2-D E-step they are put in spatial order (spatial_order.hpp): its lanes then hold nearby
  // points and skip far components together. The order is a function of the points only, so the
  // fit stays deterministic. The 2-D rows are gathered in that order straight from the input:
  // one fresh N x D buffer, not a copy and then a sorted copy (each fresh 4 KiB page costs a
  // page fault on its first write: 780 fewer on 200 000 points, docs/learner.md).
  detail::PointOrder order;
  Eigen::MatrixXd xt(n, d);
  if (detail::EStep2dApplies(d, angle_mask)) {
    order = detail::SpatialOrder2d(points, angle_mask, threads);
    detail::ParallelFor(threads, tasks, [&](long t) {
      Eigen::Index first, last;
      PassRange(t, n, &first, &last);
      double* out0 = xt.col(0).data();
      double* out1 = xt.col(1).data();
      for (Eigen::Index p = first; p < last; ++p) {
        out0[p] = AsFitValue(angle_mask, 0, points(0, order[p]));
        out1[p] = AsFitValue(angle_mask, 1, points(1, order[p]));
      }
    });
  } else {
    detail::ParallelFor(threads, tasks, [&](long t) {
      Eigen::Index first, last;
      PassRange(t, n, &first, &last);
      for (int j = 0; j < d; ++j) {
        double* out = xt.col(j).data();
        for (Eigen::Index c = first; c < last; ++c) out[c] = AsFitValue(angle_mask, j, points(j, c));
      }
    });
  }

  FitState s;
  s.xt = &xt;
  s.original_index = order.size() == 0 ? nullptr : &order;
  s.mask = angle_mask;
  s.options = &options;
  s.summary = summary;
  s.max_reseeds = options.max_reseeds < 0 ? 3 * options.k : options.max_reseeds;
  s.threads = threads;
  summary->threads = s.threads;
  ComputeDataInfo(xt, angle_mask, options, threads, &s.info);
  for (int j = 0; j < d; ++j)
    if (!(s.info.cov(j, j) > options.reg_floor))
      return Status::Error(StatusCode::kBadInput,
                           "dimension " + std::to_string(j) + " is (nearly) constant: variance " +
                               std::to_string(s.info.cov(j, j)) + " <= reg_floor");
  {
    Eigen::MatrixXd shrunk = s.info.cov * std::pow(static_cast<double>(options.k), -2.0 / d);
    shrunk.diagonal() += s.info.reg;
    Eigen::LLT<Eigen::MatrixXd> llt(shrunk);
    if (llt.info() != Eigen::Success)
      return Status::Error(StatusCode::kBadInput, "the data covariance is not positive definite");
    s.reseed_chol = llt.matrixL().toDenseMatrix();
  }

  // Candidates: each restart is k-means++ + Lloyd, one M-step from the hard assignment, then
  // screen_iterations EM steps; the best mean log-likelihood continues to convergence. On large
  // data they are built on a seeded subsample (screen_xt) and the winner moves to all points.
  std::mt19937_64 rng(options.seed);
  Eigen::MatrixXd sample_xt;
  FitState screen = s;
  screen.original_index = nullptr;  // point numbers in messages: of the sample
  if (options.screen_points > 0 && n > options.screen_points) {
    const Eigen::Index m_pts = static_cast<Eigen::Index>(std::max<int64_t>(options.screen_points, needed));
    DrawSample(xt, m_pts, threads, &rng, &sample_xt);
    screen.xt = &sample_xt;
  }
  const Eigen::MatrixXd& screen_xt = *screen.xt;
  const Eigen::Index n_screen = screen_xt.rows();
  // On a sample, the candidates' steps leave at least a quarter of the iteration cap (at least
  // one step) to the kept candidate on all points: a mixture fitted to the sample alone fits its
  // noise too, about p / (2 n_sample) nats per point below the fit to all points (0.003 for
  // K = 19 in 2-D on 20 000 points), which steps on all points remove. With the default cap
  // (500) this leaves screen_iterations as it is.
  int screen_until = options.screen_iterations;
  if (screen.xt != s.xt)
    screen_until = std::min(screen_until, std::max(0, options.max_iterations - std::max(1, options.max_iterations / 4)));
  summary->screened_on = n_screen;
  KMeansOptions ko;
  ko.k = options.k;
  ko.restarts = 1;
  ko.max_iterations = options.kmeans_max_iterations;
  std::vector<EmRun> runs(options.restarts + options.extra_starts.size());
  summary->prepare_seconds = seconds_since(stage);
  stage = Clock::now();
  // The candidates are independent, so with several threads they run side by side, one thread
  // each (the screening's E-steps on 20 000 points are too short to split well, and k-means is
  // serial): candidate r's k-means draws from its own copy of rng advanced past the draws of
  // candidates 0..r-1 (KMeansRandomDraws), so each gets the centres it would get in order and
  // the fit is the same bits for any thread count. What a candidate reports (warnings, re-seeds,
  // progress) is kept apart and passed on in candidate order afterwards; each candidate has the
  // whole re-seed budget (max_reseeds); the fit to convergence has what all of them left of it.
  const bool side_by_side = s.threads > 1 && options.restarts > 1;
  const uint64_t draws = KMeansRandomDraws(ko);
  std::vector<FitSummary> reports(options.restarts);
  std::vector<Status> failures(options.restarts, Status::Ok());
  FitOptions quiet = options;
  quiet.warn = nullptr;  // passed on below
  if (options.restarts > 1) quiet.progress = nullptr;  // one candidate: progress as it runs
  detail::ParallelFor(side_by_side ? s.threads : 1, options.restarts, [&](long r) {
    FitState cs = screen;
    cs.summary = &reports[r];
    cs.options = &quiet;
    cs.threads = side_by_side ? 1 : s.threads;
    std::mt19937_64 crng = rng;
    crng.discard(draws * static_cast<uint64_t>(r));
    KMeansResult km;
    KMeansOptions cko = ko;
    cko.threads = cs.threads;
    Status st = KMeans(screen_xt, angle_mask, cko, &crng, &km);
    if (!st.ok()) {
      failures[r] = st;
      return;
    }
    EmRun& run = runs[r];
    run.restart = static_cast<int>(r);
    run.kmeans_inertia = km.inertia;
    run.m.dim = d;
    run.m.angle_mask = angle_mask;
    HardAssignmentStats(screen_xt, angle_mask, km, cs.threads, &run.stats, &run.score);
    MStep(cs, run.stats, km.centers, run.score, 0, &run.m);
    if (run.m.k() > 0) Advance(cs, &run, screen_until);
  });
  rng.discard(draws * static_cast<uint64_t>(options.restarts));
  int best = -1;
  for (int r = 0; r < options.restarts; ++r) {
    if (!failures[r].ok()) return failures[r];
    const FitSummary& rep = reports[r];
    for (const std::string& w : rep.warnings) s.Warn(w);
    summary->reseed_iterations.insert(summary->reseed_iterations.end(), rep.reseed_iterations.begin(),
                                      rep.reseed_iterations.end());
    summary->reseeds += rep.reseeds;
    summary->dropped += rep.dropped;
    const EmRun& run = runs[r];
    if (run.m.k() > 0 && (best < 0 || run.ll.back() > runs[best].ll.back())) best = r;
    if (options.restarts > 1 && options.progress && run.m.k() > 0)
      options.progress(r, static_cast<int>(run.ll.size()) - 1, run.ll.back());
  }
  for (size_t e = 0; e < options.extra_starts.size(); ++e) {
    const Mixture& start = options.extra_starts[e];
    if (start.dim != d || start.angle_mask != angle_mask)
      return Status::Error(StatusCode::kInvalidArgument,
                           "extra start " + std::to_string(e) + " has another dimension or angle mask");
    const int r = options.restarts + static_cast<int>(e);
    EmRun& run = runs[r];
    run.restart = r;
    run.m = start;
    WrapAngleRows(angle_mask, &run.m.means);
    Advance(screen, &run, screen_until);
    if (run.m.k() > 0 && (best < 0 || run.ll.back() > runs[best].ll.back())) best = r;
    if (options.progress && run.m.k() > 0) options.progress(r, static_cast<int>(run.ll.size()) - 1, run.ll.back());
  }
  if (best < 0) return Status::Error(StatusCode::kNumericalFailure, "every component degenerate in every restart");
  summary->candidates_seconds = seconds_since(stage);
  stage = Clock::now();
  EmRun& run = runs[best];
  run.kept = true;
  if (screen.xt != s.xt) {
    // The winner continues on all points from its screened mixture (a fresh E-step there).
    EmRun full;
    full.restart = run.restart;
    full.kmeans_inertia = run.kmeans_inertia;
    full.m = std::move(run.m);
    full.iterations = run.iterations;
    full.kept = true;
    run = std::move(full);
    Advance(s, &run, std::max(0, options.max_iterations - run.iterations));
  } else if (!run.converged &&
             static_cast<int>(run.ll.size()) - 1 + run.ll_refused < options.max_iterations) {
    // The screening's E-steps count towards the cap (the log-likelihood history goes on from
    // them): a screening that reached the cap is the fit (Advance would add one more step).
    Advance(s, &run, options.max_iterations);
  }
  summary->converge_seconds = seconds_since(stage);
  if (run.m.k() == 0)
    return Status::Error(StatusCode::kNumericalFailure, "every component degenerate (all dropped)");
  Mixture m = std::move(run.m);
  summary->log_likelihood = run.ll;
  summary->iterations = run.iterations;
  summary->extrapolations_refused = run.ll_refused;
  summary->converged = run.converged;
  summary->kmeans_inertia = run.kmeans_inertia;
  summary->restart_kept = best;
  summary->k_final = m.k();
  summary->final_mean_log_likelihood = summary->log_likelihood.back();
  summary->bic = Bic(summary->final_mean_log_likelihood, n, m.k(), d);
  Status st = ValidateMixture(m);
  if (!st.ok()) return Status::Error(StatusCode::kNumericalFailure, "fit produced an invalid mixture: " + st.message);
  *mixture = std::move(m);
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
