/* The on-screen display's text over takes, as the stage is handed it
 * (host/app/takes_osd.h): which fingers come from the live glove and
 * which the take plays, the glove the keys arm, REC while recording, the
 * speed below 100 %, and the take beneath. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "takes_osd.h"

/* Thumb and index armed on the second glove, the one the keys arm: they
 * read from the live glove, the other three from the take; the first
 * glove, nothing armed, plays the take whole and has no star. */
static void a_gloves_line_names_its_armed_fingers_live_and_the_rest_the_takes(void **state) {
  (void)state;
  mr_takes_osd o = { 1.0, false, "A", 1 };
  char line[200];
  mr_takes_osd_glove(&o, 1, 0x3, line, sizeof line);
  assert_string_equal(line, "glove 2* live TI--- take --MRL");
  mr_takes_osd_glove(&o, 0, 0x0, line, sizeof line);
  assert_string_equal(line, "glove 1 live ----- take TIMRL");
  mr_takes_osd_glove(&o, 0, 0x14, line, sizeof line);
  assert_string_equal(line, "glove 1 live --M-L take TI-R-");
}

/* REC only while recording, SPEED only below full speed, both together
 * at a quarter speed while recording. */
static void the_first_line_marks_rec_while_recording_and_a_slow_speed(void **state) {
  (void)state;
  char marks[64];
  mr_takes_osd o = { 1.0, false, "A", 0 };
  mr_takes_osd_marks(&o, marks, sizeof marks);
  assert_string_equal(marks, "");
  o.recording = true;
  mr_takes_osd_marks(&o, marks, sizeof marks);
  assert_string_equal(marks, "  REC");
  o.speed = 0.25;
  mr_takes_osd_marks(&o, marks, sizeof marks);
  assert_string_equal(marks, "  SPEED 25 %  REC");
  o.recording = false;
  o.speed = 0.5;
  mr_takes_osd_marks(&o, marks, sizeof marks);
  assert_string_equal(marks, "  SPEED 50 %");
}

/* The take beneath by name, a long one cut to 20 characters; no take
 * beneath, no line. */
static void the_take_beneath_is_named_and_none_says_nothing(void **state) {
  (void)state;
  char line[64];
  mr_takes_osd o = { 1.0, false, "verse-2-take-B", 0 };
  mr_takes_osd_beneath(&o, line, sizeof line);
  assert_string_equal(line, "over verse-2-take-B");
  o.beneath = "a-name-longer-than-twenty";
  mr_takes_osd_beneath(&o, line, sizeof line);
  assert_string_equal(line, "over a-name-longer-than-t");
  o.beneath = "";
  mr_takes_osd_beneath(&o, line, sizeof line);
  assert_string_equal(line, "");
  o.beneath = NULL;
  mr_takes_osd_beneath(&o, line, sizeof line);
  assert_string_equal(line, "");
}

int main(void) {
  const struct CMUnitTest tests[] = {
    cmocka_unit_test(a_gloves_line_names_its_armed_fingers_live_and_the_rest_the_takes),
    cmocka_unit_test(the_first_line_marks_rec_while_recording_and_a_slow_speed),
    cmocka_unit_test(the_take_beneath_is_named_and_none_says_nothing),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
