/* PNGs that gnuplot draws under temporary names: reserved before the script
 * is written (the script names them), renamed over their final names only
 * once gnuplot is done, so an interrupted or failed run leaves no half-drawn
 * PNG under a plot's name. Shared by every script the analysis writes
 * (analysis_plots.h, tube_script.h). */
#ifndef TR_PLOT_OUTPUT_H
#define TR_PLOT_OUTPUT_H

#include <stddef.h>

#include "util/error.h"

#define TR_PLOTS_MAX 8
typedef struct tr_plot_script {
    size_t n;                      /* temporaries reserved, one per plot drawn */
    char tmp[TR_PLOTS_MAX][4096];  /* their paths (DIR/NAME.tmpXXXXXX, created empty) */
    const char *name[TR_PLOTS_MAX];/* the final names in DIR (static strings) */
} tr_plot_script;

/* Reserves one fresh temporary beside DIR/names[i] for each of the n names
 * (n <= TR_PLOTS_MAX), created empty with O_EXCL on DIR's file system, so the
 * final rename is atomic. TR_EIO if one cannot be made; then none is left. */
int tr_plot_reserve(const char *dir, const char *const *names, size_t n, tr_plot_script *ps,
                    tr_error *err);

/* The temporary of plot i as the script names it, relative to DIR. */
const char *tr_plot_tmp_base(const tr_plot_script *ps, const char *dir, size_t i);

/* After gnuplot has run the script: renames each plot to its name. TR_EIO
 * if one cannot be; the temporaries are gone either way. */
int tr_plot_commit(const char *dir, tr_plot_script *ps, tr_error *err);

/* Removes the temporaries of a script that was not run or failed. */
void tr_plot_discard(tr_plot_script *ps);

#endif
