/*
 * error_text.h - internal: the one way gmmrrt code fills a caller's (err, errcap) reason buffer
 * beside a gmmrrt_status_t (STYLE.md items 3 and 6: a specific status plus a reason that names
 * the problem and where). Used by the model format (model.c), the planner configuration
 * (config.c) and model files on disk (planner/io/model_file.c, which includes this directory
 * privately: the core does not depend on io/, io/ depends on the core). Not a public header.
 *
 * Static inline so that it adds no symbol to libgmmrrt and needs no link-time sharing. The text
 * itself is written by gmmrrt_vformat_reason (gmmrrt/detail/reason_text.h), the formatter the
 * message decoders and the daemon use too.
 */
#ifndef GMMRRT_ERROR_TEXT_H
#define GMMRRT_ERROR_TEXT_H

#include <stdarg.h>
#include <stddef.h>

#include "gmmrrt/detail/reason_text.h"
#include "gmmrrt/status.h"

/* Empties err[errcap] when it is usable (err may be NULL or errcap 0: nothing is written). */
static inline void gmmrrt_clear_error(char *err, size_t errcap)
{
    if (err != NULL && errcap > 0)
        err[0] = '\0';
}

/* Writes the printf-formatted reason into err[errcap] (truncated, always terminated; nothing
 * when err is NULL or errcap is 0) and returns status unchanged, so a check reads
 * `return gmmrrt_set_error(GMMRRT_ERR_..., err, errcap, "...", ...);`. */
static inline gmmrrt_status_t gmmrrt_set_error(gmmrrt_status_t status, char *err, size_t errcap,
                                               const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static inline gmmrrt_status_t gmmrrt_set_error(gmmrrt_status_t status, char *err, size_t errcap,
                                               const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    gmmrrt_vformat_reason(err, errcap, fmt, ap);
    va_end(ap);
    return status;
}

#endif /* GMMRRT_ERROR_TEXT_H */
