/* The tube pictures as gnuplot draws them: the surface of tube_picture.h
 * as grid data (one block per ring, consecutive rings making the quads
 * pm3d fills) and a script that draws it shaded (pm3d lighting, hidden
 * surfaces by depth-sorting the quads: pm3d depthorder) from each camera
 * of tube_views.h into tube_front.png, tube_top.png and tube_side.png, and
 * the struts inside the translucent tube into tube_struts.png. The
 * library writes the files; running gnuplot is the command's
 * (cli_gnuplot.h). */
#ifndef TR_TUBE_SCRIPT_H
#define TR_TUBE_SCRIPT_H

#include "analysis/plot_output.h"
#include "analysis/tube_picture.h"
#include "analysis/tube_views.h"
#include "util/error.h"

/* The pictures' size in pixels (square): the default, and the range
 * tr_tube_script_write accepts. */
#define TR_TUBE_PX_DEFAULT 720
#define TR_TUBE_PX_MIN 200
#define TR_TUBE_PX_MAX 4000

/* The pictures' names: one per camera of tube_views.h, in its order, then
 * the struts' picture (front camera). */
#define TR_TUBE_PNGS (TR_NVIEWS + 1)
extern const char *const tr_tube_png_names[TR_TUBE_PNGS];

/* The surface as gnuplot grid data: rings + 1 blocks (the first ring again
 * at the end, closing the tube) of sides + 1 rows (the first vertex again,
 * closing the ring), "x y z colour", blocks separated by a blank line;
 * comment lines start with '#'. The colour is kappa in [0, 1) for plain
 * rope, 1.5 on a kappa = 1 stretch, 2.5 at a contact. A malloc'd string in
 * *out, or TR_ENOMEM. */
int tr_tube_data_text(const tr_tube_picture *tp, char **out);

/* The struts' picture's data: the core as a thin tube, then each strut of
 * tp as a thin rod; each a surface of its own (blocks as above, surfaces
 * separated by two blank lines). Colour as above, 3.5 for a strut. A
 * malloc'd string in *out, or TR_ENOMEM. */
int tr_tube_struts_text(const tr_tube_picture *tp, char **out);

/* The script that draws DATA and STRUTS (file names relative to the
 * directory gnuplot runs in) into outputs[v] from camera v, and the struts'
 * picture into outputs[TR_NVIEWS]; title: the pictures' first title line
 * (one line, may be NULL); px: their width and height in pixels. A
 * malloc'd string in *out, or TR_ENOMEM. */
int tr_tube_script_text(const tr_tube_picture *tp, const tr_tube_views *views, const char *data,
                        const char *struts, const char *const outputs[TR_TUBE_PNGS], const char *title,
                        int px, char **out);

/* Writes DIR/tube.dat, DIR/struts.dat and DIR/tube.gp (atomically) and reserves the
 * pictures' temporaries (plot_output.h: tr_plot_commit once gnuplot has
 * run DIR/tube.gp in DIR, tr_plot_discard if it failed). TR_EINVAL for px
 * outside [TR_TUBE_PX_MIN, TR_TUBE_PX_MAX]. On failure nothing is left
 * reserved. */
int tr_tube_script_write(const char *dir, const tr_tube_picture *tp, const tr_tube_views *views,
                         const char *title, int px, tr_plot_script *ps, tr_error *err);

#endif
