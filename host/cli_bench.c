/* PLACEHOLDER: replaced by the real 'bench' command. */
#include <stdio.h>

#include "cli.h"

int tr_cmd_bench(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "tightrope bench: not built yet\n");
    return 2;
}
