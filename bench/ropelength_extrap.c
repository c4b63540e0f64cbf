/* bench/ropelength_extrap: L(N) -> L_inf by weighted least squares
 * (util/extrapolate.h), the fitter behind bench/extrapolate_trefoil.sh.
 *   ropelength_extrap TABLE [--powers P1,P2,P3] [--ref X]
 * TABLE: one point a line, "N L s" (s: the point's own standard uncertainty,
 * > 0; further columns and '#' lines are ignored). Fits L_inf + c1/N^P1,
 * then with c2/N^P2 and c3/N^P3 added (default 2,4,6); the selected fit is
 * the first that leaves chi^2/dof <= 4 (or the last with a degree of freedom
 * left). Prints every point with its residual to the selected fit, each fit,
 * the selected fit with each point left out, and the result line
 *   L_inf = X +- E
 * with E = sqrt(sigma^2 + model^2) (sigma scaled up by sqrt(chi^2/dof) when
 * the points scatter more than their bars; model: the change in L_inf when
 * the next power is added), at least the jackknife error. --ref X prints X's
 * distance from L_inf in units of E. Exit 2 on bad input, 1 when the first
 * fit is undetermined. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/extrapolate.h"

#define MAXPTS 64

static void print_fit(const char *name, const tr_extrap_fit *f, const int *pw)
{
    if (!f->ok) {
        printf("%s: undetermined (too few points)\n", name);
        return;
    }
    printf("%s: L_inf = %.10f +- %.2e (points' bars; chi2/dof = %.3g/%d, scaled +- %.2e)", name,
           f->coef[0], f->sigma[0], f->chi2, f->dof, f->sigma_scaled);
    for (int j = 1; j < f->nterms; j++)
        printf(", c%d = %.6g +- %.2g (1/N^%d)", j, f->coef[j], f->sigma[j], pw[j - 1]);
    printf("\n");
}

int main(int argc, char **argv)
{
    const char *path = NULL;
    int pw[3] = {2, 4, 6}, npw = 3;
    int have_ref = 0;
    double ref = 0.0;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--powers") && i + 1 < argc) {
            npw = sscanf(argv[++i], "%d,%d,%d", &pw[0], &pw[1], &pw[2]);
            if (npw < 1 || pw[0] <= 0 || (npw > 1 && pw[1] <= 0) || (npw > 2 && pw[2] <= 0)) {
                fprintf(stderr, "ropelength_extrap: --powers P1[,P2[,P3]] (positive)\n");
                return 2;
            }
        } else if (!strcmp(argv[i], "--ref") && i + 1 < argc) {
            ref = atof(argv[++i]);
            have_ref = 1;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            fprintf(stderr, "usage: ropelength_extrap TABLE [--powers P1,P2,P3] [--ref X]\n");
            return 2;
        } else
            path = argv[i];
    }
    if (!path) {
        fprintf(stderr, "usage: ropelength_extrap TABLE [--powers P1,P2,P3] [--ref X]\n");
        return 2;
    }
    FILE *fp = strcmp(path, "-") ? fopen(path, "r") : stdin;
    if (!fp) {
        fprintf(stderr, "ropelength_extrap: cannot open %s\n", path);
        return 2;
    }
    double n[MAXPTS], l[MAXPTS], s[MAXPTS];
    size_t np = 0;
    char line[1024];
    int lineno = 0;
    while (fgets(line, sizeof line, fp)) {
        lineno++;
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (*p == '#' || *p == '\n' || *p == '\0')
            continue;
        if (np == MAXPTS || sscanf(p, "%lf %lf %lf", &n[np], &l[np], &s[np]) != 3 || !(s[np] > 0) ||
            !(n[np] > 0)) {
            fprintf(stderr, "%s:%d: want \"N L s\" with N > 0, s > 0\n", path, lineno);
            return 2;
        }
        np++;
    }
    if (fp != stdin)
        fclose(fp);

    tr_extrap_report r;
    int bad = tr_extrap_report_make(n, l, s, np, pw, npw, &r);
    printf("%zu points; model L_inf + c1/N^%d", np, pw[0]);
    for (int k = 1; k < npw; k++)
        printf(" (+ c%d/N^%d)", k + 1, pw[k]);
    printf("\n");
    if (bad) {
        printf("first fit undetermined\n");
        return 1;
    }
    const tr_extrap_fit *sf = &r.fit[r.selected];
    printf("%8s %16s %10s %12s %8s   (residuals to the selected fit)\n", "N", "L", "s", "L - fit", "/ s");
    for (size_t i = 0; i < np; i++) {
        double fit = sf->coef[0];
        for (int j = 1; j < sf->nterms; j++)
            fit += sf->coef[j] * pow(n[i], -(double)pw[j - 1]);
        printf("%8.0f %16.10f %10.2e %12.3e %8.2f\n", n[i], l[i], s[i], l[i] - fit, (l[i] - fit) / s[i]);
    }
    for (int k = 0; k < npw; k++) {
        char name[32];
        snprintf(name, sizeof name, "fit %d power%s", k + 1, k ? "s" : "");
        if (k < r.nfits)
            print_fit(name, &r.fit[k], pw);
        else
            printf("%s: undetermined (too few points)\n", name);
    }
    printf("selected: fit %d (%s)\n", r.selected + 1,
           r.selected ? "the data ask for more powers: chi2/dof > 4 with fewer" : "chi2/dof <= 4, or no further fit with dof >= 1");
    if (np >= (size_t)sf->nterms + 1) {
        printf("leave-one-out (selected fit): L_inf in [%.10f, %.10f], jackknife +- %.2e; most influential: N = %.0f\n",
               r.loo_min, r.loo_max, r.jackknife, r.loo_worst >= 0 ? n[r.loo_worst] : 0.0);
        for (size_t i = 0; i < np; i++) {
            int use[MAXPTS];
            for (size_t j = 0; j < np; j++)
                use[j] = j != i;
            tr_extrap_fit f;
            if (tr_extrap_fit_powers(n, l, s, use, np, pw, r.selected + 1, &f) == 0)
                printf("  without N = %-6.0f L_inf = %.10f +- %.2e  chi2/dof = %.3g/%d%s\n", n[i], f.coef[0],
                       f.sigma[0], f.chi2, f.dof,
                       sf->birge > 2.0 && f.dof >= 1 && f.birge <= 1.5 ? "  <- the others agree without it: an outlier (unconverged?)" : "");
        }
    } else
        printf("leave-one-out: no point to spare\n");
    if (r.model_checked)
        printf("model error |L_inf(one more power) - L_inf| = %.2e\n", r.model_err);
    else
        printf("model error: not checked (too few points for one more power)\n");
    printf("L_inf = %.10f +- %.2e\n", r.linf, r.total_err);
    if (have_ref)
        printf("reference %.10f: L_inf - ref = %.2e (%.2f error bars)\n", ref, r.linf - ref,
               (r.linf - ref) / r.total_err);
    return 0;
}
