// cli_common.cpp - shared parts of the gmmrrt-learn subcommands (see cli_common.hpp).
#include "cli_common.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <vector>

#include "gmmrrt/model_file.h"
#include "gmmrrt_learner/background.hpp"
#include "gmmrrt_learner/demo_io.hpp"
#include "gmmrrt_learner/episode_features.hpp"
#include "gmmrrt_learner/features_csv.hpp"

namespace gmmrrt {
namespace learn {
namespace cli {

int Fail(const char* cmd, const std::string& message) {
  std::fprintf(stderr, "gmmrrt-learn %s: error: %s\n", cmd, message.c_str());
  return kExitError;
}

int UsageError(const char* cmd, const std::string& message) {
  std::fprintf(stderr, "gmmrrt-learn %s: error: %s\n(see gmmrrt-learn %s --help)\n", cmd, message.c_str(), cmd);
  return kExitUsage;
}

bool ParseInt(const std::string& text, long min, long max, long* out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE || v < min || v > max) return false;
  *out = v;
  return true;
}

bool ParseUint64(const std::string& text, uint64_t* out) {
  if (text.empty() || text[0] == '-' || text[0] == '+') return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (*end != '\0' || errno == ERANGE) return false;
  *out = static_cast<uint64_t>(v);
  return true;
}

bool ParseDouble(const std::string& text, double* out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno == ERANGE || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

namespace {
void PrintWarnings(const std::vector<std::string>& warnings, bool quiet) {
  if (quiet) return;
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}
}  // namespace

Status LoadPoints(const char* cmd, const DataSpec& spec, Eigen::MatrixXd* points, uint32_t* angle_mask) {
  if (!spec.features_csv.empty()) {
    Status s = ReadFeaturesCsv(spec.features_csv, points);
    if (!s.ok()) return s;
    if (spec.angle_mask != 0u && points->rows() < 32 && (spec.angle_mask >> points->rows()) != 0u)
      return Status::Error(StatusCode::kInvalidArgument,
                           "--angle-dims names a dimension beyond the " + std::to_string(points->rows()) +
                               " columns of " + spec.features_csv);
    *angle_mask = spec.angle_mask;
    if (!spec.quiet)
      std::fprintf(stderr, "gmmrrt-learn %s: %s: %ld points, D = %ld\n", cmd, spec.features_csv.c_str(),
                   static_cast<long>(points->cols()), static_cast<long>(points->rows()));
    return Status::Ok();
  }
  std::map<std::string, std::string> split_by_episode;
  for (const std::string& index : spec.indexes) {
    ReadResult r = ReadSplitIndex(index, &split_by_episode);
    if (!r.ok) return Status::Error(StatusCode::kBadInput, r.error);
    PrintWarnings(r.warnings, spec.quiet);
  }
  std::vector<Episode> episodes;
  for (const std::string& input : spec.inputs) {
    ReadResult r = ReadEpisodes(input, &episodes);
    if (!r.ok) return Status::Error(StatusCode::kBadInput, r.error);
    PrintWarnings(r.warnings, spec.quiet);
  }
  EpisodeFilter filter;
  filter.task = spec.task;
  filter.homotopy = spec.homotopy;
  if (!spec.split.empty()) {
    filter.split_by_episode = &split_by_episode;
    filter.split = spec.split;
  }
  std::vector<const Episode*> chosen;
  Status s = SelectEpisodes(episodes, filter, &chosen);
  if (!s.ok()) return s;
  std::vector<Episode> lines;
  if (spec.straight_lines) {
    lines = StraightLineEpisodes(chosen);
    for (size_t i = 0; i < lines.size(); ++i) chosen[i] = &lines[i];
  }
  s = EpisodeFeatures(chosen, spec.kind, points, angle_mask);
  if (!s.ok()) return s;
  if (!spec.quiet)
    std::fprintf(stderr, "gmmrrt-learn %s: %zu of %zu episodes (task %s, homotopy %s%s%s): %ld points\n", cmd,
                 chosen.size(), episodes.size(), TaskName(spec.task), HomotopyName(spec.homotopy),
                 spec.split.empty() ? "" : ", split ", spec.split.c_str(), static_cast<long>(points->cols()));
  return Status::Ok();
}

std::string DescribeData(const DataSpec& spec) {
  if (!spec.features_csv.empty()) return spec.features_csv;
  std::string files;
  for (const std::string& f : spec.inputs) files += (files.empty() ? "" : ", ") + f;
  files += std::string(" (task ") + TaskName(spec.task) + ", homotopy " + HomotopyName(spec.homotopy);
  if (!spec.split.empty()) files += ", split " + spec.split;
  return files + ")";
}

Status LoadModel(const std::string& path, gmmrrt_model_t* model, std::string* provenance) {
  auto scratch = std::make_unique<gmmrrt_model_t>();
  char err[512] = "";
  std::vector<char> text(provenance != nullptr ? GMMRRT_MAX_PROVENANCE_BYTES + 1 : 0);
  size_t text_len = 0;
  const gmmrrt_status_t st =
      gmmrrt_model_load_file_provenance(path.c_str(), scratch.get(), provenance ? text.data() : nullptr, text.size(),
                                        &text_len, err, sizeof err);
  if (st != GMMRRT_OK)
    return Status::Error(st == GMMRRT_ERR_IO ? StatusCode::kIoError : StatusCode::kBadModel,
                         err[0] ? std::string(err) : path + ": " + gmmrrt_status_str(st));
  *model = *scratch;
  if (provenance != nullptr) provenance->assign(text.data(), text_len);
  return Status::Ok();
}

Status BackgroundK(const std::string& path, int* k) {
  auto model = std::make_unique<gmmrrt_model_t>();
  auto background = std::make_unique<gmmrrt_model_t>();
  int has = 0;
  char err[512] = "";
  const gmmrrt_status_t st = gmmrrt_model_load_file_background(path.c_str(), model.get(), background.get(), &has,
                                                               nullptr, 0, nullptr, err, sizeof err);
  if (st != GMMRRT_OK)
    return Status::Error(st == GMMRRT_ERR_IO ? StatusCode::kIoError : StatusCode::kBadModel,
                         err[0] ? std::string(err) : path + ": " + gmmrrt_status_str(st));
  *k = has ? background->k : 0;
  return Status::Ok();
}

Status SaveModel(const std::string& path, const gmmrrt_model_t& model, const std::string* provenance,
                 const gmmrrt_model_t* background) {
  char err[512] = "";
  const gmmrrt_status_t st =
      gmmrrt_model_save_file_background(path.c_str(), &model, background, provenance ? provenance->data() : nullptr,
                                        provenance ? provenance->size() : 0, err, sizeof err);
  if (st != GMMRRT_OK)
    return Status::Error(st == GMMRRT_ERR_IO ? StatusCode::kIoError : StatusCode::kBadModel,
                         err[0] ? std::string(err) : path + ": " + gmmrrt_status_str(st));
  return Status::Ok();
}

}  // namespace cli
}  // namespace learn
}  // namespace gmmrrt
