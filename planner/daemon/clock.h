/*
 * clock.h - gmmrrtd's time: one local time base, and one clock model per input source.
 *
 * The daemon never takes its time from a message. Its time base is its own: CLOCK_MONOTONIC
 * when live, the event timestamps of the log (the recorder's receive times) when replaying a
 * file:// log. Every message is stamped by its sender on the sender's clock; each source
 * (input channel) gets its own estimate of the offset between its stamps and the local time
 * base, bounded and moved separately, so a sender can only ever move the estimate of its own
 * channel, and only within the limits below:
 *
 *   - residual r = utime - local - offset: how far a message is from where its source's
 *     clock is expected to be. |r| <= max_off_us: the message is on its source's clock.
 *     It is accepted; the offset follows r by at most slew_us_per_s per second of local time
 *     (clock drift and latency changes are slow; a sender stamping ahead cannot drag it).
 *   - A message stamped ahead of its source's clock (0 < r) counts as stamped "now" for
 *     the channel's order: a sender cannot push the channel's last stamp into the future and
 *     make the correctly stamped messages after it look backwards.
 *   - r > max_off_us (ahead), r < -max_off_us (behind) or a stamp older than the channel's
 *     last accepted one (backwards): rejected, unless the source has been consistently off
 *     (resync below).
 *   - Resync: a run of off-clock messages of one source in one direction whose residuals
 *     agree with the run's first within max_off_us (a real clock step moves every stamp by the
 *     same amount; a ratchet of ever later stamps does not agree with itself) that is at least
 *     resync_count messages long AND spans at least resync_us of local time. Then the source's
 *     offset steps to the new clock. Only that source's.
 *   - A source's first offset is provisional: until a second message confirms it, a message
 *     off it re-initialises it (one far-off first message cannot hold a source hostage).
 *
 * The data time of an accepted message is min(arrival, utime - offset): the local time its
 * content stands for, never later than it arrived. Staleness is judged per source on it:
 * now - data time > the channel's timeout.
 *
 * Pure functions on caller-owned structs (no I/O, no allocation, no global state) so that the
 * unit tests and the clock fuzzer drive exactly what the daemon runs. All times are int64 us;
 * inputs are limited to 0..GMMRRTD_MAX_UTIME, so no sum or difference here overflows.
 */
#ifndef GMMRRTD_CLOCK_H
#define GMMRRTD_CLOCK_H

#include <stdint.h>

/* Largest input utime accepted (us, the year 2255); larger or negative ones are refused. */
#define GMMRRTD_MAX_UTIME ((int64_t)1 << 53)

typedef struct {
    int64_t max_off_us;     /* residual bound, > 0 */
    int32_t resync_count;   /* messages in a consistent off-clock run before the offset steps, >= 1 */
    int64_t resync_us;      /* local time such a run must span, >= 0 */
    int64_t slew_us_per_s;  /* how fast an accepted residual moves the offset, >= 0 */
} gmmrrtd_clock_params_t;

/* One input source's clock model. Zero-initialised = no message yet. */
typedef struct {
    int have;               /* an offset exists */
    int confirmed;          /* a second message agreed with it */
    int64_t offset_us;      /* source stamp - local time */
    int64_t offset_local_us;/* local time the offset was last moved */
    int64_t last_utime;     /* the channel's order: last accepted stamp, clamped to the source's clock */
    int64_t data_local_us;  /* data time of the last accepted message */
    int32_t off_dir;        /* +1 ahead, -1 behind/backwards, 0: no run */
    int32_t off_run;        /* messages in the current off-clock run */
    int64_t off_first_local_us; /* local time of the run's first message */
    int64_t off_first_resid_us; /* residual of the run's first message */
} gmmrrtd_source_clock_t;

typedef enum {
    GMMRRTD_STAMP_OK = 0,        /* accepted */
    GMMRRTD_STAMP_FIRST = 1,     /* accepted; it (re)initialised the source's offset */
    GMMRRTD_STAMP_RESYNC = 2,    /* accepted; the source's offset stepped (*step_us says how far) */
    GMMRRTD_STAMP_RANGE = 3,     /* rejected: utime or local time outside 0..GMMRRTD_MAX_UTIME */
    GMMRRTD_STAMP_AHEAD = 4,     /* rejected: more than max_off_us ahead of its source's clock */
    GMMRRTD_STAMP_BACKWARDS = 5, /* rejected: older than the channel's last, or max_off_us behind its clock */
} gmmrrtd_stamp_t;

/* Judges one message of a source: utime its stamp, local_us its arrival on the local time
 * base (non-decreasing across calls). Updates *s when the message is accepted (and the run
 * counters either way). *resid_us gets the residual (0 for FIRST), *step_us the offset step
 * of a RESYNC or FIRST re-initialisation (0 otherwise). Both may be NULL. */
gmmrrtd_stamp_t gmmrrtd_clock_judge(gmmrrtd_source_clock_t *s, const gmmrrtd_clock_params_t *p, int64_t utime,
                                    int64_t local_us, int64_t *resid_us, int64_t *step_us);

/* Age of a source's data at local time now_us (us, >= 0); INT64_MAX when it has none. */
int64_t gmmrrtd_clock_age_us(const gmmrrtd_source_clock_t *s, int64_t now_us);

#endif /* GMMRRTD_CLOCK_H */
