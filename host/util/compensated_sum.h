/* This file contains compensated (Neumaier) summation, the one the lengths,
 * arclengths and parameter sums of every layer use: for N ~ 2e5 edges of
 * 1.6e-4 a plain sum loses ~1e-12 of the length, the size of a published
 * ropelength's last digit; the compensated one keeps it to rounding. */
#ifndef TR_COMPENSATED_SUM_H
#define TR_COMPENSATED_SUM_H

#include <math.h>

/* A running sum and the rounding it has lost; {0, 0} (or {start, 0}) to begin. */
typedef struct tr_csum {
    double sum, comp;
} tr_csum;

/* sum += v, the rounding of that addition carried in comp (Neumaier's
 * variant of Kahan's: correct also when |v| > |sum|). */
static inline void tr_csum_add(tr_csum *s, double v)
{
    double t = s->sum + v;
    s->comp += (fabs(s->sum) >= fabs(v)) ? (s->sum - t) + v : (v - t) + s->sum;
    s->sum = t;
}

/* The compensated value of the sum so far. */
static inline double tr_csum_value(const tr_csum *s) { return s->sum + s->comp; }

#endif
