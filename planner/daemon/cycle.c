/*
 * cycle.c - one gmmrrtd planning cycle: from the latest inputs to a plan. Picks the model by
 * the goal's task (avoid / approach, paper Sect. 4-5; for approach, the model set's direction
 * the robot comes from when a set is configured) and passes that model file's background model
 * as problem.background_model (read by [planner] task_cost = background), plans from the
 * latest robot pose (walking people with their velocities) with gmmrrt_planner_set_problem +
 * run, warm-starts from the last published path when the situation has not changed much, and
 * publishes PLAN (the drivable path, drivable.h) and PLANNER_STATUS. A start in collision is not a stop: it plans
 * an escape, published with status GMMRRT_ESCAPE and counted; only GMMRRT_ERR_FROZEN (no
 * motion increases the clearance) stops, with the core's reason logged. A stale pose or
 * obstacle list, stale scans or a stale grid (docs/world.md), a missing model or target, an
 * unusable goal or no path publishes a stop (an empty plan whose status says why), never an
 * old plan; every stop is counted by reason
 * (planner_status_t.stops) and logged rate-limited. A stale people list is dropped: the plan
 * no longer avoids people who may have left.
 */
#include <math.h>
#include <poll.h>
#include <sched.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "daemon.h"
#include "gmmrrt/problem_bounds.h"

#define ST(x) GMMRRT_PLANNER_STATUS_T_##x

/* Anytime cycles run the budget in slices this long (ms) or of this many samples, whichever
 * the budget uses: short enough that a first path is published within about a slice of being
 * found, long enough that the per-call overhead of gmmrrt_planner_run stays small. */
#define GMMRRTD_ANYTIME_SLICE_MS 1.0
#define GMMRRTD_ANYTIME_SLICE_ITERATIONS 50
/* Until a cycle on a time budget has published, its slices also end after this many samples:
 * the first path (often there at once, from the warm start's seed) is then published within a
 * few samples of existing instead of at the end of a 1 ms slice, which was most of the pose-to-
 * plan time of an event-triggered cycle (docs/daemon.md, "Where a slow plan's time goes"). */
#define GMMRRTD_ANYTIME_FIRST_SLICE_ITERATIONS 4

/* build_problem() copies wire counts (checked against the messages' MAX_*) into the core's
 * arrays (sized by limits.h, which a build may override), and publish_plan() copies a path
 * into waypoints_t: the sizes must agree or a valid message overflows an array. */
_Static_assert(GMMRRT_MAX_PEOPLE >= GMMRRT_PEOPLE_T_MAX_PEOPLE, "limits.h: GMMRRT_MAX_PEOPLE < people_t.MAX_PEOPLE");
_Static_assert(GMMRRT_MAX_CIRCLES >= GMMRRT_OBSTACLES_T_MAX_CIRCLES, "limits.h: GMMRRT_MAX_CIRCLES < obstacles_t.MAX_CIRCLES");
_Static_assert(GMMRRT_MAX_BOXES >= GMMRRT_OBSTACLES_T_MAX_BOXES, "limits.h: GMMRRT_MAX_BOXES < obstacles_t.MAX_BOXES");
_Static_assert(GMMRRT_MAX_WAYPOINTS <= GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS,
               "limits.h: GMMRRT_MAX_WAYPOINTS > waypoints_t.MAX_WAYPOINTS");

/* Counts `reason` at most once per goal (per goal content, see inputs.c). */
static void reject_once_per_goal(gmmrrtd_t *d, int reason, int why)
{
    if (d->counted_goal_version[reason] == d->goal_version)
        return;
    d->counted_goal_version[reason] = d->goal_version;
    gmmrrtd_reject(d, GMMRRTD_RL_PLANNER, reason, "goal (%.2f, %.2f): %s", d->goal.x, d->goal.y,
                   gmmrrtd_stop_str(why));
}

/* The status's time label: the log time in a replay, the host's wall clock live. */
static int64_t status_utime(const gmmrrtd_t *d, int64_t now_us)
{
    if (d->clock_mode == GMMRRTD_CLOCK_LOG)
        return now_us;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void publish_status(gmmrrtd_t *d, int64_t now_utime, int8_t state)
{
    d->status.utime = status_utime(d, now_utime);
    d->status.stale_inputs = d->stale_mask;
    d->status.state = state;
    d->status.goal_id = d->life.id;
    d->status.goal_state = d->life.state;
    d->status.goal_failure = d->life.failure;
    d->status.remaining_m = d->life.remaining_m;
    d->status.side_result = d->life.side_result;
    gmmrrt_planner_status_t_publish(d->lcm_out, d->set.ch_status, &d->status);
}

static void publish_plan(gmmrrtd_t *d, const gmmrrt_path_t *path, int status)
{
    gmmrrt_waypoints_t *m = &d->plan_msg;
    m->utime = d->pose.utime;
    m->frame = d->set.frame; /* every input was refused unless in this frame (inputs.c) */
    m->seq = ++d->plan_seq;
    const int32_t n = path != NULL ? path->num_points : 0;
    m->num_waypoints = n;
    for (int32_t i = 0; i < n; ++i) {
        m->x[i] = path->x[i];
        m->y[i] = path->y[i];
        m->yaw[i] = path->yaw[i];
    }
    for (int32_t i = n; i < GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS; ++i)
        m->x[i] = m->y[i] = m->yaw[i] = 0.0;
    m->total_cost = n > 0 ? path->cost : 0.0;
    m->length_m = n > 0 ? path->length_m : 0.0;
    m->planner = n > 0 ? (int8_t)d->set.cfg.planner : GMMRRT_WAYPOINTS_T_PLANNER_NONE;
    m->task = d->have[GMMRRTD_IN_GOAL] ? d->goal.task : GMMRRT_NAV_GOAL_T_TASK_NONE;
    m->status = (int32_t)status;
    gmmrrt_waypoints_t_publish(d->lcm_out, d->set.ch_plan, m);
    d->status.plans_published++;
}

static void clear_stats(gmmrrtd_t *d)
{
    d->status.approach_model = -1;
    d->status.iterations = 0;
    d->status.nodes = 0;
    d->status.first_solution_ms = -1.0;
    d->status.best_cost = -1.0;
}

/* The stops[] slot of a stop code. */
static int stop_slot(int why)
{
    switch (why) {
    case GMMRRTD_STOP_POSE_STALE: return ST(STOP_POSE_STALE);
    case GMMRRTD_STOP_NO_MODEL: return ST(STOP_NO_MODEL);
    case GMMRRTD_STOP_UNKNOWN_TARGET: return ST(STOP_UNKNOWN_TARGET);
    case GMMRRTD_STOP_OBSTACLES_STALE: return ST(STOP_OBSTACLES_STALE);
    case GMMRRTD_STOP_PLANNING_BOX: return ST(STOP_PLANNING_BOX);
    case GMMRRTD_STOP_SCAN_STALE: return ST(STOP_SCAN_STALE);
    case GMMRRTD_STOP_GRID_STALE: return ST(STOP_GRID_STALE);
    case GMMRRT_ERR_START_IN_COLLISION:
    case GMMRRT_ERR_START_OUT_OF_BOUNDS: return ST(STOP_START_BLOCKED);
    case GMMRRT_ERR_GOAL_IN_COLLISION:
    case GMMRRT_ERR_GOAL_OUT_OF_BOUNDS: return ST(STOP_GOAL_BLOCKED);
    case GMMRRT_NO_PATH_YET: return ST(STOP_NO_PATH);
    case GMMRRT_ERR_FROZEN: return ST(STOP_FROZEN);
    default: return ST(STOP_SETUP);
    }
}

/* The goal's failure a stop code stands for; FAILURE_NONE for stops that are not the goal's
 * (a stale pose, obstacle list, scan or grid, a blocked start: the goal may be fine once they pass). */
static int goal_failure_of(int why)
{
    switch (why) {
    case GMMRRTD_STOP_NO_MODEL: return ST(FAILURE_NO_MODEL);
    case GMMRRTD_STOP_UNKNOWN_TARGET: return ST(FAILURE_UNKNOWN_TARGET);
    case GMMRRTD_STOP_PLANNING_BOX: return ST(FAILURE_PLANNING_BOX);
    case GMMRRT_ERR_GOAL_IN_COLLISION:
    case GMMRRT_ERR_GOAL_OUT_OF_BOUNDS: return ST(FAILURE_GOAL_BLOCKED);
    case GMMRRT_NO_PATH_YET:
    case GMMRRT_NO_PATH_ON_SIDE: return ST(FAILURE_UNREACHABLE);
    case GMMRRTD_STOP_POSE_STALE:
    case GMMRRTD_STOP_OBSTACLES_STALE:
    case GMMRRTD_STOP_SCAN_STALE:
    case GMMRRTD_STOP_GRID_STALE:
    case GMMRRT_ERR_START_IN_COLLISION:
    case GMMRRT_ERR_START_OUT_OF_BOUNDS:
    case GMMRRT_ERR_FROZEN: return ST(FAILURE_NONE);
    default: return ST(FAILURE_SETUP);
    }
}

/* Stats of the cycle stay as they are (cleared by the callers that did not plan). Every stop
 * is counted by reason and logged (rate-limited). */
static void publish_stop(gmmrrtd_t *d, int64_t now_utime, int why, int8_t state)
{
    /* A stop that is the goal's fault (not the robot's or its inputs') counts towards its failure. */
    const int failure = goal_failure_of(why);
    if (failure != ST(FAILURE_NONE))
        gmmrrtd_goal_unusable(d, now_utime, failure);
    else
        d->life.remaining_m = -1.0;
    gmmrrtd_count_stop(d, stop_slot(why), "%s (code %d, goal (%.2f, %.2f))", gmmrrtd_stop_str(why), why,
                       d->goal.x, d->goal.y);
    d->last.valid = 0; /* never warm-start across a stop */
    d->status.last_error = (int32_t)why;
    publish_plan(d, NULL, why);
    publish_status(d, now_utime, state);
}

/* The people list is used only while it is fresh (people_timeout_ms): a stale list is
 * dropped, not planned around (the people may have left). */
static int people_usable(const gmmrrtd_t *d)
{
    return d->have[GMMRRTD_IN_PEOPLE] && !(d->stale_mask & ST(STALE_PEOPLE));
}

static int find_person(const gmmrrt_people_t *people, int32_t id)
{
    for (int32_t i = 0; i < people->num_people; ++i)
        if (people->people[i].id == id)
            return (int)i;
    return -1;
}

/* The planning problem from the latest inputs. Bounds: the core's rule (problem_bounds.h), the
 * box around robot and goal grown by bounds_margin_m, as gmmrrt-plan and the Python tools. */
static void build_problem(gmmrrtd_t *d, const gmmrrt_model_t *model, const gmmrrt_model_t *background,
                          int target_index)
{
    gmmrrt_problem_t *p = &d->problem;
    memset(p, 0, sizeof *p);
    p->start_x = d->pose.x;
    p->start_y = d->pose.y;
    p->goal_x = d->goal.x;
    p->goal_y = d->goal.y;
    p->goal_tolerance_m = d->goal.tolerance_m;
    p->task = d->goal.task;
    p->target_person = target_index;
    p->model = model;
    p->background_model = background; /* read by task_cost = background only */
    /* Inputs and the margin are checked finite and positive where they enter; a failure would
     * leave empty bounds, which set_problem refuses (a counted stop). */
    (void)gmmrrt_problem_bounds(p->start_x, p->start_y, p->goal_x, p->goal_y, d->set.bounds_margin_m,
                                &p->obstacles.bounds);
    p->obstacles.raster = gmmrrtd_world_raster(d); /* the grid's or the map's; read only inside the bounds */
    if (d->have[GMMRRTD_IN_OBSTACLES]) {
        const gmmrrt_obstacles_t *o = &d->obstacles;
        p->obstacles.num_circles = o->num_circles;
        for (int32_t i = 0; i < o->num_circles; ++i)
            p->obstacles.circles[i] = (gmmrrt_circle_t){o->circle_x[i], o->circle_y[i], o->circle_radius[i]};
        p->obstacles.num_boxes = o->num_boxes;
        for (int32_t i = 0; i < o->num_boxes; ++i)
            p->obstacles.boxes[i] =
                (gmmrrt_box_t){o->box_x[i], o->box_y[i], o->box_width[i], o->box_height[i], o->box_yaw[i]};
    }
    if (people_usable(d)) {
        p->obstacles.num_people = d->people.num_people;
        for (int32_t i = 0; i < d->people.num_people; ++i) {
            const gmmrrt_person_t *q = &d->people.people[i];
            p->obstacles.people[i] = (gmmrrt_pose_t){q->x, q->y, q->yaw};
            p->person_vx[i] = q->vx; /* bounded at input (inputs.c); slow ones count as standing */
            p->person_vy[i] = q->vy;
        }
    }
    /* nav_goal_t's side (+1 left, -1 right) is gmmrrt_side_t's, about the approach target or else
     * the person nearest the segment start-goal. */
    p->side = d->goal.preferred_side == GMMRRT_NAV_GOAL_T_SIDE_LEFT    ? GMMRRT_SIDE_LEFT
              : d->goal.preferred_side == GMMRRT_NAV_GOAL_T_SIDE_RIGHT ? GMMRRT_SIDE_RIGHT
                                                                      : GMMRRT_SIDE_EITHER;
    p->side_person = target_index >= 0 ? target_index : -1;
    p->nominal_speed_m_s = d->set.nominal_speed_m_s;
    p->prediction_horizon_s = d->set.prediction_horizon_s;
}

/* "Not changed much" (docs/daemon.md): same task, target and side, goal moved < warm_goal_shift_m,
 * obstacles unchanged, the same tracked ids each moved < warm_people_shift_m, and the robot
 * within warm_robot_offset_m of the last path. Then the seed is the robot followed by the
 * last path from the waypoint after the nearest one. Returns the seed length (0: cold). */
static int32_t warm_start_seed(gmmrrtd_t *d)
{
    const gmmrrtd_snapshot_t *s = &d->last;
    const gmmrrtd_settings_t *set = &d->set;
    if (!s->valid || s->task != d->goal.task || s->target_id != d->goal.target_person_id ||
        s->side != d->goal.preferred_side ||
        hypot(s->goal_x - d->goal.x, s->goal_y - d->goal.y) >= set->warm_goal_shift_m ||
        s->obstacles_version != d->obstacles_version || s->grid_version != d->grid_version)
        return 0;
    const int32_t np = people_usable(d) ? d->people.num_people : 0;
    if (np != s->num_people)
        return 0;
    for (int32_t i = 0; i < np; ++i) {
        const gmmrrt_person_t *q = &d->people.people[i];
        if (q->id != s->people_id[i] || hypot(q->x - s->people_x[i], q->y - s->people_y[i]) >= set->warm_people_shift_m)
            return 0;
    }
    const gmmrrt_path_t *lp = &d->last_path;
    if (lp->num_points < 2)
        return 0;
    int32_t nearest = 0;
    double best = INFINITY;
    for (int32_t i = 0; i < lp->num_points; ++i) {
        const double dist = hypot(lp->x[i] - d->pose.x, lp->y[i] - d->pose.y);
        if (dist < best) {
            best = dist;
            nearest = i;
        }
    }
    if (best >= set->warm_robot_offset_m)
        return 0;
    /* The published path is sampled every waypoint_spacing_m (its arcs as many short chords):
     * seeded as it is, every sample would become a tree node and a collision check. One seed
     * point per step_m (the tree's own edge length) and the path's end keep the route, not its
     * sampling. */
    int32_t n = 0;
    d->seed_x[n] = d->pose.x;
    d->seed_y[n++] = d->pose.y;
    for (int32_t i = nearest + 1; i < lp->num_points; ++i) {
        const int last = i == lp->num_points - 1;
        if (!last && hypot(lp->x[i] - d->seed_x[n - 1], lp->y[i] - d->seed_y[n - 1]) < d->set.cfg.step_m)
            continue;
        d->seed_x[n] = lp->x[i];
        d->seed_y[n++] = lp->y[i];
    }
    return n >= 2 ? n : 0;
}

static void remember_situation(gmmrrtd_t *d)
{
    gmmrrtd_snapshot_t *s = &d->last;
    s->valid = 1;
    s->goal_x = d->goal.x;
    s->goal_y = d->goal.y;
    s->task = d->goal.task;
    s->target_id = d->goal.target_person_id;
    s->side = d->goal.preferred_side;
    s->obstacles_version = d->obstacles_version;
    s->grid_version = d->grid_version;
    s->num_people = people_usable(d) ? d->people.num_people : 0;
    for (int32_t i = 0; i < s->num_people; ++i) {
        s->people_id[i] = d->people.people[i].id;
        s->people_x[i] = d->people.people[i].x;
        s->people_y[i] = d->people.people[i].y;
    }
    d->last_path = d->path;
}

/* The published path's options (drivable.h) from [drive]: approach arrives facing the target
 * (face_target) or on the goal's yaw (use_goal_yaw); other tasks on the goal's yaw when
 * use_goal_yaw, else with any heading. */
static gmmrrt_drive_options_t drive_options(const gmmrrtd_t *d)
{
    gmmrrt_drive_options_t opt;
    gmmrrt_drive_options_default(&opt);
    opt.min_turn_radius_m = d->set.min_turn_radius_m;
    opt.goal_yaw_tolerance_rad = d->set.yaw_tolerance_deg * M_PI / 180.0;
    opt.arrival_leg_m = d->set.arrival_leg_m;
    opt.goal_yaw = d->goal.yaw;
    if (d->problem.task == GMMRRT_TASK_APPROACH && d->problem.target_person >= 0 && d->set.face_target)
        opt.arrival = GMMRRT_ARRIVAL_FACE_TARGET;
    else
        opt.arrival = d->set.use_goal_yaw ? GMMRRT_ARRIVAL_YAW : GMMRRT_ARRIVAL_ANY;
    return opt;
}

/* Per-channel staleness at local time now_us (clock.h: each source's data time on the local
 * time base). Sets d->stale_mask; while there is a goal (`count`), the first stale cycle of
 * each gap is counted and logged. */
static void judge_staleness(gmmrrtd_t *d, int64_t now_us, int count)
{
    static const struct {
        int input, bit, reason;
    } k_ch[] = {
        {GMMRRTD_IN_POSE, ST(STALE_POSE), ST(REJECT_POSE_STALE)},
        {GMMRRTD_IN_PEOPLE, ST(STALE_PEOPLE), ST(REJECT_PEOPLE_STALE)},
        {GMMRRTD_IN_OBSTACLES, ST(STALE_OBSTACLES), ST(REJECT_OBSTACLES_STALE)},
        {GMMRRTD_IN_SCAN, ST(STALE_SCAN), ST(REJECT_SCAN_STALE)},
        {GMMRRTD_IN_GRID, ST(STALE_GRID), ST(REJECT_GRID_STALE)},
    };
    static const char *const k_what[] = {"robot pose", "people list", "obstacle list", "laser scan", "occupancy grid"};
    const double timeout_ms[] = {d->set.pose_timeout_ms, d->set.people_timeout_ms, d->set.obstacles_timeout_ms,
                                 d->set.scan_timeout_ms, d->set.grid_timeout_ms};
    d->stale_mask = 0;
    for (int i = 0; i < (int)(sizeof k_ch / sizeof k_ch[0]); ++i) {
        const int in = k_ch[i].input;
        if (timeout_ms[i] <= 0.0 || !d->have[in])
            continue; /* no timeout; or never seen (the pose's absence is handled by the caller) */
        const int64_t age_us = gmmrrtd_clock_age_us(&d->src[in], now_us);
        if ((double)age_us <= timeout_ms[i] * 1e3)
            continue;
        d->stale_mask |= k_ch[i].bit;
        if (count && !d->stale_counted[in]) {
            d->stale_counted[in] = 1;
            const char *consequence = in == GMMRRTD_IN_PEOPLE ? ": planning without people until the tracker is back"
                                      : in == GMMRRTD_IN_SCAN && !d->set.scan_stale_stop
                                          ? ": planning without scan marks until scans are back"
                                          : "";
            gmmrrtd_reject(d, GMMRRTD_RL_PLANNER, k_ch[i].reason, "no %s for %.3f s (limit %.3f s)%s", k_what[i],
                           (double)age_us * 1e-6, timeout_ms[i] * 1e-3, consequence);
        }
    }
}

/* The planning box does not fit the clearance grid: a counted, logged reason with the numbers. */
static void planning_box_too_large(gmmrrtd_t *d, int64_t now_us)
{
    const gmmrrt_bounds_t *b = &d->problem.obstacles.bounds;
    const double res = d->set.cfg.grid_resolution_m;
    const double cells = ceil((b->xmax - b->xmin) / res) * ceil((b->ymax - b->ymin) / res);
    if (d->counted_goal_version[ST(REJECT_PLANNING_BOX)] != d->goal_version) {
        d->counted_goal_version[ST(REJECT_PLANNING_BOX)] = d->goal_version;
        gmmrrtd_reject(d, GMMRRTD_RL_PLANNER, ST(REJECT_PLANNING_BOX),
                       "goal (%.2f, %.2f): the planning box %.1f x %.1f m (robot, goal, margin %.1f m) needs %.0f "
                       "cells of %.3f m; grid_max_cells is %d",
                       d->goal.x, d->goal.y, b->xmax - b->xmin, b->ymax - b->ymin, d->set.bounds_margin_m, cells, res,
                       (int)d->set.cfg.grid_max_cells);
    }
    publish_stop(d, now_us, GMMRRTD_STOP_PLANNING_BOX, ST(STATE_ERROR));
}

/* Live and event-triggered only: whether an LCM message is waiting to be read. A cycle that has
 * published its first plan then ends early, so the next cycle starts from the newer input
 * without waiting for this one's budget. Replays never look (their cycles follow message time). */
static int input_waiting(const gmmrrtd_t *d)
{
    if (d->clock_mode != GMMRRTD_CLOCK_LIVE || strcmp(d->set.trigger, "event") != 0 || d->lcm_in == NULL)
        return 0;
    struct pollfd pfd = {.fd = lcm_get_fileno(d->lcm_in), .events = POLLIN};
    return pfd.fd >= 0 && poll(&pfd, 1, 0) > 0 && (pfd.revents & POLLIN);
}

/* The planner's best path made drivable (drivable.h) and published as PLAN when its cost is
 * below *published_cost (the cycle's last publication; INFINITY before the first), which it
 * then becomes: the publications of one cycle never rise in cost. 1 published, 0 not (no path,
 * or no better), -1 when the smoother refused its options (a stop was published). run_st: the
 * run's status (POOL_FULL is kept in last_error). */
static int publish_drivable(gmmrrtd_t *d, int64_t now_us, int escaping, gmmrrt_status_t run_st,
                            double *published_cost)
{
    const gmmrrt_drive_options_t opt = drive_options(d);
    const gmmrrt_status_t drive_st = gmmrrt_planner_drivable_path(d->planner, &opt, &d->path, &d->drive_report);
    if (drive_st != GMMRRT_OK && drive_st != GMMRRT_ESCAPE && drive_st != GMMRRT_TIGHT_TURNS &&
        drive_st != GMMRRT_NO_PATH_YET) {
        reject_once_per_goal(d, ST(REJECT_SETUP), drive_st); /* options out of range, a tree path too long */
        publish_stop(d, now_us, drive_st, ST(STATE_ERROR));
        return -1;
    }
    if (drive_st == GMMRRT_NO_PATH_YET || d->path.num_points < 2)
        return 0;
    if (*published_cost != INFINITY && !(d->path.cost < *published_cost))
        return 0;
    *published_cost = isnan(d->path.cost) ? -INFINITY : d->path.cost; /* no cost: nothing counts as better */
    d->no_path_cycles = 0;
    d->status.last_error = run_st == GMMRRT_POOL_FULL ? (int32_t)run_st : 0;
    remember_situation(d);
    const gmmrrt_drive_report_t *rep = &d->drive_report;
    if (d->set.min_turn_radius_m > 0.0 && (rep->tight_turns > 0 || rep->turns_in_place > 0)) {
        /* Published all the same, never silently: the plan carries GMMRRT_TIGHT_TURNS (an escape
         * keeps GMMRRT_ESCAPE, whose end turns on the spot by design), the status counts it. A stop
         * would freeze the robot where no drivable arc exists, and the next cycle re-plans anyway. */
        d->status.tight_turn_plans++;
        gmmrrtd_log_limited(&d->rl_tight, gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms,
                            GMMRRTD_LOG_WARN,
                            "plan turns tighter than min_turn_radius_m = %.2f m at %d corner(s), in place at %d: "
                            "no free arc there (%lld such plans)",
                            d->set.min_turn_radius_m, (int)rep->tight_turns, (int)rep->turns_in_place,
                            (long long)d->status.tight_turn_plans);
    }
    publish_plan(d, &d->path, escaping ? GMMRRT_ESCAPE : drive_st);
    gmmrrtd_goal_planned(d, d->path.length_m);
    return 1;
}

/* Runs the planner on `budget` (time and samples: whichever ends first), anytime when
 * anytime_max_plans > 1: the budget in slices, the first path published at once, a better one only
 * when its cost falls by anytime_improvement, at most anytime_max_plans per cycle (counted in
 * *published across the calls of one cycle, with *published_cost the last one's cost). *st: the
 * run's last status. 0, or -1 when a stop was published (the cycle ends). */
static int run_budget(gmmrrtd_t *d, int64_t now_us, int escaping, const gmmrrt_budget_t *budget,
                      gmmrrt_plan_stats_t *stats, gmmrrt_status_t *st, int *published, double *published_cost)
{
    if (d->set.anytime_max_plans <= 1) {
        *st = gmmrrt_planner_run(d->planner, budget, stats);
    } else {
        /* Anytime: the budget in slices; the first path is published at once, a better one only
         * when its cost falls by anytime_improvement, at most anytime_max_plans per cycle. */
        const int64_t run_start_us = gmmrrtd_mono_us();
        int64_t iterations_left = budget->max_iterations;
        double tried_tree_cost = INFINITY;
        for (;;) {
            gmmrrt_budget_t slice = *budget;
            if (budget->time_ms > 0.0) {
                const double left_ms = budget->time_ms - (double)(gmmrrtd_mono_us() - run_start_us) * 1e-3;
                if (left_ms <= 0.0)
                    break;
                slice.time_ms = fmin(GMMRRTD_ANYTIME_SLICE_MS, left_ms);
                if (*published == 0 && budget->max_iterations <= 0)
                    slice.max_iterations = GMMRRTD_ANYTIME_FIRST_SLICE_ITERATIONS;
            }
            if (budget->max_iterations > 0) {
                if (iterations_left <= 0)
                    break;
                slice.max_iterations = iterations_left < GMMRRTD_ANYTIME_SLICE_ITERATIONS
                                           ? iterations_left
                                           : GMMRRTD_ANYTIME_SLICE_ITERATIONS;
            }
            const int64_t before = stats->iterations;
            *st = gmmrrt_planner_run(d->planner, &slice, stats);
            iterations_left -= stats->iterations - before;
            if (*st != GMMRRT_OK && *st != GMMRRT_POOL_FULL && *st != GMMRRT_NO_PATH_YET &&
                *st != GMMRRT_NO_PATH_ON_SIDE && *st != GMMRRT_TIMEOUT)
                break;
            if (*st == GMMRRT_OK || *st == GMMRRT_POOL_FULL) {
                /* The tree's cost decides when to try (the drivable path's is lower: shortcut),
                 * the drivable path's whether to publish. */
                if (*published < d->set.anytime_max_plans &&
                    stats->best_cost <= tried_tree_cost * (1.0 - d->set.anytime_improvement)) {
                    tried_tree_cost = stats->best_cost;
                    const int r = publish_drivable(d, now_us, escaping, *st, published_cost);
                    if (r < 0)
                        return -1;
                    *published += r;
                    /* Live, a plan is out and the cycle polishes on: the CPU first goes to whoever
                     * delivers and reads it. A cycle that kept it held the kernel's loopback delivery
                     * of its own datagram and the consumer's wake-up behind it for a scheduler slice,
                     * ~8 ms on a busy 2-core host (docs/daemon.md, "Where a slow plan's time goes"). */
                    if (r > 0 && d->clock_mode == GMMRRTD_CLOCK_LIVE && *published < d->set.anytime_max_plans)
                        (void)sched_yield();
                }
            }
            if (*st == GMMRRT_POOL_FULL || *published >= d->set.anytime_max_plans)
                break;
            if (*published > 0 && input_waiting(d))
                break; /* a newer pose (or world) is waiting: plan from it rather than polish this one */
        }
        if (*published > 0)
            *st = GMMRRT_OK;
    }
    return 0;
}

/* run_budget for the whole cycle, with nav_goal_t.preferred_side (docs/daemon.md, "The preferred
 * side"): with a side and people, the side (planner.h, problem.side) gets the first half of the
 * budget; when it has no path by then, the problem is set again with either side for the rest,
 * and side_result says the side was not found. Otherwise the rest goes on the same tree.
 * 0, or -1 when a stop was published. */
static int run_with_side(gmmrrtd_t *d, int64_t now_us, int escaping, const gmmrrt_budget_t *budget,
                         gmmrrt_plan_stats_t *stats, gmmrrt_status_t *st, int *published, double *published_cost)
{
    d->life.side_result = ST(SIDE_NOT_ASKED);
    if (d->problem.side == GMMRRT_SIDE_EITHER || d->problem.obstacles.num_people == 0)
        return run_budget(d, now_us, escaping, budget, stats, st, published, published_cost);
    gmmrrt_budget_t half = *budget, rest = *budget;
    half.time_ms = budget->time_ms > 0.0 ? budget->time_ms * 0.5 : 0.0;
    half.max_iterations = budget->max_iterations > 0 ? (budget->max_iterations + 1) / 2 : 0;
    rest.max_iterations = budget->max_iterations > 0 ? budget->max_iterations - half.max_iterations : 0;
    const int64_t half_start_us = gmmrrtd_mono_us();
    if (run_budget(d, now_us, escaping, &half, stats, st, published, published_cost) < 0)
        return -1;
    if (budget->time_ms > 0.0)
        rest.time_ms = fmax(budget->time_ms - (double)(gmmrrtd_mono_us() - half_start_us) * 1e-3, 1.0);
    if (*published == 0 && *st == GMMRRT_NO_PATH_ON_SIDE) {
        d->life.side_result = ST(SIDE_NOT_FOUND);
        d->problem.side = GMMRRT_SIDE_EITHER;
        const int64_t side_iterations = stats->iterations;
        *st = gmmrrt_planner_set_problem(d->planner, &d->problem); /* the same world: it was valid */
        if (*st != GMMRRT_OK && *st != GMMRRT_ESCAPE) {
            reject_once_per_goal(d, ST(REJECT_SETUP), *st);
            publish_stop(d, now_us, *st, ST(STATE_ERROR));
            return -1;
        }
        *stats = (gmmrrt_plan_stats_t){
            .first_solution_iteration = -1, .first_solution_ms = -1.0, .best_cost = INFINITY};
        const int r = run_budget(d, now_us, escaping, &rest, stats, st, published, published_cost);
        stats->iterations += side_iterations;
        return r;
    }
    if (*published > 0 || *st == GMMRRT_OK || *st == GMMRRT_POOL_FULL)
        d->life.side_result = ST(SIDE_KEPT);
    if ((rest.max_iterations > 0 || budget->max_iterations <= 0) && *published < d->set.anytime_max_plans)
        return run_budget(d, now_us, escaping, &rest, stats, st, published, published_cost);
    return 0;
}

void gmmrrtd_cycle(gmmrrtd_t *d, int64_t now_us)
{
    d->cycles++;
    d->event_pending = 0; /* this cycle takes every input so far */
    gmmrrtd_pacing_spend(&d->pacing, now_us, gmmrrtd_min_period_us(d), d->set.event_burst);
    d->status.plan_time_ms = 0.0;
    d->status.setup_time_ms = 0.0;
    clear_stats(d);
    judge_staleness(d, now_us, gmmrrtd_goal_active(d));
    if (!gmmrrtd_goal_active(d)) {
        /* No goal, or it has finished: a reached or cancelled goal's empty plan once, then idle. */
        if (d->life.announce && d->life.state != ST(GOAL_FAILED)) {
            const int why = d->life.state == ST(GOAL_REACHED) ? GMMRRTD_STOP_GOAL_REACHED : GMMRRTD_STOP_GOAL_CANCELLED;
            d->status.stops[d->life.state == ST(GOAL_REACHED) ? ST(STOP_GOAL_REACHED) : ST(STOP_GOAL_CANCELLED)]++;
            d->last.valid = 0;
            publish_plan(d, NULL, why);
        }
        d->life.announce = 0;
        publish_status(d, now_us, ST(STATE_IDLE));
        return;
    }
    d->life.state = ST(GOAL_PLANNING);

    /* No pose, or none newer than pose_timeout_ms: stop. */
    if (!d->have[GMMRRTD_IN_POSE] || (d->stale_mask & ST(STALE_POSE))) {
        if (!d->have[GMMRRTD_IN_POSE] && !d->stale_counted[GMMRRTD_IN_POSE]) {
            d->stale_counted[GMMRRTD_IN_POSE] = 1;
            gmmrrtd_reject(d, GMMRRTD_RL_PLANNER, ST(REJECT_POSE_STALE), "a goal but no robot pose yet");
        }
        d->stale_mask |= ST(STALE_POSE);
        publish_stop(d, now_us, GMMRRTD_STOP_POSE_STALE, ST(STATE_STOPPED));
        return;
    }
    /* Reached, judged on the fresh pose: the goal ends, its empty plan is published once. */
    if (gmmrrtd_goal_check_reached(d)) {
        gmmrrtd_log_limited(&d->rl_goal, gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms, GMMRRTD_LOG_INFO,
                            "goal %lld reached at (%.2f, %.2f, yaw %.2f)", (long long)d->life.id, d->pose.x, d->pose.y,
                            d->pose.yaw);
        d->status.stops[ST(STOP_GOAL_REACHED)]++;
        d->life.announce = 0;
        d->last.valid = 0;
        publish_plan(d, NULL, GMMRRTD_STOP_GOAL_REACHED);
        publish_status(d, now_us, ST(STATE_IDLE));
        return;
    }
    /* A stale obstacle list: the world may have changed; stop as for a stale pose. */
    if (d->stale_mask & ST(STALE_OBSTACLES)) {
        publish_stop(d, now_us, GMMRRTD_STOP_OBSTACLES_STALE, ST(STATE_STOPPED));
        return;
    }
    /* A stale grid (the raster planned in) or stale scans: the world may have changed. Stale
     * scans with scan_stale_stop = 0 plan on without their marks (gmmrrtd_world_prepare). */
    if (d->have_grid && (d->stale_mask & ST(STALE_GRID))) {
        publish_stop(d, now_us, GMMRRTD_STOP_GRID_STALE, ST(STATE_STOPPED));
        return;
    }
    if ((d->stale_mask & ST(STALE_SCAN)) && d->set.scan_stale_stop) {
        publish_stop(d, now_us, GMMRRTD_STOP_SCAN_STALE, ST(STATE_STOPPED));
        return;
    }

    const gmmrrt_model_t *model = NULL, *background = NULL; /* the chosen model and its file's background */
    int target = -1;
    if (d->goal.task == GMMRRT_NAV_GOAL_T_TASK_AVOID || d->goal.task == GMMRRT_NAV_GOAL_T_TASK_APPROACH) {
        const int avoid = d->goal.task == GMMRRT_NAV_GOAL_T_TASK_AVOID;
        if (!(avoid ? d->have_avoid : (d->have_approach || d->have_approach_set)) &&
            d->set.cfg.planner != GMMRRT_PLANNER_RRT_STAR) {
            reject_once_per_goal(d, ST(REJECT_NO_MODEL), (gmmrrt_status_t)GMMRRTD_STOP_NO_MODEL);
            publish_stop(d, now_us, GMMRRTD_STOP_NO_MODEL, ST(STATE_ERROR));
            return;
        }
        model = avoid ? &d->model_avoid : &d->model_approach;
        if (avoid ? d->has_bg_avoid : d->has_bg_approach)
            background = avoid ? &d->bg_avoid : &d->bg_approach;
    }
    if (d->goal.task == GMMRRT_NAV_GOAL_T_TASK_APPROACH) {
        target = people_usable(d) ? find_person(&d->people, d->goal.target_person_id) : -1;
        if (target < 0) {
            reject_once_per_goal(d, ST(REJECT_UNKNOWN_TARGET), GMMRRTD_STOP_UNKNOWN_TARGET);
            publish_stop(d, now_us, GMMRRTD_STOP_UNKNOWN_TARGET, ST(STATE_STOPPED));
            return;
        }
    }
    if (target >= 0 && d->have_approach_set) {
        /* The set's model of the direction the robot comes from (model_set.h), chosen every cycle. */
        gmmrrt_model_set_t set;
        for (int32_t k = 0; k < GMMRRT_APPROACH_DIRECTIONS; ++k)
            set.model[k] = &d->approach_set[k];
        const gmmrrt_person_t *q = &d->people.people[target];
        const gmmrrt_pose_t person = {q->x, q->y, q->yaw};
        int32_t direction = -1;
        model = gmmrrt_model_set_select(&set, &person, d->pose.x, d->pose.y, &direction);
        /* That direction's own background (index = direction, model_set.h). */
        background = (model && direction >= 0 && direction < GMMRRT_APPROACH_DIRECTIONS &&
                      d->approach_set_has_bg[direction])
                         ? &d->approach_set_bg[direction]
                         : NULL;
        d->status.approach_model = (int8_t)direction;
    }
    if (d->set.cfg.planner == GMMRRT_PLANNER_RRT_STAR) {
        model = NULL;
        background = NULL;
        d->status.approach_model = -1;
    }

    const int64_t setup_start_us = gmmrrtd_mono_us();
    build_problem(d, model, background, target);
    /* The world's set-up (a clearance-grid build after an obstacle change) may take long: the
     * watchdog gets long_step_ms for it (watchdog.c). */
    gmmrrtd_watchdog_long_step(d, 1);
    gmmrrt_status_t st = gmmrrtd_world_prepare(d, now_us);
    if (st == GMMRRT_OK)
        st = gmmrrt_planner_set_problem(d->planner, &d->problem);
    gmmrrtd_watchdog_long_step(d, 0);
    d->status.setup_time_ms = (double)(gmmrrtd_mono_us() - setup_start_us) * 1e-3;
    /* A start inside a person's disc or an inflated obstacle plans an escape (planner.h): the
     * plan first leaves along the shortest way out, then goes on to the goal. */
    const int escaping = st == GMMRRT_ESCAPE;
    if (escaping) {
        d->status.escapes++;
        gmmrrtd_log_limited(&d->rl_escape, gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms,
                            GMMRRTD_LOG_INFO, "escaping (%lld escape cycles): %s", (long long)d->status.escapes,
                            gmmrrt_planner_escape_reason(d->planner));
        st = GMMRRT_OK;
    }
    if (st == GMMRRT_ERR_FROZEN) {
        /* No motion increases the clearance: the only stop left for a start in collision. */
        gmmrrtd_count_stop(d, ST(STOP_FROZEN), "frozen at (%.2f, %.2f): %s", d->pose.x, d->pose.y,
                           gmmrrt_planner_escape_reason(d->planner));
        d->last.valid = 0;
        d->status.last_error = (int32_t)st;
        publish_plan(d, NULL, st);
        publish_status(d, now_us, ST(STATE_STOPPED));
        return;
    }
    if (st != GMMRRT_OK) {
        int8_t state = ST(STATE_STOPPED);
        if (st == GMMRRT_ERR_BUFFER_TOO_SMALL) {
            planning_box_too_large(d, now_us);
            return;
        }
        if (st == GMMRRT_ERR_GOAL_IN_COLLISION || st == GMMRRT_ERR_GOAL_OUT_OF_BOUNDS) {
            reject_once_per_goal(d, ST(REJECT_GOAL_IN_COLLISION), st);
        } else if (st == GMMRRT_ERR_START_IN_COLLISION || st == GMMRRT_ERR_START_OUT_OF_BOUNDS) {
            reject_once_per_goal(d, ST(REJECT_START_IN_COLLISION), st);
        } else {
            reject_once_per_goal(d, ST(REJECT_SETUP), st); /* model mismatch, bad argument: the set-up is wrong */
            state = ST(STATE_ERROR);
        }
        publish_stop(d, now_us, st, state);
        return;
    }

    /* The world keeps the static obstacles' grid while they stay the same (collision.h). */
    gmmrrt_world_grid_stats_t grid = {GMMRRT_GRID_BUILT, 0, 0, 0, 0};
    if (gmmrrt_world_grid_stats(gmmrrt_planner_world(d->planner), &grid) == GMMRRT_OK)
        d->grid_updates[grid.last]++;

    /* No warm start while escaping: the tree is rooted at the exit, not at the robot. */
    const int32_t n_seed = escaping ? 0 : warm_start_seed(d);
    if (n_seed > 0) {
        if (gmmrrt_planner_seed_path(d->planner, d->seed_x, d->seed_y, n_seed) == GMMRRT_OK)
            d->warm_starts++;
    }

    /* The budget covers the whole cycle: set_problem (world build) and the seed come out of it. */
    const double setup_ms = (double)(gmmrrtd_mono_us() - setup_start_us) * 1e-3;
    d->status.setup_time_ms = setup_ms;
    const double time_ms = d->set.budget_ms > 0.0 ? fmax(d->set.budget_ms - setup_ms, 1.0) : 0.0;
    LOG_DEBUG("cycle set-up %.2f ms (grid %s, %lld cells), planning %.2f ms", setup_ms,
              grid.last == GMMRRT_GRID_KEPT ? "kept" : grid.last == GMMRRT_GRID_SHIFTED ? "shifted" : "built",
              (long long)grid.last_cells, time_ms);
    const gmmrrt_budget_t budget = {
        .time_ms = time_ms,
        .max_iterations = d->set.budget_iterations,
        .converge_rel = 0.0,
        .converge_window = 0,
    };
    gmmrrt_plan_stats_t stats = {.first_solution_iteration = -1, .first_solution_ms = -1.0, .best_cost = INFINITY};
    double published_cost = INFINITY;
    int published = 0;
    if (run_with_side(d, now_us, escaping, &budget, &stats, &st, &published, &published_cost) < 0)
        return;
    d->status.iterations = stats.iterations;
    d->status.nodes = stats.nodes;
    d->status.first_solution_ms = stats.first_solution_ms;
    d->status.best_cost = isfinite(stats.best_cost) ? stats.best_cost : -1.0;
    d->status.plan_time_ms = stats.time_ms;
    LOG_DEBUG("cycle: run %.2f ms (%lld iterations), whole cycle so far %.2f ms", stats.time_ms,
              (long long)stats.iterations, (double)(gmmrrtd_mono_us() - setup_start_us) * 1e-3);

    if (published == 0 && (st == GMMRRT_OK || st == GMMRRT_POOL_FULL)) {
        const int r = publish_drivable(d, now_us, escaping, st, &published_cost);
        if (r < 0)
            return;
        published += r;
    }
    if (published > 0) {
        publish_status(d, now_us, ST(STATE_PLANNING));
        return;
    }
    if (st == GMMRRT_OK || st == GMMRRT_POOL_FULL || st == GMMRRT_TIMEOUT || st == GMMRRT_NO_PATH_ON_SIDE)
        st = GMMRRT_NO_PATH_YET;
    if (++d->no_path_cycles >= d->set.unreachable_after_cycles)
        reject_once_per_goal(d, ST(REJECT_GOAL_UNREACHABLE), st);
    publish_stop(d, now_us, st, ST(STATE_STOPPED));
}
