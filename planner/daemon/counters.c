/*
 * counters.c - gmmrrtd's counted and logged events: rejections (planner_status_t.rejected)
 * and stopped cycles (planner_status_t.stops), each logged at warn at most once per reason
 * per log_interval_ms, with the number suppressed in between. Nothing is silent: every stop
 * and every rejection is counted, and the first of each kind in an interval is logged.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <time.h>

#include "daemon.h"
#include "gmmrrt/status.h"

int64_t gmmrrtd_mono_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

int64_t gmmrrtd_now_us(const gmmrrtd_t *d)
{
    return d->clock_mode == GMMRRTD_CLOCK_LOG ? d->log_now_us : gmmrrtd_mono_us();
}

int64_t gmmrrtd_min_period_us(const gmmrrtd_t *d)
{
    return (int64_t)llround(d->set.min_period_ms * 1e3);
}

const char *gmmrrtd_stop_str(int code)
{
    switch (code) {
    case GMMRRTD_STOP_POSE_STALE: return "stopped: robot pose is stale";
    case GMMRRTD_STOP_NO_MODEL: return "stopped: no model for the task";
    case GMMRRTD_STOP_UNKNOWN_TARGET: return "stopped: approach target not tracked";
    case GMMRRTD_STOP_OBSTACLES_STALE: return "stopped: obstacle list is stale";
    case GMMRRTD_STOP_PLANNING_BOX: return "stopped: planning box exceeds the clearance grid";
    case GMMRRTD_STOP_GOAL_REACHED: return "stopped: goal reached";
    case GMMRRTD_STOP_GOAL_CANCELLED: return "stopped: goal cancelled";
    case GMMRRTD_STOP_SCAN_STALE: return "stopped: laser scans are stale";
    case GMMRRTD_STOP_GRID_STALE: return "stopped: occupancy grid is stale";
    default: return gmmrrt_status_str((gmmrrt_status_t)code);
    }
}

static const char *const k_rows[GMMRRTD_RL_ROWS] = {"pose", "people", "goal", "obstacles", "scan", "grid",
                                                           "planner", "stop"};

void gmmrrtd_reject(gmmrrtd_t *d, int row, int reason, const char *fmt, ...)
{
    d->status.rejected[reason]++;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    gmmrrtd_log_limited(&d->rl[row][reason], gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms,
                        GMMRRTD_LOG_WARN, "%s rejected (total %lld): %s", k_rows[row],
                        (long long)d->status.rejected[reason], line);
}

void gmmrrtd_count_stop(gmmrrtd_t *d, int stop, const char *fmt, ...)
{
    d->status.stops[stop]++;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    gmmrrtd_log_limited(&d->rl_stop[stop], gmmrrtd_mono_us() / 1000, (int64_t)d->set.log_interval_ms,
                        GMMRRTD_LOG_WARN, "stop (%lld cycles stopped for this reason): %s",
                        (long long)d->status.stops[stop], line);
}
