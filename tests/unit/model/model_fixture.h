/* model_fixture.h - small hand-built models shared by the model, model_file and gmm
 * tests, and a little-endian byte writer that does not use the code under test. */
#ifndef GMMRRT_TEST_MODEL_FIXTURE_H
#define GMMRRT_TEST_MODEL_FIXTURE_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "gmmrrt/model.h"

/* Features model (D = 2: d [m], theta [rad]) with K = 3; component 1 sits at
 * theta = pi - 0.1 with a correlated factor, so it straddles the +-pi seam. */
static inline void fixture_features_model(gmmrrt_model_t *m)
{
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_FEATURES;
    m->task = GMMRRT_TASK_AVOID;
    m->homotopy = GMMRRT_HOMOTOPY_LEFT;
    m->dim = 2;
    m->k = 3;
    m->angle_mask = 0x2u;
    m->delta = GMMRRT_MODEL_DEFAULT_DELTA;
    const double w[3] = {0.25, 0.35, 0.40};
    const double mu[3][2] = {{1.5, 0.8}, {2.5, M_PI - 0.1}, {3.0, -1.2}};
    const double l[3][3] = {{0.30, 0.05, 0.40}, {0.45, -0.20, 0.55}, {0.35, 0.00, 0.25}};
    for (int i = 0; i < 3; ++i) {
        m->weight[i] = w[i];
        m->mean[i][0] = mu[i][0];
        m->mean[i][1] = mu[i][1];
        for (int t = 0; t < 3; ++t)
            m->chol[i][t] = l[i][t];
    }
}

/* Generic D = 4 model, K = 2, dimension 2 an angle (angle_mask 0x4). */
static inline void fixture_generic_d4_model(gmmrrt_model_t *m)
{
    memset(m, 0, sizeof *m);
    m->kind = GMMRRT_MODEL_KIND_GENERIC;
    m->task = GMMRRT_TASK_NONE;
    m->homotopy = GMMRRT_HOMOTOPY_ALL;
    m->dim = 4;
    m->k = 2;
    m->angle_mask = 0x4u;
    m->delta = 0.01;
    m->weight[0] = 0.6;
    m->weight[1] = 0.4;
    const double mu[2][4] = {{0.0, 1.0, -3.0, 2.0}, {1.0, -1.0, 2.9, 0.5}};
    /* Packed rows: L00 | L10 L11 | L20 L21 L22 | L30 L31 L32 L33 */
    const double l[2][10] = {{1.0, 0.2, 0.8, -0.1, 0.3, 0.5, 0.4, 0.0, -0.2, 1.1},
                             {0.7, -0.3, 0.6, 0.2, 0.1, 0.7, 0.0, 0.5, 0.1, 0.9}};
    for (int i = 0; i < 2; ++i) {
        memcpy(m->mean[i], mu[i], sizeof mu[i]);
        memcpy(m->chol[i], l[i], sizeof l[i]);
    }
}

/* Little-endian writers independent of model.c. */
static inline void le_put_u16(uint8_t *p, uint16_t v)
{
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)(v >> 8);
}
static inline void le_put_u32(uint8_t *p, uint32_t v)
{
    for (int b = 0; b < 4; ++b)
        p[b] = (uint8_t)(v >> (8 * b));
}
static inline void le_put_f64(uint8_t *p, double v)
{
    uint64_t u;
    memcpy(&u, &v, sizeof u);
    for (int b = 0; b < 8; ++b)
        p[b] = (uint8_t)(u >> (8 * b));
}

#endif
