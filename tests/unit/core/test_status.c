/* planner.status: every status has its own description. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

#include "gmmrrt/status.h"

static void test_every_status_has_a_distinct_description(void **state)
{
    (void)state;
    const char *seen[64];
    int n = 0;
    for (int code = 0; code < 100; ++code) {
        const char *s = gmmrrt_status_str((gmmrrt_status_t)code);
        assert_non_null(s);
        if (strcmp(s, "unknown status") == 0)
            continue;
        for (int i = 0; i < n; ++i)
            assert_string_not_equal(seen[i], s);
        assert_true(n < 64);
        seen[n++] = s;
    }
    assert_true(n >= 20);
    assert_string_equal(gmmrrt_status_str(GMMRRT_ERR_START_IN_COLLISION), "start in collision");
    assert_string_equal(gmmrrt_status_str((gmmrrt_status_t)9999), "unknown status");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_status_has_a_distinct_description),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
