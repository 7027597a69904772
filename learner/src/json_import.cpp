// json_import.cpp - JSON mixtures (priors, means, covariances) to a validated Mixture with
// Cholesky factors (see json_import.hpp; paper eq. 1, model.h factor convention).
#include "gmmrrt_learner/json_import.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

namespace gmmrrt {
namespace learn {

namespace {

using nlohmann::json;

Status Bad(const std::string& path, const std::string& why) {
  return Status::Error(StatusCode::kBadInput, path + ": " + why);
}

std::string Keys(const json& obj) {
  std::string s;
  for (auto it = obj.begin(); it != obj.end(); ++it) s += (s.empty() ? "" : ", ") + it.key();
  return s;
}

bool ToVector(const json& j, std::vector<double>* v) {
  if (!j.is_array()) return false;
  v->clear();
  for (const json& e : j) {
    if (!e.is_number()) return false;
    v->push_back(e.get<double>());
  }
  return true;
}

}  // namespace

Status ImportJsonMixture(const std::string& path, const JsonImportOptions& options, Mixture* out,
                         std::string* note) {
  if (note) note->clear();
  int mixtures_in_task = 1;
  std::ifstream in(path);
  if (!in) return Status::Error(StatusCode::kIoError, path + ": cannot open: " + std::strerror(errno));
  json doc = json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) return Bad(path, "not valid JSON");
  if (!doc.is_object()) return Bad(path, "top level is not a JSON object");

  std::vector<double> weights;
  std::vector<std::vector<double>> means;
  std::vector<std::vector<std::vector<double>>> covs;
  std::string where;
  auto read_cov = [&](const json& j, std::vector<std::vector<double>>* c) {
    if (!j.is_array()) return false;
    c->clear();
    for (const json& row : j) {
      std::vector<double> r;
      if (!ToVector(row, &r)) return false;
      c->push_back(r);
    }
    return true;
  };
  if (doc.contains("priors")) {
    where = "";
    if (!ToVector(doc["priors"], &weights)) return Bad(path, "\"priors\" is not an array of numbers");
    if (!doc.contains("means") || !doc["means"].is_array() || !doc.contains("covs") || !doc["covs"].is_array())
      return Bad(path, "\"priors\" needs \"means\" and \"covs\" arrays next to it");
    for (const json& m : doc["means"]) {
      std::vector<double> v;
      if (!ToVector(m, &v)) return Bad(path, "\"means\" entries must be arrays of numbers");
      means.push_back(v);
    }
    for (const json& c : doc["covs"]) {
      std::vector<std::vector<double>> cv;
      if (!read_cov(c, &cv)) return Bad(path, "\"covs\" entries must be arrays of arrays of numbers");
      covs.push_back(cv);
    }
  } else if (doc.contains("sets") && doc["sets"].is_object()) {
    const json& sets = doc["sets"];
    if (!sets.contains(options.set))
      return Bad(path, "no set \"" + options.set + "\" (known: " + Keys(sets) + ")");
    const json& tasks = sets[options.set];
    if (!tasks.is_object()) return Bad(path, "set \"" + options.set + "\" is not an object");
    if (options.task_name.empty())
      return Bad(path, "a task name is needed (--task-name; known: " + Keys(tasks) + ")");
    if (!tasks.contains(options.task_name))
      return Bad(path, "no task \"" + options.task_name + "\" in set \"" + options.set +
                           "\" (known: " + Keys(tasks) + ")");
    const json& task = tasks[options.task_name];
    if (!task.is_object() || !task.contains("components") || !task["components"].is_array())
      return Bad(path, "task \"" + options.task_name + "\" has no \"components\" array");
    // A two-homotopy task concatenates two mixtures, each with priors summing to 1.
    if (task.contains("two_homotopies") && task["two_homotopies"].is_boolean() && task["two_homotopies"].get<bool>())
      mixtures_in_task = 2;
    int i = 0;
    for (const json& c : task["components"]) {
      const std::string comp = "task \"" + options.task_name + "\" component " + std::to_string(i++);
      if (!c.is_object() || !c.contains("weight") || !c["weight"].is_number())
        return Bad(path, comp + ": no numeric \"weight\"");
      std::vector<double> v;
      std::vector<std::vector<double>> cv;
      if (!c.contains("mean") || !ToVector(c["mean"], &v)) return Bad(path, comp + ": no numeric \"mean\" array");
      if (!c.contains("cov") || !read_cov(c["cov"], &cv)) return Bad(path, comp + ": no numeric \"cov\" matrix");
      weights.push_back(c["weight"].get<double>());
      means.push_back(v);
      covs.push_back(cv);
    }
  } else {
    return Bad(path, "neither a plain mixture (\"priors\", \"means\", \"covs\") nor a set of tasks (\"sets\")");
  }

  const int k = static_cast<int>(weights.size());
  if (k < 1 || k > GMMRRT_MAX_K)
    return Bad(path, std::to_string(k) + " components, expected 1.." + std::to_string(GMMRRT_MAX_K));
  if (static_cast<int>(means.size()) != k || static_cast<int>(covs.size()) != k)
    return Bad(path, "priors, means and covs differ in length");
  const int d = static_cast<int>(means[0].size());
  if (d < 1 || d > GMMRRT_MAX_DIM)
    return Bad(path, "dimension " + std::to_string(d) + " outside 1.." + std::to_string(GMMRRT_MAX_DIM));
  if (d < 32 && (options.angle_mask >> d) != 0u)
    return Status::Error(StatusCode::kInvalidArgument, path + ": angle dimension beyond D = " + std::to_string(d));

  Mixture m;
  m.dim = d;
  m.angle_mask = options.angle_mask;
  m.weights.resize(k);
  m.means.resize(d, k);
  m.chol.resize(k);
  double sum = 0.0;
  for (int i = 0; i < k; ++i) {
    const std::string comp = "component " + std::to_string(i);
    if (!std::isfinite(weights[i]) || weights[i] <= 0.0)
      return Status::Error(StatusCode::kBadModel, path + ": " + comp + ": weight is not a positive number");
    sum += weights[i];
    if (static_cast<int>(means[i].size()) != d)
      return Bad(path, comp + ": mean has " + std::to_string(means[i].size()) + " entries, expected " + std::to_string(d));
    if (static_cast<int>(covs[i].size()) != d)
      return Bad(path, comp + ": covariance is not " + std::to_string(d) + " x " + std::to_string(d));
    Eigen::MatrixXd cov(d, d);
    for (int r = 0; r < d; ++r) {
      if (static_cast<int>(covs[i][r].size()) != d)
        return Bad(path, comp + ": covariance is not " + std::to_string(d) + " x " + std::to_string(d));
      for (int c = 0; c < d; ++c) cov(r, c) = covs[i][r][c];
      m.means(r, i) = means[i][r];
    }
    if (!cov.allFinite() || !m.means.col(i).allFinite())
      return Status::Error(StatusCode::kBadModel, path + ": " + comp + ": mean or covariance is not finite");
    const double scale = cov.cwiseAbs().maxCoeff();
    if ((cov - cov.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale)
      return Status::Error(StatusCode::kBadModel, path + ": " + comp + ": covariance is not symmetric");
    Eigen::LLT<Eigen::MatrixXd> llt(cov);
    if (llt.info() != Eigen::Success || !(llt.matrixL().toDenseMatrix().diagonal().array() > 0.0).all())
      return Status::Error(StatusCode::kBadModel, path + ": " + comp + ": covariance is not positive definite");
    m.chol[i] = llt.matrixL().toDenseMatrix();
    m.weights[i] = weights[i];
  }
  if (std::fabs(sum - mixtures_in_task) > 1e-6 * mixtures_in_task)
    return Status::Error(StatusCode::kBadModel, path + ": weights sum to " + std::to_string(sum) + ", not " +
                                                    std::to_string(mixtures_in_task));
  if (mixtures_in_task > 1 && note)
    *note = "task \"" + options.task_name + "\" holds one mixture per homotopy (priors sum to " +
            std::to_string(mixtures_in_task) + "); imported as their equal-weight union (homotopy all)";
  m.weights /= sum;
  WrapAngleRows(m.angle_mask, &m.means);
  Status s = ValidateMixture(m);
  if (!s.ok()) return Status::Error(StatusCode::kBadModel, path + ": " + s.message);
  *out = std::move(m);
  return Status::Ok();
}

}  // namespace learn
}  // namespace gmmrrt
