/* Extrapolation of a discretised quantity to N -> infinity (issue 23 item 3):
 * weighted least squares of L(N) = L_inf + c_1 / N^p_1 + c_2 / N^p_2 + ...,
 * each point weighted by its own uncertainty, with the parameters'
 * covariance, chi^2, and the two checks an honest error bar needs: the model
 * error (the change in L_inf when the next power is added) and the
 * leave-one-out spread. Used by bench/ropelength_extrap (the ideal trefoil's
 * ropelength from a ladder of tightened N). */
#ifndef TR_UTIL_EXTRAPOLATE_H
#define TR_UTIL_EXTRAPOLATE_H

#include <stddef.h>

#define TR_EXTRAP_MAX_TERMS 4 /* L_inf and up to three powers of 1/N */

typedef struct {
    int ok;            /* 0 when the fit is undetermined (fewer points than parameters, singular) */
    int nterms;        /* parameters: L_inf, then one per power */
    size_t npoints;    /* points used */
    double coef[TR_EXTRAP_MAX_TERMS];  /* L_inf, c_1, c_2, ... */
    double sigma[TR_EXTRAP_MAX_TERMS]; /* from the points' uncertainties alone (no chi^2 scaling) */
    double chi2;       /* sum of ((L - fit) / s)^2 */
    int dof;           /* npoints - nterms */
    double birge;      /* sqrt(chi2 / dof) when dof > 0, else 1 */
    double sigma_scaled; /* sigma[0] * max(1, birge): L_inf's error when the data scatter more than their bars say */
} tr_extrap_fit;

/* Weighted least squares of L = coef[0] + sum_k coef[k] / N^powers[k-1] over
 * the points with use[i] != 0 (use NULL: all); s[i] > 0 is point i's
 * standard uncertainty. Solved on the weighted design matrix by Householder
 * QR with the columns scaled to unit norm (1/N^4 at N = 2e4 is 6e-18), so the
 * normal equations' squared condition number never enters. */
int tr_extrap_fit_powers(const double *n, const double *l, const double *s, const int *use,
                         size_t npoints, const int *powers, int npowers, tr_extrap_fit *out);

typedef struct {
    int nfits;             /* fits made: fit[k] has the first k + 1 powers (k < nfits) */
    tr_extrap_fit fit[TR_EXTRAP_MAX_TERMS - 1];
    int selected;          /* the fit reported: the first whose chi^2/dof is at most
                            * 4 (sqrt: 2), or the next while one with dof >= 1 exists */
    double linf;           /* fit[selected].coef[0] */
    double model_err;      /* |L_inf(selected + 1 power) - linf| (0 when that fit is undetermined) */
    int model_checked;     /* 1 when model_err could be computed */
    double loo_min, loo_max; /* range of the selected fit's L_inf with one point left out */
    double jackknife;      /* jackknife standard error of that L_inf (0 when not computable) */
    int loo_worst;         /* the point whose removal moves L_inf most (-1: none) */
    double total_err;      /* sqrt(sigma_scaled^2 + model_err^2), at least the jackknife error */
} tr_extrap_report;

/* The fits with the first 1, 2, ... npowers of powers[] (npowers <= 3), the
 * one selected (the data ask for a further power when the fit leaves
 * chi^2/dof > 4), the model error of the selected fit from its next power,
 * and leave-one-out over the selected fit (when a point can be spared).
 * Returns 0 when the first fit is determined. */
int tr_extrap_report_make(const double *n, const double *l, const double *s, size_t npoints,
                          const int *powers, int npowers, tr_extrap_report *out);

#endif
