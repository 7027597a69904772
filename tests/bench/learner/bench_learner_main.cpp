// bench_learner_main.cpp - gmmrrt-bench-learner: times the learner's EM fit (FitMixture) or its
// BIC sweep (SweepBic) on the points of a CSV file, for the comparison with scikit-learn in
// gmmrrt_tools.bench.learner (paper Sect. 3 and 5.1). Only the fit is timed, not the
// reading: wall time (steady clock) and the process's CPU time (CLOCK_PROCESS_CPUTIME_ID: the
// summed CPU time of all threads). Prints one
// JSON object: the times, the learner's summary and the fitted mixture (weights, means,
// covariances), so the peer script scores both mixtures with one evaluator.
#include <getopt.h>
#include <time.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "gmmrrt_learner/bic.hpp"
#include "gmmrrt_learner/em.hpp"

using gmmrrt::learn::BicSweepResult;
using gmmrrt::learn::FitOptions;
using gmmrrt::learn::FitSummary;
using gmmrrt::learn::Mixture;
using gmmrrt::learn::Status;

namespace {

void Usage(FILE* f) {
  std::fprintf(f,
               "usage: gmmrrt-bench-learner --points FILE (--k K | --sweep KMIN:KMAX) [options]\n"
               "Times the learner's EM fit or BIC sweep on the points of FILE (CSV, one header line,\n"
               "one point per line, D numbers) and prints one JSON object.\n\n"
               "  -i, --points FILE       the points (no angle dimensions)\n"
               "  -k, --k K               fit K components\n"
               "  -b, --sweep KMIN:KMAX   BIC sweep over K = KMIN..KMAX\n"
               "  -s, --seed S            seed (default 1)\n"
               "  -t, --tol T             convergence tolerance on the mean log-likelihood (default: learner's)\n"
               "  -m, --max-iter N        EM iterations at most (default: learner's)\n"
               "  -r, --restarts N        k-means++ seedings (default: learner's)\n"
               "  -p, --screen-points N   sample size for screening the candidates (default: learner's;\n"
               "                          0 screens on all points)\n"
               "  -j, --threads N         E-step threads (default: learner's, the cores available)\n"
               "  -A, --accel M           squarem | none (default: learner's, squarem)\n"
               "  -F, --sweep-restarts N  sweep: k-means++ candidates of a K with split starts (default:\n"
               "                          learner's)\n"
               "  -R, --ready-line        after reading the points, write \"ready\" on stderr and wait for\n"
               "                          a line on stdin before timing (starts several runs together)\n"
               "  -h, --help              this help\n");
}

bool ParseLong(const char* s, long* out) {
  char* end = nullptr;
  errno = 0;
  long v = std::strtol(s, &end, 10);
  if (errno || end == s || *end) return false;
  *out = v;
  return true;
}

bool ParseDouble(const char* s, double* out) {
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(s, &end);
  if (errno || end == s || *end) return false;
  *out = v;
  return true;
}

// Reads the CSV into a D x N matrix; false with *error naming the file and line.
bool ReadPoints(const std::string& path, Eigen::MatrixXd* points, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = "cannot open '" + path + "'";
    return false;
  }
  std::string line;
  if (!std::getline(in, line)) {
    *error = "'" + path + "' is empty (expected a header line)";
    return false;
  }
  std::vector<double> values;
  long dim = -1, line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty()) continue;
    long count = 0;
    const char* p = line.c_str();
    for (;;) {
      char* end = nullptr;
      errno = 0;
      double v = std::strtod(p, &end);
      if (end == p || errno || !std::isfinite(v)) {
        *error = path + ":" + std::to_string(line_no) + ": not a finite number";
        return false;
      }
      values.push_back(v);
      ++count;
      if (*end == ',') {
        p = end + 1;
      } else if (*end == '\0' || *end == '\r') {
        break;
      } else {
        *error = path + ":" + std::to_string(line_no) + ": unexpected character after a number";
        return false;
      }
    }
    if (dim < 0) dim = count;
    if (count != dim) {
      *error = path + ":" + std::to_string(line_no) + ": " + std::to_string(count) + " values, expected " +
               std::to_string(dim);
      return false;
    }
  }
  if (dim < 1 || values.empty()) {
    *error = "'" + path + "' holds no points";
    return false;
  }
  const long n = static_cast<long>(values.size()) / dim;
  *points = Eigen::Map<const Eigen::MatrixXd>(values.data(), dim, n);
  return true;
}

void PrintMixture(const Mixture& m) {
  std::printf("\"weights\":[");
  for (int i = 0; i < m.k(); ++i) std::printf("%s%.17g", i ? "," : "", m.weights(i));
  std::printf("],\"means\":[");
  for (int i = 0; i < m.k(); ++i) {
    std::printf("%s[", i ? "," : "");
    for (int j = 0; j < m.dim; ++j) std::printf("%s%.17g", j ? "," : "", m.means(j, i));
    std::printf("]");
  }
  std::printf("],\"covariances\":[");
  for (int i = 0; i < m.k(); ++i) {
    const Eigen::MatrixXd cov = m.chol[i] * m.chol[i].transpose();
    std::printf("%s[", i ? "," : "");
    for (int r = 0; r < m.dim; ++r) {
      std::printf("%s[", r ? "," : "");
      for (int c = 0; c < m.dim; ++c) std::printf("%s%.17g", c ? "," : "", cov(r, c));
      std::printf("]");
    }
    std::printf("]");
  }
  std::printf("]");
}

// CLOCK_MONOTONIC [s]: one clock for every process of the machine, so that runs started
// together can be checked for overlap.
double MonotonicSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

// CPU time of this process [ms].
double ProcessCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

}  // namespace

int main(int argc, char** argv) {
  std::string points_path;
  long k = 0, k_min = 0, k_max = 0, seed = 1, max_iter = -1, restarts = -1, screen_points = -1, threads = -1,
       sweep_restarts = gmmrrt::learn::kBicFreshStarts;
  int accel = -1;  // -1: the learner's default
  bool ready_line = false;
  double tol = -1.0;
  static const option opts[] = {{"points", required_argument, nullptr, 'i'}, {"k", required_argument, nullptr, 'k'},
                                {"sweep", required_argument, nullptr, 'b'},  {"seed", required_argument, nullptr, 's'},
                                {"tol", required_argument, nullptr, 't'},    {"max-iter", required_argument, nullptr, 'm'},
                                {"restarts", required_argument, nullptr, 'r'}, {"help", no_argument, nullptr, 'h'},
                                {"screen-points", required_argument, nullptr, 'p'},
                                {"threads", required_argument, nullptr, 'j'}, {"accel", required_argument, nullptr, 'A'},
                                {"sweep-restarts", required_argument, nullptr, 'F'},
                                {"ready-line", no_argument, nullptr, 'R'},
                                {nullptr, 0, nullptr, 0}};
  int c;
  while ((c = getopt_long(argc, argv, "i:k:b:s:t:m:r:p:j:A:F:Rh", opts, nullptr)) != -1) {
    bool ok = true;
    switch (c) {
      case 'i': points_path = optarg; break;
      case 'k': ok = ParseLong(optarg, &k) && k >= 1; break;
      case 'b': ok = std::sscanf(optarg, "%ld:%ld", &k_min, &k_max) == 2 && k_min >= 1 && k_max >= k_min; break;
      case 's': ok = ParseLong(optarg, &seed) && seed >= 0; break;
      case 't': ok = ParseDouble(optarg, &tol) && tol > 0; break;
      case 'm': ok = ParseLong(optarg, &max_iter) && max_iter >= 1; break;
      case 'r': ok = ParseLong(optarg, &restarts) && restarts >= 1; break;
      case 'p': ok = ParseLong(optarg, &screen_points) && screen_points >= 0; break;
      case 'j': ok = ParseLong(optarg, &threads) && threads >= 1; break;
      case 'F': ok = ParseLong(optarg, &sweep_restarts) && sweep_restarts >= 1 && sweep_restarts <= 1000; break;
      case 'A':
        ok = std::string(optarg) == "squarem" || std::string(optarg) == "none";
        accel = std::string(optarg) == "squarem" ? 1 : 0;
        break;
      case 'R': ready_line = true; break;
      case 'h': Usage(stdout); return 0;
      default: Usage(stderr); return 2;
    }
    if (!ok) {
      std::fprintf(stderr, "gmmrrt-bench-learner: bad value '%s' for option -%c (see --help)\n", optarg, c);
      return 2;
    }
  }
  if (points_path.empty() || (k == 0) == (k_min == 0)) {
    std::fprintf(stderr, "gmmrrt-bench-learner: need --points and exactly one of --k or --sweep\n");
    Usage(stderr);
    return 2;
  }
  Eigen::MatrixXd points;
  std::string error;
  if (!ReadPoints(points_path, &points, &error)) {
    std::fprintf(stderr, "gmmrrt-bench-learner: %s\n", error.c_str());
    return 1;
  }
  FitOptions options;
  options.seed = static_cast<uint64_t>(seed);
  if (tol > 0) options.tolerance = tol;
  if (max_iter > 0) options.max_iterations = static_cast<int>(max_iter);
  if (restarts > 0) options.restarts = static_cast<int>(restarts);
  if (screen_points >= 0) options.screen_points = screen_points;
  if (k > 0) options.k = static_cast<int>(k);
  if (threads > 0) options.threads = static_cast<int>(threads);
  if (accel >= 0) options.accelerate = accel == 1;
  if (!options.IsValid(&error)) {
    std::fprintf(stderr, "gmmrrt-bench-learner: %s\n", error.c_str());
    return 2;
  }

  if (ready_line) {
    std::fprintf(stderr, "ready\n");
    std::fflush(stderr);
    char line[16];
    if (std::fgets(line, sizeof line, stdin) == nullptr) {
      std::fprintf(stderr, "gmmrrt-bench-learner: --ready-line: stdin closed before the start line\n");
      return 2;
    }
  }
  if (k > 0) {
    Mixture m;
    FitSummary s;
    const double cpu0 = ProcessCpuMs();
    const double start_s = MonotonicSeconds();
    const Status st = gmmrrt::learn::FitMixture(points, 0u, options, &m, &s);
    const double end_s = MonotonicSeconds();
    const double ms = 1e3 * (end_s - start_s);
    const double cpu_ms = ProcessCpuMs() - cpu0;
    if (!st.ok()) {
      std::fprintf(stderr, "gmmrrt-bench-learner: fit failed: %s\n", st.message.c_str());
      return 1;
    }
    std::printf("{\"mode\":\"fit\",\"n\":%ld,\"dim\":%ld,\"k\":%ld,\"seed\":%ld,\"tol\":%.17g,\"max_iter\":%d,"
                "\"restarts\":%d,\"threads\":%d,\"accelerate\":%s,\"fit_ms\":%.6f,\"fit_cpu_ms\":%.6f,\"mean_log_likelihood\":%.17g,\"iterations\":%d,\"converged\":%s,"
                "\"k_final\":%d,\"bic\":%.17g,\"fit_start_monotonic_s\":%.9f,\"fit_end_monotonic_s\":%.9f,"
                "\"prepare_ms\":%.6f,\"candidates_ms\":%.6f,\"converge_ms\":%.6f,",
                static_cast<long>(points.cols()), static_cast<long>(points.rows()), k, seed, options.tolerance,
                options.max_iterations, options.restarts, s.threads, options.accelerate ? "true" : "false", ms, cpu_ms, s.final_mean_log_likelihood, s.iterations,
                s.converged ? "true" : "false", s.k_final, s.bic, start_s, end_s, 1e3 * s.prepare_seconds,
                1e3 * s.candidates_seconds, 1e3 * s.converge_seconds);
    PrintMixture(m);
    std::printf("}\n");
    return 0;
  }
  BicSweepResult r;
  const double cpu0 = ProcessCpuMs();
  const double start_s = MonotonicSeconds();
  const Status st = gmmrrt::learn::SweepBic(points, 0u, options, static_cast<int>(k_min), static_cast<int>(k_max), &r,
                                                  nullptr, gmmrrt::learn::kBicStopAfterRises,
                                                  gmmrrt::learn::kBicSplitStarts, static_cast<int>(sweep_restarts));
  const double ms = 1e3 * (MonotonicSeconds() - start_s);
  const double cpu_ms = ProcessCpuMs() - cpu0;
  if (!st.ok()) {
    std::fprintf(stderr, "gmmrrt-bench-learner: sweep failed: %s\n", st.message.c_str());
    return 1;
  }
  std::printf("{\"mode\":\"sweep\",\"n\":%ld,\"dim\":%ld,\"k_min\":%ld,\"k_max\":%ld,\"seed\":%ld,\"tol\":%.17g,"
              "\"max_iter\":%d,\"restarts\":%d,\"sweep_restarts\":%ld,\"sweep_ms\":%.6f,\"sweep_cpu_ms\":%.6f,\"best_k\":%d,\"rows\":[",
              static_cast<long>(points.cols()), static_cast<long>(points.rows()), k_min, k_max, seed,
              options.tolerance, options.max_iterations, options.restarts, sweep_restarts, ms, cpu_ms, r.best_k);
  for (size_t i = 0; i < r.rows.size(); ++i)
    std::printf("%s{\"k\":%d,\"k_final\":%d,\"mean_log_likelihood\":%.17g,\"bic\":%.17g,\"iterations\":%d,"
                "\"converged\":%s,\"fresh_starts\":%d,\"split_starts\":%d}",
                i ? "," : "", r.rows[i].k, r.rows[i].k_final, r.rows[i].mean_log_likelihood, r.rows[i].bic,
                r.rows[i].iterations, r.rows[i].converged ? "true" : "false", r.rows[i].fresh_starts,
                r.rows[i].split_starts);
  std::string note;
  for (char ch : r.note)
    if (ch == '"' || ch == '\\') note += '\\', note += ch;
    else if (static_cast<unsigned char>(ch) >= 0x20) note += ch;
  std::printf("],\"note\":\"%s\"}\n", note.c_str());
  return 0;
}
