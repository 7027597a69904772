/* daemon_fixture.c - see daemon_fixture.h. */
#include "daemon_fixture.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

void daemon_fixture_setup(gmmrrtd_t *d, int64_t budget_iterations, int32_t max_nodes, uint64_t seed)
{
    memset(d, 0, sizeof *d);
    gmmrrtd_log_set_level(GMMRRTD_LOG_ERROR);
    gmmrrtd_settings_default(&d->set);
    d->set.budget_ms = 0.0;
    d->set.budget_iterations = budget_iterations;
    d->set.cfg.max_nodes = max_nodes;
    d->set.cfg.seed = seed;
    d->set.cfg.planner = GMMRRT_PLANNER_RRT_STAR;
    d->clock_mode = GMMRRTD_CLOCK_LOG;
    d->staged.input = -1;
    d->mem_size = gmmrrt_planner_mem_size(&d->set.cfg);
    d->mem = aligned_alloc(64, (d->mem_size + 63u) / 64u * 64u);
    assert_non_null(d->mem);
    assert_int_equal(gmmrrt_planner_init(&d->planner, d->mem, d->mem_size, &d->set.cfg), GMMRRT_OK);
    d->lcm_in = d->lcm_out = lcm_create("file:///dev/null?mode=w");
    assert_non_null(d->lcm_out);
}

void daemon_fixture_teardown(gmmrrtd_t *d)
{
    lcm_destroy(d->lcm_out);
    free(d->mem);
}
