/*
 * models.c - gmmrrtd's models (paper Sect. 5: one mixture per task): loaded with
 * gmmrrt_model_load_file (planner/io), which validates everything before it overwrites
 * anything. Like a cFE table: a new file goes into a scratch model and replaces the model
 * in use only when it is good; on SIGHUP a bad file keeps the old model running and is
 * counted in planner_status_t.rejected[REJECT_MODEL_RELOAD].
 */
#include <stdio.h>
#include <string.h>

#include "daemon.h"
#include "gmmrrt/model_file.h"

static int load_one(gmmrrtd_t *d, const char *path, int32_t want_task, gmmrrt_model_t *slot, int *have, int reload)
{
    const char *task_name = want_task == GMMRRT_TASK_AVOID ? "avoid" : "approach";
    if (path[0] == '\0') {
        if (*have)
            LOG_INFO("%s model removed by the new configuration", task_name);
        *have = 0;
        return 0;
    }
    char err[512];
    const gmmrrt_status_t st = gmmrrt_model_load_file(path, &d->model_scratch, err, sizeof err);
    if (st == GMMRRT_OK && d->model_scratch.task != want_task && d->model_scratch.task != GMMRRT_TASK_NONE) {
        snprintf(err, sizeof err, "%s: model is for task %d, not %s", path, (int)d->model_scratch.task, task_name);
        if (!reload) {
            LOG_ERROR("%s", err);
            return -1;
        }
        gmmrrtd_reject(d, GMMRRTD_NUM_INPUTS, GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD, "%s (old model kept)", err);
        return -1;
    }
    if (st != GMMRRT_OK) {
        if (!reload) {
            LOG_ERROR("%s model: %s (%s)", task_name, err, gmmrrt_status_str(st));
            return -1;
        }
        gmmrrtd_reject(d, GMMRRTD_NUM_INPUTS, GMMRRT_PLANNER_STATUS_T_REJECT_MODEL_RELOAD, "%s model: %s%s", task_name,
                       err, *have ? " (old model kept)" : "");
        d->status.last_error = (int32_t)st;
        return -1;
    }
    *slot = d->model_scratch;
    *have = 1;
    LOG_INFO("%s model %s: K = %d, D = %d", task_name, path, (int)slot->k, (int)slot->dim);
    return 0;
}

int gmmrrtd_models_load(gmmrrtd_t *d, int reload)
{
    const int a = load_one(d, d->set.model_avoid, GMMRRT_TASK_AVOID, &d->model_avoid, &d->have_avoid, reload);
    const int b = load_one(d, d->set.model_approach, GMMRRT_TASK_APPROACH, &d->model_approach, &d->have_approach, reload);
    return (a == 0 && b == 0) ? 0 : -1;
}
