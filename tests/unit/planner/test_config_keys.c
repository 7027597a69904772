/*
 * planner.config_keys: the table of planner settings (config_keys.h). Every row is found by its
 * name and its flag; names and flags and fields are distinct; the defaults are in range; a value
 * written by gmmrrt_config_key_format reads back to the same bytes; a bad text or a value out of
 * range is refused with the key named and the configuration left as it was; and
 * gmmrrt_planner_config_validate checks every row's range.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "gmmrrt/config_keys.h"

/* The width of the field of k in gmmrrt_planner_config_t. */
static size_t field_size(const gmmrrt_config_key_t *k)
{
    return k->type == GMMRRT_KEY_REAL || k->type == GMMRRT_KEY_SEED ? 8 : 4;
}

static void test_every_key_is_found_by_name_and_flag_and_is_distinct(void **state)
{
    (void)state;
    const int32_t n = gmmrrt_config_key_count();
    assert_true(n >= 20 && n <= GMMRRT_CONFIG_MAX_KEYS);
    assert_null(gmmrrt_config_key_at(n));
    assert_null(gmmrrt_config_key_at(-1));
    assert_null(gmmrrt_config_key_find("no_such_setting"));
    for (int32_t i = 0; i < n; ++i) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_at(i);
        assert_ptr_equal(gmmrrt_config_key_find(k->name), k);
        assert_ptr_equal(gmmrrt_config_key_find(k->flag), k);
        assert_true(k->help != NULL && k->help[0] != '\0');
        assert_true(k->offset + field_size(k) <= sizeof(gmmrrt_planner_config_t));
        for (int32_t j = 0; j < i; ++j) {
            const gmmrrt_config_key_t *o = gmmrrt_config_key_at(j);
            assert_string_not_equal(k->name, o->name);
            assert_string_not_equal(k->flag, o->flag);
            /* No two rows share a byte of the configuration. */
            assert_true(k->offset + field_size(k) <= o->offset || o->offset + field_size(o) <= k->offset);
        }
    }
}

static void test_defaults_are_in_range_and_read_back_to_the_same_bytes(void **state)
{
    (void)state;
    gmmrrt_planner_config_t def;
    gmmrrt_planner_config_default(&def);
    char err[256], text[64];
    assert_int_equal(gmmrrt_planner_config_validate(&def, err, sizeof err), GMMRRT_OK);
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_at(i);
        assert_int_equal(gmmrrt_config_key_check(&def, k, err, sizeof err), GMMRRT_OK);
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        gmmrrt_config_key_format(&def, k, text, sizeof text);
        char def_text[64];
        assert_string_equal(gmmrrt_config_key_default(k, def_text, sizeof def_text), text);
        assert_int_equal(gmmrrt_config_key_set(&cfg, k, text, err, sizeof err), GMMRRT_OK);
        assert_memory_equal(&cfg, &def, sizeof cfg);
    }
}

/* A value inside the range but not the default: set, format, set again gives the same bytes, and
 * only the row's own field changed. */
static void test_a_set_value_changes_only_its_field_and_round_trips(void **state)
{
    (void)state;
    static const struct { const char *name, *text; } cases[] = {
        {"planner", "gmm-rrt"},  {"seed", "18446744073709551615"}, {"max_nodes", "4194304"},
        {"robot_radius_m", "0.1"}, {"gmm_bias", "0.3333333333333333"}, {"informed_sampling", "0"},
        {"task_cost", "inward"},  {"delta", "0.001"},             {"rewire_k_factor", "0"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_find(cases[c].name);
        assert_non_null(k);
        gmmrrt_planner_config_t def, a, b;
        gmmrrt_planner_config_default(&def);
        a = def;
        char err[256], text[64];
        assert_int_equal(gmmrrt_config_key_set(&a, k, cases[c].text, err, sizeof err), GMMRRT_OK);
        assert_memory_not_equal((const char *)&a + k->offset, (const char *)&def + k->offset, field_size(k));
        /* Bytes outside the field are the defaults'. */
        assert_memory_equal(&a, &def, k->offset);
        const size_t end = k->offset + field_size(k);
        assert_memory_equal((const char *)&a + end, (const char *)&def + end, sizeof a - end);
        b = def;
        assert_int_equal(gmmrrt_config_key_set(&b, k, gmmrrt_config_key_format(&a, k, text, sizeof text), err,
                                               sizeof err),
                         GMMRRT_OK);
        assert_memory_equal(&a, &b, sizeof a);
    }
}

static void test_bad_text_and_out_of_range_are_refused_naming_the_key(void **state)
{
    (void)state;
    static const struct { const char *name, *text, *reason; } cases[] = {
        {"gmm_bias", "1.5", "config.gmm_bias must be in [0, 1]"},
        {"goal_bias", "1", "config.goal_bias must be in [0, 1)"},
        {"delta", "-1", "config.delta must be finite and >= 0"},
        {"delta", "nan", "config.delta: \"nan\" is not a number"},
        {"step_m", "0", "config.step_m must be finite and > 0"},
        {"max_nodes", "1", "config.max_nodes must be in 2..4194304"},
        {"max_nodes", "1e4", "config.max_nodes: \"1e4\" is not a whole number"},
        {"max_nodes", "99999999999", "config.max_nodes must be in 2..4194304"},
        {"seed", "-1", "config.seed: \"-1\" is not a whole number"},
        {"seed", "99999999999999999999", "config.seed: \"99999999999999999999\" is not a whole number"},
        {"informed_sampling", "yes", "config.informed_sampling: \"yes\" is not a switch (0 or 1)"},
        {"planner", "rrt", "expected gmm-rrt-star, rrt-star or gmm-rrt"},
        {"task_cost", "max", "expected paper, inward or background"},
        {"robot_radius_m", "", "is not a number"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_find(cases[c].name);
        assert_non_null(k);
        gmmrrt_planner_config_t def, cfg;
        gmmrrt_planner_config_default(&def);
        cfg = def;
        char err[256];
        assert_int_equal(gmmrrt_config_key_set(&cfg, k, cases[c].text, err, sizeof err),
                         GMMRRT_ERR_INVALID_ARGUMENT);
        if (strstr(err, cases[c].reason) == NULL)
            fail_msg("%s = \"%s\": got \"%s\", expected \"%s\"", cases[c].name, cases[c].text, err, cases[c].reason);
        assert_memory_equal(&cfg, &def, sizeof cfg);
    }
}

/* validate checks each row: a field set out of its range directly is caught, named. */
static void test_validate_checks_every_row(void **state)
{
    (void)state;
    for (int32_t i = 0; i < gmmrrt_config_key_count(); ++i) {
        const gmmrrt_config_key_t *k = gmmrrt_config_key_at(i);
        if (k->type == GMMRRT_KEY_SEED)
            continue; /* every uint64 is a seed */
        gmmrrt_planner_config_t cfg;
        gmmrrt_planner_config_default(&cfg);
        if (k->type == GMMRRT_KEY_REAL) {
            const double bad = NAN;
            memcpy((char *)&cfg + k->offset, &bad, sizeof bad);
        } else {
            const int32_t bad = (int32_t)k->min - 1;
            memcpy((char *)&cfg + k->offset, &bad, sizeof bad);
        }
        char err[256], want[128];
        assert_int_equal(gmmrrt_planner_config_validate(&cfg, err, sizeof err), GMMRRT_ERR_INVALID_ARGUMENT);
        snprintf(want, sizeof want, "config.%s must be", k->name);
        if (strstr(err, want) == NULL)
            fail_msg("%s out of range: got \"%s\"", k->name, err);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_key_is_found_by_name_and_flag_and_is_distinct),
        cmocka_unit_test(test_defaults_are_in_range_and_read_back_to_the_same_bytes),
        cmocka_unit_test(test_a_set_value_changes_only_its_field_and_round_trips),
        cmocka_unit_test(test_bad_text_and_out_of_range_are_refused_naming_the_key),
        cmocka_unit_test(test_validate_checks_every_row),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
