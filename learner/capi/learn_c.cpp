// learn_c.cpp - the C API of gmmrrt_learn.h over FitMixture (em.hpp) and the C core's model,
// density, sampler and file code.
#include "gmmrrt_learn.h"

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "gmmrrt/gmm.h"
#include "gmmrrt/model.h"
#include "gmmrrt/model_file.h"
#include "gmmrrt/rng.h"
#include "gmmrrt_learner/em.hpp"
#include "gmmrrt_learner/mixture.hpp"

struct gmmrrt_learn_model {
  gmmrrt_model_t model;  // prepared (derived fields filled): ready for density and sampling
};

namespace {

gmmrrt_status_t SetError(gmmrrt_status_t st, char* err, size_t errcap, const std::string& why) {
  if (err != nullptr && errcap > 0) std::snprintf(err, errcap, "%s", why.c_str());
  return st;
}

}  // namespace

extern "C" {

gmmrrt_learn_options_t gmmrrt_learn_options_default(void) {
  const gmmrrt::learn::FitOptions d;
  gmmrrt_learn_options_t o;
  o.k = d.k;
  o.seed = d.seed;
  o.threads = d.threads;
  o.max_iter = d.max_iterations;
  o.tol = d.tolerance;
  o.restarts = d.restarts;
  o.accelerate = d.accelerate ? 1 : 0;
  return o;
}

gmmrrt_status_t gmmrrt_learn_fit(const double* points, int64_t n, int32_t dim, uint32_t angle_mask,
                                 const gmmrrt_learn_options_t* options, gmmrrt_learn_model_t** out,
                                 gmmrrt_learn_summary_t* summary, char* err, size_t errcap) {
  if (points == nullptr || options == nullptr || out == nullptr || n < 1 || dim < 1 || dim > GMMRRT_MAX_DIM)
    return SetError(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "NULL argument, n < 1 or dim outside 1..GMMRRT_MAX_DIM");
  gmmrrt::learn::FitOptions o;
  o.k = options->k;
  o.seed = options->seed;
  o.threads = options->threads;
  o.max_iterations = options->max_iter;
  o.tolerance = options->tol;
  o.restarts = options->restarts;
  o.accelerate = options->accelerate != 0;
  std::string why;
  if (!o.IsValid(&why)) return SetError(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, why);
  Eigen::MatrixXd x(dim, n);  // D x N, as FitMixture takes them
  for (int64_t p = 0; p < n; ++p)
    for (int32_t j = 0; j < dim; ++j) x(j, p) = points[p * dim + j];
  gmmrrt::learn::Mixture m;
  gmmrrt::learn::FitSummary s;
  gmmrrt::learn::Status st = gmmrrt::learn::FitMixture(x, angle_mask, o, &m, &s);
  if (!st.ok()) return SetError(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, st.message);
  auto handle = std::make_unique<gmmrrt_learn_model>();
  st = gmmrrt::learn::MixtureToModel(m, GMMRRT_MODEL_KIND_GENERIC, GMMRRT_TASK_NONE, GMMRRT_HOMOTOPY_ALL,
                                     GMMRRT_MODEL_DEFAULT_DELTA, &handle->model);
  if (!st.ok()) return SetError(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, st.message);
  char why_c[256] = "";
  const gmmrrt_status_t pst = gmmrrt_model_prepare(&handle->model, why_c, sizeof why_c);
  if (pst != GMMRRT_OK) return SetError(pst, err, errcap, why_c);
  if (summary != nullptr) {
    summary->mean_log_likelihood = s.final_mean_log_likelihood;
    summary->bic = s.bic;
    summary->iterations = s.iterations;
    summary->converged = s.converged ? 1 : 0;
    summary->k_final = s.k_final;
  }
  *out = handle.release();
  return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_learn_load(const char* path, gmmrrt_learn_model_t** out, char* err, size_t errcap) {
  if (path == nullptr || out == nullptr) return SetError(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "NULL argument");
  auto handle = std::make_unique<gmmrrt_learn_model>();
  const gmmrrt_status_t st = gmmrrt_model_load_file(path, &handle->model, err, errcap);
  if (st != GMMRRT_OK) return st;
  *out = handle.release();
  return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_learn_save(const gmmrrt_learn_model_t* model, const char* path, char* err, size_t errcap) {
  if (path == nullptr || model == nullptr) return SetError(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "NULL argument");
  return gmmrrt_model_save_file(path, &model->model, err, errcap);
}

void gmmrrt_learn_free(gmmrrt_learn_model_t* model) { delete model; }

int32_t gmmrrt_learn_dim(const gmmrrt_learn_model_t* model) { return model ? model->model.dim : 0; }
int32_t gmmrrt_learn_k(const gmmrrt_learn_model_t* model) { return model ? model->model.k : 0; }
uint32_t gmmrrt_learn_angle_mask(const gmmrrt_learn_model_t* model) { return model ? model->model.angle_mask : 0u; }

gmmrrt_status_t gmmrrt_learn_component(const gmmrrt_learn_model_t* model, int32_t i, double* weight, double* mean,
                                       double* covariance) {
  if (model == nullptr || weight == nullptr || mean == nullptr || covariance == nullptr || i < 0 ||
      i >= model->model.k)
    return GMMRRT_ERR_INVALID_ARGUMENT;
  const gmmrrt::learn::Mixture m = gmmrrt::learn::MixtureFromModel(model->model);
  const int d = m.dim;
  *weight = m.weights[i];
  const Eigen::MatrixXd cov = m.chol[i] * m.chol[i].transpose();
  for (int r = 0; r < d; ++r) {
    mean[r] = m.means(r, i);
    for (int c = 0; c < d; ++c) covariance[r * d + c] = cov(r, c);
  }
  return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_learn_log_density(const gmmrrt_learn_model_t* model, const double* points, int64_t n,
                                         double* out) {
  if (model == nullptr || points == nullptr || out == nullptr || n < 0) return GMMRRT_ERR_INVALID_ARGUMENT;
  const int32_t d = model->model.dim;
  for (int64_t p = 0; p < n; ++p) out[p] = gmmrrt_gmm_log_density(&model->model, points + p * d);
  return GMMRRT_OK;
}

gmmrrt_status_t gmmrrt_learn_sample(const gmmrrt_learn_model_t* model, uint64_t seed, int64_t n, double* out,
                                    int32_t* labels) {
  if (model == nullptr || out == nullptr || n < 0) return GMMRRT_ERR_INVALID_ARGUMENT;
  gmmrrt_rng_t rng;
  gmmrrt_rng_seed(&rng, seed);
  const int32_t d = model->model.dim;
  for (int64_t p = 0; p < n; ++p) {
    const int32_t i = gmmrrt_gmm_sample(&model->model, &rng, out + p * d);
    if (labels != nullptr) labels[p] = i;
  }
  return GMMRRT_OK;
}

}  // extern "C"
