/* tightrope: tighten knots in an ideal rope and measure their ropelength. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"

typedef struct subcommand {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} subcommand;

static const subcommand commands[] = {
    {"make", tr_cmd_make, "generate a start curve: torus knot, circle, Hopf link, simple clasp"},
    {"measure", tr_cmd_measure, "length, MinRad, struts, thickness and ropelength of curve files"},
    {"tighten", tr_cmd_tighten, "tighten a knot, link or clasp to its ideal shape"},
    {"analyze", tr_cmd_analyze, "curvature, torsion, symmetry and contact portrait of a tight knot"},
    {"devices", tr_cmd_devices, "list the compute devices (serial reference and OpenCL)"},
    {"bench", tr_cmd_bench, "throughput of the tightening step on each device"},
    {"batch", tr_cmd_batch, "tighten every knot of a manifest or folder into one table (resumable)"},
};

static void usage(FILE *out)
{
    fprintf(out, "usage: tightrope COMMAND [ARGS...]\n\ncommands:\n");
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(out, "  %-9s %s\n", commands[i].name, commands[i].summary);
    fprintf(out, "\n'tightrope COMMAND --help' describes each command.\n");
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return 0;
    }
    if (!strcmp(argv[1], "--version") || !strcmp(argv[1], "version")) {
        printf("tightrope %s\n", TIGHTROPE_VERSION);
        return 0;
    }
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name))
            return commands[i].run(argc - 1, argv + 1);
    fprintf(stderr, "tightrope: unknown command '%s' (see tightrope --help)\n", argv[1]);
    return 2;
}
