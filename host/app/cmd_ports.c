/* `marionette list-ports`: the serial ports with their USB ids, and which
 * of them has a glove on it, found by listening for its INFO (nothing is
 * written to any port, so other devices are left alone). */
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "mr_glove.h"
#include "mr_io.h"

void mr_cmd_ports_usage(void) {
  printf("usage: marionette list-ports [--no-probe] [--wait SECONDS]\n"
         "\n"
         "Lists the serial ports with their USB vendor and product ids, and marks\n"
         "the gloves among them with their uid and hand. Each USB port is listened\n"
         "to for the INFO a glove sends at least once a second; nothing is written\n"
         "to any port.\n"
         "\n"
         "options:\n"
         "  --no-probe          list the ports only\n"
         "  --wait SECONDS      how long to listen on each port (default 1.5)\n"
         "  -h, --help          show this help\n"
         "\n"
         "exit status: 0 listed (even none), 1 the ports could not be listed, 2 bad usage.\n");
}

static void print_port(const mr_serial_info *p, bool probe, double wait) {
  char ids[32] = "-";
  if (p->is_usb && p->usb_vid >= 0)
    snprintf(ids, sizeof ids, "%04x:%04x", (unsigned)p->usb_vid, (unsigned)p->usb_pid);
  char glove[160] = "";
  if (probe && p->is_usb) { /* a glove comes over USB; other ports are left alone */
    char src[200], msg[200];
    snprintf(src, sizeof src, "serial:%.180s", p->name);
    gp_info info;
    bool foreign = false;
    int found = mr_glove_probe(src, wait, &info, &foreign, msg, sizeof msg);
    if (found == 1 && foreign)
      snprintf(glove, sizeof glove,
               "  glove built from protocol 0x%08X (this host: 0x%08X): "
               "reflash it",
               (unsigned)info.spec_hash, (unsigned)GP_SPEC_HASH);
    else if (found == 1)
      snprintf(glove, sizeof glove, "  glove uid %08X%08X%08X, %s hand, firmware %u.%u.%u",
               (unsigned)info.uid[0], (unsigned)info.uid[1], (unsigned)info.uid[2],
               info.hand == GP_HAND_LEFT ? "left" : "right", info.fw_major, info.fw_minor,
               info.fw_patch);
    else if (found < 0)
      snprintf(glove, sizeof glove, "  (%.140s)", msg);
  }
  printf("%-24s %-10s %s%s\n", p->name, ids, p->description[0] ? p->description : "-", glove);
}

int mr_cmd_ports(int argc, char **argv) {
  bool probe = true;
  double wait = 1.5;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
      mr_cmd_ports_usage();
      return MR_EXIT_OK;
    } else if (strcmp(argv[i], "--no-probe") == 0) {
      probe = false;
    } else if (strcmp(argv[i], "--wait") == 0 && i + 1 < argc) {
      char *end = NULL;
      wait = strtod(argv[++i], &end);
      if (end == argv[i] || *end != '\0' || !(wait > 0 && wait <= 60)) {
        fprintf(stderr,
                "marionette list-ports: expected --wait between 0 and 60 s, got '%s' "
                "(see marionette list-ports --help)\n",
                argv[i]);
        return MR_EXIT_USAGE;
      }
    } else {
      fprintf(stderr,
              "marionette list-ports: unknown option '%s' (see marionette list-ports --help)\n",
              argv[i]);
      return MR_EXIT_USAGE;
    }
  }
  mr_serial_info ports[64];
  size_t n = 0;
  mr_io_error err;
  if (mr_serial_list(ports, 64, &n, &err) != 0) {
    fprintf(stderr, "marionette list-ports: %s\n", err.msg);
    return MR_EXIT_FAIL;
  }
  if (n == 0) {
    printf("no serial ports\n");
    return MR_EXIT_OK;
  }
  printf("%-24s %-10s %s\n", "port", "usb id", "description");
  for (size_t i = 0; i < n && i < 64; i++) print_port(&ports[i], probe, wait);
  return MR_EXIT_OK;
}
