/*
 * fuzz_msg_decode.c - libFuzzer target for every decoder of lcmtypes/include/gmmrrt/msg_decode.h:
 * the first line of defence of the daemon and of the
 * learner's log reader. Each input goes to all nine decoders; the LCM fingerprint in the
 * first 8 bytes decides which one gets past the wire format, so the seed corpus (real
 * encoded messages of each type, tools/fuzz_corpus.py) keeps every decoder busy.
 *
 * Properties checked (abort = finding): no out-of-bounds read, no UB (sanitizers); a
 * rejection comes with a message; an accepted message's counts are within their MAX_*
 * and its meaningful numbers are finite, i.e. what msg_decode.h promises the daemon.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "gmmrrt/msg_decode.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define REQUIRE(cond)                                                                       \
    do {                                                                                    \
        if (!(cond)) {                                                                      \
            fprintf(stderr, "fuzz_msg_decode: accepted message breaks: %s\n", #cond);       \
            abort();                                                                        \
        }                                                                                   \
    } while (0)

static void require_message(gmmrrt_msg_result_t r, const char *err)
{
    if (r != GMMRRT_MSG_OK && err[0] == '\0') {
        fprintf(stderr, "fuzz_msg_decode: rejection %d without a message\n", (int)r);
        abort();
    }
}

static gmmrrt_pose2d_t g_pose;
static gmmrrt_people_t g_people;
static gmmrrt_nav_goal_t g_goal;
static gmmrrt_obstacles_t g_obst;
static gmmrrt_waypoints_t g_wp;
static gmmrrt_planner_status_t g_status;
static gmmrrt_demo_info_t g_info;
static gmmrrt_planar_scan_t g_scan;
static gmmrrt_occupancy_grid_t g_grid;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[256];
    gmmrrt_msg_result_t r;

    err[0] = '\0';
    r = gmmrrt_msg_decode_pose2d(data, size, &g_pose, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK)
        REQUIRE(isfinite(g_pose.x) && isfinite(g_pose.y) && isfinite(g_pose.yaw));

    err[0] = '\0';
    r = gmmrrt_msg_decode_people(data, size, &g_people, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_people.num_people >= 0 && g_people.num_people <= GMMRRT_PEOPLE_T_MAX_PEOPLE);
        for (int32_t i = 0; i < g_people.num_people; ++i)
            REQUIRE(isfinite(g_people.people[i].x) && isfinite(g_people.people[i].y) &&
                    isfinite(g_people.people[i].yaw) && g_people.people[i].id >= 0);
    }

    err[0] = '\0';
    r = gmmrrt_msg_decode_nav_goal(data, size, &g_goal, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK)
        REQUIRE(isfinite(g_goal.x) && isfinite(g_goal.y) && g_goal.tolerance_m > 0.0 && g_goal.task >= 0 &&
                g_goal.task <= 2);

    err[0] = '\0';
    r = gmmrrt_msg_decode_obstacles(data, size, &g_obst, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_obst.num_circles >= 0 && g_obst.num_circles <= GMMRRT_OBSTACLES_T_MAX_CIRCLES);
        REQUIRE(g_obst.num_boxes >= 0 && g_obst.num_boxes <= GMMRRT_OBSTACLES_T_MAX_BOXES);
        for (int32_t i = 0; i < g_obst.num_circles; ++i)
            REQUIRE(isfinite(g_obst.circle_x[i]) && isfinite(g_obst.circle_y[i]) && g_obst.circle_radius[i] > 0.0 &&
                    isfinite(g_obst.circle_radius[i]));
        for (int32_t i = 0; i < g_obst.num_boxes; ++i)
            REQUIRE(isfinite(g_obst.box_x[i]) && isfinite(g_obst.box_y[i]) && g_obst.box_width[i] > 0.0 &&
                    g_obst.box_height[i] > 0.0 && isfinite(g_obst.box_width[i]) && isfinite(g_obst.box_height[i]) &&
                    isfinite(g_obst.box_yaw[i]));
    }

    err[0] = '\0';
    r = gmmrrt_msg_decode_waypoints(data, size, &g_wp, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK)
        REQUIRE(g_wp.num_waypoints >= 0 && g_wp.num_waypoints <= GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS);

    err[0] = '\0';
    r = gmmrrt_msg_decode_planner_status(data, size, &g_status, err, sizeof err);
    require_message(r, err);

    err[0] = '\0';
    r = gmmrrt_msg_decode_demo_info(data, size, &g_info, err, sizeof err);
    require_message(r, err);

    /* A scan: bounded count, finite geometry; ranges may be anything ("no return"). */
    err[0] = '\0';
    r = gmmrrt_msg_decode_planar_scan(data, size, &g_scan, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_scan.num_ranges >= 0 && g_scan.num_ranges <= GMMRRT_PLANAR_SCAN_T_MAX_RANGES);
        REQUIRE(isfinite(g_scan.rad0) && isfinite(g_scan.radstep) && isfinite(g_scan.sensor_x) &&
                isfinite(g_scan.sensor_y) && isfinite(g_scan.sensor_yaw));
        REQUIRE(g_scan.range_min_m >= 0.0 && g_scan.range_max_m > g_scan.range_min_m && isfinite(g_scan.range_max_m));
    }

    /* A grid: sides and count agree within MAX_CELLS, finite geometry, cells -1..100, and the
     * frame string never owned by the caller (the leak checker sees any string left behind). */
    err[0] = '\0';
    r = gmmrrt_msg_decode_occupancy_grid(data, size, &g_grid, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_grid.width >= 1 && g_grid.height >= 1 &&
                (int64_t)g_grid.width * g_grid.height == g_grid.num_cells &&
                g_grid.num_cells <= GMMRRT_OCCUPANCY_GRID_T_MAX_CELLS);
        REQUIRE(isfinite(g_grid.resolution_m) && g_grid.resolution_m > 0.0 && isfinite(g_grid.origin_x) &&
                isfinite(g_grid.origin_y) && isfinite(g_grid.origin_yaw));
        for (int32_t k = 0; k < g_grid.num_cells; ++k)
            REQUIRE(g_grid.data[k] >= -1 && g_grid.data[k] <= 100);
    }
    return 0;
}
