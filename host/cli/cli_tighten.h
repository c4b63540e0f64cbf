/* tighten's command line over the tightening layer (tighten/tighten.h):
 * its options parsed into a struct, and a run of that struct that reads
 * the start, calls tr_tighten, writes the output with its certificate and
 * says what came of it. tighten and batch share them. */
#ifndef TR_CLI_TIGHTEN_H
#define TR_CLI_TIGHTEN_H

#include <stdio.h>

#include "cli/cli.h"
#include "tighten/tighten.h"

/* The command line of one tighten. */
typedef struct tr_cli_tighten {
    tr_tighten_options opt; /* name, device, goals, roads, checkpoint... */
    const char *in, *out;   /* the start file (NULL with --resume), the output */
    int json, quiet;
} tr_cli_tighten;

void tr_cli_tighten_usage(FILE *out);

/* Parses argv as tr_cmd_tighten takes it (argv[0] the command's name)
 * into *t and checks the paths against each other. Returns -1 to go on,
 * else the exit status (0 after --help, 2 for a bad command line, with its
 * message printed). */
int tr_cli_tighten_parse(int argc, char **argv, tr_cli_tighten *t);

/* Reads t->in, tightens it (tr_tighten) and writes t->out, with the
 * command line argv in its comments; with rep the summary is not printed
 * on stdout but returned in *rep. SIGINT/SIGTERM/SIGHUP stop the run
 * (cli_interrupt.h). Returns tighten's exit status. */
int tr_cli_tighten_run(const tr_cli_tighten *t, int argc, char **argv, tr_tighten_report *rep);

/* Writes r's curve to t->out with its certificate and the command line
 * argv in comments (cli_tighten_output.c). */
int tr_cli_tighten_write(const tr_cli_tighten *t, const tr_tighten_result *r, int argc, char **argv, tr_error *err);

/* Prints the summary of the run on stdout: JSON with --json, else lines. */
void tr_cli_tighten_summary(const tr_cli_tighten *t, const tr_tighten_result *r);

/* The report batch reads (cli.h): what the summary prints, as numbers. */
void tr_cli_tighten_report(const tr_tighten_result *r, tr_tighten_report *rep);

#endif
