/* Plots of the clasp's anatomy, the paper's Fig. 3 and Fig. 4 (Przybyl &
 * Pieranski, section 3): the curvature of half a rope against arclength from
 * its free end, both halves overlaid, the pieces marked; and the regions of
 * D1 and of D2 enlarged, each arc's curvature drawn over its cell. Drawn by gnuplot
 * from the rope's curvature.csv; running gnuplot is the command's
 * (cli_gnuplot.h). */
#ifndef TR_CLASP_PLOTS_H
#define TR_CLASP_PLOTS_H

#include "analysis/clasp_anatomy.h"
#include "analysis/plot_output.h"
#include "util/error.h"

/* The PNGs it draws, in DIR. */
#define TR_CLASP_PLOT_CURVATURE "clasp_curvature.png"
#define TR_CLASP_PLOT_D1 "clasp_d1.png"
#define TR_CLASP_PLOT_D2 "clasp_d2.png"

/* Writes DIR/plots.gp for a rope whose anatomy was found (title: a short
 * name for the rope), to be run by gnuplot in DIR, and reserves the
 * temporaries it draws into (tr_plot_commit once gnuplot is done,
 * tr_plot_discard if it fails). DIR/curvature.csv must be there. On failure
 * nothing is left reserved. */
int tr_clasp_plots_script(const char *dir, const tr_clasp_rope *r, const char *title, tr_plot_script *ps,
                          tr_error *err);

#endif
