// test_model_vectors.cpp - learner.model_vectors: the learner's Eigen log-density against the
// shared test vectors of tests/data/model_vectors/ (numpy/scipy oracle, README there): every
// point within 1e-9 (relative above 1). The C mixture checks the same files (planner.gmm).
// The folder is checked in: a missing one fails the test.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "gmmrrt/model_file.h"
#include "gmmrrt_learner/mixture.hpp"

using namespace gmmrrt::learn;

namespace {

int CheckVector(const std::string& dir, const std::string& name) {
  gmmrrt_model_t model;
  char err[256] = "";
  const std::string gmm = dir + "/" + name + ".gmm", csv = dir + "/" + name + ".csv";
  if (gmmrrt_model_load_file(gmm.c_str(), &model, err, sizeof err) != GMMRRT_OK) {
    std::fprintf(stderr, "FAIL %s: %s\n", gmm.c_str(), err);
    return 1;
  }
  const Mixture m = MixtureFromModel(model);
  std::ifstream in(csv);
  std::string line;
  if (!in || !std::getline(in, line)) {
    std::fprintf(stderr, "FAIL %s: cannot read\n", csv.c_str());
    return 1;
  }
  std::vector<double> values, expected;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string field;
    std::vector<double> row;
    while (std::getline(ss, field, ',')) row.push_back(std::strtod(field.c_str(), nullptr));
    if (static_cast<int>(row.size()) != m.dim + 1) {
      std::fprintf(stderr, "FAIL %s: row with %zu fields\n", csv.c_str(), row.size());
      return 1;
    }
    values.insert(values.end(), row.begin(), row.end() - 1);
    expected.push_back(row.back());
  }
  const Eigen::Index n = static_cast<Eigen::Index>(expected.size());
  if (n < 10) {
    std::fprintf(stderr, "FAIL %s: only %ld points\n", csv.c_str(), static_cast<long>(n));
    return 1;
  }
  const Eigen::MatrixXd pts = Eigen::Map<const Eigen::MatrixXd>(values.data(), m.dim, n);
  Eigen::VectorXd ll;
  LogDensity(m, pts, &ll);
  double worst = 0.0;
  int failures = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double err_rel = std::fabs(ll[i] - expected[i]) / std::max(1.0, std::fabs(expected[i]));
    worst = std::max(worst, err_rel);
    if (!(err_rel <= 1e-9)) {
      if (failures++ < 5)
        std::fprintf(stderr, "FAIL %s point %ld: %.17g vs expected %.17g\n", name.c_str(), static_cast<long>(i), ll[i],
                     expected[i]);
    }
  }
  std::printf("%-14s %4ld points, worst relative error %.3g\n", name.c_str(), static_cast<long>(n), worst);
  return failures ? 1 : 0;
}

}  // namespace

int main() {
  const char* data = std::getenv("GMMRRT_TEST_DATA_DIR");
  const std::string dir = std::string(data ? data : "tests/data") + "/model_vectors";
  struct stat st;
  if (stat(dir.c_str(), &st) != 0) {
    std::printf("FAIL: %s not found (checked in; made by tools/gen_model_vectors.py)\n", dir.c_str());
    return 1;
  }
  int failed = 0;
  for (const char* name : {"features_seam", "xy", "generic_d4"}) failed += CheckVector(dir, name);
  return failed ? 1 : 0;
}
