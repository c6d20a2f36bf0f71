/* What the shared startup code needs from a board. */
#ifndef BOARD_H
#define BOARD_H

/* The board's entry point after .data and .bss are set up; never returns. */
void board_main(void) __attribute__((noreturn));

#endif
