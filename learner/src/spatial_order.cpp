// spatial_order.cpp - Z-order of 2-D points on a 64 x 64 grid by counting sort, so that the
// fused E-step's lanes hold nearby points (paper eq. 1; see spatial_order.hpp).
#include "spatial_order.hpp"

#include <algorithm>

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

// Interleaves the bits of x (even positions) and y (odd positions).
uint32_t Morton(uint32_t x, uint32_t y) {
  uint32_t key = 0;
  for (int b = 0; b < kBits; ++b) key |= ((x >> b) & 1u) << (2 * b) | ((y >> b) & 1u) << (2 * b + 1);
  return key;
}

}  // namespace

std::vector<Eigen::Index> SpatialOrder2d(const Eigen::MatrixXd& xt) {
  const Eigen::Index n = xt.rows();
  const double lo0 = xt.col(0).minCoeff(), lo1 = xt.col(1).minCoeff();
  const double span0 = xt.col(0).maxCoeff() - lo0, span1 = xt.col(1).maxCoeff() - lo1;
  const double scale0 = span0 > 0.0 ? kCells / span0 : 0.0, scale1 = span1 > 0.0 ? kCells / span1 : 0.0;
  std::vector<uint32_t> key(n);
  std::vector<Eigen::Index> start(kCells * kCells + 1, 0);
  for (Eigen::Index p = 0; p < n; ++p) {
    key[p] = Morton(Cell(xt(p, 0), lo0, scale0), Cell(xt(p, 1), lo1, scale1));
    ++start[key[p] + 1];
  }
  for (uint32_t c = 0; c < kCells * kCells; ++c) start[c + 1] += start[c];
  std::vector<Eigen::Index> order(n);
  for (Eigen::Index p = 0; p < n; ++p) order[start[key[p]]++] = p;
  return order;
}

}  // namespace detail
}  // namespace learn
}  // namespace gmmrrt
