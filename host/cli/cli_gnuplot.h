/* This file contains running gnuplot for the commands that draw plots: the
 * library writes the scripts (analysis/analysis_plots.h) and starts no
 * process; the command line finds gnuplot and runs it. */
#ifndef TIGHTROPE_CLI_GNUPLOT_H
#define TIGHTROPE_CLI_GNUPLOT_H

#include "analysis/plot_output.h"
#include "util/error.h"

/* 1 if a `gnuplot` executable is on PATH. */
int tr_gnuplot_available(void);

/* Runs `gnuplot SCRIPT` in DIR, its output to DIR/LOG, and waits for it.
 * TR_EIO if it cannot be started or fails (the message quotes the log's
 * last line); TR_EINTERRUPTED, with gnuplot stopped and reaped, once
 * tr_cli_interrupted() says a signal came (cli_interrupt.h). */
int tr_gnuplot_run(const char *dir, const char *script, const char *log, tr_error *err);

/* Runs DIR/SCRIPT as tr_gnuplot_run and then puts the pictures ps drew into
 * in place (tr_plot_commit), or throws them away if gnuplot failed
 * (tr_plot_discard): what every plotting command does once its script is
 * written. */
int tr_gnuplot_draw(const char *dir, const char *script, const char *log, tr_plot_script *ps, tr_error *err);

#endif
