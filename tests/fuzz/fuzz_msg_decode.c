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
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

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

/* An accepted frame: the promised name (1..64 printable bytes, no space), then released (a leak
 * or a double free is the sanitizer's to catch). */
static void require_frame(char **frame)
{
    REQUIRE(*frame != NULL);
    const size_t n = strlen(*frame);
    REQUIRE(n >= 1 && n <= GMMRRT_MSG_FRAME_MAX);
    for (size_t i = 0; i < n; ++i)
        REQUIRE((*frame)[i] > 0x20 && (*frame)[i] < 0x7f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[256];
    gmmrrt_msg_result_t r;

    err[0] = '\0';
    r = gmmrrt_msg_decode_pose2d(data, size, &g_pose, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(isfinite(g_pose.x) && isfinite(g_pose.y) && isfinite(g_pose.yaw));
        require_frame(&g_pose.frame);
        gmmrrt_msg_release_pose2d(&g_pose);
    } else
        REQUIRE(g_pose.frame == NULL);

    err[0] = '\0';
    r = gmmrrt_msg_decode_people(data, size, &g_people, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_people.num_people >= 0 && g_people.num_people <= GMMRRT_PEOPLE_T_MAX_PEOPLE);
        for (int32_t i = 0; i < g_people.num_people; ++i)
            REQUIRE(isfinite(g_people.people[i].x) && isfinite(g_people.people[i].y) &&
                    isfinite(g_people.people[i].yaw) && g_people.people[i].id >= 0);
        require_frame(&g_people.frame);
        gmmrrt_msg_release_people(&g_people);
    }

    err[0] = '\0';
    r = gmmrrt_msg_decode_nav_goal(data, size, &g_goal, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_goal.goal_id > 0);
        REQUIRE(g_goal.command == GMMRRT_NAV_GOAL_T_COMMAND_NEW || g_goal.command == GMMRRT_NAV_GOAL_T_COMMAND_CANCEL);
        if (g_goal.command == GMMRRT_NAV_GOAL_T_COMMAND_NEW)
            REQUIRE(isfinite(g_goal.x) && isfinite(g_goal.y) && g_goal.tolerance_m > 0.0 && g_goal.task >= 0 &&
                    g_goal.task <= 2 && g_goal.yaw_tolerance_rad >= 0.0 && g_goal.yaw_tolerance_rad <= M_PI &&
                    g_goal.preferred_side >= -1 && g_goal.preferred_side <= 1);
        require_frame(&g_goal.frame);
        gmmrrt_msg_release_nav_goal(&g_goal);
    }

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
        require_frame(&g_obst.frame);
        gmmrrt_msg_release_obstacles(&g_obst);
    }

    err[0] = '\0';
    r = gmmrrt_msg_decode_waypoints(data, size, &g_wp, err, sizeof err);
    require_message(r, err);
    if (r == GMMRRT_MSG_OK) {
        REQUIRE(g_wp.num_waypoints >= 0 && g_wp.num_waypoints <= GMMRRT_WAYPOINTS_T_MAX_WAYPOINTS);
        require_frame(&g_wp.frame);
        gmmrrt_msg_release_waypoints(&g_wp);
    }

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

    /* A grid: sides and count agree within MAX_CELLS, finite geometry, cells -1..100, and its
     * frame as every framed type's (a rejected grid holds none). */
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
        require_frame(&g_grid.frame);
        gmmrrt_msg_release_occupancy_grid(&g_grid);
    } else
        REQUIRE(g_grid.frame == NULL);
    return 0;
}
