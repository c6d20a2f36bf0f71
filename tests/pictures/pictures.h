/* The pictures of the stage held to goldens (tests/golden/NAME.png): the
 * display-mode scenes and the example scenes, each at one frame. Shared
 * by the desktop test (test_pictures.c) and the OpenGL ES one
 * (test_pictures_gles.c), so both draw the same list. */
#ifndef MR_TEST_PICTURES_H
#define MR_TEST_PICTURES_H

#include <stddef.h>

typedef struct picture {
  const char *name;  /* its golden: tests/golden/NAME.png */
  const char *scene; /* under host/scenes/ */
  const char *frame; /* the time of the frame, s */
} picture;

/* One frame each where the mode shows best: the beads mid-swing, the
 * links stretched, the blocks turned, the sausage bent. */
static const picture modes[] = {
  { "mode_particle", "modes/particle.yaml", "2.5" },
  { "mode_link", "modes/link.yaml", "2" },
  { "mode_rigid", "modes/rigid.yaml", "3" },
  { "mode_freeform", "modes/freeform.yaml", "3" },
};

/* And one each for the examples: the stick figure mid-stride, the
 * humanoid turning, the dragon's wings spread, the bird's tree in flight,
 * the clash's puppets meeting arm first, the ghost rocking. */
static const picture examples[] = {
  { "stick", "stick.yaml", "5" },     { "humanoid", "humanoid.yaml", "6" },
  { "dragon", "dragon.yaml", "8.5" }, { "bird", "bird.yaml", "5" },
  { "clash", "clash.yaml", "7" },     { "ghost", "ghost.yaml", "5" },
};

#define N_OF(a) (sizeof(a) / sizeof((a)[0]))

#endif
