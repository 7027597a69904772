// mixture.hpp - a Gaussian mixture in Eigen form (paper eq. 1) and its log-density over many
// points at once, with the seam-safe wrapped normal of gmm.h for angle dimensions:
//
//   log p(f) = logsumexp_i [ log w_i + log sum_{n in {-1,0,1}^A} N(delta_i + 2 pi n; 0, Sigma_i) ]
//   delta_i = f - mu_i with every angle entry wrapped into (-pi, pi] by gmmrrt_wrap_angle(),
//
// which is exactly the convention of the C core (model.h, gmm.h): the same coefficient
// log w_i - D/2 log(2 pi) - sum_j log L_i,jj and the same images. Points are the columns of a
// D x N matrix. Conversion to and from gmmrrt_model_t (model.h) is here too, so the learner
// writes models only through the C encoder.
#ifndef GMMRRT_LEARNER_MIXTURE_HPP
#define GMMRRT_LEARNER_MIXTURE_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <vector>

#include "gmmrrt/model.h"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

struct Mixture {
  int dim = 0;                 // D, 1..GMMRRT_MAX_DIM
  uint32_t angle_mask = 0;     // bit j set: dimension j is a wrapped angle [rad]
  Eigen::VectorXd weights;     // K, positive, summing to 1
  Eigen::MatrixXd means;       // D x K; angle entries in (-pi, pi]
  std::vector<Eigen::MatrixXd> chol;  // K lower-triangular D x D factors, Sigma_i = L L^T

  int k() const { return static_cast<int>(weights.size()); }
};

// Checks sizes, finiteness, weights (positive, |sum - 1| <= 1e-9), positive diagonals of the
// factors and the angle mask (no bit at or above D). kBadModel with the reason otherwise.
Status ValidateMixture(const Mixture& m);

// Number of angle dimensions and the 3^A image offsets (D x 3^A, entries 0 or +-2 pi) that the
// wrapped normal sums over. The learner accepts at most kMaxAngleDims angle dimensions.
constexpr int kMaxAngleDims = 4;
Eigen::MatrixXd ImageOffsets(int dim, uint32_t angle_mask);

// Wraps the rows flagged in angle_mask of a D x N matrix into (-pi, pi] in place.
void WrapAngleRows(uint32_t angle_mask, Eigen::MatrixXd* x);

// Per-point log-density log p(x_n) of the columns of points (D x N) into *out (N).
// The mixture must be valid (ValidateMixture). -inf only where every term underflows.
void LogDensity(const Mixture& m, const Eigen::MatrixXd& points, Eigen::VectorXd* out);

// Mean of LogDensity over the points; points must have at least one column.
double MeanLogLikelihood(const Mixture& m, const Eigen::MatrixXd& points);

// Free parameters of a full-covariance mixture: (K - 1) + K D + K D (D + 1) / 2.
int FreeParameters(int k, int dim);

// BIC = -2 N meanLL + FreeParameters ln N (lower is better).
double Bic(double mean_log_likelihood, int64_t n_points, int k, int dim);

// Fills *out (every stored field; derived ones are left for gmmrrt_model_prepare) from m.
// kind/task/homotopy are gmmrrt_model_kind_t / gmmrrt_task_t / gmmrrt_homotopy_t values and
// delta > 0 the default task-cost delta. Checks K and D against limits.h.
Status MixtureToModel(const Mixture& m, int kind, int task, int homotopy, double delta,
                      gmmrrt_model_t* out);

// The inverse: the stored fields of a (decoded) model into a Mixture.
Mixture MixtureFromModel(const gmmrrt_model_t& model);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_MIXTURE_HPP
