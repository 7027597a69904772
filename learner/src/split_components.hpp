// split_components.hpp (private to learner/src) - starts for a K + 1 component fit made from a
// fitted K component mixture by splitting one component in two (the split move of split-and-
// merge EM, Ueda et al. 2000, Neural Computation 12(9)). The BIC sweep screens them beside
// fresh k-means++ starts: on overlapping data a fresh K + 1 fit often lands in a worse optimum
// than the K fit plus one well-placed component, and then BIC chooses too few or too many.
#ifndef GMMRRT_LEARNER_SPLIT_COMPONENTS_HPP
#define GMMRRT_LEARNER_SPLIT_COMPONENTS_HPP

#include <vector>

#include "gmmrrt_learner/mixture.hpp"

namespace gmmrrt {
namespace learn {
namespace detail {

// Up to max_candidates mixtures of m.k() + 1 components (never beyond GMMRRT_MAX_K): in each,
// one component of m is replaced by two. The components split are those of largest
// w sqrt(det Sigma) (most mass spread over most volume: where two overlapping generators fitted
// as one look like), largest first. Component j ~ (w, mu, Sigma) with Sigma's largest eigenvalue
// lambda along the unit vector u becomes two of weight w / 2 at mu +- 0.8 sqrt(lambda) u with
// Sigma - 0.64 lambda u u^T: the halves of a Gaussian cut through its mean perpendicular to u
// have their means at +- sqrt(2 / pi) sigma ~ 0.8 sigma and variance (1 - 2 / pi) ~ 0.36 lambda
// along u. Angle dimensions of the new means are wrapped. m must be valid.
std::vector<Mixture> SplitCandidates(const Mixture& m, int max_candidates);

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt

#endif  // GMMRRT_LEARNER_SPLIT_COMPONENTS_HPP
