/*
 * config_keys.c - the table of the planner's settings (config_keys.h): names, types, ranges and
 * help of gmmrrt_planner_config_t's fields. The ranges here are the only ones: config.c checks
 * each field against its row. The paper fixes the mixture bias (95 %, Sect. 5.3) and delta
 * (0.001, Sect. 5.1); the other defaults and their reasons are in docs/planner.md ("Defaults").
 */
#include "gmmrrt/config_keys.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "error_text.h"
#include "gmmrrt/limits.h"

/* Upper bounds that keep the block size and the loops sane; not paper values. */
#define GMMRRT_MAX_GRID_CELLS (1 << 26) /* 256 MB of float clearances */

#define OFF(f) offsetof(gmmrrt_planner_config_t, f)
/* A real in [lo, hi] (lo_open/hi_open: the end itself excluded). */
#define REAL(f, fl, lo, lo_open, hi, hi_open, h) {#f, fl, GMMRRT_KEY_REAL, OFF(f), lo, hi, lo_open, hi_open, {NULL}, h}
#define INT(f, fl, lo, hi, h) {#f, fl, GMMRRT_KEY_INT, OFF(f), lo, hi, 0, 0, {NULL}, h}

static const gmmrrt_config_key_t k_keys[] = {
    {"planner", "planner", GMMRRT_KEY_CHOICE, OFF(planner), 1, 3, 0, 0, {"gmm-rrt-star", "rrt-star", "gmm-rrt", NULL},
     "the search: GMM-RRT* (the paper's), plain RRT* or the GMM-RRT baseline"},
    {"seed", "seed", GMMRRT_KEY_SEED, OFF(seed), 0, 0, 0, 0, {NULL}, "random seed; same seed, same problem, same tree"},
    INT(max_nodes, "max-nodes", 2, GMMRRT_MAX_NODES_CEILING, "tree node pool (memory grows with it)"),
    INT(grid_max_cells, "grid-max-cells", 1, GMMRRT_MAX_GRID_CELLS,
         "clearance grid capacity, cells (memory: 4 bytes a cell)"),
    REAL(robot_radius_m, "robot-radius", 0.0, 0, INFINITY, 0, "robot disc radius, m (0: a point robot)"),
    REAL(person_radius_m, "person-radius", 0.0, 0, INFINITY, 0, "person disc radius, m"),
    REAL(grid_resolution_m, "grid-resolution", 0.0, 1, INFINITY, 0, "clearance grid cell, m"),
    REAL(edge_resolution_m, "edge-resolution", 0.0, 1, INFINITY, 0,
         "spacing of the collision checks and cost quadrature on an edge, m"),
    REAL(step_m, "step", 0.0, 1, INFINITY, 0, "longest new edge, m"),
    REAL(goal_bias, "goal-bias", 0.0, 0, 1.0, 1, "probability of sampling the goal"),
    REAL(gmm_bias, "gmm-bias", 0.0, 0, 1.0, 0, "probability of a mixture sample (paper: 0.95)"),
    REAL(rewire_gamma, "rewire-gamma", 0.0, 1, INFINITY, 0,
         "near radius gamma sqrt(ln n / n), m, when rewire_k_factor is 0"),
    REAL(rewire_k_factor, "rewire-k", 0.0, 0, 64.0, 0,
         "near set: at least this times ln(n+1) nearest nodes (0: radius rewiring)"),
    {"informed_sampling", "informed", GMMRRT_KEY_SWITCH, OFF(informed_sampling), 0, 1, 0, 0, {NULL},
     "1: sample the informed ellipse once a path exists, 0: off"},
    {"connect_first", "connect", GMMRRT_KEY_SWITCH, OFF(connect_first), 0, 1, 0, 0, {NULL},
     "1: connect phase (RRT-Connect) until the first path, then RRT* from it; 0: RRT* from the first sample"},
    INT(connect_max_iterations, "connect-max-iterations", 1, INT32_MAX,
        "the connect phase ends after this many iterations without a path; RRT* goes on alone"),
    {"connect_domains", "connect-domains", GMMRRT_KEY_SWITCH, OFF(connect_domains), 0, 1, 0, 0, {NULL},
     "1: a connect node whose step was blocked tries targets beyond one step only as the nearest; 0: off"},
    REAL(w_length, "w-length", 0.0, 0, GMMRRT_MAX_COST_WEIGHT, 0, "weight of length in the edge cost"),
    REAL(w_task, "w-task", 0.0, 0, GMMRRT_MAX_COST_WEIGHT, 0,
         "weight of the task cost c(f) in the edge cost (paper Sect. 4)"),
    {"task_cost", "task-cost", GMMRRT_KEY_CHOICE, OFF(task_cost), 1, 3, 0, 0, {"paper", "inward", "background", NULL},
     "task cost: paper delta / max(p, delta), inward (gmm.h) or background (needs a background model)"},
    REAL(delta, "delta", 0.0, 0, INFINITY, 0,
         "task-cost floor delta of c = delta / max(p, delta) (0: the model's; paper 0.001)"),
    REAL(person_influence_m, "person-influence", 0.0, 1, INFINITY, 0,
         "the avoid model applies to people within this of the segment start-goal, m"),
    REAL(waypoint_spacing_m, "waypoint-spacing", 0.0, 1, INFINITY, 0, "spacing of the output path, m"),
};
#define N_KEYS ((int32_t)(sizeof k_keys / sizeof k_keys[0]))
_Static_assert(sizeof k_keys / sizeof k_keys[0] <= GMMRRT_CONFIG_MAX_KEYS, "raise GMMRRT_CONFIG_MAX_KEYS");

int32_t gmmrrt_config_key_count(void) { return N_KEYS; }

const gmmrrt_config_key_t *gmmrrt_config_key_at(int32_t i) { return i >= 0 && i < N_KEYS ? &k_keys[i] : NULL; }

const gmmrrt_config_key_t *gmmrrt_config_key_find(const char *name)
{
    if (name == NULL)
        return NULL;
    for (int32_t i = 0; i < N_KEYS; ++i)
        if (!strcmp(name, k_keys[i].name) || !strcmp(name, k_keys[i].flag))
            return &k_keys[i];
    return NULL;
}

static double real_of(const gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k)
{
    double v;
    memcpy(&v, (const char *)cfg + k->offset, sizeof v);
    return v;
}

static int32_t int_of(const gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k)
{
    int32_t v;
    memcpy(&v, (const char *)cfg + k->offset, sizeof v);
    return v;
}

const char *gmmrrt_config_key_range(const gmmrrt_config_key_t *k, char *out, size_t cap)
{
    if (out == NULL || cap == 0)
        return out;
    out[0] = '\0';
    if (k == NULL)
        return out;
    switch (k->type) {
    case GMMRRT_KEY_REAL:
        if (isinf(k->max))
            snprintf(out, cap, "finite and %s %g", k->min_open ? ">" : ">=", k->min);
        else
            snprintf(out, cap, "in %c%g, %g%c", k->min_open ? '(' : '[', k->min, k->max, k->max_open ? ')' : ']');
        break;
    case GMMRRT_KEY_INT:
        snprintf(out, cap, "in %.0f..%.0f", k->min, k->max);
        break;
    case GMMRRT_KEY_SEED:
        snprintf(out, cap, "in 0..18446744073709551615");
        break;
    case GMMRRT_KEY_SWITCH:
        snprintf(out, cap, "0 or 1");
        break;
    case GMMRRT_KEY_CHOICE: {
        size_t used = 0;
        for (int i = 0; i < GMMRRT_KEY_MAX_CHOICES && k->choices[i] != NULL && used < cap; ++i) {
            const int last = i + 1 == GMMRRT_KEY_MAX_CHOICES || k->choices[i + 1] == NULL;
            const char *sep = i == 0 ? "" : (last ? " or " : ", ");
            const int n = snprintf(out + used, cap - used, "%s%s", sep, k->choices[i]);
            used += n > 0 ? (size_t)n : 0;
        }
        break;
    }
    default:
        break;
    }
    return out;
}

/* Whether v is in the REAL or INT range of k. */
static int in_range(const gmmrrt_config_key_t *k, double v)
{
    if (!isfinite(v))
        return 0;
    if (k->min_open ? !(v > k->min) : !(v >= k->min))
        return 0;
    return k->max_open ? v < k->max : v <= k->max;
}

gmmrrt_status_t gmmrrt_config_key_check(const gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k, char *err,
                                        size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (cfg == NULL || k == NULL)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config key check: NULL argument");
    int ok = 1;
    switch (k->type) {
    case GMMRRT_KEY_REAL:
        ok = in_range(k, real_of(cfg, k));
        break;
    case GMMRRT_KEY_INT:
    case GMMRRT_KEY_SWITCH:
    case GMMRRT_KEY_CHOICE:
        ok = in_range(k, (double)int_of(cfg, k));
        break;
    default: /* SEED: every value */
        break;
    }
    if (ok)
        return GMMRRT_OK;
    char range[128];
    return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.%s must be %s", k->name,
                            gmmrrt_config_key_range(k, range, sizeof range));
}

/* Digits only (an optional '-' for INT): "1e3" or "2.5" are errors, never 1 or 2. */
static int parse_whole(const char *text, int negative_ok, long double *out)
{
    const char *p = text;
    if (negative_ok && *p == '-')
        ++p;
    if (*p == '\0')
        return 0;
    for (const char *q = p; *q; ++q)
        if (*q < '0' || *q > '9')
            return 0;
    errno = 0;
    char *end = NULL;
    if (negative_ok) {
        const long long v = strtoll(text, &end, 10);
        *out = (long double)v;
    } else {
        const unsigned long long v = strtoull(text, &end, 10);
        *out = (long double)v;
    }
    return errno != ERANGE && end != NULL && *end == '\0';
}

gmmrrt_status_t gmmrrt_config_key_set(gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k, const char *text,
                                      char *err, size_t errcap)
{
    gmmrrt_clear_error(err, errcap);
    if (cfg == NULL || k == NULL || text == NULL)
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config key set: NULL argument");
    gmmrrt_planner_config_t probe = *cfg;
    char *field = (char *)&probe + k->offset;
    char range[128];
    switch (k->type) {
    case GMMRRT_KEY_REAL: {
        errno = 0;
        char *end = NULL;
        const double v = strtod(text, &end);
        if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v))
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.%s: \"%s\" is not a number",
                                    k->name, text);
        memcpy(field, &v, sizeof v);
        break;
    }
    case GMMRRT_KEY_INT: {
        long double v;
        if (!parse_whole(text, 1, &v))
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                    "config.%s: \"%s\" is not a whole number (must be %s)", k->name, text,
                                    gmmrrt_config_key_range(k, range, sizeof range));
        if (v < (long double)INT32_MIN || v > (long double)INT32_MAX)
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.%s must be %s", k->name,
                                    gmmrrt_config_key_range(k, range, sizeof range));
        const int32_t i = (int32_t)v;
        memcpy(field, &i, sizeof i);
        break;
    }
    case GMMRRT_KEY_SEED: {
        errno = 0;
        char *end = NULL;
        long double ignored;
        if (!parse_whole(text, 0, &ignored))
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                    "config.%s: \"%s\" is not a whole number (must be %s)", k->name, text,
                                    gmmrrt_config_key_range(k, range, sizeof range));
        const uint64_t v = (uint64_t)strtoull(text, &end, 10);
        memcpy(field, &v, sizeof v);
        break;
    }
    case GMMRRT_KEY_SWITCH: {
        int32_t b;
        if (!strcmp(text, "1"))
            b = 1;
        else if (!strcmp(text, "0"))
            b = 0;
        else
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap,
                                    "config.%s: \"%s\" is not a switch (0 or 1)", k->name, text);
        memcpy(field, &b, sizeof b);
        break;
    }
    case GMMRRT_KEY_CHOICE: {
        int32_t found = 0;
        for (int32_t i = 0; i < GMMRRT_KEY_MAX_CHOICES && k->choices[i] != NULL && !found; ++i)
            if (!strcmp(text, k->choices[i]))
                found = i + 1;
        if (!found)
            return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.%s: \"%s\": expected %s",
                                    k->name, text, gmmrrt_config_key_range(k, range, sizeof range));
        memcpy(field, &found, sizeof found);
        break;
    }
    default:
        return gmmrrt_set_error(GMMRRT_ERR_INVALID_ARGUMENT, err, errcap, "config.%s: unknown key type", k->name);
    }
    const gmmrrt_status_t st = gmmrrt_config_key_check(&probe, k, err, errcap);
    if (st == GMMRRT_OK)
        *cfg = probe;
    return st;
}

const char *gmmrrt_config_key_format(const gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k, char *out,
                                     size_t cap)
{
    if (out == NULL || cap == 0)
        return out;
    out[0] = '\0';
    if (cfg == NULL || k == NULL)
        return out;
    switch (k->type) {
    case GMMRRT_KEY_REAL: {
        /* The shortest of 15 or 17 significant digits that reads back to the same double. */
        const double v = real_of(cfg, k);
        snprintf(out, cap, "%.15g", v);
        if (strtod(out, NULL) != v)
            snprintf(out, cap, "%.17g", v);
        break;
    }
    case GMMRRT_KEY_INT:
    case GMMRRT_KEY_SWITCH:
        snprintf(out, cap, "%d", (int)int_of(cfg, k));
        break;
    case GMMRRT_KEY_SEED: {
        uint64_t v;
        memcpy(&v, (const char *)cfg + k->offset, sizeof v);
        snprintf(out, cap, "%llu", (unsigned long long)v);
        break;
    }
    case GMMRRT_KEY_CHOICE: {
        const int32_t v = int_of(cfg, k);
        snprintf(out, cap, "%s", v >= 1 && v <= GMMRRT_KEY_MAX_CHOICES && k->choices[v - 1] ? k->choices[v - 1] : "?");
        break;
    }
    default:
        break;
    }
    return out;
}

const char *gmmrrt_config_key_default(const gmmrrt_config_key_t *k, char *out, size_t cap)
{
    gmmrrt_planner_config_t cfg;
    gmmrrt_planner_config_default(&cfg);
    return gmmrrt_config_key_format(&cfg, k, out, cap);
}
