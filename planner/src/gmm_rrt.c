/*
 * gmm_rrt.c - the GMM-RRT baseline (Claassens 2010, as read in docs/planner.md; the paper's
 * Sect. 5 compares GMM-RRT* against it): an RRT (no rewiring, length cost; strategy.c) whose
 * mixture samples walk the XY model's components in order of mean progress s. With probability
 * gmm_bias the sample comes from the current component's (x', y') in the focus person's frame;
 * the stage moves on when a node lands inside the component's 90 % ellipse (Mahalanobis^2 <=
 * 4.605, chi-square with 2 degrees of freedom); after the last component those draws go to the
 * goal. Its state is gmmrrt_gmm_rrt_t (planner_internal.h), p->gmm_rrt.
 */
#include "gmmrrt/features.h"
#include "gmmrrt/gmm.h"
#include "planner_internal.h"

#define GMMRRT_STAGE_REACHED_MAHAL2 4.605 /* chi-square, 2 dof, 90 % */

void gmmrrt_gmm_rrt_prepare(struct gmmrrt_planner *p)
{
    const gmmrrt_model_t *m = p->problem.model;
    /* Insertion sort of component indices by mean s (the file promises this order; the
     * planner does not rely on it). */
    for (int32_t i = 0; i < m->k; ++i) {
        int32_t j = i;
        while (j > 0 && m->mean[p->gmm_rrt.order[j - 1]][0] > m->mean[i][0]) {
            p->gmm_rrt.order[j] = p->gmm_rrt.order[j - 1];
            --j;
        }
        p->gmm_rrt.order[j] = i;
    }
    for (int32_t i = 0; i < m->k; ++i) {
        /* Sigma = L L^T; L packed row-major lower: row r starts at r (r + 1) / 2. */
        const double *L = m->chol[i];
        const double *r1 = L + 1, *r2 = L + 3; /* rows 1 and 2 */
        const double s11 = r1[0] * r1[0] + r1[1] * r1[1];
        const double s12 = r1[0] * r2[0] + r1[1] * r2[1];
        const double s22 = r2[0] * r2[0] + r2[1] * r2[1] + r2[2] * r2[2];
        const double det = s11 * s22 - s12 * s12;
        p->gmm_rrt.xy_mean[i][0] = m->mean[i][1];
        p->gmm_rrt.xy_mean[i][1] = m->mean[i][2];
        p->gmm_rrt.xy_inv_cov[i][0] = s22 / det;
        p->gmm_rrt.xy_inv_cov[i][1] = -s12 / det;
        p->gmm_rrt.xy_inv_cov[i][2] = s11 / det;
    }
}

int gmmrrt_gmm_rrt_sample(struct gmmrrt_planner *p, double *x, double *y)
{
    const gmmrrt_problem_t *pr = &p->problem;
    if (p->gmm_rrt.stage >= pr->model->k) {
        *x = pr->goal_x;
        *y = pr->goal_y;
        return 0;
    }
    double f[GMMRRT_MAX_DIM];
    gmmrrt_gmm_sample_component(pr->model, p->gmm_rrt.order[p->gmm_rrt.stage], &p->rng, f);
    gmmrrt_person_to_world(&pr->obstacles.people[p->focus_person], f[1], f[2], x, y);
    return 1;
}

void gmmrrt_gmm_rrt_node_added(struct gmmrrt_planner *p, double x, double y)
{
    if (!p->strategy.stages || !p->problem.model || p->focus_person < 0)
        return;
    const gmmrrt_model_t *m = p->problem.model;
    double xp, yp;
    gmmrrt_world_to_person(&p->problem.obstacles.people[p->focus_person], x, y, &xp, &yp);
    while (p->gmm_rrt.stage < m->k) {
        const int32_t c = p->gmm_rrt.order[p->gmm_rrt.stage];
        const double dx = xp - p->gmm_rrt.xy_mean[c][0], dy = yp - p->gmm_rrt.xy_mean[c][1];
        const double *ic = p->gmm_rrt.xy_inv_cov[c];
        const double m2 = ic[0] * dx * dx + 2.0 * ic[1] * dx * dy + ic[2] * dy * dy;
        if (m2 > GMMRRT_STAGE_REACHED_MAHAL2)
            break;
        ++p->gmm_rrt.stage;
    }
}
