/* Subcommands of the tightrope program. Each returns the process exit status:
 * 0 success; 2 bad input, bad usage, or an output file that cannot be
 * written (the user can fix all three); 1 anything else: a run that did not
 * reach its goal, a device failure, out of memory. The command layer is the
 * only place that prints errors. */
#ifndef TR_CLI_H
#define TR_CLI_H

int tr_cmd_measure(int argc, char **argv);
int tr_cmd_make(int argc, char **argv);
int tr_cmd_tighten(int argc, char **argv);
int tr_cmd_devices(int argc, char **argv);
int tr_cmd_bench(int argc, char **argv);
int tr_cmd_analyze(int argc, char **argv);
int tr_cmd_batch(int argc, char **argv);

/* What one tighten came to, for batch, which runs tighten's own steps on
 * every curve of a manifest (cli_tighten.h, tr_cli_tighten_run) rather
 * than a process per curve. written: the output (with its certificate) was
 * written; interrupted: SIGINT/SIGTERM stopped the run (the output and the
 * checkpoint hold its last state). */
typedef struct tr_tighten_report {
    int written, interrupted;
    const char *stop; /* tr_stop_reason_name, static */
    size_t n;         /* vertices of the written curve */
    double ropelength, thickness, minrad, dcsd;
    double kkt_residual; /* NAN: not certified */
    double elapsed;      /* seconds, the runs before a resumed checkpoint included */
    long steps;
    int tries;           /* tightenings whose best result was kept (1: one road) */
    long seed;           /* --seed: with tries and the options, what makes the roads again; -1 resumed */
    int road;            /* the road written, 1-based (1: the start's own); 0 resumed */
    int type_checked;    /* 1: the curve written is the start's knot type (tr_tighten_result) */
} tr_tighten_report;

/* tighten's command-line checks alone, on argv as tr_cmd_tighten takes it
 * (argv[0] the command's name): the options and their values, and the
 * paths against each other; nothing is read, run or written. Returns -1
 * when they pass, else tighten's exit status, its one-line message printed
 * on stderr. batch checks every knot's command line with it before it runs
 * any, so that a bad option fails at once rather than when its knot comes
 * (an hour in). */
int tr_tighten_check_args(int argc, char **argv);

/* Whether SIGINT/SIGTERM has asked the running tighten to stop (the
 * handler tighten installs stays in place after it returns). */
int tr_tighten_stop_requested(void);

#endif
