/* This file contains the monotonic clock that every time limit, deadline and
 * timing in Tightrope reads (the engine's --time-limit, the polish's
 * deadline, bench's figures). */
#ifndef TR_CLOCK_H
#define TR_CLOCK_H

/* Seconds on CLOCK_MONOTONIC from an arbitrary origin: differences only.
 * Never goes back, whatever happens to the wall clock. */
double tr_clock_seconds(void);

#endif
