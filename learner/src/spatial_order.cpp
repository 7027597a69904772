// spatial_order.cpp - Z-order of 2-D points on a 64 x 64 grid by counting sort, so that the
// fused E-step's lanes hold nearby points (paper eq. 1; see spatial_order.hpp).
#include "spatial_order.hpp"

#include <algorithm>
#include <memory>

#include "angle_dims.hpp"
#include "parallel.hpp"

namespace gmmrrt {
namespace learn {
namespace detail {

namespace {

constexpr int kBits = 6;  // 64 cells per axis
constexpr uint32_t kCells = 1u << kBits;

// Cell index 0..63 of v in [lo, lo + span].
uint32_t Cell(double v, double lo, double scale) {
  const double c = (v - lo) * scale;
  if (!(c > 0.0)) return 0;
  return std::min<uint32_t>(static_cast<uint32_t>(c), kCells - 1);
}

// Bits of a cell index 0..63 spread to the even positions (bit b to bit 2 b).
struct SpreadTable {
  uint32_t v[kCells];
  constexpr SpreadTable() : v() {
    for (uint32_t x = 0; x < kCells; ++x)
      for (int b = 0; b < kBits; ++b) v[x] |= ((x >> b) & 1u) << (2 * b);
  }
};
constexpr SpreadTable kSpread;

// Interleaves the bits of x (even positions) and y (odd positions).
inline uint32_t Morton(uint32_t x, uint32_t y) { return kSpread.v[x] | kSpread.v[y] << 1; }

}  // namespace

PointOrder SpatialOrder2d(const Eigen::MatrixXd& points, uint32_t angle_mask, int threads) {
  eigen_assert(points.rows() == 2);  // read below as pairs of coordinates
  const Eigen::Index n = points.cols();
  if (n == 0) return PointOrder();
  // Coordinates read through a copied pointer (points is 2 x n, column-major), not through
  // `points`, so that the counts' stores below cannot alias what the loops read.
  const double* const pts = points.data();
  const auto x = [pts, angle_mask](Eigen::Index p) { return AsFitValue(angle_mask, 0, pts[2 * p]); };
  const auto y = [pts, angle_mask](Eigen::Index p) { return AsFitValue(angle_mask, 1, pts[2 * p + 1]); };
  const long tasks = PassTasks(static_cast<long>(n));
  // The bounding box: minima and maxima per task, then over the tasks (exact in any order).
  std::vector<double> box(static_cast<size_t>(tasks) * 4);
  ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    // In locals, stored once: the tasks' slots share cache lines, and a store per point into
    // them (which the compiler must keep, as they might alias the points) made the pass slower
    // on two threads than on one.
    double x_lo = x(first), x_hi = x_lo, y_lo = y(first), y_hi = y_lo;
    for (Eigen::Index p = first + 1; p < last; ++p) {
      const double xp = x(p), yp = y(p);
      x_lo = std::min(x_lo, xp);
      x_hi = std::max(x_hi, xp);
      y_lo = std::min(y_lo, yp);
      y_hi = std::max(y_hi, yp);
    }
    double* b = box.data() + 4 * t;
    b[0] = x_lo;
    b[1] = x_hi;
    b[2] = y_lo;
    b[3] = y_hi;
  });
  double lo0 = box[0], hi0 = box[1], lo1 = box[2], hi1 = box[3];
  for (long t = 1; t < tasks; ++t) {
    lo0 = std::min(lo0, box[4 * t]);
    hi0 = std::max(hi0, box[4 * t + 1]);
    lo1 = std::min(lo1, box[4 * t + 2]);
    hi1 = std::max(hi1, box[4 * t + 3]);
  }
  const double span0 = hi0 - lo0, span1 = hi1 - lo1;
  const double scale0 = span0 > 0.0 ? kCells / span0 : 0.0, scale1 = span1 > 0.0 ? kCells / span1 : 0.0;
  // Keys and each task's count per cell; then each (cell, task) pair's first slot, cells in
  // order and tasks in order within a cell: a stable counting sort split over the tasks.
  constexpr size_t kAllCells = static_cast<size_t>(kCells) * kCells;
  // Left uninitialised here and first written by the tasks: zeroing megabytes on the calling
  // thread (and taking their page faults there) was serial time.
  std::unique_ptr<uint32_t[]> key(new uint32_t[static_cast<size_t>(n)]);
  std::unique_ptr<Eigen::Index[]> start(new Eigen::Index[kAllCells * static_cast<size_t>(tasks)]);  // [t * cells + c]
  ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    Eigen::Index* count = start.get() + static_cast<size_t>(t) * kAllCells;
    std::fill(count, count + kAllCells, Eigen::Index{0});
    for (Eigen::Index p = first; p < last; ++p) {
      key[p] = Morton(Cell(x(p), lo0, scale0), Cell(y(p), lo1, scale1));
      ++count[key[p]];
    }
  });
  // Cells' totals (in blocks of cells on the threads), their running sums, then each task's
  // first slot per cell: exact integer sums, so the same for any split.
  constexpr long kCellBlock = 256;
  constexpr long kCellBlocks = static_cast<long>(kAllCells) / kCellBlock;
  std::vector<Eigen::Index> cell_start(kAllCells + 1, 0);
  ParallelFor(threads, kCellBlocks, [&](long b) {
    for (size_t c = static_cast<size_t>(b * kCellBlock); c < static_cast<size_t>((b + 1) * kCellBlock); ++c)
      for (long t = 0; t < tasks; ++t) cell_start[c + 1] += start[static_cast<size_t>(t) * kAllCells + c];
  });
  for (size_t c = 0; c < kAllCells; ++c) cell_start[c + 1] += cell_start[c];
  ParallelFor(threads, kCellBlocks, [&](long b) {
    for (size_t c = static_cast<size_t>(b * kCellBlock); c < static_cast<size_t>((b + 1) * kCellBlock); ++c) {
      Eigen::Index next = cell_start[c];
      for (long t = 0; t < tasks; ++t) {
        Eigen::Index& slot = start[static_cast<size_t>(t) * kAllCells + c];
        const Eigen::Index count = slot;
        slot = next;
        next += count;
      }
    }
  });
  PointOrder order(n);  // uninitialised: every entry is written below
  ParallelFor(threads, tasks, [&](long t) {
    Eigen::Index first, last;
    PassRange(t, n, &first, &last);
    Eigen::Index* slot = start.get() + static_cast<size_t>(t) * kAllCells;
    for (Eigen::Index p = first; p < last; ++p) order[slot[key[p]]++] = p;
  });
  return order;
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
