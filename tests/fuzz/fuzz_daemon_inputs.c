/*
 * fuzz_daemon_inputs.c - libFuzzer target for gmmrrtd's message handling (bad and
 * missing input): the bytes of a sequence of LCM messages go through
 * gmmrrtd_handle_message, the function behind the daemon's four LCM handlers (decode and
 * validate, time checks, counters, state update, and in log-clock mode the planning
 * cycles that fall due), so the fuzzer drives the whole daemon from its inputs: the
 * problem it builds, the GMM-RRT* run (paper Alg. 1 with the mixture of eq. 1) and the
 * plan and status it publishes (into a file:///dev/null LCM).
 *
 * Input format (tools/fuzz_corpus.py writes seeds from the scenario logs): records of
 *   [channel: 1 byte, value mod GMMRRTD_NUM_INPUTS = GMMRRTD_IN_*][length: 2 bytes LE][payload: length bytes]
 * (a length past the end takes what is left), then one more cycle after the last record.
 * Each record is received at the log time of its own utime (bytes 8..15, big-endian, as in
 * a recorded log, where the recorder stamps a message as it arrives); a record too short for
 * one arrives at the previous record's time.
 *
 * Each input starts from the same state (a copy taken after set-up). Properties checked
 * (abort = finding): the sanitizers' (memory, UB); the daemon's accepted state is always
 * within bounds and finite; each rejection is counted (counters never decrease); the plan
 * message never claims more waypoints than it holds and every waypoint is finite.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "daemon.h"

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static gmmrrtd_t g_d;        /* the daemon under test */
static gmmrrtd_t g_initial;  /* its state right after set-up */

#define REQUIRE(cond)                                                                   \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "fuzz_daemon_inputs: broken: %s\n", #cond);                 \
            abort();                                                                    \
        }                                                                               \
    } while (0)

/* A features model (D = 2: d [m], theta [rad, wrapped]) with two uncorrelated components. */
static void make_model(gmmrrt_model_t *m, int32_t task, double theta0, double theta1)
{
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_FEATURES;
    m->task = task;
    m->dim = 2;
    m->k = 2;
    m->angle_mask = 0x2;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    const double th[2] = {theta0, theta1};
    for (int i = 0; i < 2; ++i) {
        m->weight[i] = 0.5;
        m->mean[i][0] = 1.2;
        m->mean[i][1] = th[i];
        m->chol[i][0] = 0.3;
        m->chol[i][1] = 0.0;
        m->chol[i][2] = 0.35;
    }
    char err[256];
    if (gmmrrt_model_prepare(m, err, sizeof err) != GMMRRT_OK) {
        fprintf(stderr, "fuzz_daemon_inputs: test model: %s\n", err);
        abort();
    }
}

/* A 20 m x 20 m free map at 10 cm around the origin, so scans mark and the planner reads a raster.
 * Laid out again for every input: the struct copy resets its header, not the cells and marks. */
enum { k_map_side = 200 };
static void reset_map(gmmrrtd_t *d)
{
    if (gmmrrt_raster_set_geometry(&d->map, k_map_side, k_map_side, 0.1, -10.0, -10.0, 0.0, 1) != GMMRRT_OK) {
        fprintf(stderr, "fuzz_daemon_inputs: map geometry refused\n");
        abort();
    }
    memset(d->map.cells, GMMRRT_RASTER_FREE, (size_t)k_map_side * k_map_side);
    (void)gmmrrt_raster_update_distance(&d->map, 0, 0.0);
    d->have_map = 1;
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    gmmrrtd_t *d = &g_d;
    char err[512];
    gmmrrtd_log_set_level(GMMRRTD_LOG_ERROR);
    gmmrrtd_settings_default(&d->set);
    snprintf(d->set.clock, sizeof d->set.clock, "log");
    d->set.budget_ms = 0.0;           /* deterministic: iterations only */
    d->set.budget_iterations = 48;    /* small, so an input runs in well under a millisecond per cycle */
    d->set.cfg.max_nodes = 256;
    d->set.cfg.seed = 7;
    d->set.cfg.grid_resolution_m = 0.5; /* coarse clearance grid: its FCL build dominates a cycle otherwise */
    if (gmmrrtd_settings_validate(&d->set, err, sizeof err) != 0) {
        fprintf(stderr, "fuzz_daemon_inputs: settings: %s\n", err);
        abort();
    }
    d->clock_mode = GMMRRTD_CLOCK_LOG;
    d->staged.input = -1;
    d->status.first_solution_ms = -1.0;
    d->status.best_cost = -1.0;
    make_model(&d->model_avoid, GMMRRT_TASK_AVOID, 1.5707963267948966, -1.5707963267948966);
    make_model(&d->model_approach, GMMRRT_TASK_APPROACH, 0.0, 0.3);
    d->have_avoid = d->have_approach = 1;
    d->mem_size = gmmrrt_planner_mem_size(&d->set.cfg);
    d->mem = aligned_alloc(64, (d->mem_size + 63u) / 64u * 64u); /* lives as long as the process */
    if (d->mem == NULL || gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg) != GMMRRT_OK) {
        fprintf(stderr, "fuzz_daemon_inputs: planner set-up failed\n");
        abort();
    }
    d->lcm_in = d->lcm_out = lcm_create("file:///dev/null?mode=w");
    if (d->lcm_out == NULL) {
        fprintf(stderr, "fuzz_daemon_inputs: cannot open file:///dev/null?mode=w\n");
        abort();
    }
    const size_t map_size = gmmrrt_raster_mem_size(k_map_side * k_map_side, k_map_side);
    d->map_mem = aligned_alloc(64, (map_size + 63u) / 64u * 64u);
    if (d->map_mem == NULL ||
        gmmrrt_raster_init(&d->map, d->map_mem, map_size, k_map_side * k_map_side, k_map_side) != GMMRRT_OK ||
        gmmrrtd_grid_setup(d) != 0) {
        fprintf(stderr, "fuzz_daemon_inputs: raster set-up failed\n");
        abort();
    }
    g_initial = *d;
    return 0;
}

static void check_state(const gmmrrtd_t *d, const int64_t *rejected_before)
{
    for (int i = 0; i < GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS; ++i)
        REQUIRE(d->status.rejected[i] >= rejected_before[i]);
    if (d->have[GMMRRTD_IN_POSE])
        REQUIRE(isfinite(d->pose.x) && isfinite(d->pose.y) && isfinite(d->pose.yaw));
    if (d->have[GMMRRTD_IN_PEOPLE])
        REQUIRE(d->people.num_people >= 0 && d->people.num_people <= GMMRRT_MAX_PEOPLE);
    if (d->have[GMMRRTD_IN_GOAL])
        REQUIRE(isfinite(d->goal.x) && isfinite(d->goal.y) && d->goal.tolerance_m > 0.0);
    if (d->have[GMMRRTD_IN_OBSTACLES])
        REQUIRE(d->obstacles.num_circles >= 0 && d->obstacles.num_circles <= GMMRRT_MAX_CIRCLES &&
                d->obstacles.num_boxes >= 0 && d->obstacles.num_boxes <= GMMRRT_MAX_BOXES);
    const gmmrrt_waypoints_t *p = &d->plan_msg;
    REQUIRE(p->num_waypoints >= 0 && p->num_waypoints <= GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS);
    for (int32_t i = 0; i < p->num_waypoints; ++i)
        REQUIRE(isfinite(p->x[i]) && isfinite(p->y[i]) && isfinite(p->yaw[i]));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gmmrrtd_t *d = &g_d;
    *d = g_initial;
    reset_map(d);
    int64_t before[GMMRRT_PLANNER_STATUS_T_NUM_REJECT_REASONS];
    size_t off = 0;
    int64_t recv = 0;
    while (size - off >= 3) {
        const int input = data[off] % GMMRRTD_NUM_INPUTS;
        size_t len = (size_t)data[off + 1] | (size_t)data[off + 2] << 8;
        off += 3;
        if (len > size - off)
            len = size - off;
        if (len >= 16) {
            uint64_t u = 0;
            for (int b = 8; b < 16; ++b)
                u = u << 8 | data[off + (size_t)b];
            recv = (int64_t)u;
        }
        memcpy(before, d->status.rejected, sizeof before);
        gmmrrtd_handle_message(d, input, recv, data + off, len);
        check_state(d, before);
        off += len;
    }
    if (d->have_time) {
        memcpy(before, d->status.rejected, sizeof before);
        gmmrrtd_cycle(d, d->log_now_us);
        check_state(d, before);
    }
    return 0;
}
