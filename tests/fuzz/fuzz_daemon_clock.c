/*
 * fuzz_daemon_clock.c - libFuzzer target for gmmrrtd's per-source clocks
 * (planner/daemon/clock.h): sequences of stamps on several channels, arriving on a
 * non-decreasing local time base, as the daemon judges them.
 *
 * Input: records of 12 bytes
 *   [source: 1 byte, low 2 bits][local advance: 3 bytes LE, us][stamp: 8 bytes LE, int64]
 * A stamp is taken as given (any int64: negative, huge) or, when byte 0's bit 7 is set, as an
 * offset of at most +-2^31 us from the source's last stamp (to reach the interesting region
 * near its clock). Properties (abort = finding), besides the sanitizers':
 *   - a message judges only its own source: the others' models are bit-for-bit unchanged;
 *   - a rejected message never moves its source's offset, order or data time;
 *   - an accepted message's data time is never after its arrival, and the channel's order
 *     (last_utime) never runs ahead of the source's clock;
 *   - an accepted message moves the offset by at most slew_us_per_s per second of local time,
 *     unless it (re)started or resynchronised the source;
 *   - ages are never negative.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define REQUIRE(cond)                                                                   \
    do {                                                                                \
        if (!(cond)) {                                                                  \
            fprintf(stderr, "fuzz_daemon_clock: broken: %s\n", #cond);                  \
            abort();                                                                    \
        }                                                                               \
    } while (0)

enum { N_SRC = 4, REC = 12 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const gmmrrtd_clock_params_t p = {.max_off_us = 2000000, .resync_count = 5, .resync_us = 1000000,
                                      .slew_us_per_s = 10000};
    gmmrrtd_source_clock_t src[N_SRC];
    memset(src, 0, sizeof src);
    int64_t local = 1000000;
    for (size_t off = 0; off + REC <= size; off += REC) {
        const uint8_t *r = data + off;
        const int i = r[0] & 3;
        local += (int64_t)r[1] | (int64_t)r[2] << 8 | (int64_t)r[3] << 16;
        uint64_t raw = 0;
        for (int b = 7; b >= 0; --b)
            raw = raw << 8 | r[4 + b];
        int64_t stamp;
        if (r[0] & 0x80) {
            const int64_t delta = (int64_t)(int32_t)(uint32_t)raw;
            stamp = src[i].have ? src[i].last_utime + delta : delta;
        } else {
            memcpy(&stamp, &raw, sizeof stamp);
        }
        gmmrrtd_source_clock_t before[N_SRC];
        memcpy(before, src, sizeof src);
        int64_t resid = 0, step = 0;
        const gmmrrtd_stamp_t v = gmmrrtd_clock_judge(&src[i], &p, stamp, local, &resid, &step);
        for (int j = 0; j < N_SRC; ++j)
            if (j != i)
                REQUIRE(memcmp(&before[j], &src[j], sizeof src[j]) == 0);
        const gmmrrtd_source_clock_t *s = &src[i], *b = &before[i];
        switch (v) {
        case GMMRRTD_STAMP_RANGE:
        case GMMRRTD_STAMP_AHEAD:
        case GMMRRTD_STAMP_BACKWARDS:
            REQUIRE(s->have == b->have && s->offset_us == b->offset_us && s->last_utime == b->last_utime &&
                    s->data_local_us == b->data_local_us);
            break;
        case GMMRRTD_STAMP_OK: {
            REQUIRE(b->have);
            const int64_t elapsed = local - b->offset_local_us;
            const int64_t allow = (elapsed > 1000000000 ? 1000000000 : elapsed) * p.slew_us_per_s / 1000000;
            const int64_t moved = s->offset_us - b->offset_us;
            REQUIRE(moved <= allow && -moved <= allow);
            break;
        }
        case GMMRRTD_STAMP_FIRST:
        case GMMRRTD_STAMP_RESYNC: REQUIRE(s->offset_us == stamp - local); break;
        default: REQUIRE(0);
        }
        if (v == GMMRRTD_STAMP_OK || v == GMMRRTD_STAMP_FIRST || v == GMMRRTD_STAMP_RESYNC) {
            REQUIRE(s->data_local_us <= local);
            REQUIRE(s->last_utime <= local + s->offset_us || s->last_utime == stamp);
        }
        for (int j = 0; j < N_SRC; ++j)
            REQUIRE(gmmrrtd_clock_age_us(&src[j], local) >= 0);
    }
    return 0;
}
