/*
 * detail/reason_text.h - the one way gmmrrt code writes a reason into a caller's (err, errcap)
 * buffer: the core and its model-file layer (through planner/src/error_text.h, beside a
 * gmmrrt_status_t), the message decoders (lcmtypes/msg_decode.c, beside a gmmrrt_msg_result_t)
 * and the daemon's settings. A reason names the problem and where (STYLE.md items 3 and 6).
 * Not an API of its own: static inline, so it adds no symbol to any library.
 */
#ifndef GMMRRT_DETAIL_REASON_TEXT_H
#define GMMRRT_DETAIL_REASON_TEXT_H

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

/* Writes the printf-formatted reason into err[errcap], truncated and always terminated;
 * nothing when err is NULL or errcap is 0. */
static inline void gmmrrt_vformat_reason(char *err, size_t errcap, const char *fmt, va_list ap)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 0)))
#endif
    ;

static inline void gmmrrt_vformat_reason(char *err, size_t errcap, const char *fmt, va_list ap)
{
    if (err != NULL && errcap > 0)
        vsnprintf(err, errcap, fmt, ap);
}

#endif /* GMMRRT_DETAIL_REASON_TEXT_H */
