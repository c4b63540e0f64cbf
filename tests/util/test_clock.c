/* This file contains the test of the monotonic clock (util/clock.h): it
 * never goes back and measures a sleep as long as the sleep. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "testlib.h"
#include "util/clock.h"

int main(void)
{
    double t0 = tr_clock_seconds(), prev = t0;
    for (int i = 0; i < 100000; i++) {
        double t = tr_clock_seconds();
        CHECK(t >= prev);
        prev = t;
    }
    double a = tr_clock_seconds();
    struct timespec nap = {0, 50000000}; /* 50 ms */
    nanosleep(&nap, NULL);
    double b = tr_clock_seconds();
    CHECK(b - a >= 0.05);
    CHECK(b - a < 5.0); /* seconds, not milli- or nanoseconds */
    return tr_test_finish("test_clock");
}
