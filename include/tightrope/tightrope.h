/* Tightrope's public C API: make, read, measure, certify, tighten and
 * analyze knots, links and clasps (ropes of radius 1 tightened to the
 * shortest length; docs/library.md, docs/physics.md).
 *
 * Conventions
 *  - Every public name starts with tightrope_ / TIGHTROPE_ (the library's
 *    internal symbols, tr_*, are not exported).
 *  - Functions that can fail return an int status: TIGHTROPE_OK (0) or a
 *    negative tightrope_status. Their last argument is a tightrope_error
 *    the caller owns (may be NULL), filled on failure with the status and
 *    one line that says what failed first. There is no global state: calls
 *    on different handles may run in different threads at once.
 *  - Curves are opaque handles (tightrope_curve). Coordinates go in and out
 *    as arrays of doubles, x0 y0 z0 x1 y1 z1 ..., all components one after
 *    the other; component k holds vertices [offsets[k], offsets[k+1]). A
 *    closed component does not repeat its first vertex.
 *  - What a function allocates, the matching _free releases. */
#ifndef TIGHTROPE_TIGHTROPE_H
#define TIGHTROPE_TIGHTROPE_H

#include <signal.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(__GNUC__)
#define TIGHTROPE_API __attribute__((visibility("default")))
#else
#define TIGHTROPE_API
#endif

/* ------------------------------------------------------------ errors */

typedef enum tightrope_status {
    TIGHTROPE_OK = 0,
    TIGHTROPE_EIO = -1,          /* a file could not be opened, read, written or renamed */
    TIGHTROPE_EPARSE = -2,       /* malformed input file (the message names FILE:LINE) */
    TIGHTROPE_EINVAL = -3,       /* bad argument or option value */
    TIGHTROPE_ENOMEM = -4,       /* allocation failed */
    TIGHTROPE_EGEOMETRY = -5,    /* the curve cannot be handled (overlap, too coarse, ...) */
    TIGHTROPE_EOPENCL = -6,      /* an OpenCL call failed (the message names the call) */
    TIGHTROPE_ETOPOLOGY = -7,    /* a step would have let strands pass through each other */
    TIGHTROPE_EINTERRUPTED = -8, /* stopped by the caller's cancel flag */
    TIGHTROPE_EUNSUPPORTED = -9  /* the device or build lacks a needed feature */
} tightrope_status;

typedef struct tightrope_error {
    int status;        /* the status the call returned */
    char message[1024]; /* one lower-case line, e.g. "k.vect:7: expected 3 numbers, got 2" */
} tightrope_error;

/* A short static description of a status ("bad argument", ...). */
TIGHTROPE_API const char *tightrope_strerror(int status);

/* The library's version, "MAJOR.MINOR.PATCH" (static). */
TIGHTROPE_API const char *tightrope_version(void);

/* ------------------------------------------------------------ curves */

typedef struct tightrope_curve tightrope_curve;

/* A curve of ncomp components from xyz (3 * offsets[ncomp] doubles);
 * offsets: ncomp + 1 increasing vertex offsets starting at 0; closed: one
 * flag per component (NULL: all closed). Refused (TIGHTROPE_EINVAL): a
 * closed component of fewer than 3 vertices, an open one of fewer than 2,
 * a coordinate that is not finite, consecutive vertices that coincide, a
 * curve whose numbers cannot hold its shape (curve far from the origin
 * for its size). The coordinates are copied. */
TIGHTROPE_API int tightrope_curve_new(int ncomp, const size_t *offsets, const int *closed, const double *xyz,
                                      tightrope_curve **out, tightrope_error *err);
TIGHTROPE_API int tightrope_curve_copy(const tightrope_curve *c, tightrope_curve **out, tightrope_error *err);
TIGHTROPE_API void tightrope_curve_free(tightrope_curve *c);

TIGHTROPE_API size_t tightrope_curve_vertices(const tightrope_curve *c);
TIGHTROPE_API int tightrope_curve_components(const tightrope_curve *c);
/* Offset of component k's first vertex, k in [0, ncomp]; offset(ncomp) = vertices. */
TIGHTROPE_API size_t tightrope_curve_offset(const tightrope_curve *c, int k);
TIGHTROPE_API int tightrope_curve_closed(const tightrope_curve *c, int k);
/* Vertices held by a constraint (a clasp's ends on their planes, plCurve's
 * VECT constraints); such curves come from tightrope_make or a file. */
TIGHTROPE_API int tightrope_curve_constraints(const tightrope_curve *c);
/* The 3 * vertices coordinates, valid while c lives. */
TIGHTROPE_API const double *tightrope_curve_xyz(const tightrope_curve *c);

/* ------------------------------------------------------------ start curves */

/* A start curve for a rope of radius 1, embedded with room to tighten, the
 * same as the command line's `tightrope make`:
 *   "torus P Q"   torus knot T(P,Q) (coprime, |P|,|Q| >= 2), default n 200
 *   "trefoil"     the same as "torus 2 3"
 *   "circle [R]"  round circle of radius R (default 3), default n 64
 *   "hopf"        two circles through each other's centre, n per circle, default 64
 *   "clasp [H]"   two open ropes hooked, ends on the planes z = +-H (default 5), n per rope,
 *                 default 100
 *   "knot NAME"   a prime knot to 12 crossings by its KnotInfo name (3_1 ... 10_165,
 *                 11a_1 ... 12n_888): its minimal diagram or braid closure relaxed
 *                 (the shorter), at thickness 1.25,
 *                 its type checked (docs/knots.md); n in all, default from edges ~0.22
 *   "link NAME"   a prime link to 9 crossings by its LinkInfo name (L2a1, L6a4{1}, ...)
 *   "NAME"        either, by name
 *   "braid WORD"  the closure of a braid word, "braid 1,-2,1,-2" (a knot or a link)
 *   "pd CODE"     a knot's PD code, "pd [[1,5,2,4],[3,1,4,6],[5,3,6,2]]", laid out in the
 *                 plane and lifted at its crossings (a loose start), checked against the
 *                 code's own invariants
 * n: vertices (per component for the generated links); 0: the default.
 * Unknown names are TIGHTROPE_EINVAL (the message names the nearest); a
 * curve made that is not of its name's type, TIGHTROPE_EGEOMETRY. */
TIGHTROPE_API int tightrope_make(const char *spec, size_t n, tightrope_curve **out, tightrope_error *err);

/* ------------------------------------------------------------ files */

/* Reads a curve file: VECT (.vect, with plCurve constraints), TSV (.tsv),
 * KnotPlot "x y z" lists (.txt, .dat, .knot), by extension, then content. */
TIGHTROPE_API int tightrope_read(const char *path, tightrope_curve **out, tightrope_error *err);
/* The same from text in memory; name (e.g. "k.vect") picks the format and names it in messages. */
TIGHTROPE_API int tightrope_parse(const char *name, const char *text, size_t len, tightrope_curve **out,
                                  tightrope_error *err);
/* Writes c in the format path's extension names (.vect, .tsv, .txt), %.17g
 * (exact on reading back), atomically (a temporary file renamed into place);
 * comments (may be NULL) become "# ..." lines at the top. */
TIGHTROPE_API int tightrope_write(const char *path, const tightrope_curve *c, const char *comments,
                                  tightrope_error *err);

/* ------------------------------------------------------------ measure */

/* A strut: the closest points of edges edges[0] > edges[1] (numbered over
 * all components, component 0's first; edge l of a component runs from its
 * vertex l to l + 1), at parameters positions[] in [0, 1] along them. */
typedef struct tightrope_strut {
    size_t edges[2];
    double positions[2];
    double length;
} tightrope_strut;

/* Rawdon's polygonal thickness, as `tightrope measure --json` prints it
 * (the same names; INFINITY or NAN where it prints null). */
typedef struct tightrope_measurement {
    size_t vertices;
    double length, minrad, dcsd, thickness, ropelength;
    double L_p, L_c, L_a;   /* the paper's lengths; NAN unless closed and near-equilateral */
    size_t minrad_vertex;
    int has_shortest_strut; /* dcsd is finite and shortest_strut holds its strut */
    tightrope_strut shortest_strut;
} tightrope_measurement;

/* The whole curve (component -1) or component k alone. */
TIGHTROPE_API int tightrope_measure(const tightrope_curve *c, int component, tightrope_measurement *out,
                                    tightrope_error *err);

/* Every strut no longer than (1 + rel_tol) x the shortest: *struts is
 * allocated (tightrope_free), *n of them. */
TIGHTROPE_API int tightrope_struts(const tightrope_curve *c, double rel_tol, tightrope_strut **struts, size_t *n,
                                   tightrope_error *err);
TIGHTROPE_API void tightrope_free(void *p);

/* The KKT certificate of tightness (docs/physics.md 7.1), as `measure --kkt
 * --json` prints it: the part of the rope's tension no compressive strut
 * or curvature bound holds (0 critical, 1 nothing holds it). */
typedef struct tightrope_kkt {
    double residual, band, radius, tension;
    size_t strut_rows, strut_active, minrad_rows, minrad_active;
    double strut_force_max, optimality;
    int converged; /* the multipliers are optimal (else residual is an upper bound) */
} tightrope_kkt;

/* band <= 0: the default 1e-6. tension and unresolved (3 * vertices each,
 * either may be NULL) get the tension at every vertex and the part of it
 * nothing holds. */
TIGHTROPE_API int tightrope_certify(const tightrope_curve *c, double band, tightrope_kkt *out, double *tension,
                                    double *unresolved, tightrope_error *err);

/* ------------------------------------------------------------ tighten */

typedef struct tightrope_progress {
    size_t n;          /* vertices, all components */
    long steps;        /* accepted steps of this road */
    double ropelength; /* the engine's estimate */
    double residual;   /* the engine's residual */
    double elapsed;    /* seconds */
    double steps_per_s;
    int road, roads;   /* the road under way, 1-based, of how many */
} tightrope_progress;

typedef void (*tightrope_progress_fn)(const tightrope_progress *p, void *user);

/* The command line's `tighten` options; tightrope_tighten_options_init
 * sets every one to its default. */
typedef struct tightrope_tighten_options {
    double time_limit;     /* seconds for the whole call (0: none) */
    long n;                /* first resample every component to n vertices (0: no) */
    long refine_to;        /* tighten, then refine and re-tighten up to this N (0: no; with n 0
                              too, a loose start of N >= 200 a component goes as n N/4,
                              refine_to N, and N is a goal: goal_missed) */
    double residual;       /* stop below this engine residual (default 1e-4) */
    double target;         /* stop at this ropelength estimate (0: off) */
    long steps;            /* accepted steps in all (0: off) */
    const char *device;    /* "reference", "auto", a device spec (NULL: $TIGHTROPE_DEVICE or auto) */
    int newton;            /* 1 the second-order solver at the finest level, 0 only on a tight
                              start (default), -1 never */
    int polish;            /* the polish stage (default 1) */
    int scale;             /* scale the start to thickness 1 first (default 0) */
    long tries, shuffles, seed; /* roads (default 0: chosen, as the command line does without --tries), shuffled roads (0), their seed (1) */
    int kkt;               /* certify: 1 always, 0 never, -1 (default) up to N = 2400 */
    const char *checkpoint; /* a checkpoint file to write (NULL: none) */
    tightrope_progress_fn progress; /* NULL: none */
    double progress_every; /* seconds between progress calls (default 0.25) */
    void *user;            /* passed to progress */
    /* raised by the caller (another thread, a signal handler) to stop the
     * run: it ends at its next step and returns its best state, with
     * interrupted set (NULL: none) */
    volatile sig_atomic_t *cancel;
} tightrope_tighten_options;

TIGHTROPE_API void tightrope_tighten_options_init(tightrope_tighten_options *o);

typedef struct tightrope_tighten_result {
    size_t n;
    double ropelength, thickness, minrad, dcsd, length;
    double residual;     /* the engine's; NAN: no step taken */
    double kkt_residual; /* NAN: not certified */
    int certified;       /* kkt holds the certificate of the curve */
    tightrope_kkt kkt;
    char stopped[32];    /* why the run stopped: "residual", "jammed", "target", "steps", "time-limit",
                            "signal" (the cancel flag), "solved", "refine-failed" (a refined level
                            could not be settled: the curve is the level before it) */
    int interrupted;     /* the cancel flag stopped it */
    int goal_missed;     /* a goal not reached: a target or residual asked for, refine_to's N, or
                            (n and refine_to 0, a loose start of 200 or more vertices a
                            component, no automatic roads) the start's own N */
    double elapsed;      /* seconds */
    long steps, rejected;
    double steps_per_s;
    long tries, road, seed;
    int rescaled;        /* the result was scaled to thickness exactly 1 */
    double shift[3];     /* a start whose box misses the origin is tightened about it: the
                            result is moved by -shift (0 0 0: not moved) */
    char device[128];
    double start_ropelength; /* the start's, as given, measured before the run; NAN: not
                                compared (constrained ends, the vertex model, a start through
                                itself). A result longer than it is a run stopped before it came
                                below it (the command line warns) */
} tightrope_tighten_result;

/* Tightens start as o says (NULL: defaults) into *out (the tight curve,
 * scaled to thickness 1 when no vertex is constrained) and *result. A run
 * stopped by the cancel flag, the time limit or a goal returns
 * TIGHTROPE_OK with its best state (result->interrupted says), except
 * that a cancel before the start is settled has no state yet:
 * TIGHTROPE_EINTERRUPTED. A result that is not the start's knot type
 * (Alexander polynomial, determinant, signature; a link's linking numbers;
 * docs/knots.md) is never returned: TIGHTROPE_EGEOMETRY. */
TIGHTROPE_API int tightrope_tighten(const tightrope_curve *start, const tightrope_tighten_options *o,
                                    tightrope_curve **out, tightrope_tighten_result *result,
                                    tightrope_error *err);

/* ------------------------------------------------------------ analyze */

typedef struct tightrope_analysis tightrope_analysis;

typedef struct tightrope_analyze_options {
    size_t m;          /* averaging block (0: the paper's window, as `analyze`) */
    int no_scale;      /* analyse the coordinates as given (default: scaled to thickness 1) */
    double strut_tol;  /* contacts: struts up to (1 + strut_tol) x the shortest (<= 0: 1e-4) */
} tightrope_analyze_options;

/* The profiles of one component as `tightrope analyze` finds them
 * (docs/physics.md 3-5): curvature and torsion of the inscribed-arc
 * curve, for a closed component also the contacts and the whole summary
 * (symmetry, plateaus, jumps, contact functions). opt NULL: defaults. */
TIGHTROPE_API int tightrope_analyze(const tightrope_curve *c, int component, const tightrope_analyze_options *opt,
                                    tightrope_analysis **out, tightrope_error *err);
TIGHTROPE_API void tightrope_analysis_free(tightrope_analysis *a);

typedef enum tightrope_profile {
    TIGHTROPE_ARC_POSITION = 0,     /* arclength of arc k (its vertex) from the origin */
    TIGHTROPE_ARC_CURVATURE,        /* curvature of arc k */
    TIGHTROPE_ARC_LENGTH,           /* length of arc k */
    TIGHTROPE_JUNCTION_POSITION,    /* arclength of junction k (between arcs k and k+1) */
    TIGHTROPE_JUNCTION_TORSION,     /* torsion at junction k (angle / arclength between the arcs' middles) */
    TIGHTROPE_JUNCTION_ANGLE,       /* signed angle between the osculating planes */
    TIGHTROPE_JUNCTION_ACCUMULATED, /* accumulated torsion, the angles' running sum */
    TIGHTROPE_CONTACTS              /* 3 per contact: arclengths l_i, l_j and the strut's length */
} tightrope_profile;

/* One profile; *n its values (contacts: 3 per contact). Valid while a lives. */
TIGHTROPE_API const double *tightrope_analysis_profile(const tightrope_analysis *a, tightrope_profile which,
                                                       size_t *n);
/* The summary, the JSON object `analyze` writes to summary.json. */
TIGHTROPE_API const char *tightrope_analysis_summary(const tightrope_analysis *a);

#ifdef __cplusplus
}
#endif

#endif
