/* A broker's URL taken apart (mr_net_url_parse): every field of URLs that
 * are right, the edges of the port and the topic, and the one line that
 * says what is wrong with one that is not. No broker. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "mr_net.h"

static mr_net_url parsed(const char *url) {
  mr_net_url u;
  mr_io_error err;
  memset(&err, 0, sizeof err);
  if (mr_net_url_parse(url, &u, &err) != 0) fail_msg("%s refused: %s", url, err.msg);
  return u;
}

/* url parsed, field by field against want. */
static void parsed_as(const char *url, mr_net_url want) {
  mr_net_url u = parsed(url);
  assert_int_equal(u.tls, want.tls);
  assert_int_equal(u.port, want.port);
  assert_string_equal(u.user, want.user);
  assert_string_equal(u.host, want.host);
  assert_string_equal(u.topic, want.topic);
  assert_string_equal(u.cafile, want.cafile);
  assert_string_equal(u.password_file, want.password_file);
}

static void every_field_of_a_url_is_taken(void **state) {
  (void)state;
  parsed_as("mqtts://alice@broker.example:8884/theater/glove1?cafile=/etc/ca.pem&password-file=p",
            (mr_net_url){ .tls = true,
                          .port = 8884,
                          .user = "alice",
                          .host = "broker.example",
                          .topic = "theater/glove1",
                          .cafile = "/etc/ca.pem",
                          .password_file = "p" }); /* one letter is a path too */
  parsed_as("mqtt://localhost/glove",
            (mr_net_url){ .port = 1883, .host = "localhost", .topic = "glove" });
  parsed_as("mqtts://h/g", (mr_net_url){ .tls = true, .port = 8883, .host = "h", .topic = "g" });
  parsed_as("mqtt://[::1]:1884/g", (mr_net_url){ .port = 1884, .host = "::1", .topic = "g" });
  parsed_as("mqtt://[::1]/g", (mr_net_url){ .port = 1883, .host = "::1", .topic = "g" });
}

/* Ports 1 to 65535, written in decimal, a leading zero or not. */
static void ports_run_from_1_to_65535(void **state) {
  (void)state;
  assert_int_equal(parsed("mqtt://h:1/g").port, 1);
  assert_int_equal(parsed("mqtt://h:65535/g").port, 65535);
  assert_int_equal(parsed("mqtt://h:01883/g").port, 1883);
  static const char *const bad[] = { "0", "65536", "", "12a", "-1", "+80", " 80", "99999999999" };
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    char url[64], want[128];
    snprintf(url, sizeof url, "mqtt://h:%s/g", bad[i]);
    snprintf(want, sizeof want, "%s: port '%s' is not 1..65535", url, bad[i]);
    mr_net_url u;
    mr_io_error err;
    assert_int_equal(mr_net_url_parse(url, &u, &err), -1);
    assert_string_equal(err.msg, want);
  }
}

/* A topic of 1 to 190 characters: the glove's own topics add "/reply". */
static void topics_run_from_1_to_190_characters(void **state) {
  (void)state;
  char url[300], topic[200];
  memset(topic, 'a', sizeof topic);
  for (size_t n = 189; n <= 191; n++) {
    topic[n] = '\0';
    snprintf(url, sizeof url, "mqtt://h/%s", topic);
    mr_net_url u;
    mr_io_error err;
    int rc = mr_net_url_parse(url, &u, &err);
    topic[n] = 'a';
    if (n <= 190) {
      assert_int_equal(rc, 0);
      assert_int_equal(strlen(u.topic), n);
    } else {
      assert_int_equal(rc, -1);
      assert_non_null(strstr(err.msg, "the topic must be 1..190 characters"));
    }
  }
}

/* What is wrong is said whole, after the URL itself. */
static void what_is_wrong_is_said(void **state) {
  (void)state;
  static const char *const cases[][2] = {
    { "http://h/g", "http://h/g: expected mqtt://[USER@]HOST[:PORT]/TOPIC" },
    { "mqtts://h", "mqtts://h: no topic (expected mqtts://HOST/TOPIC)" },
    { "mqtt://@h/g", "mqtt://@h/g: expected a user name before '@'" },
    { "mqtt://[::1/g", "mqtt://[::1/g: expected [ADDRESS]" },
    { "mqtt://[::1]x/g", "mqtt://[::1]x/g: expected [ADDRESS] or [ADDRESS]:PORT" },
    { "mqtt://[::1]1883/g", "mqtt://[::1]1883/g: expected [ADDRESS] or [ADDRESS]:PORT" },
    { "mqtt:///g", "mqtt:///g: no broker host" },
    { "mqtt://u@:1883/g", "mqtt://u@:1883/g: no broker host" },
    { "mqtt://h/", "mqtt://h/: the topic must be 1..190 characters without + or # and not "
                   "end in /" },
    { "mqtt://h/a/", "mqtt://h/a/: the topic must be 1..190 characters without + or # and not "
                     "end in /" },
    { "mqtt://h/a/+/b", "mqtt://h/a/+/b: the topic must be 1..190 characters without + or # "
                        "and not end in /" },
    { "mqtts://h/g?cafile=", "mqtts://h/g?cafile=: unknown option 'cafile=' (expected "
                             "cafile=PATH or password-file=PATH)" },
    { "mqtt://h/g?password-file=p&x", "mqtt://h/g?password-file=p&x: unknown option 'x' "
                                      "(expected cafile=PATH or password-file=PATH)" },
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mr_net_url u;
    mr_io_error err;
    assert_int_equal(mr_net_url_parse(cases[i][0], &u, &err), -1);
    assert_int_equal(err.status, MR_IO_ERR_SPEC);
    assert_string_equal(err.msg, cases[i][1]);
  }
  mr_io_error err;
  mr_net_url u;
  assert_int_equal(mr_net_url_parse(NULL, &u, &err), -1);
  assert_string_equal(err.msg, ": expected mqtt://[USER@]HOST[:PORT]/TOPIC");
  char path[sizeof u.cafile + 1]; /* one character more than it holds */
  memset(path, 'p', sizeof path);
  path[sizeof path - 1] = '\0';
  char url[400];
  snprintf(url, sizeof url, "mqtts://h/g?cafile=%s", path);
  assert_int_equal(mr_net_url_parse(url, &u, &err), -1);
  assert_non_null(strstr(err.msg, ": the cafile path is too long"));
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(every_field_of_a_url_is_taken),
    cmocka_unit_test(ports_run_from_1_to_65535),
    cmocka_unit_test(topics_run_from_1_to_190_characters),
    cmocka_unit_test(what_is_wrong_is_said),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
