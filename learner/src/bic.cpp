// bic.cpp - BIC sweep over K for `--k auto` (see bic.hpp; paper Sect. 5.1 chose k = 19 by hand).
#include "gmmrrt_learner/bic.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>

#include "split_components.hpp"

namespace gmmrrt {
namespace learn {

Status SweepBic(const Eigen::MatrixXd& points, uint32_t angle_mask, const FitOptions& options,
                int k_min, int k_max, BicSweepResult* result,
                const std::function<void(const BicRow&)>& on_row, int stop_after_rises, int split_starts,
                int fresh_starts) {
  if (k_min < 1 || k_max < k_min || k_max > GMMRRT_MAX_K)
    return Status::Error(StatusCode::kInvalidArgument,
                         "K range " + std::to_string(k_min) + ".." + std::to_string(k_max) +
                             " is not within 1.." + std::to_string(GMMRRT_MAX_K));
  if (split_starts < 0)
    return Status::Error(StatusCode::kInvalidArgument, "split_starts must be >= 0");
  if (fresh_starts < 1) return Status::Error(StatusCode::kInvalidArgument, "fresh_starts must be >= 1");
  if (stop_after_rises < 0)
    return Status::Error(StatusCode::kInvalidArgument, "stop_after_rises must be >= 0 (0: whole range)");
  *result = BicSweepResult();
  double best_bic = std::numeric_limits<double>::infinity();
  int rises = 0;  // consecutive K with a BIC above best_bic
  Mixture previous;  // the fit of K - 1, whose splits are extra starts for K
  for (int k = k_min; k <= k_max; ++k) {
    FitOptions o = options;
    o.k = k;
    if (split_starts > 0 && previous.k() == k - 1)
      for (Mixture& start : detail::SplitCandidates(previous, split_starts)) o.extra_starts.push_back(std::move(start));
    // With warm starts from the K - 1 optimum, the k-means++ candidates only guard against a
    // basin the chain of splits carries along: fresh_starts of them are enough (bic.hpp).
    if (!o.extra_starts.empty()) o.restarts = std::min(o.restarts, fresh_starts);
    Mixture m;
    FitSummary s;
    Status st = FitMixture(points, angle_mask, o, &m, &s);
    if (st.code == StatusCode::kNotEnoughData && k > k_min) {
      result->note = "sweep stopped at K = " + std::to_string(k - 1) + ": " + st.message;
      break;
    }
    if (!st.ok()) return st;
    BicRow row;
    row.k = k;
    row.k_final = s.k_final;
    row.mean_log_likelihood = s.final_mean_log_likelihood;
    row.bic = s.bic;
    row.iterations = s.iterations;
    row.converged = s.converged;
    row.fresh_starts = o.restarts;
    row.split_starts = static_cast<int>(o.extra_starts.size());
    result->rows.push_back(row);
    previous = m;
    if (on_row) on_row(row);
    if (s.bic < best_bic) {
      best_bic = s.bic;
      result->best_k = k;
      result->best = m;
      result->best_summary = s;
      rises = 0;
    } else if (stop_after_rises > 0 && ++rises >= stop_after_rises && k < k_max) {
      result->note = "sweep stopped at K = " + std::to_string(k) + ": BIC above its minimum (K = " +
                     std::to_string(result->best_k) + ") for " + std::to_string(rises) +
                     " K in a row (--bic-patience)";
      break;
    }
  }
  return Status::Ok();
}

std::string FormatBicTable(const BicSweepResult& result) {
  std::ostringstream o;
  char line[160];
  std::snprintf(line, sizeof line, "%4s %7s %16s %18s %6s %s\n", "K", "K_final", "mean_loglik", "BIC",
                "iters", "converged");
  o << line;
  for (const BicRow& r : result.rows) {
    std::snprintf(line, sizeof line, "%4d %7d %16.6f %18.3f %6d %s%s\n", r.k, r.k_final,
                  r.mean_log_likelihood, r.bic, r.iterations, r.converged ? "yes" : "no",
                  r.k == result.best_k ? "  *" : "");
    o << line;
  }
  if (!result.note.empty()) o << "note: " << result.note << "\n";
  return o.str();
}

}  // namespace learn
}  // namespace gmmrrt
