/* The embedded knot and link tables, notation and linking numbers
 * (topology/knot_table.h, knot_notation.h, linking.h), held against
 * independent facts:
 *  - every table knot's PD code (KnotInfo's pd_notation column) gives, by our
 *    Alexander algebra and Gordon-Litherland signature, the Alexander
 *    polynomial, determinant and signature (sign included) KnotInfo lists in
 *    other columns: 2977 knots to 12 crossings;
 *  - the table's counts: 1 + 249 knots to 10 crossings (Rolfsen), 552 of 11
 *    and 2176 of 12 (KnotInfo's census), 130 prime links to 9 crossings in
 *    354 orientations (LinkInfo);
 *  - names in their spellings, unknown names and the nearest suggested;
 *  - braid words and PD codes that are no notation are refused, each fault
 *    with its own message;
 *  - linking numbers against testlib's independent Gauss sum and closed
 *    forms (the Hopf link: 1; a circle far away: 0). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "curve/generate.h"
#include "testlib.h"
#include "topology/knot_table.h"
#include "topology/linking.h"
#include "topology/signature.h"

static void test_counts_and_pd(const tr_knot_table *t)
{
    int knots = 0, to10 = 0, c11 = 0, c12 = 0, links = 0, unoriented = 0, pd_checked = 0, pd_bad = 0;
    for (int i = 0; i < t->n; i++) {
        const tr_table_entry *e = &t->e[i];
        if (e->is_link) {
            links++;
            unoriented += i == 0 || strcmp(t->e[i - 1].unoriented, e->unoriented) != 0;
            CHECK(e->braid.len > 0 && tr_braid_components(&e->braid, NULL) == e->components);
            continue;
        }
        knots++;
        to10 += e->crossings <= 10;
        c11 += e->crossings == 11;
        c12 += e->crossings == 12;
        if (e->crossings == 0) {
            CHECK(!strcmp(e->name, "0_1") && e->pd.n == 0 && e->braid.len == 0);
            continue;
        }
        CHECK(tr_braid_components(&e->braid, NULL) == 1);
        CHECK(e->pd.n == e->crossings);
        tr_alexander a;
        tr_error err;
        if (tr_alexander_from_pd((const int(*)[4])e->pd.x, e->pd.n, &a, &err) ||
            !tr_alexander_equal(&a, &e->alexander) || a.determinant != e->determinant) {
            if (pd_bad++ < 5)
                tr_test_report(__FILE__, __LINE__, "%s: its PD code's Alexander polynomial is not the table's",
                               e->name);
        }
        int sig;
        if (tr_signature_from_pd((const int(*)[4])e->pd.x, e->pd.n, &sig, &err) || !e->has_signature ||
            sig != e->signature) {
            if (pd_bad++ < 5)
                tr_test_report(__FILE__, __LINE__, "%s: its PD code's signature %d is not the table's %d", e->name, sig,
                               e->signature);
        }
        pd_checked++;
    }
    CHECK(pd_bad == 0);
    CHECK(knots == 2978);
    CHECK(to10 == 250);
    CHECK(c11 == 552);
    CHECK(c12 == 2176);
    CHECK(links == 354);
    CHECK(unoriented == 130);
    printf("%d knots (%d to 10 crossings), %d PD codes checked, %d links (%d unoriented)\n", knots, to10, pd_checked,
           links, unoriented);
}

static void test_names(const tr_knot_table *t)
{
    struct {
        const char *ask;
        int want_link;
        const char *want;
    } cases[] = {
        {"3_1", 0, "3_1"},         {"3.1", 0, "3_1"},           {"K3_1", 0, "3_1"},
        {" 10_165 ", 0, "10_165"}, {"11A1", 0, "11a_1"},        {"12n_888", 0, "12n_888"},
        {"0_1", 0, "0_1"},         {"L2a1", 1, "L2a1{0}"},      {"l2a1{1}", 1, "L2a1{1}"},
        {"2^2_1", 1, "L2a1{0}"},   {"L6a4", -1, "L6a4{0,0}"},   {"3_1", -1, "3_1"},
        {"L2a1", 0, NULL},         {"3_1", 1, NULL},            {"3_l", -1, NULL},
        {"10_166", 0, NULL},       {"", -1, NULL},              {"13n_1", 0, NULL},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const tr_table_entry *e = tr_knot_table_find(t, cases[k].ask, cases[k].want_link);
        if (cases[k].want ? !e || strcmp(e->name, cases[k].want) : e != NULL)
            tr_test_report(__FILE__, __LINE__, "find '%s' gives %s, want %s", cases[k].ask, e ? e->name : "none",
                           cases[k].want ? cases[k].want : "none"), tr_test_failures++;
    }
    char buf[256];
    tr_knot_table_suggest(t, "3_l", 0, buf, sizeof buf);
    CHECK(!strncmp(buf, "3_1", 3));
    tr_knot_table_suggest(t, "10_1655", 0, buf, sizeof buf);
    CHECK(strstr(buf, "10_165") != NULL);
    tr_knot_table_suggest(t, "L2a2", 1, buf, sizeof buf);
    CHECK(strstr(buf, "L2a1") != NULL && strstr(buf, "{") == NULL);
}

static void expect_braid_error(const char *text, const char *what)
{
    tr_braid b;
    tr_error err = {{0}};
    int rc = tr_braid_parse(text, &b, &err);
    if (rc != TR_EINVAL || !strstr(err.msg, what)) {
        tr_test_report(__FILE__, __LINE__, "braid '%s': status %d, message '%s', want '%s'", text, rc, err.msg, what);
    }
    tr_braid_free(&b);
}

static void expect_pd_error(const char *text, const char *what)
{
    tr_pd p;
    tr_error err = {{0}};
    int rc = tr_pd_parse(text, &p, &err);
    if (rc != TR_EINVAL || !strstr(err.msg, what)) {
        tr_test_report(__FILE__, __LINE__, "PD '%s': status %d, message '%s', want '%s'", text, rc, err.msg, what);
    }
    tr_pd_free(&p);
}

static void test_notation(void)
{
    tr_braid b;
    tr_error err;
    CHECK_OK(tr_braid_parse("[1, 1, -2]", &b, &err));
    CHECK(b.strands == 3 && b.len == 3 && b.word[2] == -2);
    /* (1 2) after sigma_1 twice is the identity: the third strand alone */
    CHECK(tr_braid_components(&b, NULL) == 2);
    tr_braid_free(&b);
    CHECK_OK(tr_braid_parse("1 -2 1 -2", &b, &err));
    CHECK(tr_braid_components(&b, NULL) == 1); /* the figure eight */
    tr_braid_free(&b);
    CHECK_OK(tr_braid_parse("1,3", &b, &err));
    int comp[4];
    CHECK(tr_braid_components(&b, comp) == 2 && comp[0] == comp[1] && comp[2] == comp[3] && comp[0] != comp[2]);
    tr_braid_free(&b);
    expect_braid_error("", "empty");
    expect_braid_error(" [ ] ", "empty");
    expect_braid_error("1,0,1", "generator 2 is 0");
    expect_braid_error("1,a", "unexpected 'a'");
    expect_braid_error("1,x", "unexpected 'x'");
    expect_braid_error("X[1,1,1]", "unexpected 'X'");
    expect_braid_error("1,-", "not followed by a number");
    expect_braid_error("1,2,99", "strands");

    tr_pd p;
    CHECK_OK(tr_pd_parse("[[1,5,2,4],[3,1,4,6],[5,3,6,2]]", &p, &err));
    CHECK(p.n == 3 && p.x[2][3] == 2);
    tr_pd_free(&p);
    CHECK_OK(tr_pd_parse("X[1,5,2,4] X[3,1,4,6] X[5,3,6,2]", &p, &err));
    CHECK(p.n == 3);
    tr_pd_free(&p);
    expect_pd_error("", "empty");
    expect_pd_error("[[1,5,2,4],[3,1,4,6],[5,3,6]]", "not 4 per crossing");
    expect_pd_error("[[1,5,2,4],[3,1,4,6],[5,3,6,7]]", "outside 1..6");
    expect_pd_error("[[1,5,2,4],[3,1,4,6],[5,3,5,2]]", "appears 3 times");
    expect_pd_error("[[1,5,3,4],[2,1,4,6],[5,3,6,2]]", "under strand runs 1 -> 3");
    expect_pd_error("[[1,5,2,3],[3,1,4,6],[5,4,6,2]]", "not consecutive");
    expect_pd_error("[[1,5,2,4];(3,1,4,6)|", "unexpected '|'");
    expect_pd_error("X[1,5,2,4] X3,1,4,6", "unexpected 'X'");
}

static void test_linking(void)
{
    tr_curve h;
    tr_error err;
    REQUIRE_OK(tr_make_hopf(&h, 64, &err));
    int lk[4];
    CHECK_OK(tr_linking_numbers(&h, lk, &err));
    double ref = tr_test_linking_number(h.x, 64, h.x + 3 * 64, 64);
    CHECK(abs(lk[1]) == 1 && lk[1] == lk[2] && lk[0] == 0 && lk[1] == (int)lround(ref));
    /* the second circle moved far away: unlinked */
    for (size_t i = 64; i < 128; i++)
        h.x[3 * i] += 100;
    CHECK_OK(tr_linking_numbers(&h, lk, &err));
    CHECK(lk[1] == 0);
    /* an open rope has no linking number */
    h.closed[1] = 0;
    CHECK(tr_linking_numbers(&h, lk, &err) == TR_EINVAL);
    tr_curve_free(&h);
}

int main(void)
{
    tr_knot_table t;
    tr_error err;
    if (tr_knot_table_load(&t, &err)) {
        tr_test_report(__FILE__, __LINE__, "the table does not load: %s", err.msg);
        return 1;
    }
    test_counts_and_pd(&t);
    test_names(&t);
    test_notation();
    test_linking();
    tr_knot_table_free(&t);
    return tr_test_finish("test_knot_table");
}
