/* This file contains the test of the monotonic clock (util/clock.h): it
 * never goes back and measures a sleep as long as the sleep; a deadline
 * passes with the clock or a raised stop flag. */
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

    /* the deadline: none, the clock past it, a stop flag raised */
    CHECK(tr_deadline_passed(NULL) == 0);
    tr_deadline none = {0};
    CHECK(tr_deadline_passed(&none) == 0 && tr_deadline_left(&none) > 1e300);
    volatile sig_atomic_t stop = 0;
    tr_deadline soon = {.at = tr_clock_seconds() + 0.05, .stop = &stop};
    CHECK(tr_deadline_passed(&soon) == 0);
    CHECK(tr_deadline_left(&soon) > 0.0 && tr_deadline_left(&soon) <= 0.05);
    nanosleep(&nap, NULL);
    CHECK(tr_deadline_passed(&soon) == 1 && tr_deadline_left(&soon) == 0.0);
    stop = 1;
    CHECK(tr_deadline_passed(&soon) == 2);
    CHECK(tr_deadline_min(0, 3) == 3 && tr_deadline_min(5, 0) == 5 && tr_deadline_min(5, 3) == 3 &&
          tr_deadline_min(0, 0) == 0);
    return tr_test_finish("test_clock");
}
