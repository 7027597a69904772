/*
 * goal.c - the goal's life in gmmrrtd (docs/daemon.md, "The goal's life"): a nav_goal_t NEW is
 * ACCEPTED, becomes PLANNING at its first cycle, and ends REACHED (judged on the robot's pose:
 * within tolerance_m and, when asked, yaw_tolerance_rad), CANCELLED (a CANCEL of its id) or
 * FAILED (no cycle could plan it for goal_fail_after_ms, with the cause). A finished goal's id
 * joins a ring of the last GMMRRTD_FINISHED_GOALS, so a late re-send of it cannot start it
 * again. The messages were validated by msg_decode.c; this file keeps only the state.
 */
#include <math.h>

#include "daemon.h"
#include "gmmrrt/features.h"

#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

static int is_finished(const gmmrrtd_goal_life_t *g, int64_t id)
{
    for (int i = 0; i < GMMRRTD_FINISHED_GOALS; ++i)
        if (g->finished[i] == id)
            return 1;
    return 0;
}

static void remember_finished(gmmrrtd_goal_life_t *g, int64_t id)
{
    if (id <= 0 || is_finished(g, id))
        return;
    g->finished[g->finished_next] = id;
    g->finished_next = (g->finished_next + 1) % GMMRRTD_FINISHED_GOALS;
}

int gmmrrtd_goal_active(const gmmrrtd_t *d)
{
    return d->have[GMMRRTD_IN_GOAL] && (d->life.state == ST(GOAL_ACCEPTED) || d->life.state == ST(GOAL_PLANNING));
}

static int same_goal(const gmmrrt_nav_goal_t *a, const gmmrrt_nav_goal_t *b)
{
    return a->x == b->x && a->y == b->y && a->yaw == b->yaw && a->tolerance_m == b->tolerance_m &&
           a->yaw_tolerance_rad == b->yaw_tolerance_rad && a->task == b->task &&
           a->target_person_id == b->target_person_id && a->preferred_side == b->preferred_side;
}

int gmmrrtd_goal_apply(gmmrrtd_t *d, const gmmrrt_nav_goal_t *m)
{
    gmmrrtd_goal_life_t *g = &d->life;
    const int current = d->have[GMMRRTD_IN_GOAL] && m->goal_id == g->id;
    if (m->command == GMMRRT_NAV_GOAL_T_COMMAND_CANCEL) {
        if (current && gmmrrtd_goal_active(d)) {
            gmmrrtd_goal_finish(d, ST(GOAL_CANCELLED), ST(FAILURE_NONE));
            gmmrrtd_log_limited(&d->rl_goal, gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms,
                                GMMRRTD_LOG_INFO, "goal %lld cancelled", (long long)m->goal_id);
            return 1;
        }
        if (is_finished(g, m->goal_id))
            return 0; /* a re-sent cancel, or a cancel of a goal that ended meanwhile: nothing to do */
        gmmrrtd_reject(d, GMMRRTD_IN_GOAL, ST(REJECT_BAD_VALUE),
                       "CANCEL of goal %lld, which is not the current goal (%lld)", (long long)m->goal_id,
                       (long long)g->id);
        return 0;
    }
    if (is_finished(g, m->goal_id)) {
        gmmrrtd_reject(d, GMMRRTD_IN_GOAL, ST(REJECT_GOAL_ID_REUSED),
                       "goal %lld has already finished; a new goal needs a new id (current goal %lld)",
                       (long long)m->goal_id, (long long)g->id);
        return 0;
    }
    if (current) {
        if (same_goal(m, &d->goal))
            return 0; /* a re-send */
        d->goal = *m;
        d->goal_version++;
        d->no_path_cycles = 0;
        g->unusable_since_us = -1;
        gmmrrtd_log_limited(&d->rl_goal, gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_INFO,
                            "goal %lld updated: (%.2f, %.2f) task %d target %d side %d", (long long)m->goal_id, m->x,
                            m->y, (int)m->task, (int)m->target_person_id, (int)m->preferred_side);
        return 1;
    }
    /* A new id: the current goal, if still active, is replaced and counts as finished. */
    if (d->have[GMMRRTD_IN_GOAL])
        remember_finished(g, g->id);
    d->have[GMMRRTD_IN_GOAL] = 1;
    d->goal = *m;
    d->goal_version++;
    d->no_path_cycles = 0;
    g->id = m->goal_id;
    g->state = ST(GOAL_ACCEPTED);
    g->failure = ST(FAILURE_NONE);
    g->announce = 0;
    g->unusable_since_us = -1;
    g->remaining_m = -1.0;
    g->side_result = ST(SIDE_NOT_ASKED);
    gmmrrtd_log_limited(&d->rl_goal, gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_INFO,
                        "new goal %lld (%.2f, %.2f) task %d target %d side %d", (long long)m->goal_id, m->x, m->y,
                        (int)m->task, (int)m->target_person_id, (int)m->preferred_side);
    return 1;
}

int gmmrrtd_goal_check_reached(gmmrrtd_t *d)
{
    const gmmrrt_nav_goal_t *g = &d->goal;
    if (hypot(d->pose.x - g->x, d->pose.y - g->y) > g->tolerance_m)
        return 0;
    if (g->yaw_tolerance_rad > 0.0 && fabs(gmmrrt_wrap_angle(d->pose.yaw - g->yaw)) > g->yaw_tolerance_rad)
        return 0;
    gmmrrtd_goal_finish(d, ST(GOAL_REACHED), ST(FAILURE_NONE));
    d->life.remaining_m = 0.0;
    return 1;
}

void gmmrrtd_goal_planned(gmmrrtd_t *d, double length_m)
{
    d->life.unusable_since_us = -1;
    d->life.remaining_m = length_m;
}

void gmmrrtd_goal_unusable(gmmrrtd_t *d, int64_t now_us, int failure)
{
    gmmrrtd_goal_life_t *g = &d->life;
    g->remaining_m = -1.0;
    if (g->unusable_since_us < 0)
        g->unusable_since_us = now_us;
    if ((double)(now_us - g->unusable_since_us) < d->set.goal_fail_after_ms * 1e3)
        return;
    gmmrrtd_goal_finish(d, ST(GOAL_FAILED), (int8_t)failure);
    d->life.announce = 0; /* this cycle's stop is the goal's last plan */
    LOG_WARN("goal %lld failed after %.1f s without a plan (failure %d)", (long long)g->id,
             (double)(now_us - g->unusable_since_us) * 1e-6, failure);
}

void gmmrrtd_goal_finish(gmmrrtd_t *d, int8_t state, int8_t failure)
{
    gmmrrtd_goal_life_t *g = &d->life;
    g->state = state;
    g->failure = failure;
    g->announce = 1;
    remember_finished(g, g->id);
    d->last.valid = 0; /* the next goal starts cold */
}
