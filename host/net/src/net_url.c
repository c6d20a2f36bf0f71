/* mqtt://[USER@]HOST[:PORT]/TOPIC[?OPTION&...] taken apart (mr_net.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "net_internal.h"

bool mr_net_is_url(const char *s) {
  return s != NULL && (strncmp(s, "mqtt://", 7) == 0 || strncmp(s, "mqtts://", 8) == 0);
}

/* Copies [s, s + n) into out (size bytes): 0, or -1 if it does not fit. */
static int copy_n(char *out, size_t size, const char *s, size_t n) {
  if (n >= size) return -1;
  memcpy(out, s, n);
  out[n] = '\0';
  return 0;
}

/* One NAME=VALUE of the query. */
static int parse_option(mr_net_url *u, const char *url, const char *opt, size_t n,
                        mr_io_error *err) {
  static const char *const names[] = { "cafile=", "password-file=" };
  char *const dest[] = { u->cafile, u->password_file };
  const size_t sizes[] = { sizeof u->cafile, sizeof u->password_file };
  for (int i = 0; i < 2; i++) {
    size_t k = strlen(names[i]);
    if (n <= k || strncmp(opt, names[i], k) != 0) continue;
    if (copy_n(dest[i], sizes[i], opt + k, n - k) != 0)
      return mr_net_err(err, MR_IO_ERR_SPEC, "%s: the %.*s path is too long", url, (int)k - 1,
                        names[i]);
    return 0;
  }
  return mr_net_err(err, MR_IO_ERR_SPEC,
                    "%s: unknown option '%.*s' (expected cafile=PATH or password-file=PATH)", url,
                    (int)n, opt);
}

/* HOST[:PORT] or [V6]:PORT. */
static int parse_host(mr_net_url *u, const char *url, const char *s, size_t n, mr_io_error *err) {
  const char *colon = NULL;
  if (n > 0 && s[0] == '[') {
    const char *close = memchr(s, ']', n);
    if (close == NULL) return mr_net_err(err, MR_IO_ERR_SPEC, "%s: expected [ADDRESS]", url);
    if (copy_n(u->host, sizeof u->host, s + 1, (size_t)(close - s - 1)) != 0)
      return mr_net_err(err, MR_IO_ERR_SPEC, "%s: host name too long", url);
    if (close + 1 < s + n && close[1] != ':')
      return mr_net_err(err, MR_IO_ERR_SPEC, "%s: expected [ADDRESS] or [ADDRESS]:PORT", url);
    colon = close + 1 < s + n ? close + 1 : NULL;
  } else {
    colon = memchr(s, ':', n);
    if (copy_n(u->host, sizeof u->host, s, colon ? (size_t)(colon - s) : n) != 0)
      return mr_net_err(err, MR_IO_ERR_SPEC, "%s: host name too long", url);
  }
  if (u->host[0] == '\0') return mr_net_err(err, MR_IO_ERR_SPEC, "%s: no broker host", url);
  if (colon == NULL) return 0;
  char digits[8];
  size_t dn = (size_t)(s + n - colon - 1);
  char *end;
  long p = -1;
  if (dn > 0 && copy_n(digits, sizeof digits, colon + 1, dn) == 0) p = strtol(digits, &end, 10);
  if (p < 1 || p > 65535 || *end != '\0' || digits[0] < '0' || digits[0] > '9')
    return mr_net_err(err, MR_IO_ERR_SPEC, "%s: port '%.*s' is not 1..65535", url, (int)dn,
                      colon + 1);
  u->port = (int)p;
  return 0;
}

int mr_net_url_parse(const char *url, mr_net_url *u, mr_io_error *err) {
  memset(u, 0, sizeof *u);
  if (!mr_net_is_url(url))
    return mr_net_err(err, MR_IO_ERR_SPEC, "%s: expected mqtt://[USER@]HOST[:PORT]/TOPIC",
                      url ? url : "");
  u->tls = url[4] == 's';
  u->port = u->tls ? 8883 : 1883;
  const char *s = url + (u->tls ? 8 : 7);
  const char *slash = strchr(s, '/');
  if (slash == NULL)
    return mr_net_err(err, MR_IO_ERR_SPEC, "%s: no topic (expected %s://HOST/TOPIC)", url,
                      u->tls ? "mqtts" : "mqtt");
  const char *at = memchr(s, '@', (size_t)(slash - s));
  if (at != NULL) {
    if (at == s || copy_n(u->user, sizeof u->user, s, (size_t)(at - s)) != 0)
      return mr_net_err(err, MR_IO_ERR_SPEC, "%s: expected a user name before '@'", url);
    if (strchr(u->user, ':') != NULL)
      return mr_net_err(err, MR_IO_ERR_SPEC,
                        "%s: no password in the URL (ps shows it): use MR_MQTT_PASSWORD or "
                        "?password-file=PATH",
                        url);
    s = at + 1;
  }
  if (parse_host(u, url, s, (size_t)(slash - s), err) != 0) return -1;
  const char *topic = slash + 1, *q = strchr(topic, '?');
  size_t tn = q ? (size_t)(q - topic) : strlen(topic);
  /* The glove's three topics are TOPIC, TOPIC/cmd and TOPIC/reply: a
   * wildcard would read other gloves', and room is kept for "/reply".
   * The bound the copy holds is the one the message says. */
  enum { TOPIC_CHARS = 190 };
  _Static_assert(TOPIC_CHARS + sizeof "/reply" <= sizeof u->topic, "room for /reply");
  if (tn == 0 || copy_n(u->topic, TOPIC_CHARS + 1, topic, tn) != 0 ||
      strpbrk(u->topic, "+#") != NULL || u->topic[tn - 1] == '/')
    return mr_net_err(err, MR_IO_ERR_SPEC,
                      "%s: the topic must be 1..%d characters without + or # and not end in /", url,
                      TOPIC_CHARS);
  while (q != NULL) {
    const char *opt = q + 1, *amp = strchr(opt, '&');
    size_t on = amp ? (size_t)(amp - opt) : strlen(opt);
    if (parse_option(u, url, opt, on, err) != 0) return -1;
    q = amp;
  }
  if (u->cafile[0] && !u->tls)
    return mr_net_err(err, MR_IO_ERR_SPEC, "%s: cafile= is for mqtts:// only", url);
  return 0;
}
