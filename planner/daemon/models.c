/*
 * models.c - gmmrrtd's models (paper Sect. 5: one mixture per task): loaded with
 * gmmrrt_model_load_file (planner/io: a regular file only, opened without blocking, every
 * field validated before anything is overwritten), then checked against their use: the task
 * they were learned for (gmmrrt_model_task_fits) and the feature space the configured planner needs
 * (gmmrrt_planner_model_fits, the rule gmmrrt_planner_set_problem applies; an x-y or generic
 * model for GMM-RRT* would make every goal of its task stop with MODEL_MISMATCH). Like a cFE
 * table: a new file goes into a scratch model and replaces the model in use only when it is
 * good; on SIGHUP a bad file keeps the old model running, is counted in
 * planner_status_t.rejected[REJECT_MODEL_RELOAD] and logged every time (error level, not
 * rate-limited: a reload is an operator's act and each failure deserves its line).
 * A model file may carry a background model (model.h, the background section: where walkers
 * would have been without the person), which [planner] task_cost = background divides by
 * (config.h, GMMRRT_TASK_COST_BACKGROUND; docs/planner.md, "The background cost"). It is loaded
 * with its model (gmmrrt_model_load_file_background checks that it matches the model) into
 * scratch storage and replaces the one in use together with its model: never a new model with
 * an old background. With task_cost = background a file without one is refused like a bad file,
 * as gmmrrt-plan refuses it, when the configured planner uses the task cost
 * (gmmrrt_planner_needs_background: GMM-RRT*; RRT* and GMM-RRT never read the background).
 */
#include <stdio.h>
#include <string.h>

#include "daemon.h"
#include "gmmrrt/model_file.h"

static const char *kind_name(int32_t kind)
{
    switch (kind) {
    case GMMRRT_MODEL_KIND_FEATURES: return "features (d, theta)";
    case GMMRRT_MODEL_KIND_XY: return "x-y (s, x', y')";
    case GMMRRT_MODEL_KIND_GENERIC: return "generic";
    default: return "unknown";
    }
}

static int refuse(gmmrrtd_t *d, int reload, int have, gmmrrt_status_t st, const char *what)
{
    if (!reload) {
        LOG_ERROR("%s", what);
        return -1;
    }
    d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD]++;
    d->status.last_error = (int32_t)st;
    LOG_ERROR("reload rejected (total %lld): %s%s",
              (long long)d->status.rejected[GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD], what,
              have ? " (old model kept)" : "");
    return -1;
}

/* Loads the model file `path` for want_task into *slot (*have = 1) and its background into
 * *bg_slot (*has_bg = 1 when the file has one, else 0), all four written only when the file is
 * good for its use; otherwise none is touched. */
static int load_one(gmmrrtd_t *d, const char *path, int32_t want_task, gmmrrt_model_t *slot, int *have,
                    gmmrrt_model_t *bg_slot, int *has_bg, int reload)
{
    const char *task_name = want_task == GMMRRT_TASK_AVOID ? "avoid" : "approach";
    if (path[0] == '\0') {
        if (*have)
            LOG_INFO("%s model removed by the new configuration", task_name);
        *have = 0;
        *has_bg = 0;
        return 0;
    }
    char err[512], what[768];
    int file_has_bg = 0;
    const gmmrrt_status_t st = gmmrrt_model_load_file_background(path, &d->model_scratch, &d->bg_scratch,
                                                                 &file_has_bg, NULL, 0, NULL, err, sizeof err);
    if (st != GMMRRT_OK) {
        snprintf(what, sizeof what, "%s model: %s (%s)", task_name, err, gmmrrt_status_str(st));
        return refuse(d, reload, *have, st, what);
    }
    const gmmrrt_model_t *m = &d->model_scratch;
    if (gmmrrt_model_task_fits(m, want_task) != GMMRRT_OK) {
        snprintf(what, sizeof what, "%s model %s: learned for task %d, not %s", task_name, path, (int)m->task,
                 task_name);
        return refuse(d, reload, *have, GMMRRT_ERR_MODEL_MISMATCH, what);
    }
    const gmmrrt_status_t fit = gmmrrt_planner_model_fits(&d->set.cfg, m);
    if (fit != GMMRRT_OK) {
        snprintf(what, sizeof what, "%s model %s: a %s model with D = %d does not fit the %s planner (%s)", task_name,
                 path, kind_name(m->kind), (int)m->dim, gmmrrtd_planner_name(d->set.cfg.planner), gmmrrt_status_str(fit));
        return refuse(d, reload, *have, fit, what);
    }
    if (gmmrrt_planner_needs_background(&d->set.cfg) && !file_has_bg) {
        snprintf(what, sizeof what,
                 "%s model %s has no background model, which [planner] task_cost = background needs (fit the "
                 "model with gmmrrt-learn fit --background straight, or set task_cost = paper or inward)",
                 task_name, path);
        return refuse(d, reload, *have, GMMRRT_ERR_MODEL_MISMATCH, what);
    }
    *slot = *m;
    *have = 1;
    if (file_has_bg)
        *bg_slot = d->bg_scratch;
    *has_bg = file_has_bg;
    if (file_has_bg)
        LOG_INFO("%s model %s: %s, K = %d, D = %d, background K = %d", task_name, path, kind_name(slot->kind),
                 (int)slot->k, (int)slot->dim, (int)bg_slot->k);
    else
        LOG_INFO("%s model %s: %s, K = %d, D = %d, no background", task_name, path, kind_name(slot->kind),
                 (int)slot->k, (int)slot->dim);
    return 0;
}

/* The approach model set: <dir>/<direction name>.gmm for each of the 8 directions
 * (model_set.h), each loaded and checked like a single model into the scratch set, then the set
 * as a whole (gmmrrt_model_set_validate); only a complete, valid set replaces the one in use. A
 * missing or bad file refuses the set with that file named. */
static int load_set(gmmrrtd_t *d, int reload)
{
    const char *dir = d->set.approach_set;
    if (dir[0] == '\0') {
        if (d->have_approach_set)
            LOG_INFO("approach model set removed by the new configuration");
        d->have_approach_set = 0;
        return 0;
    }
    gmmrrt_model_set_t set;
    for (int32_t k = 0; k < GMMRRT_APPROACH_DIRECTIONS; ++k) {
        char file[GMMRRTD_PATH_MAX + 32];
        snprintf(file, sizeof file, "%s/%s.gmm", dir, gmmrrt_approach_direction_name(k));
        int have = 0;
        if (load_one(d, file, GMMRRT_TASK_APPROACH, &d->approach_set_scratch[k], &have, &d->approach_set_bg_scratch[k],
                     &d->approach_set_has_bg_scratch[k], reload) != 0) {
            LOG_ERROR("approach model set %s refused: direction %s (%s) did not load%s", dir,
                      gmmrrt_approach_direction_name(k), file, d->have_approach_set ? " (old set kept)" : "");
            return -1;
        }
        set.model[k] = &d->approach_set_scratch[k];
    }
    char err[256], what[GMMRRTD_PATH_MAX + 320];
    const gmmrrt_status_t st = gmmrrt_model_set_validate(&set, err, sizeof err);
    if (st != GMMRRT_OK) {
        snprintf(what, sizeof what, "approach model set %s: %s", dir, err);
        return refuse(d, reload, d->have_approach_set, st, what);
    }
    memcpy(d->approach_set, d->approach_set_scratch, sizeof d->approach_set);
    memcpy(d->approach_set_bg, d->approach_set_bg_scratch, sizeof d->approach_set_bg);
    memcpy(d->approach_set_has_bg, d->approach_set_has_bg_scratch, sizeof d->approach_set_has_bg);
    d->have_approach_set = 1;
    LOG_INFO("approach model set %s: %d directions", dir, GMMRRT_APPROACH_DIRECTIONS);
    return 0;
}

int gmmrrtd_models_load(gmmrrtd_t *d, int reload)
{
    const int a = load_one(d, d->set.model_avoid, GMMRRT_TASK_AVOID, &d->model_avoid, &d->have_avoid, &d->bg_avoid,
                           &d->has_bg_avoid, reload);
    const int b = load_one(d, d->set.model_approach, GMMRRT_TASK_APPROACH, &d->model_approach, &d->have_approach,
                           &d->bg_approach, &d->has_bg_approach, reload);
    const int c = load_set(d, reload);
    return (a == 0 && b == 0 && c == 0) ? 0 : -1;
}

/* One model in use against cfg: the planner's rule (gmmrrt_planner_model_fits) and, when the
 * planner divides by one (gmmrrt_planner_needs_background), a background of its own. */
static int fits(const gmmrrt_planner_config_t *cfg, const gmmrrt_model_t *m, int has_bg, const char *name, char *why,
                size_t cap)
{
    const gmmrrt_status_t st = gmmrrt_planner_model_fits(cfg, m);
    if (st != GMMRRT_OK) {
        snprintf(why, cap, "the %s model does not fit the %s planner (%s)", name, gmmrrtd_planner_name(cfg->planner),
                 gmmrrt_status_str(st));
        return 0;
    }
    if (gmmrrt_planner_needs_background(cfg) && !has_bg) {
        snprintf(why, cap, "the %s model has no background model, which task_cost = background needs", name);
        return 0;
    }
    return 1;
}

int gmmrrtd_models_fit_config(const gmmrrtd_t *d, const gmmrrt_planner_config_t *cfg, char *why, size_t cap)
{
    if (d->have_avoid && !fits(cfg, &d->model_avoid, d->has_bg_avoid, "avoid", why, cap))
        return 0;
    if (d->have_approach && !fits(cfg, &d->model_approach, d->has_bg_approach, "approach", why, cap))
        return 0;
    if (d->have_approach_set)
        for (int32_t k = 0; k < GMMRRT_APPROACH_DIRECTIONS; ++k)
            if (!fits(cfg, &d->approach_set[k], d->approach_set_has_bg[k], gmmrrt_approach_direction_name(k), why,
                      cap))
                return 0;
    return 1;
}
