/*
 * log.h - gmmrrtd's levelled logging to stderr, with a rate limiter so that a flood of bad
 * input gives one line per reason per interval, not one per message: bad input is logged without flooding the log.
 */
#ifndef GMMRRTD_LOG_H
#define GMMRRTD_LOG_H

#include <stdint.h>

typedef enum { GMMRRTD_LOG_ERROR = 0, GMMRRTD_LOG_WARN = 1, GMMRRTD_LOG_INFO = 2, GMMRRTD_LOG_DEBUG = 3 } gmmrrtd_log_level_t;

/* Messages above `level` are dropped. */
void gmmrrtd_log_set_level(gmmrrtd_log_level_t level);

/* "error", "warn", "info", "debug" -> 0 and *out; anything else -> -1. */
int gmmrrtd_log_level_parse(const char *name, gmmrrtd_log_level_t *out);

void gmmrrtd_log(gmmrrtd_log_level_t level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* A rate limiter for one kind of message: at most one line per interval_ms; the next line
 * that gets through says how many were suppressed in between. */
typedef struct {
    int64_t last_ms;     /* monotonic ms of the last line written; 0 = never */
    int64_t suppressed;  /* lines dropped since */
} gmmrrtd_ratelimit_t;

void gmmrrtd_log_limited(gmmrrtd_ratelimit_t *rl, int64_t now_ms, int64_t interval_ms, gmmrrtd_log_level_t level,
                         const char *fmt, ...) __attribute__((format(printf, 5, 6)));

#define LOG_ERROR(...) gmmrrtd_log(GMMRRTD_LOG_ERROR, __VA_ARGS__)
#define LOG_WARN(...) gmmrrtd_log(GMMRRTD_LOG_WARN, __VA_ARGS__)
#define LOG_INFO(...) gmmrrtd_log(GMMRRTD_LOG_INFO, __VA_ARGS__)
#define LOG_DEBUG(...) gmmrrtd_log(GMMRRTD_LOG_DEBUG, __VA_ARGS__)

#endif /* GMMRRTD_LOG_H */
