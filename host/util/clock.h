/* This file contains the monotonic clock that every time limit, deadline and
 * timing in Tightrope reads (the engine's --time-limit, the polish's
 * deadline, bench's figures), and the run's hard bound: a deadline on that
 * clock with the stop flag a signal raises, which every loop that can run
 * long checks (the settle, the shuffle, the roads of tighten). */
#ifndef TR_CLOCK_H
#define TR_CLOCK_H

#include <signal.h>
#include <stddef.h>

/* Seconds on CLOCK_MONOTONIC from an arbitrary origin: differences only.
 * Never goes back, whatever happens to the wall clock. */
double tr_clock_seconds(void);

/* A bound on a computation: the clock passing `at` (tr_clock_seconds;
 * 0: none) or *stop raised (NULL: none). Zero-initialised: no bound. */
typedef struct tr_deadline {
    double at;
    volatile sig_atomic_t *stop;
} tr_deadline;

/* 0 while the bound holds (d may be NULL); 1 once the clock has passed
 * d->at; 2 once *d->stop is raised (a signal outranks the clock). */
int tr_deadline_passed(const tr_deadline *d);

/* tr_deadline_passed for a pass over `work` items (vertices, say), 0
 * below TR_DEADLINE_WORK of them: a short pass finishes first, as the
 * neighbour search's does (it looks at the bound every 64 leaves), so a
 * small curve is measured or resampled whole even under a raised stop
 * (a cancelled tighten hands back its start, measured) */
#define TR_DEADLINE_WORK 65536
int tr_deadline_passed_for(const tr_deadline *d, size_t work);

/* The seconds left before d->at (INFINITY without one; never below 0). */
double tr_deadline_left(const tr_deadline *d);

/* The earlier of two clock times, where 0 means none. */
double tr_deadline_min(double a, double b);

#endif
