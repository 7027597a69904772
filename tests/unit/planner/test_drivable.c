/*
 * test_drivable.c - planner.drivable: drivable paths (drivable.h, smooth.c), arrival headings,
 * the escape from a start in collision (escape.c) and walking people (moving_people.c).
 * Oracles: the output's own geometry (turn between consecutive chords against the bound,
 * chords checked with the collision world), the exact time along the path for walkers, and a
 * standing person given a sub-threshold velocity planned bit for bit as one without.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#include "gmmrrt/drivable.h"
#include "gmmrrt/features.h"
#include "gmmrrt/model_set.h"
#include "planner_fixtures.h"
#include "planner_internal.h" /* gmmrrt_walkers_cost */

static gmmrrt_budget_t iters(int64_t n) { return (gmmrrt_budget_t){0.0, n, 0.0, 0}; }

/* Largest heading change between consecutive chords divided by the mean chord length (1/m),
 * over chords longer than 1 mm (the turn per metre a follower of the waypoints sees). */
static double max_turn_per_m(const gmmrrt_path_t *path)
{
    double worst = 0.0;
    for (int32_t i = 1; i + 1 < path->num_points; ++i) {
        const double ax = path->x[i] - path->x[i - 1], ay = path->y[i] - path->y[i - 1];
        const double bx = path->x[i + 1] - path->x[i], by = path->y[i + 1] - path->y[i];
        const double la = hypot(ax, ay), lb = hypot(bx, by);
        if (la < 1e-3 || lb < 1e-3)
            continue;
        const double turn = fabs(gmmrrt_wrap_angle(atan2(by, bx) - atan2(ay, ax)));
        const double k = turn / (0.5 * (la + lb));
        if (k > worst)
            worst = k;
    }
    return worst;
}

static void assert_chords_free(const gmmrrt_planner_t *p, const gmmrrt_path_t *path, int32_t from)
{
    const gmmrrt_world_t *w = gmmrrt_planner_world(p);
    for (int32_t i = from; i + 1 < path->num_points; ++i)
        if (!gmmrrt_world_segment_free(w, path->x[i], path->y[i], path->x[i + 1], path->y[i + 1])) {
            fail_msg("chord %d (%.3f, %.3f)-(%.3f, %.3f) is not free", i, path->x[i], path->y[i], path->x[i + 1],
                     path->y[i + 1]);
        }
}

static gmmrrt_problem_t clutter_problem(void)
{
    gmmrrt_problem_t pr = empty_problem(-5.0, -1.0, 5.0, 1.0);
    pr.obstacles.num_circles = 3;
    pr.obstacles.circles[0] = (gmmrrt_circle_t){-2.0, 0.0, 0.8};
    pr.obstacles.circles[1] = (gmmrrt_circle_t){1.5, 1.0, 0.6};
    pr.obstacles.circles[2] = (gmmrrt_circle_t){1.0, -2.0, 0.7};
    pr.obstacles.num_boxes = 1;
    pr.obstacles.boxes[0] = (gmmrrt_box_t){3.5, -0.5, 0.4, 2.0, 0.3};
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){-0.3, -0.8, 1.0};
    return pr;
}

static void test_no_output_turn_exceeds_the_bound(void **state)
{
    (void)state;
    const double radii[] = {0.3, 0.6};
    for (int r = 0; r < 2; ++r) {
        for (uint64_t seed = 1; seed <= 4; ++seed) {
            gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
            cfg.robot_radius_m = 0.3;
            cfg.seed = seed;
            test_planner_t t;
            assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
            gmmrrt_problem_t pr = clutter_problem();
            assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
            gmmrrt_budget_t b = iters(3000);
            gmmrrt_plan_stats_t st;
            assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
            gmmrrt_drive_options_t opt;
            gmmrrt_drive_options_default(&opt);
            opt.min_turn_radius_m = radii[r];
            gmmrrt_path_t raw, path;
            gmmrrt_drive_report_t rep;
            assert_int_equal(gmmrrt_planner_best_path(t.p, &raw), GMMRRT_OK);
            assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
            const double k = max_turn_per_m(&path);
            printf("R %.1f seed %d: raw %.2f m turn %.1f rad/m; drivable %.2f m turn %.2f rad/m (bound %.2f), "
                   "vertices %d -> %d, tight %d, in place %d\n",
                   radii[r], (int)seed, raw.length_m, max_turn_per_m(&raw), path.length_m, k, 1.0 / radii[r],
                   rep.vertices_in, rep.vertices_out, rep.tight_turns, rep.turns_in_place);
            assert_int_equal(rep.tight_turns, 0);
            assert_int_equal(rep.turns_in_place, 0);
            assert_true(rep.max_curvature <= 1.0 / radii[r] * (1.0 + 1e-9));
            /* Chords of an arc turn by chord / R; 2 % for the chord-vs-arc length difference. */
            assert_true(k <= 1.02 / radii[r]);
            assert_chords_free(t.p, &path, 0);
            /* Shortcuts never raise the planner's cost. */
            assert_true(rep.cost <= st.best_cost * (1.0 + 1e-9));
            assert_true(path.length_m <= raw.length_m + 1e-9);
            /* yaw is the tangent: within half a chord's turn of the chord's direction. */
            for (int32_t i = 0; i + 1 < path.num_points; ++i) {
                const double chord = atan2(path.y[i + 1] - path.y[i], path.x[i + 1] - path.x[i]);
                const double len = hypot(path.y[i + 1] - path.y[i], path.x[i + 1] - path.x[i]);
                if (len > 1e-3)
                    assert_true(fabs(gmmrrt_wrap_angle(path.yaw[i] - chord)) <= 0.51 * len / radii[r] + 1e-9);
            }
            assert_true(path.x[0] == pr.start_x && path.y[0] == pr.start_y);
            assert_true(path.x[path.num_points - 1] == pr.goal_x && path.y[path.num_points - 1] == pr.goal_y);
            test_planner_free(&t);
        }
    }
}

static void test_zero_radius_turns_in_place(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = disc_problem();
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = iters(3000);
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    gmmrrt_drive_options_t opt;
    gmmrrt_drive_options_default(&opt);
    opt.min_turn_radius_m = 0.0;
    gmmrrt_path_t path;
    gmmrrt_drive_report_t rep;
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
    assert_true(rep.turns_in_place > 0);
    assert_true(rep.max_curvature == 0.0);
    assert_chords_free(t.p, &path, 0);
    test_planner_free(&t);
}

/* A tree path of far more vertices than GMMRRT_DRIVE_MAX_VERTICES, all but one of them on two
 * straight legs (what rewiring along a straight stretch leaves, off the line by rounding only):
 * the smoother takes it as the three-vertex polyline it is. */
static void test_long_collinear_tree_path_is_taken(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-5.0, 0.0, 5.0, 0.0);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    enum { LEG = 400 };
    static double x[2 * LEG + 1], y[2 * LEG + 1];
    for (int i = 0; i <= 2 * LEG; ++i) {
        const double f = (double)(i % LEG) / LEG;
        const double jitter = (i % 2 ? 1e-9 : -1e-9); /* rounding-size offsets from the line */
        x[i] = i < LEG ? -5.0 + 5.0 * f : (i == 2 * LEG ? 5.0 : 5.0 * f);
        y[i] = (i < LEG ? 1.0 * f : (i == 2 * LEG ? 0.0 : 1.0 - f)) + (i % LEG ? jitter : 0.0);
    }
    assert_int_equal(gmmrrt_planner_seed_path(t.p, x, y, 2 * LEG + 1), GMMRRT_OK);
    assert_true(gmmrrt_planner_node_count(t.p) > GMMRRT_DRIVE_MAX_VERTICES);
    gmmrrt_drive_options_t opt;
    gmmrrt_drive_options_default(&opt);
    gmmrrt_path_t path;
    gmmrrt_drive_report_t rep;
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
    assert_true(rep.vertices_in <= 4);
    assert_true(path.num_points >= 2);
    assert_true(fabs(path.x[path.num_points - 1] - 5.0) < 1e-6 && fabs(path.y[path.num_points - 1]) < 1e-6);
    assert_chords_free(t.p, &path, 0);
    test_planner_free(&t);
}

/* Approach from behind: the person faces +x, the robot starts 3 m behind them, the goal is
 * 1.2 m in front; the path must go round and arrive facing the person. */
static void test_approach_from_behind_arrives_facing(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.robot_radius_m = 0.3;
        cfg.seed = seed;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-3.0, 0.2, 1.2, 0.0);
        pr.task = GMMRRT_TASK_APPROACH;
        pr.target_person = 0;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = iters(3000);
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        opt.arrival = GMMRRT_ARRIVAL_FACE_TARGET;
        gmmrrt_path_t raw, path;
        gmmrrt_drive_report_t rep;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &raw), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
        const double facing = M_PI; /* from the goal (1.2, 0) to the person at the origin */
        const double raw_err = fabs(gmmrrt_wrap_angle(raw.yaw[raw.num_points - 1] - facing));
        const double err = fabs(gmmrrt_wrap_angle(path.yaw[path.num_points - 1] - facing));
        printf("seed %d: arrival error raw %.1f deg, drivable %.1f deg (reported %.1f), tight %d\n", (int)seed,
               raw_err * 180.0 / M_PI, err * 180.0 / M_PI, rep.arrival_error_rad * 180.0 / M_PI, rep.tight_turns);
        assert_true(err <= 15.0 * M_PI / 180.0);
        assert_true(rep.arrival_met);
        assert_true(fabs(rep.arrival_error_rad - err) < 1e-9);
        assert_int_equal(rep.tight_turns, 0);
        assert_true(max_turn_per_m(&path) <= 1.02 / opt.min_turn_radius_m);
        assert_chords_free(t.p, &path, 0);
        test_planner_free(&t);
    }
}

/* Where the polyline crosses the vertical line x = x0 (the person's), the y of each crossing:
 * an oracle of the side a path passes a person, independent of smooth.c's swept angles. */
static int32_t crossings_at_x(const gmmrrt_path_t *path, double x0, double *ys, int32_t cap)
{
    int32_t n = 0;
    for (int32_t i = 0; i + 1 < path->num_points && n < cap; ++i) {
        const double a = path->x[i] - x0, b = path->x[i + 1] - x0;
        if ((a < 0.0) != (b < 0.0))
            ys[n++] = path->y[i] + (path->y[i + 1] - path->y[i]) * a / (a - b);
    }
    return n;
}

/* Approach from the person's right, arriving in front of them and a little to their left (a
 * Table 1 scene, "approach / right", demonstration start and goal): the tree path goes round
 * the right side. The arrival leg that faces the person starts further out in front; the vertex
 * that sees the leg's start with room for both arcs used to be the robot's start, whose chord
 * passes the person's left: the drivable path swapped sides. Every plan must stay on the right. */
static void test_arrival_leg_keeps_the_tree_path_side_of_the_person(void **state)
{
    (void)state;
    const double tree_x[] = {-3.305, -2.17, -1.13, 0.04, 0.57, 0.9, 0.78, 0.7728};
    const double tree_y[] = {-0.201, -0.57, -1.11, -1.27, -1.01, -0.52, 0.04, 0.1835};
    const int32_t n = (int32_t)(sizeof tree_x / sizeof tree_x[0]);
    const double radii[] = {0.3, 0.5, 0.0};
    for (int r = 0; r < 3; ++r) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.robot_radius_m = 0.3;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(tree_x[0], tree_y[0], tree_x[n - 1], tree_y[n - 1]);
        pr.task = GMMRRT_TASK_APPROACH;
        pr.target_person = 0;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_seed_path(t.p, tree_x + 1, tree_y + 1, n - 1), GMMRRT_OK);
        gmmrrt_path_t raw, path;
        assert_int_equal(gmmrrt_planner_best_path(t.p, &raw), GMMRRT_OK);
        double ys[8];
        assert_int_equal(crossings_at_x(&raw, 0.0, ys, 8), 1);
        assert_true(ys[0] < 0.0); /* the tree path: the person's right */
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        opt.arrival = GMMRRT_ARRIVAL_FACE_TARGET;
        opt.min_turn_radius_m = radii[r];
        gmmrrt_drive_report_t rep;
        assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
        const int32_t nc = crossings_at_x(&path, 0.0, ys, 8);
        printf("radius %.1f: %d crossing(s) of x = 0, first at y = %.2f; arrival %.1f deg off, side kept %d\n",
               radii[r], (int)nc, nc ? ys[0] : NAN, rep.arrival_error_rad * 180.0 / M_PI, (int)rep.side_kept);
        assert_int_equal(nc, 1);
        assert_true(ys[0] < -(cfg.robot_radius_m + cfg.person_radius_m));
        assert_true(rep.side_kept);
        assert_true(rep.arrival_met);
        assert_chords_free(t.p, &path, 0);
        test_planner_free(&t);
    }
}

/* A right-angle corner hugging the corner of a box: no arc of 0.3 m is free there and the chord
 * over it crosses the box, so the corner is turned tighter. The path is returned all the same,
 * flagged GMMRRT_TIGHT_TURNS (and counted); with R = 0 turning in place is allowed: GMMRRT_OK. */
static void test_a_corner_without_a_free_arc_is_flagged(void **state)
{
    (void)state;
    const double tree_x[] = {-1.5, 0.05, 0.05}, tree_y[] = {0.05, 0.05, -1.5};
    const double radii[] = {0.3, 0.0};
    for (int r = 0; r < 2; ++r) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(tree_x[0], tree_y[0], tree_x[2], tree_y[2]);
        pr.obstacles.num_boxes = 1;
        pr.obstacles.boxes[0] = (gmmrrt_box_t){-1.0, -1.0, 2.0, 2.0, 0.0}; /* x, y in [-2, 0] */
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_seed_path(t.p, tree_x + 1, tree_y + 1, 2), GMMRRT_OK);
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        opt.min_turn_radius_m = radii[r];
        gmmrrt_path_t path;
        gmmrrt_drive_report_t rep;
        const gmmrrt_status_t st = gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep);
        printf("radius %.1f: status %d, tight %d, in place %d\n", radii[r], st, rep.tight_turns, rep.turns_in_place);
        assert_int_equal(st, rep.status);
        assert_true(path.num_points > 10);
        assert_chords_free(t.p, &path, 0);
        if (radii[r] > 0.0) {
            assert_int_equal(st, GMMRRT_TIGHT_TURNS);
            assert_true(rep.tight_turns + rep.turns_in_place >= 1);
            assert_true(max_turn_per_m(&path) > 1.02 / radii[r]); /* the flag is true: it does turn tighter */
        } else {
            assert_int_equal(st, GMMRRT_OK);
        }
        test_planner_free(&t);
    }
}

/* A right-angle corner rounded by the arc of R = 0.6 m round a disc c = 2.3 mm inside it: a
 * circle obstacle concentric with the arc, one nearest the arc's middle, and a person at the
 * arc's centre. The arc's own chords of at most 5 cm cut inside it by at most
 * (0.05)^2 / 8R = 0.52 mm and stay outside the 1 mm edge margin; chords 0.1 m apart (the default
 * waypoint spacing) cut inside by up to 2.1 mm and come within 0.2 mm of the disc. The published
 * chords are what the robot drives: every one must pass the collision world's segment test, and
 * the corner stays round (no tight turn, the turn bound kept). Failed before: a 0.1 m chord of
 * the arc was published unchecked. */
static void test_published_chords_of_an_arc_close_to_its_inside_are_free(void **state)
{
    (void)state;
    const double R = 0.6, c = 0.0023;
    const double tree_x[] = {-2.0, 0.0, 0.0}, tree_y[] = {0.0, 0.0, -2.0};
    /* the disc's centre: the arc's centre, or 0.3 m from it towards the corner (nearest the
     * arc's middle); the third disc is a person */
    const double inside[3][2] = {{-R, -R}, {-R + 0.3 * M_SQRT1_2, -R + 0.3 * M_SQRT1_2}, {-R, -R}};
    for (int d = 0; d < 3; ++d) {
        const double cx = inside[d][0], cy = inside[d][1];
        /* radius: the arc's nearest point to the disc's centre is c clear of it */
        const double radius = R - hypot(cx + R, cy + R) - c;
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.person_radius_m = radius;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(tree_x[0], tree_y[0], tree_x[2], tree_y[2]);
        if (d < 2) {
            pr.obstacles.num_circles = 1;
            pr.obstacles.circles[0] = (gmmrrt_circle_t){cx, cy, radius};
        } else {
            pr.obstacles.num_people = 1;
            pr.obstacles.people[0] = (gmmrrt_pose_t){cx, cy, 0.0};
        }
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_seed_path(t.p, tree_x + 1, tree_y + 1, 2), GMMRRT_OK);
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        opt.min_turn_radius_m = R;
        opt.shortcut = 0; /* the corner as given (the small disc leaves the chord over it free) */
        gmmrrt_path_t path;
        gmmrrt_drive_report_t rep;
        const gmmrrt_status_t st = gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep);
        double nearest = INFINITY; /* the published polyline's clearance to the disc */
        for (int32_t i = 0; i + 1 < path.num_points; ++i) {
            const double ax = path.x[i], ay = path.y[i], bx = path.x[i + 1], by = path.y[i + 1];
            const double l2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
            double u = l2 > 0.0 ? ((cx - ax) * (bx - ax) + (cy - ay) * (by - ay)) / l2 : 0.0;
            u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
            const double dist = hypot(ax + u * (bx - ax) - cx, ay + u * (by - ay) - cy) - radius;
            if (dist < nearest)
                nearest = dist;
        }
        printf("disc %d: status %d, %d waypoints, tight %d, nearest chord %.2f mm from the disc\n", d, st,
               (int)path.num_points, rep.tight_turns, 1e3 * nearest);
        assert_int_equal(st, GMMRRT_OK);
        assert_int_equal(rep.tight_turns, 0);
        assert_int_equal(rep.turns_in_place, 0);
        assert_chords_free(t.p, &path, 0);
        assert_true(nearest > GMMRRT_EDGE_MIN_CLEARANCE_M);
        assert_true(nearest < c); /* the corner is rounded on the arc, not cut wider */
        assert_true(max_turn_per_m(&path) <= 1.02 / R);
        assert_true(path.x[path.num_points - 1] == pr.goal_x && path.y[path.num_points - 1] == pr.goal_y);
        test_planner_free(&t);
    }
}

/* The same corner on a path too long for GMMRRT_MAX_WAYPOINTS at a 5 cm spacing: the equally
 * spaced waypoints are widened to fit (7.7 cm apart, cutting 1.25 mm inside the arc) and come
 * within the edge margin of a disc 1.9 mm inside the arc; the arc is then published at its own
 * 5 cm chords and the straight parts are widened instead, within the capacity. */
static void test_published_chords_of_a_long_path_fit_the_capacity(void **state)
{
    (void)state;
    const double R = 0.6, c = 0.0019;
    const double tree_x[] = {-6.0, 6.0, 6.0}, tree_y[] = {4.0, 4.0, -4.0};
    const double cx = 6.0 - R, cy = 4.0 - R, radius = R - c; /* concentric with the arc */
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.waypoint_spacing_m = 0.05;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(tree_x[0], tree_y[0], tree_x[2], tree_y[2]);
    pr.obstacles.num_circles = 1;
    pr.obstacles.circles[0] = (gmmrrt_circle_t){cx, cy, radius};
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    assert_int_equal(gmmrrt_planner_seed_path(t.p, tree_x + 1, tree_y + 1, 2), GMMRRT_OK);
    gmmrrt_drive_options_t opt;
    gmmrrt_drive_options_default(&opt);
    opt.min_turn_radius_m = R;
    opt.shortcut = 0;
    gmmrrt_path_t path;
    gmmrrt_drive_report_t rep;
    const gmmrrt_status_t st = gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep);
    double nearest = INFINITY, longest = 0.0;
    int32_t on_arc = 0; /* waypoints on the arc (within 0.1 mm of its circle, inside its quarter) */
    for (int32_t i = 0; i < path.num_points; ++i) {
        if (path.x[i] > cx - 1e-9 && path.y[i] > cy - 1e-9 && fabs(hypot(path.x[i] - cx, path.y[i] - cy) - R) < 1e-4)
            ++on_arc;
        if (i + 1 == path.num_points)
            break;
        const double ax = path.x[i], ay = path.y[i], bx = path.x[i + 1], by = path.y[i + 1];
        const double l2 = (bx - ax) * (bx - ax) + (by - ay) * (by - ay);
        double u = l2 > 0.0 ? ((cx - ax) * (bx - ax) + (cy - ay) * (by - ay)) / l2 : 0.0;
        u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
        nearest = fmin(nearest, hypot(ax + u * (bx - ax) - cx, ay + u * (by - ay) - cy) - radius);
        longest = fmax(longest, sqrt(l2));
    }
    printf("status %d, %d waypoints (%d on the arc), longest chord %.1f cm, nearest chord %.2f mm from the disc\n",
           st, (int)path.num_points, (int)on_arc, 1e2 * longest, 1e3 * nearest);
    assert_int_equal(st, GMMRRT_OK);
    assert_int_equal(rep.tight_turns, 0);
    assert_true(path.num_points <= GMMRRT_MAX_WAYPOINTS);
    assert_true(longest > cfg.waypoint_spacing_m); /* the straight parts were widened to fit */
    assert_true(on_arc >= (int32_t)ceil(0.5 * M_PI * R / 0.05) + 1); /* the arc at its own 5 cm chords */
    assert_chords_free(t.p, &path, 0);
    assert_true(nearest > GMMRRT_EDGE_MIN_CLEARANCE_M && nearest < c);
    assert_true(max_turn_per_m(&path) <= 1.02 / R);
    assert_true(path.x[path.num_points - 1] == pr.goal_x && path.y[path.num_points - 1] == pr.goal_y);
    test_planner_free(&t);
}

static void test_arrival_yaw_is_honoured_and_options_checked(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 2.0, 0.0);
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    gmmrrt_budget_t b = iters(2000);
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    gmmrrt_drive_options_t opt;
    gmmrrt_drive_options_default(&opt);
    opt.arrival = GMMRRT_ARRIVAL_YAW;
    opt.goal_yaw = M_PI / 2.0; /* arrive heading +y */
    opt.goal_yaw_tolerance_rad = 5.0 * M_PI / 180.0;
    gmmrrt_path_t path;
    gmmrrt_drive_report_t rep;
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
    assert_true(rep.arrival_met);
    assert_true(fabs(gmmrrt_wrap_angle(path.yaw[path.num_points - 1] - M_PI / 2.0)) <= 5.0 * M_PI / 180.0);
    opt.goal_yaw_tolerance_rad = 0.0;
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_ERR_INVALID_ARGUMENT);
    opt.goal_yaw_tolerance_rad = 0.1;
    opt.min_turn_radius_m = NAN;
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_ERR_INVALID_ARGUMENT);
    opt.min_turn_radius_m = 0.3;
    opt.arrival = GMMRRT_ARRIVAL_FACE_TARGET; /* no approach target in this problem */
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_ERR_INVALID_ARGUMENT);
    test_planner_free(&t);
}

/* A person steps into the robot's disc: one set_problem + run escapes and reaches the goal. */
static void test_person_stepping_into_the_disc_is_escaped(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.robot_radius_m = 0.3;
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(0.0, 0.0, 4.0, 0.0);
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){0.35, 0.1, M_PI}; /* 0.36 m away, contact at 0.55 m */
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ESCAPE);
    assert_non_null(strstr(gmmrrt_planner_escape_reason(t.p), "person 0"));
    gmmrrt_budget_t b = iters(3000);
    assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
    gmmrrt_drive_options_t opt;
    gmmrrt_drive_options_default(&opt);
    gmmrrt_path_t path;
    gmmrrt_drive_report_t rep;
    assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_ESCAPE);
    assert_int_equal(rep.status, GMMRRT_ESCAPE);
    assert_true(path.x[0] == 0.0 && path.y[0] == 0.0);
    assert_true(path.x[path.num_points - 1] == 4.0 && path.y[path.num_points - 1] == 0.0);
    /* Distance to the person never falls until the robot is clear (0.55 m), and stays clear. */
    const double contact = cfg.robot_radius_m + cfg.person_radius_m;
    double prev = 0.0;
    int clear = 0;
    for (int32_t i = 0; i < path.num_points; ++i) {
        const double d = hypot(path.x[i] - 0.35, path.y[i] - 0.1);
        if (!clear)
            assert_true(d >= prev - 1e-12);
        else
            assert_true(d > contact);
        if (d > contact)
            clear = 1;
        prev = d;
    }
    assert_true(clear);
    /* The shortest way out is straight away from the person (within the 5 degree ray spacing). */
    const double away = atan2(0.0 - 0.1, 0.0 - 0.35);
    assert_true(fabs(gmmrrt_wrap_angle(atan2(path.y[1], path.x[1]) - away)) <= 2.5 * M_PI / 180.0 + 1e-9);
    test_planner_free(&t);
}

/* A person steps in beside the robot, the goal ahead: the escape leaves straight away from them
 * and then drives an arc of the turning radius onto the way to the goal instead of turning on the
 * spot at the exit. With the goal behind the person (the way out points away from it) no arc of
 * that radius is free: the robot turns on the spot there, counted. */
static void test_escape_ends_with_a_drivable_arc_when_one_is_free(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.robot_radius_m = 0.3;
    const double contact = cfg.robot_radius_m + cfg.person_radius_m;
    const struct {
        double px, py;
        int in_place;
    } cases[] = {{0.0, 0.35, 0}, {0.35, 0.1, 1}};
    for (int c = 0; c < 2; ++c) {
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(0.0, 0.0, 4.0, 0.0);
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){cases[c].px, cases[c].py, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ESCAPE);
        gmmrrt_budget_t b = iters(3000);
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        gmmrrt_path_t path;
        gmmrrt_drive_report_t rep;
        assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_ESCAPE);
        printf("person (%.2f, %.2f): turns in place %d, tight %d, max turn %.2f 1/m (bound %.2f)\n", cases[c].px,
               cases[c].py, rep.turns_in_place, rep.tight_turns, max_turn_per_m(&path), 1.02 / opt.min_turn_radius_m);
        assert_int_equal(rep.turns_in_place, cases[c].in_place);
        if (!cases[c].in_place) {
            assert_int_equal(rep.tight_turns, 0);
            assert_true(max_turn_per_m(&path) <= 1.02 / opt.min_turn_radius_m);
        }
        /* The distance to the person never falls until clear, and then stays clear. */
        double prev = 0.0;
        int clear = 0;
        for (int32_t i = 0; i < path.num_points; ++i) {
            const double dist = hypot(path.x[i] - cases[c].px, path.y[i] - cases[c].py);
            if (!clear)
                assert_true(dist >= prev - 1e-12);
            else
                assert_true(dist > contact);
            clear = clear || dist > contact;
            prev = dist;
        }
        assert_true(clear);
        assert_chords_free(t.p, &path, (int32_t)ceil(0.6 / cfg.waypoint_spacing_m)); /* past the way out */
        test_planner_free(&t);
    }
}

/* A start outside every disc but closer than the edge margin (1 mm, collision.h) to one: the
 * point is free, yet every edge from it passes within the margin and is refused. It used to give
 * no path, cycle after cycle (a closed-loop robot stalled at the edge of a person's disc, 0.55 m
 * from them); it is a start to leave like one in contact: an escape, then the goal. */
static void test_start_within_the_edge_margin_of_a_disc_escapes(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    cfg.robot_radius_m = 0.3;
    const double contact = cfg.robot_radius_m + cfg.person_radius_m;
    const double gaps[] = {0.0005, 0.0};
    for (int g = 0; g < 2; ++g) {
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(contact + gaps[g], 0.0, 4.0, 1.0);
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, 0.0};
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ESCAPE);
        if (gaps[g] > 0.0)
            assert_true(gmmrrt_world_point_free(gmmrrt_planner_world(t.p), pr.start_x, pr.start_y));
        gmmrrt_budget_t b = iters(2000);
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        gmmrrt_path_t path;
        gmmrrt_drive_report_t rep;
        assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_ESCAPE);
        assert_true(path.x[0] == pr.start_x && path.y[0] == pr.start_y);
        assert_true(hypot(path.x[path.num_points - 1] - 4.0, path.y[path.num_points - 1] - 1.0) < 1e-9);
        for (int32_t i = 1; i < path.num_points; ++i) /* never closer to the person than the start */
            assert_true(hypot(path.x[i], path.y[i]) >= contact + gaps[g] - 1e-9);
        test_planner_free(&t);
    }
}

/* A walker crossing the robot's line where the robot will be: the plan keeps clear of where
 * they are at each waypoint's time, while the prediction-free plan meets them. */
static void test_walker_crossing_is_passed_at_a_safe_distance(void **state)
{
    (void)state;
    const double speed = 1.0, vy = -0.6;
    for (int with_velocity = 0; with_velocity <= 1; ++with_velocity) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
        cfg.robot_radius_m = 0.3;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){1.0, 3.0, -M_PI / 2.0}; /* at (1, 0) at t = 5 s */
        pr.person_vy[0] = with_velocity ? vy : 0.0;
        pr.nominal_speed_m_s = speed;
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = iters(4000);
        assert_int_equal(gmmrrt_planner_run(t.p, &b, NULL), GMMRRT_OK);
        gmmrrt_drive_options_t opt;
        gmmrrt_drive_options_default(&opt);
        gmmrrt_path_t path;
        gmmrrt_drive_report_t rep;
        assert_int_equal(gmmrrt_planner_drivable_path(t.p, &opt, &path, &rep), GMMRRT_OK);
        /* Independent check: the walker at each waypoint's time s / speed. */
        double s = 0.0, closest = INFINITY;
        for (int32_t i = 0; i < path.num_points; ++i) {
            if (i > 0)
                s += hypot(path.x[i] - path.x[i - 1], path.y[i] - path.y[i - 1]);
            const double tt = fmin(s / speed, GMMRRT_DEFAULT_PREDICTION_HORIZON_S);
            const double d = hypot(path.x[i] - 1.0, path.y[i] - (3.0 + vy * tt));
            if (d < closest)
                closest = d;
        }
        printf("%s: closest to the walker %.2f m (contact %.2f m), reported clearance %.2f m\n",
               with_velocity ? "predicted" : "prediction-free", closest, 0.55, rep.min_walker_clearance_m);
        if (with_velocity) {
            /* the search's time window is wider than the exact times, so the comfort margin holds */
            assert_true(closest >= 0.55 + GMMRRT_WALKER_COMFORT_M - 1e-3);
            assert_int_equal(rep.walker_conflict, 0);
            assert_true(fabs(rep.min_walker_clearance_m - (closest - 0.55)) < 0.02); /* waypoint arc vs chord sums */
        } else {
            assert_true(closest < 0.55); /* the scenario really is a collision without prediction */
        }
        test_planner_free(&t);
    }
}

static void test_slow_person_is_standing_bit_for_bit(void **state)
{
    (void)state;
    gmmrrt_model_t model;
    const double theta[] = {M_PI / 2.0};
    assert_int_equal(make_features_model(&model, theta, 1, 1.2, 0.2, 0.3), GMMRRT_OK);
    gmmrrt_path_t paths[2];
    double costs[2];
    for (int v = 0; v < 2; ++v) {
        gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_GMM_RRT_STAR);
        cfg.robot_radius_m = 0.3;
        test_planner_t t;
        assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
        gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
        pr.task = GMMRRT_TASK_AVOID;
        pr.model = &model;
        pr.obstacles.num_people = 1;
        pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 0.0, M_PI};
        pr.person_vx[0] = v ? 0.15 : 0.0; /* below GMMRRT_STANDING_SPEED_M_S */
        pr.person_vy[0] = v ? -0.1 : 0.0;
        assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
        gmmrrt_budget_t b = iters(3000);
        gmmrrt_plan_stats_t st;
        assert_int_equal(gmmrrt_planner_run(t.p, &b, &st), GMMRRT_OK);
        assert_int_equal(gmmrrt_planner_best_path(t.p, &paths[v]), GMMRRT_OK);
        costs[v] = st.best_cost;
        test_planner_free(&t);
    }
    assert_true(memcmp(&costs[0], &costs[1], sizeof costs[0]) == 0);
    assert_int_equal(paths[0].num_points, paths[1].num_points);
    assert_memory_equal(paths[0].x, paths[1].x, sizeof(double) * (size_t)paths[0].num_points);
    assert_memory_equal(paths[0].y, paths[1].y, sizeof(double) * (size_t)paths[0].num_points);
}

/* Crossing a walker's lane where they are about to walk costs more than crossing behind them, at
 * the same distance; the cost is where they will be when the robot gets there. */
static void test_walker_cost_is_higher_in_front_than_behind(void **state)
{
    (void)state;
    gmmrrt_walkers_t w;
    memset(&w, 0, sizeof w);
    w.count = 1;
    w.x[0] = 0.0;
    w.y[0] = 0.0;
    w.vy[0] = 1.0; /* walking +y */
    w.speed_m_s = 1.0;
    w.horizon_s = 5.0;
    w.root_x = 0.0;
    w.root_y = -100.0; /* far: the robot gets there at the horizon, the walker at (0, 5) */
    const double front = gmmrrt_walkers_cost(&w, -1.0, 6.0, 1.0, 6.0, 0.05);
    const double behind = gmmrrt_walkers_cost(&w, -1.0, 4.0, 1.0, 4.0, 0.05);
    const double far = gmmrrt_walkers_cost(&w, -1.0, 20.0, 1.0, 20.0, 0.05);
    printf("walker cost of a 2 m crossing 1 m ahead %.3f, 1 m behind %.3f, 15 m ahead %.3g\n", front, behind, far);
    assert_true(front > 1.0);         /* close to the full 2 m x 1 of the lane */
    assert_true(behind < 0.1 * front);
    assert_true(far < 1e-6);
    /* A robot near the walker's start meets them there: the same crossing is now behind them. */
    w.root_y = 0.0;
    w.root_x = 0.0;
    assert_true(gmmrrt_walkers_cost(&w, -1.0, -1.0, 1.0, -1.0, 0.05) < 0.1);
}

/* The robot's bearing in the person's frame picks the direction (+left, right = negative). */
static void test_approach_direction_sectors(void **state)
{
    (void)state;
    const gmmrrt_pose_t person = {1.0, 2.0, M_PI / 2.0}; /* facing world +y */
    const char *expect[8] = {"1-front", "8-45_left", "7-90_left", "6-135_left", "5-back", "4-135_right",
                             "3-90_right", "2-45_right"};
    for (int i = 0; i < 8; ++i) {
        for (int j = -2; j <= 2; ++j) { /* +-20 degrees inside the sector */
            const double theta = i * M_PI / 4.0 + j * (10.0 * M_PI / 180.0);
            double x, y;
            gmmrrt_features_to_xy(&person, 2.0, theta, &x, &y);
            const int32_t k = gmmrrt_approach_direction(&person, x, y);
            assert_string_equal(gmmrrt_approach_direction_name(k), expect[i]);
        }
    }
    assert_int_equal(gmmrrt_approach_direction(&person, NAN, 0.0), -1);
    assert_null(gmmrrt_approach_direction_name(8));
    gmmrrt_model_t m;
    const double theta[] = {0.0};
    assert_int_equal(make_features_model(&m, theta, 1, 1.2, 0.2, 0.3), GMMRRT_OK);
    m.task = GMMRRT_TASK_APPROACH;
    gmmrrt_model_set_t set;
    for (int i = 0; i < 8; ++i)
        set.model[i] = &m;
    char err[128];
    assert_int_equal(gmmrrt_model_set_validate(&set, err, sizeof err), GMMRRT_OK);
    set.model[5] = NULL;
    assert_int_equal(gmmrrt_model_set_validate(&set, err, sizeof err), GMMRRT_ERR_MODEL_MISMATCH);
    assert_non_null(strstr(err, "6-135_left"));
}

static void test_bad_velocities_are_refused(void **state)
{
    (void)state;
    gmmrrt_planner_config_t cfg = point_robot_config(GMMRRT_PLANNER_RRT_STAR);
    test_planner_t t;
    assert_int_equal(test_planner_make(&t, &cfg), GMMRRT_OK);
    gmmrrt_problem_t pr = empty_problem(-4.0, 0.0, 4.0, 0.0);
    pr.obstacles.num_people = 1;
    pr.obstacles.people[0] = (gmmrrt_pose_t){0.0, 2.0, 0.0};
    pr.person_vx[0] = NAN;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr.person_vx[0] = GMMRRT_MAX_PERSON_SPEED_M_S + 0.1;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    pr.person_vx[0] = GMMRRT_MAX_PERSON_SPEED_M_S - 0.1;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_OK);
    pr.nominal_speed_m_s = -1.0;
    assert_int_equal(gmmrrt_planner_set_problem(t.p, &pr), GMMRRT_ERR_INVALID_ARGUMENT);
    test_planner_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_output_turn_exceeds_the_bound),
        cmocka_unit_test(test_zero_radius_turns_in_place),
        cmocka_unit_test(test_long_collinear_tree_path_is_taken),
        cmocka_unit_test(test_approach_from_behind_arrives_facing),
        cmocka_unit_test(test_arrival_leg_keeps_the_tree_path_side_of_the_person),
        cmocka_unit_test(test_a_corner_without_a_free_arc_is_flagged),
        cmocka_unit_test(test_published_chords_of_an_arc_close_to_its_inside_are_free),
        cmocka_unit_test(test_published_chords_of_a_long_path_fit_the_capacity),
        cmocka_unit_test(test_arrival_yaw_is_honoured_and_options_checked),
        cmocka_unit_test(test_person_stepping_into_the_disc_is_escaped),
        cmocka_unit_test(test_escape_ends_with_a_drivable_arc_when_one_is_free),
        cmocka_unit_test(test_start_within_the_edge_margin_of_a_disc_escapes),
        cmocka_unit_test(test_walker_crossing_is_passed_at_a_safe_distance),
        cmocka_unit_test(test_slow_person_is_standing_bit_for_bit),
        cmocka_unit_test(test_walker_cost_is_higher_in_front_than_behind),
        cmocka_unit_test(test_approach_direction_sectors),
        cmocka_unit_test(test_bad_velocities_are_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
