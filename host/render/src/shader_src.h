/* The shaders' bodies, for GLSL 3.30 core and GLSL ES 3.00 both
 * (shader_src.c; shaders.c prepends the #version line). */
#ifndef MR_RENDER_SHADER_SRC_H
#define MR_RENDER_SHADER_SRC_H

extern const char mr_src_mesh_vs[], mr_src_mesh_fs[], mr_src_depth_fs[];
extern const char mr_src_line_vs[], mr_src_line_fs[];
extern const char mr_src_star_vs[], mr_src_star_fs[];
extern const char mr_src_text_vs[], mr_src_text_fs[];

#endif
