/* Plots of the shape analysis: the gnuplot script that draws them from the
 * CSV files the command has written into the output directory (curvature
 * and torsion over the representative interval [0, L/6), the plateau region
 * zoomed, the accumulated torsion, the contact-function image and sigma-^9
 * against the diagonal). Running gnuplot is the command's (cli_gnuplot.h). */
#ifndef TR_ANALYSIS_PLOTS_H
#define TR_ANALYSIS_PLOTS_H

#include "util/error.h"
#include "analysis/plot_output.h"
#include "analysis/portrait.h"

/* Writes DIR/plots.gp, to be run by gnuplot in DIR (the caller runs it: the
 * library starts no process), and reserves the temporaries it draws into
 * (tr_plot_commit once gnuplot is done, tr_plot_discard if it fails). The
 * CSV files must already be in DIR. On failure nothing is left reserved. */
int tr_analysis_plots_script(const char *dir, const tr_analysis *a, tr_plot_script *ps, tr_error *err);

#endif
