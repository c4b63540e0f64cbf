/* Curve files: exact round trips in all three formats (constraints and
 * several components included), every shipped data file read with the vertex
 * count its header announces, plCurve's constraint syntax, atomic writes, and
 * the corpus of broken files in tests/bad/ with the FILE:LINE of each error. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "curve/curve_io.h"
#include "testlib.h"

static int same_curve(const tr_curve *a, const tr_curve *b)
{
    if (a->nv != b->nv || a->ncomp != b->ncomp || a->ncst != b->ncst)
        return 0;
    if (memcmp(a->x, b->x, 3 * a->nv * sizeof *a->x))
        return 0;
    for (int k = 0; k <= a->ncomp; k++)
        if (a->start[k] != b->start[k])
            return 0;
    for (int k = 0; k < a->ncomp; k++)
        if (a->closed[k] != b->closed[k])
            return 0;
    for (int k = 0; k < a->ncst; k++) {
        const tr_constraint *p = &a->cst[k], *q = &b->cst[k];
        if (p->kind != q->kind || p->id != q->id || memcmp(p->p, q->p, sizeof p->p) ||
            memcmp(p->u, q->u, sizeof p->u) || memcmp(&p->d, &q->d, sizeof p->d))
            return 0;
    }
    for (size_t i = 0; a->ncst && i < a->nv; i++)
        if (a->vcst[i] != b->vcst[i])
            return 0;
    return 1;
}

static char *slurp(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long m = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)m + 1);
    if (buf && fread(buf, 1, (size_t)m, f) != (size_t)m) {
        free(buf);
        buf = NULL;
    }
    fclose(f);
    if (buf)
        buf[m] = '\0';
    *n = (size_t)m;
    return buf;
}

/* Coordinates that stress %.17g: thirds, tiny and huge magnitudes, signed
 * zero, subnormals, integers. */
static double awkward(size_t i)
{
    static const double v[] = {1.0 / 3.0, -2.0 / 7.0, 1e-300, -4.9406564584124654e-324, 6.02214076e23,
                               0.1, -0.0, 12345678901234567.0, 2.5, -1.7976931348623157e308 / 4};
    return v[i % 10] + (double)i;
}

static void round_trip(const char *path, tr_format fmt, const tr_curve *c, const char *comments)
{
    tr_error err = {{0}};
    tr_curve d;
    int rc = tr_curve_write(path, fmt, c, comments, &err);
    CHECK(rc == TR_OK);
    if (rc) {
        fprintf(stderr, "write %s: %s\n", path, err.msg);
        return;
    }
    rc = tr_curve_read(path, TR_FORMAT_AUTO, &d, &err);
    CHECK(rc == TR_OK);
    if (rc) {
        fprintf(stderr, "read %s: %s\n", path, err.msg);
        return;
    }
    CHECK(same_curve(c, &d));
    /* and a second generation is byte-identical to the first */
    size_t n1, n2;
    char *t1 = slurp(path, &n1);
    CHECK_OK(tr_curve_write(path, fmt, &d, comments, &err));
    char *t2 = slurp(path, &n2);
    CHECK(t1 && t2 && n1 == n2 && !memcmp(t1, t2, n1));
    free(t1);
    free(t2);
    tr_curve_free(&d);
}

static void test_round_trips(void)
{
    tr_error err;
    char path[1024];
    /* a closed 5-gon, an open 4-rope and a closed triangle, awkward numbers */
    size_t nv[3] = {5, 4, 3};
    unsigned char closed[3] = {1, 0, 1};
    tr_curve c;
    CHECK_OK(tr_curve_alloc(&c, 3, nv, closed, &err));
    for (size_t i = 0; i < 3 * c.nv; i++)
        c.x[i] = awkward(i);
    snprintf(path, sizeof path, "%s/io_rt.vect", TR_BINARY_DIR);
    round_trip(path, TR_FORMAT_AUTO, &c, "made by test_curve_io\nsecond line\n\nafter a blank");

    /* constraints of every kind, ids as a file might number them */
    tr_constraint plane = {.kind = TR_CST_PLANE, .id = 7, .u = {0, 0, -1}, .d = 15.013};
    tr_constraint line = {.kind = TR_CST_LINE, .id = 2, .p = {1.0 / 3, 2, 3}, .u = {0.6, 0.8, 0}};
    tr_constraint fixed = {.kind = TR_CST_FIXED, .id = 3, .p = {awkward(5), awkward(6), awkward(7)}};
    tr_constraint unused = {.kind = TR_CST_PLANE, .id = 9, .u = {1, 0, 0}, .d = -2};
    CHECK(tr_curve_add_constraint(&c, &plane, &err) == 0);
    CHECK(tr_curve_add_constraint(&c, &line, &err) == 1);
    CHECK(tr_curve_add_constraint(&c, &fixed, &err) == 2);
    CHECK(tr_curve_add_constraint(&c, &unused, &err) == 3);
    c.vcst[5] = 0;
    c.vcst[8] = 0;
    c.vcst[0] = 1;
    c.vcst[11] = 2;
    /* a vertex lies on its constraint (the reader refuses one far off it) */
    for (size_t i = 0; i < c.nv; i++)
        if (c.vcst[i] >= 0)
            tr_constraint_project(&c.cst[c.vcst[i]], c.x + 3 * i);
    round_trip(path, TR_FORMAT_VECT, &c, NULL);

    /* plCurve's spelling on disk */
    size_t n;
    char *text = slurp(path, &n);
    CHECK(text && strstr(text, "# Constraint 7 Plane 0 0 -1 15.013\n"));
    CHECK(text && strstr(text, "# Constraint 2 Line 0.59999999999999998 0.80000000000000004 0 "));
    CHECK(text && strstr(text, "# Cst: 7\n"));
    free(text);

    /* writers refuse what their format cannot say */
    snprintf(path, sizeof path, "%s/io_rt.tsv", TR_BINARY_DIR);
    CHECK(tr_curve_write(path, TR_FORMAT_AUTO, &c, NULL, &err) == TR_EINVAL);
    tr_curve_free(&c);

    /* TSV: several closed components; KnotPlot: one */
    size_t nv2[3] = {3, 7, 4};
    CHECK_OK(tr_curve_alloc(&c, 3, nv2, NULL, &err));
    for (size_t i = 0; i < 3 * c.nv; i++)
        c.x[i] = awkward(3 * i + 1);
    round_trip(path, TR_FORMAT_AUTO, &c, "tsv comment");
    snprintf(path, sizeof path, "%s/io_rt.txt", TR_BINARY_DIR);
    CHECK(tr_curve_write(path, TR_FORMAT_AUTO, &c, NULL, &err) == TR_EINVAL);
    snprintf(path, sizeof path, "%s/io_rt.vect", TR_BINARY_DIR);
    round_trip(path, TR_FORMAT_AUTO, &c, NULL);
    tr_curve_free(&c);
    size_t nv3 = 6;
    CHECK_OK(tr_curve_alloc(&c, 1, &nv3, NULL, &err));
    for (size_t i = 0; i < 3 * c.nv; i++)
        c.x[i] = awkward(7 * i);
    snprintf(path, sizeof path, "%s/io_rt.txt", TR_BINARY_DIR);
    round_trip(path, TR_FORMAT_AUTO, &c, "knotplot comment");
    /* an unknown extension is told by content */
    snprintf(path, sizeof path, "%s/io_rt.curve", TR_BINARY_DIR);
    round_trip(path, TR_FORMAT_VECT, &c, NULL);
    round_trip(path, TR_FORMAT_TSV, &c, NULL);
    tr_curve_free(&c);
}

/* The vertex count the header announces, read independently of the library. */
static long header_vertices(const char *text)
{
    long ncomp, nverts, ncol;
    const char *p = strstr(text, "VECT");
    if (!p || sscanf(p + 4, "%ld %ld %ld", &ncomp, &nverts, &ncol) != 3)
        return -1;
    return nverts;
}

/* Every VECT file of a data folder reads: ../shared/data's whole corpus
 * when it is there, else the repository's few of it (tests/data). */
static void test_data_dir(const char *rel, int want_min_files, int want_min_here)
{
    char dir[1024], path[2048];
    if (tr_have_shared(rel))
        tr_shared_path(dir, sizeof dir, rel);
    else {
        char here[64];
        snprintf(here, sizeof here, "tests/%s", rel);
        tr_source_path(dir, sizeof dir, here);
        want_min_files = want_min_here;
    }
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "cannot open %s\n", dir);
        CHECK(d != NULL);
        return;
    }
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t m = strlen(e->d_name);
        if (m < 5 || strcmp(e->d_name + m - 5, ".vect"))
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        tr_error err = {{0}};
        tr_curve c;
        int rc = tr_curve_read(path, TR_FORMAT_AUTO, &c, &err);
        if (rc) {
            fprintf(stderr, "%s\n", err.msg);
            CHECK(rc == TR_OK);
            continue;
        }
        size_t n;
        char *text = slurp(path, &n);
        CHECK(text && header_vertices(text) == (long)c.nv);
        free(text);
        CHECK(tr_curve_length(&c) > 0);
        files++;
        tr_curve_free(&c);
    }
    closedir(d);
    printf("%s: %d vect files read\n", rel, files);
    CHECK(files >= want_min_files);
}

static void test_clasp_file(void)
{
    char path[1024];
    tr_error err;
    tr_curve c;
    tr_source_path(path, sizeof path, "tests/data/knotplot/simple_clasp.vect");
    REQUIRE_OK(tr_curve_read(path, TR_FORMAT_AUTO, &c, &err));
    if (c.nv == 0)
        return;
    CHECK(c.ncomp == 2 && tr_comp_nv(&c, 0) == 33 && tr_comp_nv(&c, 1) == 38);
    CHECK(!c.closed[0] && !c.closed[1]);
    CHECK(c.ncst == 4);
    /* ends of both ropes constrained, nothing else */
    size_t ends[4] = {0, 32, 33, 70};
    int constrained = 0;
    for (size_t i = 0; i < c.nv; i++)
        constrained += c.vcst[i] >= 0;
    CHECK(constrained == 4);
    for (int j = 0; j < 4; j++) {
        int k = c.vcst[ends[j]];
        CHECK(k == j);
        if (k < 0)
            continue;
        CHECK(c.cst[k].kind == TR_CST_PLANE && c.cst[k].id == j + 1);
        CHECK_NEAR(sqrt(c.cst[k].u[0] * c.cst[k].u[0] + c.cst[k].u[1] * c.cst[k].u[1] +
                        c.cst[k].u[2] * c.cst[k].u[2]),
                   1.0, 1e-15);
        /* the file prints the planes with %g: satisfied to its 6 digits */
        CHECK(tr_constraint_violation(&c.cst[k], c.x + 3 * ends[j]) < 1e-3);
    }
    CHECK_NEAR(c.cst[3].u[2], -1.0, 0);
    CHECK_NEAR(c.cst[3].d, 15.013, 0);
    tr_curve_free(&c);
}

static void test_parse_memory(void)
{
    tr_error err;
    tr_curve c;
    /* plCurve Line (direction, then point) and Fixed, CRLF line ends, a
     * prose comment starting with "Constraint", comments everywhere */
    const char *t = "# leading comment\r\nVECT # magic\r\n1 4 1\r\n4\r\n1\r\n"
                    "# Constraint violation was 0.001 here\r\n"
                    "# Constraint 1 Line 0 0 2 5 6 7\r\n# Constraint 2 Fixed 1 2 3\r\n"
                    "5 6 0 # Cst: 1\r\n1 2 3 # Cst: 2\r\n# between\r\n4 4 4\r\n5 6 9 # Cst: 1\r\n0.5 0.5 0.5 1\r\n";
    int rc = tr_curve_parse("mem.vect", t, strlen(t), TR_FORMAT_AUTO, &c, &err);
    CHECK(rc == TR_OK);
    if (rc) {
        fprintf(stderr, "%s\n", err.msg);
        return;
    }
    CHECK(c.nv == 4 && !c.closed[0] && c.ncst == 2);
    CHECK(c.cst[0].kind == TR_CST_LINE && c.cst[0].u[2] == 1.0 && c.cst[0].p[0] == 5 && c.cst[0].p[2] == 7);
    CHECK(c.cst[1].kind == TR_CST_FIXED && c.cst[1].p[1] == 2);
    CHECK(c.vcst[0] == 0 && c.vcst[1] == 1 && c.vcst[2] == -1 && c.vcst[3] == 0);
    CHECK(tr_constraint_violation(&c.cst[0], c.x + 9) == 0.0);
    tr_curve_free(&c);

    /* numbers may share lines or spread over several (Geomview is token based) */
    t = "VECT 1 3 0 -3 0 0 0 0\n1 0\n0 0 1 0";
    CHECK_OK(tr_curve_parse("mem.vect", t, strlen(t), TR_FORMAT_VECT, &c, &err));
    CHECK(c.nv == 3 && c.closed[0] && c.x[3] == 1.0 && c.x[7] == 1.0);
    tr_curve_free(&c);

    /* TSV: tabs or spaces, blank lines (several) between components, no final newline */
    t = "0\t0\t0\n1 0 0\n0  1 0\n\n\n  \n2 2 2\n3 2 2\n2 3 2";
    CHECK_OK(tr_curve_parse("mem.tsv", t, strlen(t), TR_FORMAT_AUTO, &c, &err));
    CHECK(c.ncomp == 2 && c.nv == 6 && c.closed[0] && c.closed[1]);
    tr_curve_free(&c);
    /* the same text as a KnotPlot list is one component */
    CHECK_OK(tr_curve_parse("mem.txt", t, strlen(t), TR_FORMAT_AUTO, &c, &err));
    CHECK(c.ncomp == 1 && c.nv == 6);
    tr_curve_free(&c);

    /* a NULL buffer of length 0 is an empty file, not a crash */
    CHECK(tr_curve_parse("nothing.vect", NULL, 0, TR_FORMAT_AUTO, &c, &err) == TR_EPARSE);
    CHECK(tr_curve_read("/nonexistent/dir/x.vect", TR_FORMAT_AUTO, &c, &err) == TR_EIO);
}

typedef struct bad_case {
    const char *file;
    int line;
} bad_case;

static void test_bad_corpus(void)
{
    static const bad_case cases[] = {
        {"empty.vect", 1},           {"only_comments.tsv", 1},       {"bad_header.vect", 1},
        {"missing_counts.vect", 2},  {"count_mismatch.vect", 3},     {"colour_mismatch.vect", 4},
        {"header_too_big.vect", 2},  {"nonnumeric.vect", 7},         {"nan.vect", 6},
        {"inf.tsv", 3},              {"overflow.tsv", 3},            {"closed_two.vect", 4},
        {"open_one.vect", 3},        {"closed_two.tsv", 5},          {"coincident.vect", 7},
        {"repeats_first.tsv", 5},    {"unknown_constraint.vect", 5}, {"undefined_constraint.vect", 8},
        {"constraint_numbers.vect", 5}, {"trailing.vect", 8},        {"truncated.vect", 7},
        {"fields.tsv", 2},           {"fields.txt", 2},              {"binary.vect", 6},
        {"vect_missing_number.vect", 8}, {"vect_extra_number.vect", 8}, {"hex.tsv", 1},
        {"hex.vect", 6},             {"far_origin.vect", 7},         {"subnormal.vect", 7},
        {"off_constraint.vect", 7},
    };
    int seen = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char rel[256], path[1024], want[1100];
        snprintf(rel, sizeof rel, "tests/bad/%s", cases[i].file);
        tr_source_path(path, sizeof path, rel);
        snprintf(want, sizeof want, "%s:%d: ", path, cases[i].line);
        tr_error err = {{0}};
        tr_curve c;
        int rc = tr_curve_read(path, TR_FORMAT_AUTO, &c, &err);
        int ok = rc == TR_EPARSE && !strncmp(err.msg, want, strlen(want)) && !strchr(err.msg, '\n') &&
                 strlen(err.msg) > strlen(want);
        if (!ok)
            fprintf(stderr, "%s: rc %d, message '%s', want prefix '%s'\n", cases[i].file, rc, err.msg, want);
        else
            printf("  %s\n", err.msg + strlen(path) + 1);
        CHECK(ok);
        CHECK(c.nv == 0 && c.x == NULL);
        seen++;
    }
    /* every file in tests/bad has a case above */
    char dir[1024];
    tr_source_path(dir, sizeof dir, "tests/bad");
    DIR *d = opendir(dir);
    int files = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        files += e->d_name[0] != '.';
    if (d)
        closedir(d);
    CHECK(files == seen);
}

static void test_atomic_write(void)
{
    tr_error err;
    char dir[1024], target[1100], inner[1200];
    snprintf(dir, sizeof dir, "%s/io_atomic", TR_BINARY_DIR);
    mkdir(dir, 0777);
    /* the target name is taken by a non-empty directory: rename must fail
     * after the temporary file was written, and the temporary must go */
    snprintf(target, sizeof target, "%s/out.vect", dir);
    mkdir(target, 0777);
    snprintf(inner, sizeof inner, "%s/keep", target);
    FILE *f = fopen(inner, "w");
    if (f)
        fclose(f);
    CHECK(tr_write_file_atomic(target, "VECT\n", 5, &err) == TR_EIO);
    CHECK(strstr(err.msg, target) != NULL);
    DIR *d = opendir(dir);
    int entries = 0;
    struct dirent *e;
    while (d && (e = readdir(d)))
        if (e->d_name[0] != '.') {
            entries++;
            CHECK(!strcmp(e->d_name, "out.vect"));
        }
    if (d)
        closedir(d);
    CHECK(entries == 1);
    CHECK(tr_write_file_atomic("/nonexistent/dir/x.vect", "x", 1, &err) == TR_EIO);

    /* a successful write replaces the old content whole */
    snprintf(target, sizeof target, "%s/plain.txt", dir);
    CHECK_OK(tr_write_file_atomic(target, "first version, longer\n", 22, &err));
    CHECK_OK(tr_write_file_atomic(target, "second\n", 7, &err));
    size_t n;
    char *t = slurp(target, &n);
    CHECK(t && n == 7 && !memcmp(t, "second\n", 7));
    free(t);
    unlink(target);
    unlink(inner);
    rmdir(snprintf(inner, sizeof inner, "%s/out.vect", dir) > 0 ? inner : dir);
    rmdir(dir);
}

int main(void)
{
    test_round_trips();
    test_parse_memory();
    test_data_dir("data/knotplot", 200, 3);
    test_data_dir("data/tightknot", 249, 2);
    test_clasp_file();
    test_bad_corpus();
    test_atomic_write();
    return tr_test_finish("test_curve_io");
}
