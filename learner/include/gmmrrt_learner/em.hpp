// em.hpp - fitting a Gaussian mixture (paper Sect. 3, eq. 1) by expectation-maximisation in log
// space, seeded by k-means++ (kmeans.hpp), with the seam-safe wrapped normal for angle
// dimensions (gmm.h): the E-step gives responsibilities over component x image n in
// {-1,0,1}^A, the M-step averages the unwrapped copies mu + wrap(f - mu) + 2 pi n and wraps the
// new means back into (-pi, pi].
//
// Numerics: covariances are kept as Cholesky factors L (Sigma = L L^T); the E-step uses
// z = L^-1 (f - mu) (L^-T is the Cholesky factor of the precision) and log-sum-exp over the
// K * 3^A terms. Regularisation adds reg_j = max(reg_relative * data variance of dimension j,
// reg_floor) to diagonal entry j of every covariance: it follows each feature's scale, with an
// absolute floor so that data of tiny scale still gets a positive definite covariance. It is
// kept small (1e-8 relative): with 1e-6 x the mean variance, a thin component of the peer test's
// 8-component data stayed on a likelihood ridge and the fit ended 0.07 nats/point lower.
// D = 2 without angle dimensions takes a fused, vectorised E-step (learner/src/estep_2d.cpp)
// that computes the same quantities.
// Convergence: a plain EM step changes the mean log-likelihood per point by less than
// tolerance, capped by max_iterations steps. EM is accelerated by SQUAREM (squarem.hpp): each
// cycle is one EM step, an extrapolation along the last two EM steps, and a check that the
// extrapolated mixture is at least as likely as the EM iterate (otherwise the plain EM step).
//
// Restarts: `restarts` candidates, each k-means++ + Lloyd, one M-step from the hard labels and
// screen_iterations EM steps, plus any extra_starts given (screen_iterations EM steps each);
// the one with the highest mean log-likelihood runs to convergence.
// On large data (N > screen_points) the candidates are built and screened on a seeded random
// subsample and only the kept one runs on all points: the screening ranks starts, for which a
// sample of 20 000 points is enough, and screening on all points was most of the run time. (On
// the benchmark's 200 000 points, K = 19, seeds 1-10: 20 000-point samples reached a median of
// -4.3884 nats/point, worst -4.3911; 10 000-point samples -4.3897, worst -4.4004, for 0.6x the
// time; docs/learner.md.)
//
// A component is degenerate when its effective point count falls below D + 1, a variance
// collapses onto the regularisation (raw variance <= reg_j) or its Cholesky fails: it is
// re-seeded at the worst-explained point with the data covariance shrunk by K^(-2/D) and weight
// 1/K (warning), and once max_reseeds are spent it is dropped (warning). The fit never aborts
// because of it; convergence is re-armed after either.
// Deterministic: the same points, options and seed give the same mixture bit for bit.
#ifndef GMMRRT_LEARNER_EM_HPP
#define GMMRRT_LEARNER_EM_HPP

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "gmmrrt_learner/mixture.hpp"
#include "gmmrrt_learner/status.hpp"

namespace gmmrrt {
namespace learn {

struct FitOptions {
  int k = 19;                   // components (the paper's choice, Sect. 5.1), 1..GMMRRT_MAX_K
  uint64_t seed = 1;            // seeds k-means++; same seed -> same result
  int restarts = 8;             // candidate starts: k-means++ seeding + Lloyd + screen_iterations
                                // EM steps each; the highest log-likelihood continues (short-EM
                                // selection, Biernacki et al. 2003)
  int screen_iterations = 20;   // EM steps per candidate before choosing (when restarts > 1);
                                // on a sample (screen_points) at most max_iterations minus
                                // max(1, max_iterations / 4), so the kept candidate gets a
                                // quarter of the cap on all points
  int64_t screen_points = 20000;  // when N is larger, the candidates (k-means++, Lloyd and the
                                // screening steps) run on this many points drawn without
                                // replacement (seeded), and only the kept candidate runs on all
                                // N points; 0 screens on all points
  int kmeans_max_iterations = 100;
  int max_iterations = 500;     // EM M-steps at most
  double tolerance = 1e-6;      // stop when |delta mean log-likelihood per point| < this [nats]
  double reg_relative = 1e-8;   // regularisation relative to each dimension's data variance
  double reg_floor = 1e-10;     // absolute regularisation floor [unit^2 of each dimension]
  int max_reseeds = -1;         // re-seeds allowed over the fit; -1 means 3 K
  bool accelerate = true;       // SQUAREM (Varadhan and Roland 2008; learner/src/squarem.hpp)
                                // with a monotonicity safeguard; false: plain EM
  int threads = 0;              // E-step threads; 0: the cores this process may use. The
                                // result is the same bits for any value (fixed split, sums
                                // added in a fixed order)
  // Further candidate starts (each with K = k, this D and angle mask, valid), screened like
  // the k-means++ ones after them: the BIC sweep passes splits of the best K - 1 mixture.
  std::vector<Mixture> extra_starts;
  // Progress, may be empty. With restarts > 1: once per candidate after its screening steps,
  // then after each E-step of the kept candidate; with restarts == 1 after each E-step.
  // iteration 0 is the seed mixture; the value is the mean log-likelihood per point.
  std::function<void(int restart, int iteration, double mean_log_likelihood)> progress;
  // Called with each warning (degenerate component re-seeded or dropped); may be empty.
  std::function<void(const std::string& warning)> warn;

  // True when every option is in range; otherwise false with the reason in *error.
  bool IsValid(std::string* error) const;
};

struct FitSummary {
  int64_t n_points = 0;
  int dim = 0;
  int k_requested = 0;
  int k_final = 0;                      // k_requested minus dropped components
  int iterations = 0;                   // kept candidate, screening included: M-steps (plain EM)
                                        // or E-steps after the first (accelerated)
  bool converged = false;               // tolerance reached before max_iterations
  std::vector<double> log_likelihood;   // kept candidate: mean log-likelihood per point after each
                                        // step (0 = seed); with a screening subsample, entry 0 is
                                        // the screened mixture on all points
  int64_t screened_on = 0;              // points the candidates were screened on (N or the sample)
  std::vector<int> reseed_iterations;   // iterations at which a component was re-seeded or dropped
  double final_mean_log_likelihood = 0.0;
  double bic = 0.0;                     // Bic(final mean LL, N, k_final, D)
  double kmeans_inertia = 0.0;           // of the kept candidate's k-means
  int restart_kept = 0;                  // which candidate was kept
  int reseeds = 0;                       // over all candidates
  int dropped = 0;
  int threads = 1;                       // E-step threads used
  int extrapolations_refused = 0;        // SQUAREM steps of the kept candidate that lowered the
                                         // log-likelihood (replaced by a plain EM step)
  // Wall time of the fit's stages (steady clock), to see where a fit's time goes: preparing the
  // data (checks, copies, spatial order, moments, the screening sample), building and screening
  // the candidates (without a sample, the kept one's screening steps are among them), and the
  // kept candidate's further steps on all points. Set on success.
  double prepare_seconds = 0.0;
  double candidates_seconds = 0.0;
  double converge_seconds = 0.0;
  std::vector<std::string> warnings;

  // One line: N, D, K, iterations, convergence, final mean LL, BIC, re-seeds, dropped
  // components, the stages' seconds.
  std::string BriefReport() const;
};

// The E-step threads FitOptions::threads = 0 stands for: the CPUs this process may run on.
int DefaultThreadCount();

// Fits a mixture to the columns of points (D x N, finite; angle rows flagged in angle_mask may
// hold any angle and are wrapped first). On kOk, *mixture is valid (ValidateMixture) and
// *summary describes the run. Errors: kInvalidArgument (options, D, angle mask),
// kNotEnoughData (N < K (D + 1)), kBadInput (non-finite value, or a constant dimension),
// kNumericalFailure (every component dropped).
Status FitMixture(const Eigen::MatrixXd& points, uint32_t angle_mask, const FitOptions& options,
                  Mixture* mixture, FitSummary* summary);

}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_EM_HPP
