/* Byte sources and sinks for glove streams, and the stream recording format.
 *
 * Everything is a plain POSIX file descriptor underneath: stdin/stdout,
 * regular files, FIFOs, pseudo-terminals, TCP sockets and serial devices.
 * libserialport lists, opens and configures real serial devices; ptys go
 * through termios on a plain fd, because libserialport cannot open them
 * (measured: sp_get_port_by_name fails on /dev/pts/N, and sp_open on a pty
 * fails with "Inappropriate ioctl for device").
 *
 * Nothing here prints or aborts: every failure comes back as a status plus an
 * mr_io_error naming what and where.
 */
#ifndef MR_IO_H
#define MR_IO_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* --- status ----------------------------------------------------------------- */

/* The library's one status type. A read or write ends on MR_IO_OK or on one
 * of the outcomes above 0; the MR_IO_ERR_* values, below 0, are failures,
 * and the mr_io_error that comes with them says what failed and where (the
 * path or spec first). Calls that return an int give 0 on success and -1
 * with err->status set. */
typedef enum mr_io_status {
  MR_IO_OK = 0,             /* bytes moved, or the call succeeded */
  MR_IO_TIMEOUT = 1,        /* nothing moved within the timeout; the link is still up */
  MR_IO_EOF = 2,            /* end of a file, a pipe or FIFO whose writer left */
  MR_IO_HANGUP = 3,         /* the link is gone: device unplugged, pty's other end
                               closed, TCP peer closed or reset */
  MR_IO_ERR_SYSTEM = -1,    /* a system call failed; sys_errno says which errno */
  MR_IO_ERR_SPEC = -2,      /* an unparsable open spec ("tcp:nohost", "serial:@9"):
                               the caller's usage, not the system's state */
  MR_IO_ERR_SERIAL = -3,    /* libserialport refused (not a serial port, bad setting) */
  MR_IO_ERR_FORMAT = -4,    /* a malformed recording; the message names the byte offset */
  MR_IO_ERR_TRUNCATED = -5, /* a recording's last chunk is cut short */
  MR_IO_ERR_ARG = -6,       /* a caller's argument is out of range */
} mr_io_status;

/* True for the MR_IO_ERR_* values. */
static inline int mr_io_failed(mr_io_status st) {
  return st < 0;
}

typedef struct mr_io_error {
  mr_io_status status;
  int sys_errno; /* for MR_IO_ERR_SYSTEM, else 0 */
  char msg[320];
} mr_io_error;

/* --- sources and sinks ------------------------------------------------------ */

typedef enum mr_io_kind {
  MR_IO_STDIO,      /* "-": stdin to read, stdout to write */
  MR_IO_FILE,       /* a regular file */
  MR_IO_FIFO,       /* a named pipe */
  MR_IO_PTY,        /* the master side of a pty this process created */
  MR_IO_TTY,        /* a tty opened through termios (a pty's slave side) */
  MR_IO_SERIAL,     /* a serial device opened through libserialport */
  MR_IO_TCP,        /* a connected TCP socket */
  MR_IO_TCP_LISTEN, /* a listening socket; the first read/write accepts */
} mr_io_kind;

enum { MR_IO_READ = 1, MR_IO_WRITE = 2 };

#define MR_IO_DEFAULT_BAUD 115200

typedef struct mr_io {
  mr_io_kind kind;
  int fd;         /* the descriptor bytes move through (-1 before accept) */
  int listen_fd;  /* from "tcp-listen:": the listening socket */
  int mode;       /* MR_IO_READ and/or MR_IO_WRITE */
  int baud;       /* ttys and serial devices */
  int port;       /* TCP: the port actually bound or connected */
  int peer_seen;  /* MR_IO_PTY: a peer has opened the slave side */
  char path[256]; /* file or device path, pty slave path, or host:port */
  void *sp;       /* libserialport's port, for MR_IO_SERIAL */
} mr_io;

/* Opens a source or sink named by spec:
 *   "-"                      stdin (MR_IO_READ) or stdout (MR_IO_WRITE)
 *   "file:PATH"              a regular file or FIFO (created for writing)
 *   PATH                     the same, except that a character device other
 *                            than /dev/null, /dev/zero and their kin opens
 *                            as "serial:PATH" at the default baud
 *   "pty"                    a new pseudo-terminal, raw mode; mr_io_path()
 *                            names its slave side for the peer to open
 *   "tcp:HOST:PORT"          connect
 *   "tcp-listen:[HOST:]PORT" listen (HOST defaults to 127.0.0.1, the loopback
 *                            only; PORT 0 picks a free port, read it back
 *                            from io->port) and serve one peer at a time:
 *                            while one is served, reads accept and close
 *                            any other at once (it reads end of stream)
 *   "serial:DEV[@BAUD]"      8N1 at BAUD (default 115200); a pty slave path is
 *                            recognised and opened through termios
 * Returns 0, or -1 with *err filled. */
int mr_io_open(mr_io *io, const char *spec, int mode, mr_io_error *err);

/* Checks spec as mr_io_open would take it, opening nothing (so a serial
 * board is not reset by a raised DTR): 0, or -1 with *err filled, status
 * MR_IO_ERR_SPEC for anything the user wrote wrong: a spec that does not
 * parse, a port outside 1..65535 (0..65535 to listen), a baud outside
 * 1..100000000, a device that is not there or not a character device, a
 * file to read that is missing or a directory. A spec that is sound but
 * worth a word (tcp-listen beyond the loopback: plain TCP has no
 * authentication) puts one line in note (if given), else note is "". */
int mr_io_spec_check(const char *spec, int mode, char *note, size_t note_size, mr_io_error *err);

/* Reads up to cap bytes, waiting at most timeout_ms (negative: forever).
 * MR_IO_OK sets *got > 0. Bytes that arrived before a hang-up are returned
 * first; the hang-up is reported by the next call. */
mr_io_status mr_io_read(mr_io *io, void *buf, size_t cap, int timeout_ms, size_t *got,
                        mr_io_error *err);

/* Writes all len bytes, waiting at most timeout_ms for the link to take each
 * piece (negative: forever). On anything but MR_IO_OK, *sent (if not NULL)
 * says how many went out. */
mr_io_status mr_io_write(mr_io *io, const void *buf, size_t len, int timeout_ms, size_t *sent,
                         mr_io_error *err);

/* MR_IO_TCP_LISTEN: waits for one peer and adopts it (later reads and writes
 * go to it). Other kinds: MR_IO_OK at once. */
mr_io_status mr_io_accept(mr_io *io, int timeout_ms, mr_io_error *err);

/* A connection accepted from "tcp-listen:": drops the peer and goes back to
 * listening on the same port, so the next read or write accepts the next
 * peer (a glove that reconnects). 0, or -1 for any other kind. */
int mr_io_rearm(mr_io *io);

/* MR_IO_PTY: waits until a peer has opened the slave side. Other kinds:
 * MR_IO_OK at once. */
mr_io_status mr_io_wait_peer(mr_io *io, int timeout_ms, mr_io_error *err);

/* MR_IO_PTY: waits until the peer has read everything written, because
 * closing the master discards what the slave has not read yet. Other kinds:
 * MR_IO_OK at once. MR_IO_HANGUP if the peer left first. */
mr_io_status mr_io_drain(mr_io *io, int timeout_ms, mr_io_error *err);

/* The path or address the source is known by (for a created pty: the slave
 * path to hand to the peer). */
const char *mr_io_path(const mr_io *io);

const char *mr_io_status_name(mr_io_status st);

void mr_io_close(mr_io *io);

/* True if path names a pseudo-terminal's slave side (e.g. /dev/pts/3). */
int mr_io_is_pty_slave(const char *path);

/* --- serial devices (libserialport) ------------------------------------------ */

typedef struct mr_serial_info {
  char name[128]; /* /dev/ttyUSB0 */
  char description[128];
  int is_usb;
  int usb_vid, usb_pid; /* -1 when not USB */
  char serial[64];      /* USB serial number, "" if none */
  char manufacturer[64];
  char product[64];
} mr_serial_info;

/* Fills up to cap entries, sets *n to how many ports exist. 0 or -1. */
int mr_serial_list(mr_serial_info *out, size_t cap, size_t *n, mr_io_error *err);

/* --- stream recordings (*.mrec; protocol/SPEC.md, "Stream recordings") ----- */

#define MR_REC_MAGIC            "MRSTREAM"
#define MR_REC_VERSION          1u
#define MR_REC_HEADER_LEN       32u
#define MR_REC_CHUNK_HEADER_LEN 12u
#define MR_REC_MAX_CHUNK        1048576u
/* The longest silence a take holds: a chunk's time is at most this much
 * after the chunk before it (the first chunk's: after 0). A replay plays
 * silence at its recorded length, so without a bound one flipped bit in a
 * time field (2^60 ns) would stall a replay for ever. */
#define MR_REC_MAX_GAP_NS 3600000000000ull

typedef struct mr_rec_header {
  uint16_t version;
  uint16_t header_len;
  uint32_t spec_hash;     /* the recorder's; informational */
  uint64_t start_unix_ns; /* 0 if unknown */
  /* The scene the take was performed on: the state hash of its world as
   * built, before the first step (mr_world_state_hash); 0 if unknown (a
   * take from before it was recorded, or not from a show). */
  uint64_t scene_hash;
} mr_rec_header;

typedef struct mr_rec_writer {
  int fd;
  uint64_t offset; /* bytes written so far */
  uint64_t last_t_ns;
  uint64_t chunks;
  char path[256];
} mr_rec_writer;

/* Creates (truncates) path and writes the header. 0 or -1. */
int mr_rec_writer_open(mr_rec_writer *w, const char *path, uint32_t spec_hash,
                       uint64_t start_unix_ns, mr_io_error *err);
/* The same, stamping the take with the scene it is performed on
 * (mr_rec_header's scene_hash; 0: unknown). */
int mr_rec_writer_open_scene(mr_rec_writer *w, const char *path, uint32_t spec_hash,
                             uint64_t start_unix_ns, uint64_t scene_hash, mr_io_error *err);
/* Appends one chunk: 1..MR_REC_MAX_CHUNK bytes at t_ns since the start,
 * never earlier than the chunk before and at most MR_REC_MAX_GAP_NS after
 * it. 0 or -1. */
int mr_rec_writer_add(mr_rec_writer *w, uint64_t t_ns, const void *data, size_t len,
                      mr_io_error *err);
/* Flushes and closes; 0 or -1 (the file may be incomplete). */
int mr_rec_writer_close(mr_rec_writer *w, mr_io_error *err);

typedef struct mr_rec_reader {
  int fd;
  int owns_fd;
  mr_rec_header header;
  uint64_t offset; /* bytes consumed from the file so far */
  uint64_t last_t_ns;
  uint64_t chunks;
  uint8_t *data; /* the current chunk */
  size_t data_cap;
  const uint8_t *prefix; /* bytes already read from fd by the caller */
  size_t prefix_len;
  char name[256];
} mr_rec_reader;

/* Opens path and reads the header. 0, or -1 with the offending byte offset
 * in the message. */
int mr_rec_reader_open(mr_rec_reader *r, const char *path, mr_io_error *err);
/* The same over an open descriptor whose first prefix_len bytes the caller has
 * already read (e.g. to sniff the magic); prefix must outlive the header
 * read. name appears in messages. */
int mr_rec_reader_open_fd(mr_rec_reader *r, int fd, const char *name, const void *prefix,
                          size_t prefix_len, mr_io_error *err);

/* The next chunk: 1 with *t_ns, *data (valid until the next call) and *len
 * set; 0 at a clean end of file; -1 on a malformed chunk (MR_IO_ERR_FORMAT:
 * a length of 0 or over MR_REC_MAX_CHUNK, a time going back or jumping
 * more than MR_REC_MAX_GAP_NS) or a
 * final chunk cut short (MR_IO_ERR_TRUNCATED: offset and bytes missing in the
 * message). Every chunk returned before an error is complete. */
int mr_rec_reader_next(mr_rec_reader *r, uint64_t *t_ns, const uint8_t **data, size_t *len,
                       mr_io_error *err);

void mr_rec_reader_close(mr_rec_reader *r);

/* True if buf starts with the recording magic (needs 8 bytes). */
int mr_rec_is_recording(const void *buf, size_t len);

/* The host's clocks, in ns: monotonic for the times inside a recording and
 * for pacing, Unix time for a recording's header. */
uint64_t mr_io_monotonic_ns(void);
uint64_t mr_io_unix_ns(void);

#ifdef __cplusplus
}
#endif

#endif
