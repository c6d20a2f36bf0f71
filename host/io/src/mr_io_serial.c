/* Real serial devices through libserialport: it finds them, tells their USB
 * ids and sets the line up; the bytes then move through its fd like any
 * other source, so a timeout and a hang-up look the same everywhere. */
#include <errno.h>
#include <fcntl.h>
#include <libserialport.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "mr_io_internal.h"

static int sp_fail(mr_io_error *err, enum sp_return rc, const char *what, const char *path) {
  if (rc == SP_ERR_FAIL) {
    char *m = sp_last_error_message();
    mr_io_err_set(err, MR_IO_ERR_SERIAL, "%s: %s: %s", path, what, m ? m : "failed");
    if (m) sp_free_error_message(m);
  } else {
    mr_io_err_set(err, MR_IO_ERR_SERIAL, "%s: %s: %s", path, what,
                  rc == SP_ERR_ARG    ? "invalid argument"
                  : rc == SP_ERR_SUPP ? "not supported by this device"
                  : rc == SP_ERR_MEM  ? "out of memory"
                                      : "failed");
  }
  return -1;
}

int mr_io_serial_open(mr_io *io, const char *path, int baud, mr_io_error *err) {
  struct sp_port *port = NULL;
  struct stat st;
  enum sp_return rc;
  int fd = -1;
  enum sp_mode mode = (io->mode & MR_IO_WRITE) ? SP_MODE_READ_WRITE : SP_MODE_READ;

  /* A missing device or a refused open reads exactly as it does for a file
   * (mr_io_open's open_file): one failure, one message, whatever the kind. */
  if (stat(path, &st) != 0) return mr_io_err_sys(err, "%s: cannot open", path);
  rc = sp_get_port_by_name(path, &port);
  if (rc != SP_OK) return sp_fail(err, rc, "not a serial port", path);
  rc = sp_open(port, mode);
  if (rc != SP_OK) {
    if (rc == SP_ERR_FAIL) {
      errno = sp_last_error_code();
      mr_io_err_sys(err, "%s: cannot open", path);
    } else {
      sp_fail(err, rc, "cannot open", path);
    }
    sp_free_port(port);
    return -1;
  }
  /* 8N1, no flow control: what the firmware's USART speaks. */
  if ((rc = sp_set_baudrate(port, baud)) != SP_OK || (rc = sp_set_bits(port, 8)) != SP_OK ||
      (rc = sp_set_parity(port, SP_PARITY_NONE)) != SP_OK ||
      (rc = sp_set_stopbits(port, 1)) != SP_OK ||
      (rc = sp_set_flowcontrol(port, SP_FLOWCONTROL_NONE)) != SP_OK) {
    char what[64];
    snprintf(what, sizeof what, "cannot set %d 8N1", baud);
    sp_fail(err, rc, what, path);
    sp_close(port);
    sp_free_port(port);
    return -1;
  }
  if (sp_get_port_handle(port, &fd) != SP_OK || fd < 0) {
    sp_close(port);
    sp_free_port(port);
    return mr_io_err_set(err, MR_IO_ERR_SERIAL, "%s: no file descriptor for the port", path);
  }
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  io->sp = port;
  io->fd = fd;
  io->kind = MR_IO_SERIAL;
  io->baud = baud;
  snprintf(io->path, sizeof io->path, "%s", path);
  return 0;
}

void mr_io_serial_close(mr_io *io) {
  if (io->sp) {
    sp_close(io->sp);
    sp_free_port(io->sp);
    io->sp = NULL;
  }
  io->fd = -1;
}

static void copy_str(char *dst, size_t cap, const char *src) {
  snprintf(dst, cap, "%s", src ? src : "");
}

int mr_serial_list(mr_serial_info *out, size_t cap, size_t *n, mr_io_error *err) {
  struct sp_port **ports = NULL;
  enum sp_return rc = sp_list_ports(&ports);
  size_t i;
  *n = 0;
  if (rc != SP_OK) return sp_fail(err, rc, "cannot list ports", "serial");
  for (i = 0; ports[i]; i++) {
    struct sp_port *p = ports[i];
    if (i < cap) {
      mr_serial_info *s = &out[i];
      memset(s, 0, sizeof *s);
      copy_str(s->name, sizeof s->name, sp_get_port_name(p));
      copy_str(s->description, sizeof s->description, sp_get_port_description(p));
      s->usb_vid = s->usb_pid = -1;
      s->is_usb = sp_get_port_transport(p) == SP_TRANSPORT_USB;
      if (s->is_usb) {
        sp_get_port_usb_vid_pid(p, &s->usb_vid, &s->usb_pid);
        copy_str(s->serial, sizeof s->serial, sp_get_port_usb_serial(p));
        copy_str(s->manufacturer, sizeof s->manufacturer, sp_get_port_usb_manufacturer(p));
        copy_str(s->product, sizeof s->product, sp_get_port_usb_product(p));
      }
    }
  }
  *n = i;
  sp_free_port_list(ports);
  return 0;
}
