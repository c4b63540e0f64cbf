/* This file contains the monotonic clock and the deadline (clock.h). */
#include "util/clock.h"

#include <math.h>
#include <time.h>

double tr_clock_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int tr_deadline_passed(const tr_deadline *d)
{
    if (!d)
        return 0;
    if (d->stop && *d->stop)
        return 2;
    return d->at > 0 && tr_clock_seconds() >= d->at;
}

double tr_deadline_left(const tr_deadline *d)
{
    if (!d || !(d->at > 0))
        return INFINITY;
    return fmax(d->at - tr_clock_seconds(), 0.0);
}

double tr_deadline_min(double a, double b)
{
    if (!(a > 0))
        return b;
    if (!(b > 0))
        return a;
    return a < b ? a : b;
}

int tr_deadline_passed_for(const tr_deadline *d, size_t work)
{
    return work >= TR_DEADLINE_WORK ? tr_deadline_passed(d) : 0;
}
