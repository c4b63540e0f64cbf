/* Plots of the shape analysis: the gnuplot script that draws them from the
 * CSV files the command has written into the output directory (curvature
 * and torsion over the representative interval [0, L/6), the plateau region
 * zoomed, the accumulated torsion, the contact-function image and sigma-^9
 * against the diagonal). Running gnuplot is the command's (cli_gnuplot.h). */
#ifndef TR_ANALYSIS_PLOTS_H
#define TR_ANALYSIS_PLOTS_H

#include "util/error.h"
#include "analysis/portrait.h"

/* The plots a script draws: each to a temporary name beside its own, which
 * tr_analysis_plots_commit renames once gnuplot is done, so an interrupted
 * or failed run leaves no half-drawn PNG under a plot's name. */
#define TR_PLOTS_MAX 5
typedef struct tr_plot_script {
    size_t n;                      /* temporaries reserved, one per plot drawn */
    char tmp[TR_PLOTS_MAX][4096];  /* their paths (DIR/NAME.tmpXXXXXX, created empty) */
} tr_plot_script;

/* Writes DIR/plots.gp, to be run by gnuplot in DIR (the caller runs it: the
 * library starts no process), and reserves the temporaries it draws into.
 * The CSV files must already be in DIR. On failure nothing is left
 * reserved. */
int tr_analysis_plots_script(const char *dir, const tr_analysis *a, tr_plot_script *ps, tr_error *err);

/* After gnuplot has run the script: renames each plot to its name. TR_EIO
 * if one cannot be; the temporaries are gone either way. */
int tr_analysis_plots_commit(const char *dir, tr_plot_script *ps, tr_error *err);

/* Removes the temporaries of a script that was not run or failed. */
void tr_analysis_plots_discard(tr_plot_script *ps);

#endif
