/* The shaders' bodies, for GLSL 3.30 core and GLSL ES 3.00 both
 * (shader_src.c; shaders.c prepends the #version line). */
#ifndef MR_RENDER_SHADER_SRC_H
#define MR_RENDER_SHADER_SRC_H

#include <stddef.h>

extern const char mr_src_depth_fs[];
/* The mesh vertex shader, skinned (freeform models) or not, into buf; -1
 * when it does not fit. */
int mr_src_mesh_vs_make(char *buf, size_t size, int skinned);
/* What a lit fragment shader draws: items and skins (and the theater's
 * set), the backdrop, or the floor (the backdrop's, with its boards). */
typedef enum mr_src_surface {
  MR_SRC_ITEMS = 0,
  MR_SRC_BACKDROP = 1,
  MR_SRC_FLOOR = 2
} mr_src_surface;
/* The lit fragment shader for n_spots spots (0 to 8) and a shadow filter
 * of shadow_taps reads (1, 4 or 9), for surface, with the footlights'
 * light or not, into buf; -1 when it does not fit. */
int mr_src_mesh_fs_make(char *buf, size_t size, int n_spots, int shadow_taps,
                        mr_src_surface surface, int footlights);
extern const char mr_src_line_vs[], mr_src_line_fs[];
extern const char mr_src_star_vs[], mr_src_star_fs[];
extern const char mr_src_text_vs[], mr_src_text_fs[];
extern const char mr_src_post_vs[], mr_src_smooth_fs[];

#endif
