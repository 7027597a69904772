// kmeans.cpp - greedy k-means++ seeding and Lloyd iterations with restarts, seam-safe for angle
// dimensions (the update moves a center by the mean wrapped difference, then wraps it).
// Seeds EM (em.cpp); see kmeans.hpp. Points are rows (N x D) so distances are vector ops.
//
// Both the seeding and the assignment step skip work by bounds, without changing a result: the
// points are taken in groups of kGroupPoints consecutive ones (EM's callers put them in spatial
// order, so a group's bounding box is small), and a center is left out of a group when the
// smallest squared distance from it to the group's box exceeds what the computed distances it
// would compete with can be (the bound pruning of Moore's mrkd-tree EM, NIPS 1999, and of
// Pelleg and Moore's k-means, KDD 1999, on one level of the ordered points). The bounds take
// the same floating-point operations as the point distances on the box's corners, which are
// monotone in each coordinate, so a skipped center is farther than the kept one from every
// point in the group as computed, not only in exact arithmetic; a relative margin of 1e-12
// covers a compiler that contracts the sums differently. The Lloyd passes after the first also
// carry an upper and a lower distance bound per group across passes (Hamerly's bounds, SDM 2010,
// per group: GroupBounds), moved by how far the centers moved, so a group of one label far from
// every other center keeps its labels without a distance computed. The work runs on up to
// KMeansOptions::threads threads in tasks of a fixed number of groups, and everything that is
// summed is summed per group and then in group order, so any thread count gives the same bits.
#include "gmmrrt_learner/kmeans.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "gmmrrt/features.h"
#include "gmmrrt_learner/mixture.hpp"
#include "angle_dims.hpp"
#include "parallel.hpp"

namespace gmmrrt {
namespace learn {

bool KMeansOptions::IsValid(std::string* error) const {
  if (k < 1) { *error = "k must be >= 1"; return false; }
  if (restarts < 1) { *error = "restarts must be >= 1"; return false; }
  if (max_iterations < 1) { *error = "max_iterations must be >= 1"; return false; }
  if (threads < 1) { *error = "threads must be >= 1"; return false; }
  return true;
}

// The candidates per k-means++ step (greedy k-means++).
static int SeedTrials(int k) { return 2 + static_cast<int>(std::log(static_cast<double>(k))); }

uint64_t KMeansRandomDraws(const KMeansOptions& options) {
  return static_cast<uint64_t>(options.restarts) *
         (1u + static_cast<uint64_t>(options.k - 1) * static_cast<uint64_t>(SeedTrials(options.k)));
}

double Uniform01(std::mt19937_64* rng) {
  return static_cast<double>((*rng)() >> 11) * (1.0 / 9007199254740992.0);
}

namespace {

// One angle difference per point, centre and iteration: the core's wrap, inline (features.h).
inline double Wrap(double v) { return gmmrrt_wrap_angle_inline(v); }

using detail::IsAngleDim;  // angle_dims.hpp

}  // namespace

void SquaredDistances(const Eigen::MatrixXd& points, const Eigen::VectorXd& center,
                      uint32_t angle_mask, Eigen::ArrayXd* d2) {
  const Eigen::Index n = points.rows();
  d2->resize(n);
  if (angle_mask == 0u) {  // one pass, no temporary (the same sums: 0 + a^2 = a^2 exactly)
    *d2 = (points.col(0).array() - center[0]).square();
    for (Eigen::Index c = 1; c < points.cols(); ++c) *d2 += (points.col(c).array() - center[c]).square();
    return;
  }
  d2->setZero();
  Eigen::ArrayXd diff(n);
  for (Eigen::Index c = 0; c < points.cols(); ++c) {
    diff = points.col(c).array() - center[c];
    if (IsAngleDim(angle_mask, c))
      for (Eigen::Index p = 0; p < n; ++p) diff[p] = Wrap(diff[p]);
    *d2 += diff.square();
  }
}

namespace {

// Points per group (bounding box) and groups per task. 64 points: the E-step's culling groups
// (estep_2d.cpp) for the same reason; 128 groups = 8192 points per task, the E-step's split.
constexpr Eigen::Index kGroupPoints = 64;
constexpr Eigen::Index kTaskGroups = detail::kPassTaskPoints / kGroupPoints;
static_assert(kTaskGroups * kGroupPoints == detail::kPassTaskPoints, "a task is whole groups");
// A center is skipped for a group only when its lower bound exceeds the competing value by
// this relative margin (see the file comment).
constexpr double kBoundMargin = 1e-12;

// The sum of a group's values in a fixed order: eight interleaved partial sums (independent
// chains, which vectorise), then added pairwise.
inline double GroupSum(const double* v, int size) {
  double acc[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  int q = 0;
  for (; q + 8 <= size; q += 8)
    for (int j = 0; j < 8; ++j) acc[j] += v[q + j];
  for (int j = 0; q < size; ++q, ++j) acc[j] += v[q];
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

// 1 when the size labels all equal lab[0] (a group of one label), without a branch per label.
inline bool OneLabel(const int* lab, int size) {
  int mixed = 0;
  for (int q = 1; q < size; ++q) mixed |= lab[q] ^ lab[0];
  return mixed == 0;
}

// The points' columns and groups: what every pass below reads.
struct Layout {
  const Eigen::MatrixXd* x = nullptr;
  Eigen::Index n = 0;
  int d = 0;
  uint32_t mask = 0;
  Eigen::Index groups = 0;
  Eigen::MatrixXd lo, hi;  // D x groups: each group's bounding box
  Eigen::MatrixXd xsum;    // D x groups: each group's sum of each dimension (GroupSum)
  int threads = 1;
  bool prune = true;

  Eigen::Index First(Eigen::Index g) const { return g * kGroupPoints; }
  int Size(Eigen::Index g) const { return static_cast<int>(std::min(kGroupPoints, n - g * kGroupPoints)); }
  long Tasks() const { return static_cast<long>((groups + kTaskGroups - 1) / kTaskGroups); }
  template <typename F>
  void ForGroups(const F& f) const {  // f(g) for every group, tasks of kTaskGroups on the threads
    detail::ParallelFor(threads, Tasks(), [&](long t) {
      const Eigen::Index end = std::min<Eigen::Index>(groups, (t + 1) * kTaskGroups);
      for (Eigen::Index g = t * kTaskGroups; g < end; ++g) f(g);
    });
  }
};

void MakeLayout(const Eigen::MatrixXd& x, uint32_t mask, const KMeansOptions& o, Layout* l) {
  l->x = &x;
  l->n = x.rows();
  l->d = static_cast<int>(x.cols());
  l->mask = mask;
  l->threads = o.threads;
  l->prune = o.prune;
  l->groups = (l->n + kGroupPoints - 1) / kGroupPoints;
  l->lo.resize(l->d, l->groups);
  l->hi.resize(l->d, l->groups);
  l->xsum.resize(l->d, l->groups);
  l->ForGroups([l](Eigen::Index g) {
    const Eigen::Index first = l->First(g), last = first + l->Size(g);
    for (int c = 0; c < l->d; ++c) {
      const double* xc = l->x->col(c).data();
      l->xsum(c, g) = GroupSum(xc + first, l->Size(g));
      double lo = xc[first], hi = lo;
      for (Eigen::Index p = first + 1; p < last; ++p) {
        lo = std::min(lo, xc[p]);
        hi = std::max(hi, xc[p]);
      }
      l->lo(c, g) = lo;
      l->hi(c, g) = hi;
    }
  });
}

// Bounds of the squared (wrapped) distance from center to any point of group g, as the point
// distances compute it: *lower <= GroupDistances' values <= *upper. Per dimension, the
// difference x - c is monotone in x, so over the box it lies between the corners' differences
// (computed with the same rounding); an angle dimension whose corner differences are both in
// (-pi, pi], where the wrap is the identity, is bounded the same way, any other by [0, pi].
// One plain dimension of those bounds, from the corners' differences a <= b: the nearest and
// farthest |x - c| over [a, b] (branch-free, so a loop over centers of it vectorises).
inline void DimensionBounds(double a, double b, double* near, double* far) {
  *near = a > 0.0 ? a : (b < 0.0 ? -b : 0.0);
  *far = -a > b ? -a : b;
}

inline void BoxBounds(const Layout& l, Eigen::Index g, const double* center, double* lower, double* upper) {
  double lo_sum = 0.0, hi_sum = 0.0;
  for (int c = 0; c < l.d; ++c) {
    const double a = l.lo(c, g) - center[c], b = l.hi(c, g) - center[c];
    double near, far;
    if (IsAngleDim(l.mask, c) && !(a > -M_PI && b <= M_PI)) {
      near = 0.0;
      far = M_PI;
    } else {
      DimensionBounds(a, b, &near, &far);
    }
    lo_sum += near * near;
    hi_sum += far * far;
  }
  *lower = lo_sum;
  *upper = hi_sum;
}

// Squared distances of group g's points to center into d2 (Size(g) values): the operations
// and order of SquaredDistances (0 + a^2 = a^2 exactly).
inline void GroupDistances(const Layout& l, Eigen::Index g, const double* center, double* d2) {
  const Eigen::Index first = l.First(g);
  const int size = l.Size(g);
  if (l.d == 2 && l.mask == 0u) {  // the common case in one pass (the same sums in the same order)
    const double *x0 = l.x->col(0).data() + first, *x1 = l.x->col(1).data() + first;
    const double c0 = center[0], c1 = center[1];
    // Two statements, as the per-dimension loop below adds them: the same rounding even where
    // a compiler contracts a * a + b * b within one expression (Clang does by default).
    for (int q = 0; q < size; ++q) {
      const double s0 = (x0[q] - c0) * (x0[q] - c0);
      d2[q] = s0 + (x1[q] - c1) * (x1[q] - c1);
    }
    return;
  }
  for (int c = 0; c < l.d; ++c) {
    const double* xc = l.x->col(c).data() + first;
    const double cc = center[c];
    if (IsAngleDim(l.mask, c)) {
      for (int q = 0; q < size; ++q) {
        const double v = Wrap(xc[q] - cc);
        d2[q] = c == 0 ? v * v : d2[q] + v * v;
      }
    } else if (c == 0) {
      for (int q = 0; q < size; ++q) d2[q] = (xc[q] - cc) * (xc[q] - cc);
    } else {
      for (int q = 0; q < size; ++q) d2[q] += (xc[q] - cc) * (xc[q] - cc);
    }
  }
}

Eigen::Index UniformIndex(Eigen::Index n, std::mt19937_64* rng) {
  return std::min<Eigen::Index>(static_cast<Eigen::Index>(Uniform01(rng) * static_cast<double>(n)), n - 1);
}

// Index drawn with probability proportional to closest (total > 0): the group by the running
// sums of the group sums (cum), then the point by the running sum inside it.
Eigen::Index DrawProportional(const Layout& l, const Eigen::ArrayXd& closest, const std::vector<double>& cum,
                              std::mt19937_64* rng) {
  const double u = Uniform01(rng) * cum.back();
  const Eigen::Index g = std::min<Eigen::Index>(std::upper_bound(cum.begin(), cum.end(), u) - cum.begin(),
                                                l.groups - 1);
  const Eigen::Index first = l.First(g), last = first + l.Size(g);
  double s = g > 0 ? cum[g - 1] : 0.0;
  Eigen::Index pick = last - 1;
  for (Eigen::Index p = first; p < last; ++p) {
    if (closest[p] > 0.0) pick = p;  // rounding left u past every running sum: the last one with weight
    s += closest[p];
    if (s > u && closest[p] > 0.0) return p;
  }
  return pick;
}

// Greedy k-means++: each new center is the best (lowest potential sum_p min(closest_p, d2_p)) of
// SeedTrials candidates drawn with probability proportional to closest. A group whose box is
// farther from a candidate than its largest closest value keeps its closest values, so its
// part of the potential is its sum of them (gsum), the same bits as computing it point by point.
void SeedPlusPlus(const Layout& l, int k, std::mt19937_64* rng, Eigen::MatrixXd* centers) {
  const Eigen::MatrixXd& x = *l.x;
  const Eigen::Index n = l.n, ng = l.groups;
  const int d = l.d;
  centers->resize(d, k);
  centers->col(0) = x.row(UniformIndex(n, rng)).transpose();
  Eigen::ArrayXd closest(n);
  std::vector<double> gsum(ng), gmax(ng), cum(ng);
  auto refresh = [&](Eigen::Index g) {  // gsum and gmax of group g from closest
    const Eigen::Index first = l.First(g);
    const int size = l.Size(g);
    gsum[g] = GroupSum(closest.data() + first, size);
    double m = 0.0;
    const double* cl = closest.data() + first;
    for (int q = 0; q < size; ++q) m = cl[q] > m ? cl[q] : m;
    gmax[g] = m;
  };
  {
    const Eigen::VectorXd c0 = centers->col(0);
    l.ForGroups([&](Eigen::Index g) {
      GroupDistances(l, g, c0.data(), closest.data() + l.First(g));
      refresh(g);
    });
  }
  const int trials = SeedTrials(k);
  Eigen::MatrixXd cand(d, trials);
  std::vector<double> part(static_cast<size_t>(ng) * trials);
  for (int c = 1; c < k; ++c) {
    std::partial_sum(gsum.begin(), gsum.end(), cum.begin());
    for (int t = 0; t < trials; ++t) {
      const Eigen::Index p = cum.back() > 0.0 ? DrawProportional(l, closest, cum, rng) : UniformIndex(n, rng);
      cand.col(t) = x.row(p).transpose();
    }
    l.ForGroups([&](Eigen::Index g) {
      double d2[kGroupPoints];
      const Eigen::Index first = l.First(g);
      const int size = l.Size(g);
      for (int t = 0; t < trials; ++t) {
        double lower, upper;
        BoxBounds(l, g, cand.col(t).data(), &lower, &upper);
        double& out = part[static_cast<size_t>(g) * trials + t];
        if (l.prune && lower > gmax[g] * (1.0 + kBoundMargin)) {
          out = gsum[g];
          continue;
        }
        GroupDistances(l, g, cand.col(t).data(), d2);
        const double* cl = closest.data() + first;
        for (int q = 0; q < size; ++q) d2[q] = d2[q] < cl[q] ? d2[q] : cl[q];  // min, without a branch
        out = GroupSum(d2, size);
      }
    });
    int best = 0;
    double best_potential = std::numeric_limits<double>::infinity();
    for (int t = 0; t < trials; ++t) {
      double potential = 0.0;
      for (Eigen::Index g = 0; g < ng; ++g) potential += part[static_cast<size_t>(g) * trials + t];
      if (potential < best_potential) {
        best_potential = potential;
        best = t;
      }
    }
    centers->col(c) = cand.col(best);
    const double* bc = cand.col(best).data();
    l.ForGroups([&](Eigen::Index g) {
      double lower, upper;
      BoxBounds(l, g, bc, &lower, &upper);
      if (l.prune && lower > gmax[g] * (1.0 + kBoundMargin)) return;
      double d2[kGroupPoints];
      const Eigen::Index first = l.First(g);
      GroupDistances(l, g, bc, d2);
      double* cl = closest.data() + first;
      for (int q = 0; q < l.Size(g); ++q) cl[q] = d2[q] < cl[q] ? d2[q] : cl[q];
      refresh(g);
    });
  }
}

// Bounds carried from one assignment pass to the next, per group of points (Hamerly, "Making
// k-means even faster", SDM 2010, with one upper and one lower bound per group instead of per
// point; the triangle inequality holds for the wrapped metric too). For a group whose points
// all have one label a: upper[g] >= the exact distance (Euclidean, angle dimensions wrapped)
// from any of its points to center a, lower[g] <= the exact distance from any of its points to
// any other center; label[g] = a. label[g] = -1: a group of several labels, no bounds.
//
// The computed squared distances that decide the labels differ from the exact ones by rounding
// only: at most about (D + 10) ulps of S^2, S^2 the squared diagonal of the data's box (the
// differences are of points and centers inside it, and a wrapped difference errs by a few ulps
// of 2 pi, which only happens when the box spans more than pi), so below 2.5e-13 S^2 for
// D <= kMaxBoundedDim (higher D runs without these bounds). slack2 = 1e-12 S^2 covers those
// errors, and every step below keeps a bound on the safe side of the exact value by at least
// part of it, so a group the bounds keep is nearer its own center than any other in the
// computed distances, strictly (a tie is rescanned).
struct GroupBounds {
  std::vector<double> upper, lower;
  std::vector<int> label;
  double slack2 = 0.0;
};
constexpr int kMaxBoundedDim = 1024;

// How the centers moved in the last update, for the bounded pass: drift[c] >= the exact
// distance center c moved; drift_max and drift_next the largest and second largest drift
// (drift_arg moved most), so the other centers of center a moved at most drift_max, or
// drift_next for a = drift_arg. keep[a]: a group of center a whose upper bound is below it is
// within half the distance from a to every other center, less a margin, so no other center can
// be nearer to any of its points (Hamerly's second test).
struct Moves {
  std::vector<double> drift, keep;
  double drift_max = 0.0, drift_next = 0.0;
  int drift_arg = -1;
};

// Upper bound on an exact distance from a computed squared one (slack2 as in GroupBounds).
inline double UpperDistance(double d2, double slack2) { return std::sqrt(d2 + slack2); }
// Lower bound on an exact distance from a computed squared one (or a box's lower bound on it).
inline double LowerDistance(double d2, double slack2) { return std::sqrt(std::max(0.0, d2 - slack2)); }

// The moves of the centers from previous to centers (both D x K, angle rows wrapped), and the
// keep thresholds of the new centers, for the bounded pass after an update.
void MakeMoves(uint32_t mask, const Eigen::MatrixXd& previous, const Eigen::MatrixXd& centers, double slack2,
               Moves* m) {
  const Eigen::Index k = centers.cols();
  Eigen::MatrixXd moved = centers - previous;
  WrapAngleRows(mask, &moved);
  m->drift.resize(static_cast<size_t>(k));
  m->drift_max = m->drift_next = 0.0;
  m->drift_arg = -1;
  for (Eigen::Index c = 0; c < k; ++c) {
    const double drift = UpperDistance(moved.col(c).squaredNorm(), slack2);
    m->drift[static_cast<size_t>(c)] = drift;
    if (drift > m->drift_max) {
      m->drift_next = m->drift_max;
      m->drift_max = drift;
      m->drift_arg = static_cast<int>(c);
    } else {
      m->drift_next = std::max(m->drift_next, drift);
    }
  }
  // A point within h - g of center a, h half the exact distance from a to its nearest other
  // center and g = sqrt(slack2), is farther than h + g from every other center: 2 g more than
  // from its own, which the computed squares cannot undo (4 slack2 of room against their errors).
  const double g = std::sqrt(slack2);
  m->keep.assign(static_cast<size_t>(k), -1.0);
  Eigen::MatrixXd diff(centers.rows(), 1);
  for (Eigen::Index a = 0; a < k; ++a) {
    double nearest2 = std::numeric_limits<double>::infinity();
    for (Eigen::Index c = 0; c < k; ++c) {
      if (c == a) continue;
      diff = centers.col(c) - centers.col(a);
      WrapAngleRows(mask, &diff);
      nearest2 = std::min(nearest2, diff.squaredNorm());
    }
    m->keep[static_cast<size_t>(a)] = 0.5 * LowerDistance(nearest2, slack2) - g;
  }
}

// The centers that can be nearest to a point of group g: those whose box lower bound is within
// the smallest box upper bound, in index order, into cand (*n_cand of them); *skipped_low gets the
// smallest box lower bound of the others (infinity if none).
void GroupCandidates(const Layout& l, Eigen::Index g, const Eigen::MatrixXd& centers,
                     const std::vector<double>& by_dim, int* cand, int* n_cand, double* skipped_low) {
  const int k = static_cast<int>(centers.cols());
  double low_small[64];
  std::vector<double> low_big;  // more than 64 centers (GMMRRT_MAX_K is below that)
  double* low = low_small;
  if (k > 64) {
    low_big.resize(k);
    low = low_big.data();
  }
  double threshold = std::numeric_limits<double>::infinity();
  if (l.mask == 0u && k <= 64) {
    // BoxBounds for all centers at once, dimension by dimension (the same operations in the
    // same order, so the same values; a loop over centers that vectorises).
    double up[64];
    for (int c = 0; c < k; ++c) low[c] = up[c] = 0.0;
    for (int j = 0; j < l.d; ++j) {
      const double lo = l.lo(j, g), hi = l.hi(j, g);
      const double* cj = by_dim.data() + static_cast<size_t>(j) * k;
      for (int c = 0; c < k; ++c) {
        double near, far;
        DimensionBounds(lo - cj[c], hi - cj[c], &near, &far);
        low[c] += near * near;
        up[c] += far * far;
      }
    }
    for (int c = 0; c < k; ++c) threshold = std::min(threshold, up[c]);
  } else {
    for (int c = 0; c < k; ++c) {
      double upper;
      BoxBounds(l, g, centers.col(c).data(), &low[c], &upper);
      threshold = std::min(threshold, upper);
    }
  }
  threshold = l.prune ? threshold * (1.0 + kBoundMargin) : std::numeric_limits<double>::infinity();
  int n = 0;
  double skipped = std::numeric_limits<double>::infinity();
  for (int c = 0; c < k; ++c) {
    if (low[c] > threshold)
      skipped = std::min(skipped, low[c]);
    else
      cand[n++] = c;
  }
  *n_cand = n;
  *skipped_low = skipped;
}

// Group g's labels (ties: the lower index) and squared distances to the nearest center into
// lab and bst (Size(g) values each), from GroupCandidates' centers visited in index order: the
// labels and distances of a scan over all centers. With bounds, group g's GroupBounds entries
// are set: from the largest distance to the nearest center, and from the smallest of the second
// smallest computed distances among the candidates and the box lower bounds of the others.
void ScanGroup(const Layout& l, Eigen::Index g, const Eigen::MatrixXd& centers, const std::vector<double>& by_dim,
               double* bst, int* lab, GroupBounds* bounds) {
  std::vector<int> cand_big;
  int cand_small[64];
  int* cand = cand_small;
  if (centers.cols() > 64) {
    cand_big.resize(static_cast<size_t>(centers.cols()));
    cand = cand_big.data();
  }
  int n_cand;
  double skipped_low;
  GroupCandidates(l, g, centers, by_dim, cand, &n_cand, &skipped_low);
  const int size = l.Size(g);
  double d2[kGroupPoints];
  GroupDistances(l, g, centers.col(cand[0]).data(), bst);
  // Each point's smallest distance to a center other than its nearest (sec): a center's distance
  // counts for every point but those it is nearest to, whose earlier nearest counts instead.
  // Selections, not branches: which way they go depends on the data.
  // As Eigen array operations, which vectorise (the compiler left the plain loop's selections as
  // branches, which the data mispredict): closer = d2 < bst; the labels are held as doubles
  // (exact for these integers) so that every operand has one width. The distances are >= +0, so
  // min and max give the same bits as the selections they stand for.
  double sec_data[kGroupPoints], lab_data[kGroupPoints];
  Eigen::Map<Eigen::ArrayXd> best_q(bst, size), d2_q(d2, size), sec(sec_data, size), labd(lab_data, size);
  sec.setConstant(skipped_low);
  labd.setConstant(cand[0]);
  for (int i = 1; i < n_cand; ++i) {
    GroupDistances(l, g, centers.col(cand[i]).data(), d2);
    labd = (d2_q < best_q).select(static_cast<double>(cand[i]), labd);
    sec = sec.min(d2_q.max(best_q));
    best_q = best_q.min(d2_q);
  }
  for (int q = 0; q < size; ++q) lab[q] = static_cast<int>(lab_data[q]);
  if (!bounds) return;
  const double far = best_q.maxCoeff(), second = std::min(skipped_low, sec.minCoeff());
  const size_t gi = static_cast<size_t>(g);
  bounds->label[gi] = OneLabel(lab, size) ? lab[0] : -1;
  bounds->upper[gi] = UpperDistance(far, bounds->slack2);
  bounds->lower[gi] = LowerDistance(second, bounds->slack2);
}

// Squared distances of group g's points to their own centers (labels lab) into bst: the values
// a scan gives them (GroupDistances, once per label in the group).
void OwnDistances(const Layout& l, Eigen::Index g, const Eigen::MatrixXd& centers, const int* lab, double* bst) {
  const int size = l.Size(g);
  if (OneLabel(lab, size)) {
    GroupDistances(l, g, centers.col(lab[0]).data(), bst);
    return;
  }
  double d2[kGroupPoints];
  bool filled[kGroupPoints] = {};
  for (int start = 0; start < size; ++start) {
    if (filled[start]) continue;
    const int a = lab[start];
    GroupDistances(l, g, centers.col(a).data(), d2);
    for (int q = start; q < size; ++q)
      if (lab[q] == a) {
        bst[q] = d2[q];
        filled[q] = true;
      }
  }
}

// Assigns every point to its nearest center (ties: the lower index) by scanning every group;
// returns the inertia (summed per group, then in group order). Labels and distances are those
// of a scan over all centers. changed (if not null; *labels then holds the previous pass's
// labels): whether any label differs from before. bounds (if not null): set for every group.
double Assign(const Layout& l, const Eigen::MatrixXd& centers, Eigen::ArrayXi* labels, Eigen::ArrayXd* best,
              bool* changed, GroupBounds* bounds) {
  const int k = static_cast<int>(centers.cols());
  labels->resize(l.n);
  best->resize(l.n);
  std::vector<double> group_sum(static_cast<size_t>(l.groups));
  std::vector<char> group_changed(static_cast<size_t>(l.groups), 0);
  std::vector<double> by_dim(static_cast<size_t>(l.d) * k);  // center c's coordinate j at [j k + c]
  for (int j = 0; j < l.d; ++j)
    for (int c = 0; c < k; ++c) by_dim[static_cast<size_t>(j) * k + c] = centers(j, c);
  l.ForGroups([&](Eigen::Index g) {
    const Eigen::Index first = l.First(g);
    const int size = l.Size(g);
    double* bst = best->data() + first;
    int lab[kGroupPoints];  // copied out below, compared with the previous labels on the way
    ScanGroup(l, g, centers, by_dim, bst, lab, bounds);
    group_sum[static_cast<size_t>(g)] = GroupSum(bst, size);
    int* out = labels->data() + first;
    int differ = 0;
    if (changed)
      for (int q = 0; q < size; ++q) differ |= out[q] ^ lab[q];
    for (int q = 0; q < size; ++q) out[q] = lab[q];
    group_changed[static_cast<size_t>(g)] = differ != 0;
  });
  if (changed) *changed = std::find(group_changed.begin(), group_changed.end(), 1) != group_changed.end();
  double inertia = 0.0;
  for (double v : group_sum) inertia += v;
  return inertia;
}

// Whether a group of center a with bounds upper and lower (as in GroupBounds) keeps its labels:
// below center a's keep threshold, or every other center farther than its own from each of its
// points by more than the computed squares can err (less than slack2 each).
inline bool Rules(const Moves& moves, int a, double upper, double lower, double slack2) {
  return upper < moves.keep[static_cast<size_t>(a)] || (lower > upper && lower * lower - upper * upper > 2.0 * slack2);
}

// The assignment after an update with bounds (set by the last pass, with *labels): a group of
// one label whose bounds, moved by moves, still rule every other center out keeps its labels
// without a distance computed (nor its distances in *best: those are left as they were); any
// other group is scanned (ScanGroup) and its bounds set anew. Returns whether any label changed;
// the labels are those of a scan over all centers.
bool AssignBounded(const Layout& l, const Eigen::MatrixXd& centers, const Moves& moves, Eigen::ArrayXi* labels,
                   Eigen::ArrayXd* best, GroupBounds* bounds) {
  const int k = static_cast<int>(centers.cols());
  std::vector<char> group_changed(static_cast<size_t>(l.groups), 0);
  std::vector<double> by_dim(static_cast<size_t>(l.d) * k);  // center c's coordinate j at [j k + c]
  for (int j = 0; j < l.d; ++j)
    for (int c = 0; c < k; ++c) by_dim[static_cast<size_t>(j) * k + c] = centers(j, c);
  const double slack2 = bounds->slack2;
  l.ForGroups([&](Eigen::Index g) {
    const size_t gi = static_cast<size_t>(g);
    const int a = bounds->label[gi];
    if (a >= 0) {
      const double upper = bounds->upper[gi] + moves.drift[static_cast<size_t>(a)];
      const double lower = std::max(0.0, bounds->lower[gi] - (a == moves.drift_arg ? moves.drift_next : moves.drift_max));
      bounds->upper[gi] = upper;
      bounds->lower[gi] = lower;
      if (Rules(moves, a, upper, lower, slack2)) return;
      // Hamerly's tightening: the upper bound from the points' distances to their moved center
      // (which are then in *best), before the scan.
      double* bst = best->data() + l.First(g);
      GroupDistances(l, g, centers.col(a).data(), bst);
      double far = 0.0;
      for (int q = 0; q < l.Size(g); ++q) far = bst[q] > far ? bst[q] : far;
      bounds->upper[gi] = UpperDistance(far, slack2);
      if (Rules(moves, a, bounds->upper[gi], lower, slack2)) return;
    }
    const Eigen::Index first = l.First(g);
    const int size = l.Size(g);
    int lab[kGroupPoints];
    ScanGroup(l, g, centers, by_dim, best->data() + first, lab, bounds);
    int* out = labels->data() + first;
    int differ = 0;
    for (int q = 0; q < size; ++q) differ |= out[q] ^ lab[q];
    for (int q = 0; q < size; ++q) out[q] = lab[q];
    group_changed[gi] = differ != 0;
  });
  return std::find(group_changed.begin(), group_changed.end(), 1) != group_changed.end();
}

// The inertia of the labels (summed per group, then in group order, as Assign does) with each
// point's squared distance to its own center put into *best: after AssignBounded, the values a
// scan over all centers would have given.
double Inertia(const Layout& l, const Eigen::MatrixXd& centers, const Eigen::ArrayXi& labels, Eigen::ArrayXd* best) {
  std::vector<double> group_sum(static_cast<size_t>(l.groups));
  l.ForGroups([&](Eigen::Index g) {
    double* bst = best->data() + l.First(g);
    OwnDistances(l, g, centers, labels.data() + l.First(g), bst);
    group_sum[static_cast<size_t>(g)] = GroupSum(bst, l.Size(g));
  });
  double inertia = 0.0;
  for (double v : group_sum) inertia += v;
  return inertia;
}

// Moves the centers to their clusters' means; returns the summed squared center shift. The sums
// per cluster, of x for a plain dimension and of the wrapped x - center for an angle (whose mean
// is taken about the center), are taken per task in group order and the tasks' sums added in
// task order. A group whose points all have one label (most, in spatial order) adds its plain
// dimensions' sums from the layout (computed once, as the pass over its points would by
// GroupSum) and its angles' by GroupSum's independent partial sums; a group of several labels
// adds its points in order.
// An empty cluster takes the point farthest from its center by *best, which is first recomputed
// (Inertia) unless best_current says it holds every point's distance (not after AssignBounded).
// group_label (if not null, GroupBounds::label of the same labels): a group with a label there
// is known to have one label, which saves reading its points' labels.
double Update(const Layout& l, const Eigen::ArrayXi& labels, Eigen::ArrayXd* best, bool best_current,
              Eigen::MatrixXd* centers, const std::vector<int>* group_label) {
  const Eigen::MatrixXd& x = *l.x;
  const uint32_t mask = l.mask;
  const Eigen::Index k = centers->cols(), n = l.n;
  const long tasks = l.Tasks();
  std::vector<Eigen::MatrixXd> task_shift(static_cast<size_t>(tasks));
  std::vector<Eigen::VectorXd> task_count(static_cast<size_t>(tasks));
  detail::ParallelFor(l.threads, tasks, [&](long t) {
    Eigen::MatrixXd& shift = task_shift[static_cast<size_t>(t)];
    Eigen::VectorXd& count = task_count[static_cast<size_t>(t)];
    shift.setZero(l.d, k);
    count.setZero(k);
    double diff[kGroupPoints];
    const Eigen::Index end = std::min<Eigen::Index>(l.groups, (t + 1) * kTaskGroups);
    for (Eigen::Index g = t * kTaskGroups; g < end; ++g) {
      const Eigen::Index first = l.First(g);
      const int size = l.Size(g);
      const int* lab = labels.data() + first;
      const int one = lab[0];
      const bool same = (group_label && (*group_label)[static_cast<size_t>(g)] >= 0) || OneLabel(lab, size);
      // Runs of equal labels (ends after run_end[i]) for a group of several: the points' additions
      // in point order, each run's in a register rather than through memory.
      int run_end[kGroupPoints];
      int runs = 0;
      if (same) {
        count[one] += static_cast<double>(size);  // integers: exact in any grouping
      } else {
        for (int q = 1; q < size; ++q)
          if (lab[q] != lab[q - 1]) run_end[runs++] = q;
        run_end[runs++] = size;
        for (int i = 0, q = 0; i < runs; q = run_end[i++]) count[lab[q]] += static_cast<double>(run_end[i] - q);
      }
      for (int c = 0; c < l.d; ++c) {
        const bool angle = IsAngleDim(mask, c);
        const double* xc = x.col(c).data() + first;
        if (same && !angle) {
          shift(c, one) += l.xsum(c, g);
        } else if (same) {
          const double center = (*centers)(c, one);
          for (int q = 0; q < size; ++q) diff[q] = Wrap(xc[q] - center);
          shift(c, one) += GroupSum(diff, size);
        } else {
          for (int i = 0, q = 0; i < runs; ++i) {
            const int a = lab[q];
            const double center = (*centers)(c, a);
            double acc = shift(c, a);
            if (angle)
              for (; q < run_end[i]; ++q) acc += Wrap(xc[q] - center);
            else
              for (; q < run_end[i]; ++q) acc += xc[q];
            shift(c, a) = acc;
          }
        }
      }
    }
  });
  Eigen::MatrixXd shift = Eigen::MatrixXd::Zero(l.d, k);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(k);
  for (long t = 0; t < tasks; ++t) {
    shift += task_shift[static_cast<size_t>(t)];
    count += task_count[static_cast<size_t>(t)];
  }
  if (!best_current && (count.array() == 0.0).any()) Inertia(l, *centers, labels, best);
  std::vector<bool> taken(n, false);
  Eigen::MatrixXd previous = *centers;
  for (Eigen::Index c = 0; c < k; ++c) {
    if (count[c] > 0.0) {
      for (int j = 0; j < l.d; ++j)
        (*centers)(j, c) = IsAngleDim(mask, j) ? (*centers)(j, c) + shift(j, c) / count[c] : shift(j, c) / count[c];
    } else {
      // An empty cluster takes the point farthest from its center (deterministic).
      Eigen::Index far = 0;
      double far_d2 = -1.0;
      for (Eigen::Index p = 0; p < n; ++p)
        if (!taken[p] && (*best)[p] > far_d2) { far_d2 = (*best)[p]; far = p; }
      taken[far] = true;
      centers->col(c) = x.row(far).transpose();
    }
  }
  WrapAngleRows(mask, centers);
  Eigen::MatrixXd moved = *centers - previous;
  WrapAngleRows(mask, &moved);
  return moved.squaredNorm();
}

}  // namespace

Status KMeans(const Eigen::MatrixXd& points, uint32_t angle_mask, const KMeansOptions& options,
              std::mt19937_64* rng, KMeansResult* result) {
  std::string why;
  if (!options.IsValid(&why)) return Status::Error(StatusCode::kInvalidArgument, "k-means: " + why);
  if (points.rows() < options.k)
    return Status::Error(StatusCode::kNotEnoughData,
                         "k-means: " + std::to_string(points.rows()) + " points for " +
                             std::to_string(options.k) + " clusters");
  Layout layout;
  MakeLayout(points, angle_mask, options, &layout);
  // scikit-learn's tolerance: 1e-4 of the mean per-dimension variance (sums per group by
  // GroupSum, then in group order).
  const int d = layout.d;
  const double inv_n = 1.0 / static_cast<double>(layout.n);
  const Eigen::VectorXd mean = layout.xsum.rowwise().sum() * inv_n;
  Eigen::MatrixXd part(d, layout.groups);
  layout.ForGroups([&](Eigen::Index g) {
    double dev2[kGroupPoints];
    const Eigen::Index first = layout.First(g);
    const int size = layout.Size(g);
    for (int c = 0; c < d; ++c) {
      const double* xc = points.col(c).data() + first;
      for (int q = 0; q < size; ++q) dev2[q] = (xc[q] - mean[c]) * (xc[q] - mean[c]);
      part(c, g) = GroupSum(dev2, size);
    }
  });
  const double shift_tol = 1e-4 * part.sum() * inv_n / d;
  // The Lloyd passes after the first carry bounds per group (GroupBounds), allocated once here;
  // without pruning every pass scans every center.
  GroupBounds group_bounds;
  GroupBounds* bounds = nullptr;
  if (options.prune && d <= kMaxBoundedDim) {
    double diagonal2 = 0.0;  // S^2 of GroupBounds
    for (int c = 0; c < d; ++c) {
      const double extent = layout.hi.row(c).maxCoeff() - layout.lo.row(c).minCoeff();
      diagonal2 += extent * extent;
    }
    const size_t groups = static_cast<size_t>(layout.groups);
    group_bounds.upper.resize(groups);
    group_bounds.lower.resize(groups);
    group_bounds.label.resize(groups);
    group_bounds.slack2 = 1e-12 * diagonal2;
    bounds = &group_bounds;
  }
  result->inertia = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd centers, previous;
  Eigen::ArrayXi labels;
  Eigen::ArrayXd best;
  Moves moves;
  for (int r = 0; r < options.restarts; ++r) {
    SeedPlusPlus(layout, options.k, rng, &centers);
    double inertia = Assign(layout, centers, &labels, &best, nullptr, bounds);
    bool best_current = true;  // best holds every point's distance to its center
    int it = 0;
    while (it < options.max_iterations) {
      ++it;
      previous = centers;
      const double shift = Update(layout, labels, &best, best_current, &centers, bounds ? &bounds->label : nullptr);
      bool changed = true;
      if (bounds) {
        MakeMoves(angle_mask, previous, centers, bounds->slack2, &moves);
        changed = AssignBounded(layout, centers, moves, &labels, &best, bounds);
        best_current = false;
      } else {
        inertia = Assign(layout, centers, &labels, &best, &changed, nullptr);
      }
      if (!changed || shift <= shift_tol) break;
    }
    if (!best_current) inertia = Inertia(layout, centers, labels, &best);
    if (inertia < result->inertia) {
      result->inertia = inertia;
      result->centers = centers;
      result->labels.assign(labels.data(), labels.data() + labels.size());
      result->iterations = it;
    }
  }
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
