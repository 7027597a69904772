/*
 * config_keys.h - the one table of the planner's settings: every user-settable field of
 * gmmrrt_planner_config_t (config.h) with its name, type, range and help. gmmrrt-plan's flags,
 * gmmrrtd's [planner] keys and flags, both --help texts, gmmrrt_planner_config_validate's
 * per-field checks and the Python tools (gmmrrt_tools.core.config_keys) all read this table,
 * so a setting has one name, one range and one default everywhere (docs/settings.md).
 *
 * A setting's name is its INI key in gmmrrtd's [planner] section and its Python name; its flag
 * is the long option of both programs (gmm_bias: --gmm-bias; the flag drops a unit suffix and
 * some long words: robot_radius_m: --robot-radius, rewire_k_factor: --rewire-k). The defaults
 * are gmmrrt_planner_config_default's.
 */
#ifndef GMMRRT_CONFIG_KEYS_H
#define GMMRRT_CONFIG_KEYS_H

#include <stddef.h>
#include <stdint.h>

#include "gmmrrt/config.h"
#include "gmmrrt/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    GMMRRT_KEY_REAL = 1,   /* double, finite */
    GMMRRT_KEY_INT = 2,    /* int32_t, digits only */
    GMMRRT_KEY_SEED = 3,   /* uint64_t, digits only */
    GMMRRT_KEY_SWITCH = 4, /* int32_t 0 or 1, written 0 or 1 */
    GMMRRT_KEY_CHOICE = 5  /* int32_t 1..n: the n names of `choices` */
} gmmrrt_key_type_t;

/* Most settings the table will hold: programs size their option arrays with it (config_keys.c
 * checks the table against it at compile time). */
#define GMMRRT_CONFIG_MAX_KEYS 32
/* Largest number of names a CHOICE key has. */
#define GMMRRT_KEY_MAX_CHOICES 4

typedef struct {
    const char *name;   /* INI key and Python name */
    const char *flag;   /* long option of gmmrrt-plan and gmmrrtd, without the leading "--" */
    int32_t type;       /* gmmrrt_key_type_t */
    size_t offset;      /* of the field in gmmrrt_planner_config_t */
    double min, max;    /* REAL and INT: the range (max INFINITY: none above); SEED: unused */
    int32_t min_open;   /* 1: min itself is outside the range (> min), 0: >= min */
    int32_t max_open;   /* 1: < max, 0: <= max */
    const char *choices[GMMRRT_KEY_MAX_CHOICES]; /* CHOICE: names of 1, 2, ...; NULL after the last */
    const char *help;   /* one line: what it does, units, what 0 means where it means something */
} gmmrrt_config_key_t;

/* Number of settings; gmmrrt_config_key_at(0 .. count-1) is each, in --help order. */
int32_t gmmrrt_config_key_count(void);

/* The i-th setting, NULL when i is out of range. */
const gmmrrt_config_key_t *gmmrrt_config_key_at(int32_t i);

/* The setting whose name (gmm_bias) or flag (gmm-bias, without "--") is `name`; NULL when
 * there is none. */
const gmmrrt_config_key_t *gmmrrt_config_key_find(const char *name);

/* Parses `text` as key k's type and stores it in cfg when it is in k's range. GMMRRT_OK, or
 * GMMRRT_ERR_INVALID_ARGUMENT with the reason in err[errcap] ("config.<name> must be ..." or
 * "not a number") and cfg unchanged. Rules across settings are gmmrrt_planner_config_validate's. */
gmmrrt_status_t gmmrrt_config_key_set(gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k, const char *text,
                                      char *err, size_t errcap);

/* Whether cfg's field of k is in k's range: GMMRRT_OK or INVALID_ARGUMENT with
 * "config.<name> must be <range>" in err[errcap]. */
gmmrrt_status_t gmmrrt_config_key_check(const gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k,
                                        char *err, size_t errcap);

/* cfg's value of k as text a later gmmrrt_config_key_set reads back to the same value (a CHOICE
 * by its name, a REAL with 17 significant digits), into out[cap]. Returns out. */
const char *gmmrrt_config_key_format(const gmmrrt_planner_config_t *cfg, const gmmrrt_config_key_t *k, char *out,
                                     size_t cap);

/* k's default (gmmrrt_planner_config_default) as gmmrrt_config_key_format writes it, into
 * out[cap]; for programs and bindings that do not hold a gmmrrt_planner_config_t. Returns out. */
const char *gmmrrt_config_key_default(const gmmrrt_config_key_t *k, char *out, size_t cap);

/* k's range as the text the error messages and --help show ("in [0, 1]", "> 0",
 * "in 2..4194304", "gmm-rrt-star, rrt-star or gmm-rrt"), into out[cap]. Returns out. */
const char *gmmrrt_config_key_range(const gmmrrt_config_key_t *k, char *out, size_t cap);

#ifdef __cplusplus
}
#endif
#endif /* GMMRRT_CONFIG_KEYS_H */
