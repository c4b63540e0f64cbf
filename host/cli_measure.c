/* PLACEHOLDER: replaced by the real 'measure' command. */
#include <stdio.h>

#include "cli.h"

int tr_cmd_measure(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    fprintf(stderr, "tightrope measure: not built yet\n");
    return 2;
}
