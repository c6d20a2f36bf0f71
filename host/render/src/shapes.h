/* The built-in shapes as meshes, and the mesh helpers the model loader
 * shares with them. Private to mr_render. */
#ifndef MR_RENDER_SHAPES_H
#define MR_RENDER_SHAPES_H

#include <stdbool.h>
#include <stddef.h>

#include "model.h"

/* Fills out with shape s of unit size (mr_stage.h), wearing no material
 * (the caller sets it): smooth normals, uvs (v = 0 on the texture's top
 * row), front faces counter-clockwise seen from outside. Returns 0, or -1
 * when s is not a built-in shape or memory runs out (out left empty). */
int mr_shape_mesh(mr_shape s, mr_mesh *out);

/* The built-in shapes come in MR_SHAPE_LEVELS tessellations, level 0 the
 * finest (mr_shape_mesh's: 32 segments round), each next one half as
 * many segments and rings (16, then 8), for shapes drawn small. */
enum { MR_SHAPE_LEVELS = 3 };

/* Shape s at `level` (0 .. MR_SHAPE_LEVELS - 1), as mr_shape_mesh. */
int mr_shape_mesh_lod(mr_shape s, int level, mr_mesh *out);

/* The segments round of `level`; 0 for a level that is not one. */
int mr_shape_segments(int level);

/* Allocates a mesh's arrays for n_vertices and n_triangles (uvs too when
 * with_uvs). Returns 0, or -1 with the mesh left empty. */
int mr_mesh_alloc(mr_mesh *m, size_t n_vertices, size_t n_triangles, int with_uvs);

/* True when the mesh is closed and wound counter-clockwise seen from
 * outside: vertices at the same position taken as one, every edge is
 * shared by two triangles that run it in opposite directions, and each
 * connected part encloses a positive volume. Its back faces are then
 * hidden behind its front ones and can be culled. False too when memory
 * runs out. */
bool mr_mesh_is_closed_outward(const mr_mesh *m);

/* Frees a mesh's arrays and empties it. */
void mr_mesh_release(mr_mesh *m);

#endif
