// test_support.hpp - synthetic Gaussian mixture data for the learner tests (deterministic).
#ifndef GMMRRT_LEARNER_TEST_SUPPORT_HPP
#define GMMRRT_LEARNER_TEST_SUPPORT_HPP

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "gmmrrt/features.h"

namespace test_support {

struct Blob {
  Eigen::VectorXd mean;
  Eigen::MatrixXd chol;  // Sigma = L L^T
  int count;
};

// Points (D x N) drawn blob after blob; angle rows in angle_mask wrapped into (-pi, pi].
inline Eigen::MatrixXd Sample(const std::vector<Blob>& blobs, uint32_t angle_mask, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  int n = 0;
  for (const Blob& b : blobs) n += b.count;
  const int d = static_cast<int>(blobs[0].mean.size());
  Eigen::MatrixXd x(d, n);
  int col = 0;
  for (const Blob& b : blobs) {
    for (int i = 0; i < b.count; ++i) {
      Eigen::VectorXd z(d);
      for (int j = 0; j < d; ++j) z[j] = normal(rng);
      x.col(col) = b.mean + b.chol * z;
      for (int j = 0; j < d; ++j)
        if ((angle_mask >> j) & 1u) x(j, col) = gmmrrt_wrap_angle(x(j, col));
      ++col;
    }
  }
  return x;
}

inline Eigen::MatrixXd Diag(std::initializer_list<double> sd) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(sd.size()));
  int i = 0;
  for (double s : sd) v[i++] = s;
  return v.asDiagonal();
}

inline Eigen::VectorXd Vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  int i = 0;
  for (double s : values) v[i++] = s;
  return v;
}

}  // namespace test_support

#endif
