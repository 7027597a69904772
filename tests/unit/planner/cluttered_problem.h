/*
 * cluttered_problem.h - the cluttered benchmark problem (tests/data/bench_problems/problem_B.txt:
 * 40 circles of radius 0.6-1.2 in [-10, 10]^2, (-9, -9) -> (9, 9), point robot, optimum
 * 26.2074 m) as a problem builder for the planner tests.
 */
#ifndef GMMRRT_TEST_CLUTTERED_PROBLEM_H
#define GMMRRT_TEST_CLUTTERED_PROBLEM_H

#include "planner_fixtures.h"

static inline gmmrrt_problem_t cluttered_problem(void)
{
    static const double c[][3] = {
        {8.7039, -6.5411, 0.6851},
        {9.1628, -8.0291, 0.7159},
        {-4.7825, -3.1433, 1.1573},
        {5.8115, 6.0578, 1.132},
        {-7.2795, 5.0913, 0.9749},
        {1.8751, 8.1334, 1.1162},
        {0.9732, 6.302, 0.7977},
        {7.7919, 2.0946, 0.7512},
        {0.2018, 0.9144, 0.9517},
        {4.3313, -3.537, 0.6165},
        {6.9071, -8.2687, 1.1183},
        {-5.8153, -0.2023, 0.9731},
        {8.5795, 2.4615, 0.6936},
        {2.8865, 6.8004, 0.7939},
        {-6.0838, 2.9158, 0.726},
        {6.5565, 6.222, 0.9915},
        {0.7737, -6.6056, 1.1294},
        {-3.7922, -0.6267, 1.1915},
        {-3.4822, 2.2566, 0.6274},
        {4.7674, 6.7735, 0.6471},
        {5.2863, 3.7836, 1.0086},
        {-5.6186, -7.3128, 0.7942},
        {1.3142, -1.0182, 1.0238},
        {1.3558, -5.3384, 0.7531},
        {-0.8814, -4.4304, 1.0228},
        {-5.5091, -0.2387, 0.7062},
        {-5.7178, 4.6341, 0.6137},
        {8.6806, -7.3858, 1.0051},
        {3.6081, 2.8018, 1.1626},
        {-0.2464, 4.2248, 1.1075},
        {7.2851, -4.8972, 0.6837},
        {-4.0043, 0.5986, 0.6574},
        {-0.9727, 3.6688, 0.7812},
        {0.6142, 0.5882, 0.9203},
        {-1.2547, -1.241, 0.8903},
        {-1.9417, -2.3694, 0.7427},
        {0.1679, -3.2283, 0.7498},
        {-3.853, -5.16, 0.6765},
        {6.8597, -8.3532, 1.0895},
        {-4.0971, -3.6928, 0.6114},
    };
    gmmrrt_problem_t pr = empty_problem(-9.0, -9.0, 9.0, 9.0);
    pr.obstacles.bounds = (gmmrrt_bounds_t){-10.0, -10.0, 10.0, 10.0};
    pr.obstacles.num_circles = (int32_t)(sizeof c / sizeof c[0]);
    for (int32_t i = 0; i < pr.obstacles.num_circles; ++i)
        pr.obstacles.circles[i] = (gmmrrt_circle_t){c[i][0], c[i][1], c[i][2]};
    return pr;
}

#endif /* GMMRRT_TEST_CLUTTERED_PROBLEM_H */
