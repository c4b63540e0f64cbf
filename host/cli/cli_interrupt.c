/* This file contains the interrupt flag of the commands that stop cleanly
 * on a signal (cli_interrupt.h): the one piece of process state. */
#include "cli/cli_interrupt.h"

#include <signal.h>
#include <string.h>

static volatile sig_atomic_t interrupted = 0;

static void on_interrupt(int sig) { interrupted = sig; }

void tr_cli_catch_interrupts(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    /* no SA_RESTART: a wait for gnuplot or for a FIFO's reader ends with
     * EINTR, so the command sees the flag at once */
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
}

int tr_cli_interrupted(void) { return interrupted; }

volatile sig_atomic_t *tr_cli_interrupt_flag(void) { return &interrupted; }
