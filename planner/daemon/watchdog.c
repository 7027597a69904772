/*
 * watchdog.c - systemd's watchdog for gmmrrtd (sd_notify, when built with libsystemd).
 *
 * The main loop pings once per cycle. A step that may take longer than the unit's WatchdogSec
 * (the world's set-up after an obstacle change, a reload reading files) is bracketed: before
 * it the daemon pings and stretches the interval to long_step_ms (WATCHDOG_USEC=, systemd
 * >= 236), after it restores the unit's interval and pings again. A step that hangs past
 * long_step_ms is still killed by systemd: the stretch is a bound, not a blank cheque.
 */
#include <stdio.h>

#include "daemon.h"

#ifdef GMMRRT_HAVE_SYSTEMD
#include <systemd/sd-daemon.h>
#endif

void gmmrrtd_watchdog_ping(const gmmrrtd_t *d)
{
    (void)d;
#ifdef GMMRRT_HAVE_SYSTEMD
    (void)sd_notify(0, "WATCHDOG=1");
#endif
}

void gmmrrtd_watchdog_long_step(const gmmrrtd_t *d, int begin)
{
#ifdef GMMRRT_HAVE_SYSTEMD
    if (d->watchdog_usec <= 0)
        return;
    const long long usec = begin ? (long long)(d->set.long_step_ms * 1e3) : (long long)d->watchdog_usec;
    (void)sd_notifyf(0, "WATCHDOG=1\nWATCHDOG_USEC=%lld", usec);
#else
    (void)d;
    (void)begin;
#endif
}
