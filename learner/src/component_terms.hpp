// component_terms.hpp (private to learner/src) - the per-component, per-image log terms of a
// mixture on a block of points, shared by LogDensity (mixture.cpp) and the E-step (em.cpp) so
// that the density is written once. Paper eq. 1; wrapped normal as in gmm.h.
#ifndef GMMRRT_LEARNER_COMPONENT_TERMS_HPP
#define GMMRRT_LEARNER_COMPONENT_TERMS_HPP

#include <Eigen/Dense>
#include <vector>

#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {
namespace detail {

// Points are processed in blocks of this many columns: the K * 3^A log terms of a block stay
// in cache and memory does not grow with N.
constexpr int kBlockPoints = 4096;

struct PreparedMixture {
  int dim = 0;
  int k = 0;
  int images = 1;                       // M = 3^A
  Eigen::MatrixXd offsets;              // D x M image offsets (0 or +-2 pi on angle rows)
  std::vector<Eigen::MatrixXd> inv_chol;        // K of L_i^-1 (lower triangular)
  std::vector<Eigen::MatrixXd> inv_chol_offsets;// K of L_i^-1 * offsets (D x M)
  Eigen::VectorXd log_coef;             // K of log w_i - D/2 log(2 pi) - sum_j log L_i,jj
};

// The mixture must be valid.
void Prepare(const Mixture& m, PreparedMixture* p);

// Blocks hold points as ROWS (B x D, one contiguous column per dimension): every operation
// below is then a vector operation over B points, which Eigen vectorises; with points as
// columns of a 2 x B matrix the inner loops would run over D = 2 entries only.

// delta = block - mu_i^T with angle columns wrapped into (-pi, pi] (B x D).
void ComponentDelta(const Mixture& m, int i, const Eigen::Ref<const Eigen::MatrixXd>& block,
                    Eigen::MatrixXd* delta);

// terms (B x K*M): column i*M + j is log w_i + log N(delta_i + offset_j; 0, Sigma_i).
// When deltas is non-null it receives the K deltas (B x D each) for reuse by the M-step.
void LogTerms(const Mixture& m, const PreparedMixture& p,
              const Eigen::Ref<const Eigen::MatrixXd>& block, Eigen::MatrixXd* terms,
              std::vector<Eigen::MatrixXd>* deltas = nullptr);

// Row-wise log-sum-exp of terms into *lse (B); -inf rows stay -inf.
void LogSumExpRows(const Eigen::MatrixXd& terms, Eigen::VectorXd* lse);

// The same, and turns terms into the responsibilities exp(terms - lse) in place, with one
// exponential per term (exp is the E-step's cost).
void LogSumExpToResponsibilities(Eigen::MatrixXd* terms, Eigen::VectorXd* lse);

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_COMPONENT_TERMS_HPP
