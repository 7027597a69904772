/*
 * log.c - levelled, rate-limited logging to stderr (see log.h). One line per call,
 * written with a single fprintf so lines from a journal never interleave.
 */
#include "log.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static gmmrrtd_log_level_t g_level = GMMRRTD_LOG_INFO;
static const char *const k_names[] = {"error", "warn", "info", "debug"};

void gmmrrtd_log_set_level(gmmrrtd_log_level_t level) { g_level = level; }

int gmmrrtd_log_level_parse(const char *name, gmmrrtd_log_level_t *out)
{
    for (int i = 0; i < 4; ++i)
        if (name != NULL && strcmp(name, k_names[i]) == 0) {
            *out = (gmmrrtd_log_level_t)i;
            return 0;
        }
    return -1;
}

static void vlog(gmmrrtd_log_level_t level, const char *suffix, const char *fmt, va_list ap)
{
    char line[1024];
    vsnprintf(line, sizeof line, fmt, ap);
    /* systemd's journal reads "<N>" prefixes as priorities: err 3, warning 4, info 6, debug 7. */
    static const int k_prio[] = {3, 4, 6, 7};
    static int under_journal = -1;
    if (under_journal < 0)
        under_journal = getenv("JOURNAL_STREAM") != NULL;
    if (under_journal)
        fprintf(stderr, "<%d>%s: %s%s\n", k_prio[level], k_names[level], line, suffix);
    else
        fprintf(stderr, "gmmrrtd %s: %s%s\n", k_names[level], line, suffix);
}

void gmmrrtd_log(gmmrrtd_log_level_t level, const char *fmt, ...)
{
    if (level > g_level)
        return;
    va_list ap;
    va_start(ap, fmt);
    vlog(level, "", fmt, ap);
    va_end(ap);
}

void gmmrrtd_log_limited(gmmrrtd_ratelimit_t *rl, int64_t now_ms, int64_t interval_ms, gmmrrtd_log_level_t level,
                         const char *fmt, ...)
{
    if (level > g_level)
        return;
    if (rl->last_ms != 0 && now_ms - rl->last_ms < interval_ms) {
        rl->suppressed++;
        return;
    }
    char suffix[64] = "";
    if (rl->suppressed > 0)
        snprintf(suffix, sizeof suffix, " (%lld similar suppressed)", (long long)rl->suppressed);
    rl->last_ms = now_ms > 0 ? now_ms : 1;
    rl->suppressed = 0;
    va_list ap;
    va_start(ap, fmt);
    vlog(level, suffix, fmt, ap);
    va_end(ap);
}
