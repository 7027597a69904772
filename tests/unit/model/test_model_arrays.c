/* planner.model_arrays: gmmrrt_model_from_arrays / gmmrrt_model_to_arrays (model.h), the way the
 * Python tools hand a model's numbers to the core without mirroring gmmrrt_model_t.
 * A model taken apart and rebuilt encodes to the same bytes; bad sizes, NULL arrays and a
 * factor that is not positive definite are each rejected with their status and a reason. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>
#include <cmocka.h>

#include "gmmrrt/model.h"
#include "model_fixture.h"

typedef struct {
    int32_t head[6];
    double delta;
    double weight[GMMRRT_MAX_K];
    double mean[GMMRRT_MAX_K * GMMRRT_MAX_DIM];
    double chol[GMMRRT_MAX_K * GMMRRT_MAX_TRI];
} flat_model_t;

static flat_model_t g_flat;
static gmmrrt_model_t g_model, g_rebuilt;
static uint8_t g_a[4096], g_b[4096];

static gmmrrt_status_t rebuild(const flat_model_t *f, gmmrrt_model_t *out, char *err, size_t errcap)
{
    return gmmrrt_model_from_arrays(f->head[0], f->head[1], f->head[2], f->head[3], f->head[4],
                                    (uint32_t)f->head[5], f->delta, f->weight, f->mean, f->chol, out, err, errcap);
}

static void test_taken_apart_and_rebuilt_encodes_to_the_same_bytes(void **state)
{
    (void)state;
    void (*fixtures[])(gmmrrt_model_t *) = {fixture_features_model, fixture_generic_d4_model};
    for (size_t i = 0; i < sizeof fixtures / sizeof fixtures[0]; ++i) {
        fixtures[i](&g_model);
        char err[256] = "";
        assert_int_equal(gmmrrt_model_prepare(&g_model, err, sizeof err), GMMRRT_OK);
        gmmrrt_model_to_arrays(&g_model, g_flat.head, &g_flat.delta, g_flat.weight, g_flat.mean, g_flat.chol);
        assert_int_equal(g_flat.head[3], g_model.dim);
        assert_int_equal(g_flat.head[4], g_model.k);
        const gmmrrt_status_t st = rebuild(&g_flat, &g_rebuilt, err, sizeof err);
        if (st != GMMRRT_OK)
            fail_msg("from_arrays: %s: %s", gmmrrt_status_str(st), err);
        size_t la = 0, lb = 0;
        assert_int_equal(gmmrrt_model_encode(&g_model, g_a, sizeof g_a, &la, NULL, 0), GMMRRT_OK);
        assert_int_equal(gmmrrt_model_encode(&g_rebuilt, g_b, sizeof g_b, &lb, NULL, 0), GMMRRT_OK);
        assert_int_equal(la, lb);
        assert_memory_equal(g_a, g_b, la);
        /* The derived fields are filled (prepare ran), so the model is ready to evaluate. */
        assert_true(g_rebuilt.cum_weight[g_rebuilt.k - 1] == 1.0);
        assert_memory_equal(g_rebuilt.log_coef, g_model.log_coef, sizeof g_model.log_coef);
    }
}

static void expect(gmmrrt_status_t got, gmmrrt_status_t want, const char *err, const char *needle)
{
    if (got != want)
        fail_msg("got %s (%s), expected %s", gmmrrt_status_str(got), err, gmmrrt_status_str(want));
    if (strstr(err, needle) == NULL)
        fail_msg("reason \"%s\" does not mention \"%s\"", err, needle);
}

static void test_bad_sizes_null_arrays_and_bad_factors_are_rejected(void **state)
{
    (void)state;
    fixture_features_model(&g_model);
    gmmrrt_model_to_arrays(&g_model, g_flat.head, &g_flat.delta, g_flat.weight, g_flat.mean, g_flat.chol);
    char err[256];

    flat_model_t f = g_flat;
    f.head[3] = 0;
    expect(rebuild(&f, &g_rebuilt, err, sizeof err), GMMRRT_ERR_MODEL_BAD_SIZE, err, "D = 0");
    f = g_flat;
    f.head[4] = GMMRRT_MAX_K + 1;
    expect(rebuild(&f, &g_rebuilt, err, sizeof err), GMMRRT_ERR_MODEL_BAD_SIZE, err, "K =");

    expect(gmmrrt_model_from_arrays(1, 1, 0, 2, 1, 0x2, 0.001, NULL, g_flat.mean, g_flat.chol, &g_rebuilt, err,
                                    sizeof err),
           GMMRRT_ERR_INVALID_ARGUMENT, err, "NULL");

    f = g_flat;
    f.chol[0] = -0.3; /* L00 of the first component: not a Cholesky factor */
    const gmmrrt_status_t st = rebuild(&f, &g_rebuilt, err, sizeof err);
    expect(st, GMMRRT_ERR_MODEL_NOT_POSITIVE_DEFINITE, err, "");
    assert_true(err[0] != '\0');
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_taken_apart_and_rebuilt_encodes_to_the_same_bytes),
        cmocka_unit_test(test_bad_sizes_null_arrays_and_bad_factors_are_rejected),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
