// bench_armadillo_main.cpp - gmmrrt-bench-armadillo: Armadillo's gmm_full (k-means seeding, then
// EM with full covariances, multi-threaded through OpenMP) timed on the points of a CSV file:
// the peer of gmmrrt-bench-learner in tools/gmmrrt_tools/bench/learner.py. Benchmark-only, built when Debian's
// libarmadillo-dev is installed. Armadillo's EM runs em_iter iterations and stops earlier only
// when the mean log-likelihood changes by less than machine epsilon, so the comparison is made
// at the same number of EM iterations (ours with --accel none and a tolerance of 1e-300, which
// no step reaches). Threads: OMP_NUM_THREADS. Prints one JSON object with the times, Armadillo's
// own mean log-likelihood and the mixture (for scoring by one evaluator).
#include <armadillo>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <time.h>

namespace {

double ProcessCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr,
                 "usage: gmmrrt-bench-armadillo POINTS.csv K KM_ITER EM_ITER SEED\n"
                 "POINTS.csv: one header line, then one point per line (D comma-separated numbers).\n");
    return 2;
  }
  const int k = std::atoi(argv[2]), km_iter = std::atoi(argv[3]), em_iter = std::atoi(argv[4]);
  const int seed = std::atoi(argv[5]);
  if (k < 1 || km_iter < 0 || em_iter < 1) {
    std::fprintf(stderr, "gmmrrt-bench-armadillo: bad K, KM_ITER or EM_ITER\n");
    return 2;
  }
  arma::mat rows;
  if (!rows.load(arma::csv_name(argv[1], arma::csv_opts::with_header))) {
    std::fprintf(stderr, "gmmrrt-bench-armadillo: cannot read %s as CSV with a header\n", argv[1]);
    return 1;
  }
  const arma::mat data = rows.t();  // D x N: Armadillo's gmm takes points as columns
  arma::arma_rng::set_seed(static_cast<arma::arma_rng::seed_type>(seed));
  arma::gmm_full model;
  const double cpu0 = ProcessCpuMs();
  const auto t0 = std::chrono::steady_clock::now();
  // The learner's seeding: k-means with centres spread over the data (random_spread), Euclidean
  // distance, var_floor 1e-10 (ours: 1e-8 x each dimension's variance, floor 1e-10).
  const bool ok = model.learn(data, static_cast<arma::uword>(k), arma::eucl_dist, arma::random_spread,
                              static_cast<arma::uword>(km_iter), static_cast<arma::uword>(em_iter), 1e-10, false);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const double cpu_ms = ProcessCpuMs() - cpu0;
  if (!ok) {
    std::fprintf(stderr, "gmmrrt-bench-armadillo: gmm_full::learn failed\n");
    return 1;
  }
  const char* omp = std::getenv("OMP_NUM_THREADS");
  std::printf("{\"n\":%llu,\"dim\":%llu,\"k\":%d,\"km_iter\":%d,\"em_iter\":%d,\"seed\":%d,\"omp_num_threads\":\"%s\","
              "\"fit_ms\":%.6f,\"fit_cpu_ms\":%.6f,\"mean_log_likelihood\":%.17g,\"weights\":[",
              static_cast<unsigned long long>(data.n_cols), static_cast<unsigned long long>(data.n_rows), k, km_iter,
              em_iter, seed, omp ? omp : "", ms, cpu_ms, model.avg_log_p(data));
  for (arma::uword i = 0; i < model.n_gaus(); ++i) std::printf("%s%.17g", i ? "," : "", model.hefts(i));
  std::printf("],\"means\":[");
  for (arma::uword i = 0; i < model.n_gaus(); ++i) {
    std::printf("%s[", i ? "," : "");
    for (arma::uword j = 0; j < model.n_dims(); ++j) std::printf("%s%.17g", j ? "," : "", model.means(j, i));
    std::printf("]");
  }
  std::printf("],\"covariances\":[");
  for (arma::uword i = 0; i < model.n_gaus(); ++i) {
    std::printf("%s[", i ? "," : "");
    for (arma::uword r = 0; r < model.n_dims(); ++r) {
      std::printf("%s[", r ? "," : "");
      for (arma::uword c = 0; c < model.n_dims(); ++c) std::printf("%s%.17g", c ? "," : "", model.fcovs(r, c, i));
      std::printf("]");
    }
    std::printf("]");
  }
  std::printf("]}\n");
  return 0;
}
