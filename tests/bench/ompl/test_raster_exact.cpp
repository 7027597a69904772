/*
 * test_raster_exact.cpp - the map scene's exact validators (raster_exact.hpp) against a
 * brute-force oracle: every blocked cell (a ring of outside cells included) against points
 * sampled every 1 mm along the motion. The oracle's sampled minimum distance d_s over-estimates
 * the true minimum by at most half the sample spacing, so a motion with d_s > r + 0.5 mm must be
 * called free and one with d_s <= r must be called blocked; the band between is not judged (and
 * counted, so a test that judges nothing fails). And the Planner Arena log (arena_log.hpp): its
 * run table holds what was given, with unknown values left empty.
 */
#include <cmath>
#include <csetjmp>
#include <cstdarg>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern "C" {
#include <cmocka.h>
}

#include "arena_log.hpp"
#include "raster_exact.hpp"

namespace {

struct Scene {
    std::vector<unsigned char> mem;
    gmmrrt_raster_t r{};
};

/* A 40 x 30 raster of 0.1 m cells, rotated by 0.3 rad, about 8 % of the cells occupied and a few
 * unknown, the outside blocking (unknown_blocked 1). */
void make_scene(Scene *s, uint64_t seed)
{
    const int32_t w = 40, h = 30;
    s->mem.assign(gmmrrt_raster_mem_size(w * h, 64) + 8, 0);
    void *mem = reinterpret_cast<void *>((reinterpret_cast<uintptr_t>(s->mem.data()) + 7u) & ~uintptr_t(7));
    assert_int_equal(gmmrrt_raster_init(&s->r, mem, s->mem.size() - 8, w * h, 64), GMMRRT_OK);
    assert_int_equal(gmmrrt_raster_set_geometry(&s->r, w, h, 0.1, 1.0, -2.0, 0.3, 1), GMMRRT_OK);
    uint64_t x = seed;
    for (int32_t k = 0; k < w * h; ++k) {
        uint8_t &c = s->r.cells[k];
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        const unsigned v = static_cast<unsigned>(x >> 56);
        c = v < 20 ? GMMRRT_RASTER_OCCUPIED : (v < 24 ? GMMRRT_RASTER_UNKNOWN : (v < 28 ? 50 : GMMRRT_RASTER_FREE));
    }
}

double oracle_min_distance(const gmmrrt_raster_t &r, double x0, double y0, double x1, double y1)
{
    const double len = std::hypot(x1 - x0, y1 - y0);
    const int n = 1 + static_cast<int>(len / 1e-3);
    double best = INFINITY;
    for (int k = 0; k <= n; ++k) {
        const double t = static_cast<double>(k) / n;
        const double dx = x0 + t * (x1 - x0) - r.origin_x, dy = y0 + t * (y1 - y0) - r.origin_y;
        const double u = dx * std::cos(r.origin_yaw) + dy * std::sin(r.origin_yaw);
        const double v = -dx * std::sin(r.origin_yaw) + dy * std::cos(r.origin_yaw);
        for (long j = -3; j < r.height + 3; ++j)
            for (long i = -3; i < r.width + 3; ++i) {
                if (!gmmrrt_bench::raster_cell_blocks(r, i, j))
                    continue;
                const double lo_u = i * r.resolution_m, lo_v = j * r.resolution_m;
                const double eu = u < lo_u ? lo_u - u : (u > lo_u + r.resolution_m ? u - lo_u - r.resolution_m : 0.0);
                const double ev = v < lo_v ? lo_v - v : (v > lo_v + r.resolution_m ? v - lo_v - r.resolution_m : 0.0);
                best = std::min(best, std::hypot(eu, ev));
            }
    }
    return best;
}

void test_cell_rule_is_the_rasters(void **)
{
    Scene s;
    make_scene(&s, 7);
    for (long j = -1; j <= s.r.height; ++j)
        for (long i = -1; i <= s.r.width; ++i) {
            const bool outside = i < 0 || j < 0 || i >= s.r.width || j >= s.r.height;
            const uint8_t c = outside ? GMMRRT_RASTER_UNKNOWN : s.r.cells[j * s.r.width + i];
            const bool want = c == GMMRRT_RASTER_OCCUPIED || c == GMMRRT_RASTER_UNKNOWN; /* scale values do not block */
            assert_int_equal(gmmrrt_bench::raster_cell_blocks(s.r, i, j), want);
        }
}

void test_motions_and_discs_match_brute_force(void **)
{
    Scene s;
    make_scene(&s, 11);
    uint64_t x = 99;
    auto uniform = [&x](double lo, double hi) {
        x = x * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * static_cast<double>(x >> 11) / 9007199254740992.0;
    };
    int judged_free = 0, judged_blocked = 0, band = 0;
    for (int k = 0; k < 400; ++k) {
        const double radius = k % 4 == 0 ? 0.0 : uniform(0.02, 0.3);
        /* Endpoints within 0.2 m of the raster (in its frame), so every blocked cell within
         * 0.3 m of the motion lies in the oracle's ring of 3 outside cells. */
        const bool disc = k % 5 == 0;
        const double u0 = uniform(-0.2, 4.2), v0 = uniform(-0.2, 3.2);
        const double u1 = disc ? u0 : std::min(4.2, std::max(-0.2, u0 + uniform(-1.0, 1.0)));
        const double v1 = disc ? v0 : std::min(3.2, std::max(-0.2, v0 + uniform(-1.0, 1.0)));
        const double cs = std::cos(s.r.origin_yaw), sn = std::sin(s.r.origin_yaw);
        const double x0 = s.r.origin_x + u0 * cs - v0 * sn, y0 = s.r.origin_y + u0 * sn + v0 * cs;
        const double x1 = s.r.origin_x + u1 * cs - v1 * sn, y1 = s.r.origin_y + u1 * sn + v1 * cs;
        const double d = oracle_min_distance(s.r, x0, y0, x1, y1);
        const bool got = disc ? gmmrrt_bench::raster_disc_free(s.r, radius, x0, y0)
                              : gmmrrt_bench::raster_motion_free(s.r, radius, x0, y0, x1, y1);
        if (d > radius + 0.5e-3) {
            if (!got)
                fail_msg("motion %d (%g,%g)->(%g,%g) r %g: oracle distance %g, called blocked", k, x0, y0, x1, y1,
                         radius, d);
            ++judged_free;
        } else if (d <= radius) {
            if (got)
                fail_msg("motion %d (%g,%g)->(%g,%g) r %g: oracle distance %g, called free", k, x0, y0, x1, y1,
                         radius, d);
            ++judged_blocked;
        } else {
            ++band;
        }
    }
    assert_true(judged_free > 50);
    assert_true(judged_blocked > 50);
    assert_true(band < 20);
}

void test_arena_log_holds_the_runs(void **)
{
    const std::string path = "test_arena_log.log";
    std::vector<gmmrrt_bench::ArenaPlanner> planners = {
        {"gmmrrt", {{0.002, 0.01, 10.0, 10.8}, {0.003, NAN, 10.0, INFINITY}}},
        {"RRTstar", {{0.05, 0.5, 10.0, 11.1}}},
    };
    std::string err;
    assert_true(gmmrrt_bench::write_arena_log(path, "A_10ms", "set-up text", 10.0, 1, 0.5, planners, &err));
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    std::remove(path.c_str());
    const std::string t = text.str();
    assert_true(t.rfind("OMPL version 1.5", 0) == 0);
    assert_non_null(std::strstr(t.c_str(), "\nExperiment A_10ms\n"));
    assert_non_null(std::strstr(t.c_str(), "\n0.01 seconds per run\n0 MB per run\n2 runs per planner\n"));
    assert_non_null(std::strstr(t.c_str(), "\n2 planners\ngeometric_gmmrrt\n"));
    /* cost; first (s); setup (s); solved; set-up + solve (s) */
    assert_non_null(std::strstr(t.c_str(), "\n2 runs\n10.8; 1e-05; 2e-06; 1; 0.010002; \n; ; 3e-06; 0; 0.010003; \n.\n"));
    assert_non_null(std::strstr(t.c_str(), "\ngeometric_RRTstar\n0 common properties\n5 properties for each run\n"));
}

} // namespace

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cell_rule_is_the_rasters),
        cmocka_unit_test(test_motions_and_discs_match_brute_force),
        cmocka_unit_test(test_arena_log_holds_the_runs),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}
