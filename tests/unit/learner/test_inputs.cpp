// test_inputs.cpp - learner.inputs: the features CSV reader, --angle-dims parsing, JSON mixture
// import (both shapes, non-positive-definite covariance, unknown task), and episodes to (d,
// theta) / (s, x', y') features through features.h, with selection by task / homotopy / split.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

#include "gmmrrt_learner/episode_features.hpp"
#include "gmmrrt_learner/features_csv.hpp"
#include "gmmrrt_learner/json_import.hpp"

// cmocka last: its fail() macro would clash with the standard library.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
extern "C" {
#include <cmocka.h>
}

using namespace gmmrrt::learn;

namespace {

std::string TempFile(const std::string& content) {
  char path[] = "/tmp/gmmrrt_learner_test_XXXXXX";
  const int fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  std::ofstream(path) << content;
  return path;
}

void test_csv_reads_rows_and_skips_header_and_comments(void** state) {
  (void)state;
  const std::string p = TempFile("a,b\n# comment\n1,2\n\n3.5, -4e-1\n");
  Eigen::MatrixXd x;
  assert_true(ReadFeaturesCsv(p, &x).ok());
  assert_int_equal(x.rows(), 2);
  assert_int_equal(x.cols(), 2);
  assert_true(x(0, 1) == 3.5 && x(1, 1) == -0.4);
  std::remove(p.c_str());
}

void test_csv_errors_name_file_and_line(void** state) {
  (void)state;
  struct Case {
    const char* text;
    const char* needle;
    StatusCode code;
  } cases[] = {
      {"1,2\n3,nan\n", ":2: 'nan' is not a finite number", StatusCode::kBadInput},
      {"nan,1\n", ":1: 'nan' is not a finite number", StatusCode::kBadInput},
      {"1,2\n3,inf\n", ":2:", StatusCode::kBadInput},
      {"1,2\n3\n", ":2: 1 columns, expected 2", StatusCode::kBadInput},
      {"1,2\n3,x\n", ":2: 'x' is not a number", StatusCode::kBadInput},
      {"1,2\n3,\n", ":2: empty field", StatusCode::kBadInput},
      {"1,2,3,4,5,6,7,8,9\n", "at most 8", StatusCode::kBadInput},
      {"# nothing\n", "no data rows", StatusCode::kNotEnoughData},
  };
  for (const Case& c : cases) {
    const std::string p = TempFile(c.text);
    Eigen::MatrixXd x;
    const Status s = ReadFeaturesCsv(p, &x);
    if (s.message.find(c.needle) == std::string::npos || s.message.find(p) == std::string::npos)
      fail_msg("'%s': got '%s'", c.text, s.message.c_str());
    assert_int_equal(static_cast<int>(s.code), static_cast<int>(c.code));
    std::remove(p.c_str());
  }
  Eigen::MatrixXd x;
  assert_int_equal(static_cast<int>(ReadFeaturesCsv("/nonexistent/f.csv", &x).code),
                   static_cast<int>(StatusCode::kIoError));
}

void test_angle_dims(void** state) {
  (void)state;
  uint32_t mask = 0;
  assert_true(ParseAngleDims("1,3", 4, &mask).ok());
  assert_int_equal(mask, 0x5u);
  assert_false(ParseAngleDims("0", 4, &mask).ok());
  assert_false(ParseAngleDims("5", 4, &mask).ok());
  assert_false(ParseAngleDims("1,,2", 4, &mask).ok());
  assert_false(ParseAngleDims("a", 4, &mask).ok());
}

void test_json_plain_mixture_is_factorised(void** state) {
  (void)state;
  const std::string p = TempFile(
      R"({"priors": [0.25, 0.75], "means": [[1, 3.5], [2, -1]],
          "covs": [[[4, 2], [2, 5]], [[1, 0], [0, 0.25]]]})");
  JsonImportOptions o;
  o.angle_mask = 1u << 1;
  Mixture m;
  const Status s = ImportJsonMixture(p, o, &m);
  assert_true(s.ok());
  assert_int_equal(m.k(), 2);
  // Sigma_0 = [[4, 2], [2, 5]] -> L = [[2, 0], [1, 2]].
  assert_true(std::fabs(m.chol[0](0, 0) - 2.0) < 1e-15 && std::fabs(m.chol[0](1, 0) - 1.0) < 1e-15 &&
              std::fabs(m.chol[0](1, 1) - 2.0) < 1e-15);
  assert_true(std::fabs(m.means(1, 0) - (3.5 - 2 * M_PI)) < 1e-12);  // theta wrapped
  std::remove(p.c_str());
}

void test_json_errors(void** state) {
  (void)state;
  struct Case {
    const char* text;
    const char* needle;
  } cases[] = {
      {R"({"priors": [1], "means": [[0, 0]], "covs": [[[1, 2], [2, 1]]]})", "component 0: covariance is not positive definite"},
      {R"({"priors": [1], "means": [[0, 0]], "covs": [[[1, 0.5], [0, 1]]]})", "not symmetric"},
      {R"({"priors": [0.5], "means": [[0, 0]], "covs": [[[1, 0], [0, 1]]]})", "weights sum to"},
      {R"({"priors": [1], "means": [[0, 0]]})", "\"covs\""},
      {R"({"sets": {"tasks": {"1-front": {"components": []}}}})", "no task \"2-x\" in set \"tasks\" (known: 1-front)"},
      {"{not json", "not valid JSON"},
  };
  for (const Case& c : cases) {
    const std::string p = TempFile(c.text);
    JsonImportOptions o;
    o.task_name = "2-x";
    Mixture m;
    const Status s = ImportJsonMixture(p, o, &m);
    assert_false(s.ok());
    if (s.message.find(c.needle) == std::string::npos) fail_msg("'%s': got '%s'", c.text, s.message.c_str());
    std::remove(p.c_str());
  }
}

Episode MakeEpisode(const std::string& id, int task, int homotopy, int n) {
  Episode e;
  e.id = id;
  e.task = task;
  e.homotopy = homotopy;
  for (int i = 0; i < n; ++i) {
    // Person at (1, 1) facing +y; robot walks along x = 1 + 2 (in front of the person... no:
    // the person faces +y, so the robot at (1, 1 + 2) is straight in front.
    PoseSample s{0.1 * i, 1.0 - 1.0 + i * 0.0, 3.0, 0.0, 1.0, 1.0, M_PI / 2};
    s.robot_x = 1.0 - i * 0.5;  // moves to the person's left (their left is -x when facing +y)
    e.samples.push_back(s);
  }
  return e;
}

void test_episode_features_and_selection(void** state) {
  (void)state;
  std::vector<Episode> all = {MakeEpisode("a", GMMRRT_TASK_AVOID, GMMRRT_HOMOTOPY_LEFT, 3),
                              MakeEpisode("b", GMMRRT_TASK_AVOID, GMMRRT_HOMOTOPY_RIGHT, 2),
                              MakeEpisode("c", GMMRRT_TASK_APPROACH, GMMRRT_HOMOTOPY_FRONTAL, 4)};
  EpisodeFilter f;
  f.task = GMMRRT_TASK_AVOID;
  f.homotopy = GMMRRT_HOMOTOPY_LEFT;
  std::vector<const Episode*> chosen;
  assert_true(SelectEpisodes(all, f, &chosen).ok());
  assert_int_equal(chosen.size(), 1);
  Eigen::MatrixXd x;
  uint32_t mask = 0;
  assert_true(EpisodeFeatures(chosen, GMMRRT_MODEL_KIND_FEATURES, &x, &mask).ok());
  assert_int_equal(mask, 2u);
  assert_int_equal(x.cols(), 3);
  assert_true(std::fabs(x(0, 0) - 2.0) < 1e-12 && std::fabs(x(1, 0)) < 1e-12);  // straight ahead
  assert_true(x(1, 1) > 0.0);                                                  // on the left
  assert_true(EpisodeFeatures(chosen, GMMRRT_MODEL_KIND_XY, &x, &mask).ok());
  assert_int_equal(mask, 0u);
  assert_true(x(0, 0) == 0.0 && x(0, 1) == 0.5 && x(0, 2) == 1.0);  // progress s
  assert_true(std::fabs(x(1, 0) - 2.0) < 1e-12 && std::fabs(x(2, 0)) < 1e-12);

  f.homotopy = GMMRRT_HOMOTOPY_ALL;
  std::map<std::string, std::string> split = {{"a", "train"}, {"b", "test"}, {"c", "train"}};
  f.split_by_episode = &split;
  f.split = "test";
  assert_true(SelectEpisodes(all, f, &chosen).ok());
  assert_int_equal(chosen.size(), 1);
  assert_string_equal(chosen[0]->id.c_str(), "b");
  split.erase("a");
  const Status missing = SelectEpisodes(all, f, &chosen);
  assert_int_equal(static_cast<int>(missing.code), static_cast<int>(StatusCode::kBadInput));
  assert_true(missing.message.find("'a'") != std::string::npos);
  f.split_by_episode = nullptr;
  f.homotopy = GMMRRT_HOMOTOPY_FRONTAL;
  assert_int_equal(static_cast<int>(SelectEpisodes(all, f, &chosen).code),
                   static_cast<int>(StatusCode::kNotEnoughData));
  int task = 0;
  assert_false(ParseTask("walk", &task).ok());
  assert_false(ParseHomotopy("up", &task).ok());
}

// labels.hpp: every name parses back to its value (one table read both ways); an unknown word
// is refused naming the known ones and leaves the output alone.
void test_task_and_homotopy_names_round_trip(void** state) {
  (void)state;
  for (int t : {GMMRRT_TASK_AVOID, GMMRRT_TASK_APPROACH}) {
    int back = -1;
    assert_true(ParseTask(TaskName(t), &back).ok());
    assert_int_equal(back, t);
  }
  for (int h : {GMMRRT_HOMOTOPY_ALL, GMMRRT_HOMOTOPY_LEFT, GMMRRT_HOMOTOPY_RIGHT, GMMRRT_HOMOTOPY_FRONTAL}) {
    int back = -1;
    assert_true(ParseHomotopy(HomotopyName(h), &back).ok());
    assert_int_equal(back, h);
  }
  assert_string_equal(TaskName(GMMRRT_TASK_NONE), "none");
  assert_string_equal(TaskName(7), "unknown");
  assert_string_equal(HomotopyName(-1), "unknown");
  int out = 42;
  const Status bad = ParseHomotopy("sideways", &out);
  assert_int_equal(static_cast<int>(bad.code), static_cast<int>(StatusCode::kInvalidArgument));
  assert_string_equal(bad.message.c_str(), "unknown homotopy 'sideways' (known: all, left, right, frontal)");
  assert_int_equal(out, 42);
  assert_string_equal(ParseTask("dance", &out).message.c_str(), "unknown task 'dance' (known: avoid, approach)");
}

void test_xy_components_sorted_by_progress(void** state) {
  (void)state;
  Mixture m;
  m.dim = 3;
  m.weights = Eigen::Vector3d(0.2, 0.3, 0.5);
  m.means.resize(3, 3);
  m.means << 0.9, 0.1, 0.5, 1, 2, 3, 4, 5, 6;
  m.chol = {Eigen::Matrix3d::Identity(), 2 * Eigen::Matrix3d::Identity(), 3 * Eigen::Matrix3d::Identity()};
  SortComponentsByProgress(&m);
  assert_true(m.means(0, 0) == 0.1 && m.means(0, 1) == 0.5 && m.means(0, 2) == 0.9);
  assert_true(m.weights[0] == 0.3 && m.chol[0](0, 0) == 2.0 && m.means(1, 2) == 1.0);
}

}  // namespace

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_csv_reads_rows_and_skips_header_and_comments),
      cmocka_unit_test(test_csv_errors_name_file_and_line),
      cmocka_unit_test(test_angle_dims),
      cmocka_unit_test(test_json_plain_mixture_is_factorised),
      cmocka_unit_test(test_json_errors),
      cmocka_unit_test(test_episode_features_and_selection),
      cmocka_unit_test(test_task_and_homotopy_names_round_trip),
      cmocka_unit_test(test_xy_components_sorted_by_progress),
  };
  return cmocka_run_group_tests(tests, nullptr, nullptr);
}
