/* Plots of the shape analysis, drawn by gnuplot from the CSV files the
 * command has written into the output directory: curvature and torsion over
 * the representative interval [0, L/6), the plateau region zoomed, the
 * accumulated torsion, the contact-function image and sigma-^9 against the
 * diagonal. */
#ifndef TR_ANALYSIS_PLOTS_H
#define TR_ANALYSIS_PLOTS_H

#include "util/error.h"
#include "analysis/portrait.h"

/* 1 if a `gnuplot` executable is on PATH. */
int tr_gnuplot_available(void);

/* Writes DIR/plots.gp and runs gnuplot in DIR (its output goes to
 * DIR/gnuplot.log). TR_EUNSUPPORTED if gnuplot is missing, TR_EIO if it
 * fails. The CSV files must already be in DIR. */
int tr_analysis_plots(const char *dir, const tr_analysis *a, tr_error *err);

#endif
