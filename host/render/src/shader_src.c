/* The shaders' bodies, in the subset GLSL 3.30 core (the oldest core
 * profile every backend here gives; Mesa's OSMesa and EGL give 4.5) and
 * GLSL ES 3.00 share: no implicit int to float, float literals with a
 * point, no features past 3.30. shaders.c puts the #version line (and
 * ES's precision statements) before each at compile time, so
 * MR_GLSL_VERSION, which opens every body, stands for that header and is
 * empty here. Every fragment shader writes sRGB itself (mr_to_srgb): the
 * framebuffers are plain RGBA8, because SDL's sRGB framebuffer flag is
 * unreliable and headless backends have no default framebuffer to ask it
 * of. */
#include "shader_src.h"

#include <stdio.h>

#define MR_GLSL_VERSION ""
/* Linear to sRGB. Above the linear toe, 1.055 c^(1/2.4) - 0.055 is
 * matched by a least-squares fit in c^(1/2), c^(1/4), c^(1/8) and c
 * (worst error 0.02/255, so an 8-bit value moves by at most its
 * rounding): three square roots, where pow is a log and an exponential
 * worked out in software GL, about a tenth of a scenery pixel's
 * instructions. */
#define MR_GLSL_SRGB                                                                \
  "vec3 mr_to_srgb(vec3 c) {\n"                                                     \
  "  c = clamp(c, 0.0, 1.0);\n"                                                     \
  "  vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);\n"                            \
  "  vec3 hi = 0.6452007 * s1 + 0.7091280 * s2 - 0.3356885 * s3 - 0.0186766 * c;\n" \
  "  return mix(c * 12.92, hi, step(vec3(0.0031308), c));\n"                        \
  "}\n"

/* Meshes: an item's model matrix, or (MR_SKINNED) the blend of its
 * bones' matrices, read from a 4 x n_bones float texture, one column a
 * texel: linear blend skinning, p' = sum_k w_k M_k p (§3.3, freeform).
 * Normals go through the inverse transpose, since links stretch along y:
 * an item's is worked out once on the CPU (u_normal), a skin's a vertex.
 * Skinned or not is a constant of the source (mr_src_mesh_vs_make), not
 * a uniform: software GL runs both sides of a branch, and would read 16
 * bone texels for every vertex of every item. */
static const char mesh_vs_body[] =
    "layout(location = 0) in vec3 a_pos;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 2) in vec2 a_uv;\n"
    "layout(location = 3) in ivec4 a_bones;\n"
    "layout(location = 4) in vec4 a_weights;\n"
    "uniform mat4 u_model, u_normal, u_view_proj, u_light_vp;\n"
    "uniform sampler2D u_bones;\n"
    "out vec3 v_world, v_normal;\n"
    "out vec2 v_uv;\n"
    "out vec4 v_light;\n"
    "mat4 bone(int i) {\n"
    "  return mat4(texelFetch(u_bones, ivec2(0, i), 0), texelFetch(u_bones, ivec2(1, i), 0),\n"
    "              texelFetch(u_bones, ivec2(2, i), 0), texelFetch(u_bones, ivec2(3, i), 0));\n"
    "}\n"
    "void main() {\n"
    "#if MR_SKINNED\n"
    "  mat4 m = a_weights.x * bone(a_bones.x) + a_weights.y * bone(a_bones.y) +\n"
    "           a_weights.z * bone(a_bones.z) + a_weights.w * bone(a_bones.w);\n"
    "  v_normal = transpose(inverse(mat3(m))) * a_normal;\n"
    "#else\n"
    "  mat4 m = u_model;\n"
    "  v_normal = mat3(u_normal) * a_normal;\n"
    "#endif\n"
    "  vec4 w = m * vec4(a_pos, 1.0);\n"
    "  v_world = w.xyz;\n"
    "  v_uv = a_uv;\n"
    "  v_light = u_light_vp * w;\n"
    "  gl_Position = u_view_proj * w;\n"
    "}\n";

/* Lighting: ambient, the sun (Lambert and a normalised Blinn-Phong lobe
 * whose exponent is the roughness's, s = 2 / r^2 - 2, the inverse of the
 * loader's r = sqrt(2 / (s + 2))), its shadow from the shadow map
 * (percentage-closer filtering, MR_SHADOW_TAPS reads of the map, each a
 * bilinear 2 x 2 compare: 1, 4 at half-texel offsets, or 9 on a 3 x 3
 * grid), and MR_N_SPOTS spots (0 to 8): a cone with a smooth edge and
 * 1 / (1 + k d^2) falloff. Both counts are constants of the source
 * (mr_src_mesh_fs_make): software GL reads a uniform array at a varying
 * index lane by lane, and runs both sides of every branch, so a loop up
 * to a uniform count costs several times the unrolled one. MR_SCENERY:
 * the floor and the backdrop, untextured, of roughness 0.9, whose
 * exponent 2 / 0.81 - 2 is clamped to 1, so the lobe is the cosine
 * itself and the compiler drops the pow (scene.c draws them with that
 * roughness). The floor's boards (MR_SCENERY 2; the backdrop is 1) are
 * worked out here from world x and z: boards u_board m across running
 * towards the audience (across u_board_right), in lengths of 1.7 m whose
 * joints are staggered board by board, each length a tone between
 * u_color and u_color2 (a hash of its place), flat (a grain that
 * varied within a length moved pixels by rounding between two otherwise
 * equal frames, and the smoothing test holds frames equal away from
 * edges), and dark seams between them, blurred over a pixel (fwidth) so
 * that far boards do not shimmer. MR_FOOTLIGHTS: the footlights' warm light, a line
 * light along their row (u_foot_a to u_foot_a + u_foot_ab; the nearest
 * point of it lights a pixel, diffuse only, falling as 1 / (1 + d^2)). Their normals (the floor's +y, the
 * backdrop's +z, as meshes.c makes them), no metal and no glow are
 * constants too, so nothing is interpolated or worked out for them. */
static const char mesh_fs_body[] = MR_GLSL_SRGB
    "in vec3 v_world, v_normal;\n"
    "in vec2 v_uv;\n"
    "in vec4 v_light;\n"
    "uniform vec4 u_color;\n"
    "uniform vec3 u_emissive, u_color2, u_eye, u_ambient, u_sun_dir, u_sun_color;\n"
    "uniform float u_roughness, u_metallic, u_cell, u_shadow_texel;\n"
    "uniform int u_textured, u_shadows;\n"
    "uniform bool u_mirrored;\n"
    "uniform sampler2D u_texture;\n"
    "uniform sampler2DShadow u_shadow_map;\n"
    "uniform vec3 u_spot_pos[8], u_spot_dir[8], u_spot_color[8];\n"
    "uniform vec2 u_spot_cos[8];\n"
    "uniform vec3 u_foot_a, u_foot_ab, u_foot_color, u_board_right;\n"
    "uniform float u_board;\n"
    "out vec4 o_color;\n"
    "float sun_shadow(float ndl) {\n"
    "  if (u_shadows == 0) return 1.0;\n"
    "  vec3 p = v_light.xyz / v_light.w * 0.5 + 0.5;\n"
    "  if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;\n"
    "  float z = p.z - max(0.0015 * (1.0 - ndl), 0.0004);\n"
    "#if MR_SHADOW_TAPS == 9\n"
    "  float lit = 0.0;\n"
    "  for (int i = -1; i <= 1; i++)\n"
    "    for (int j = -1; j <= 1; j++)\n"
    "      lit += texture(u_shadow_map, vec3(p.xy + vec2(i, j) * u_shadow_texel, z));\n"
    "  return lit / 9.0;\n"
    "#elif MR_SHADOW_TAPS == 4\n"
    "  float d = 0.5 * u_shadow_texel;\n"
    "  return 0.25 * (texture(u_shadow_map, vec3(p.x - d, p.y - d, z)) +\n"
    "                 texture(u_shadow_map, vec3(p.x + d, p.y - d, z)) +\n"
    "                 texture(u_shadow_map, vec3(p.x - d, p.y + d, z)) +\n"
    "                 texture(u_shadow_map, vec3(p.x + d, p.y + d, z)));\n"
    "#else\n"
    "  return texture(u_shadow_map, vec3(p.xy, z));\n"
    "#endif\n"
    "}\n"
    "#if MR_SCENERY\n"
    "#define METALLIC 0.0\n"
    "#else\n"
    "#define METALLIC u_metallic\n"
    "#endif\n"
    "vec3 light(vec3 n, vec3 v, vec3 l, vec3 base, vec3 f0, float shin) {\n"
    "  float ndl = max(dot(n, l), 0.0);\n"
    "  vec3 h = normalize(l + v);\n"
    "  float spec = pow(max(dot(n, h), 0.0), shin) * (shin + 8.0) / 25.13;\n"
    "  return (base * (1.0 - METALLIC) + f0 * spec) * ndl;\n"
    "}\n"
    "float hash(vec2 p) { return fract(sin(dot(p, vec2(12.9898, 78.233))) * 43758.5453); }\n"
    "vec3 boards(vec3 c) {\n"
    "  vec2 right = u_board_right.xz, front = vec2(-right.y, right.x);\n"
    "  float u = dot(v_world.xz, right) / u_board + 0.5, i = floor(u);\n"
    "  float s = dot(v_world.xz, front) / 1.7 + hash(vec2(i, 7.0)), j = floor(s);\n"
    "  float h = hash(vec2(i, j));\n"
    "  c = mix(c, u_color2, h);\n"
    "  vec2 e = vec2(fwidth(u), fwidth(s)) + 1e-5;\n"
    "  vec2 edge = min(fract(vec2(u, s)), 1.0 - fract(vec2(u, s)));\n"
    "  vec2 seam = smoothstep(vec2(0.04, 0.006), vec2(0.04, 0.006) + e, edge);\n"
    "  return c * mix(0.35, 1.0, seam.x * seam.y);\n"
    "}\n"
    "vec3 footlight(vec3 n, vec3 base) {\n"
    "  vec3 q = u_foot_a + clamp(dot(v_world - u_foot_a, u_foot_ab) /\n"
    "                                max(dot(u_foot_ab, u_foot_ab), 1e-6), 0.0, 1.0) * u_foot_ab;\n"
    "  vec3 d = q - v_world;\n"
    "  float d2 = max(dot(d, d), 1e-4);\n"
    "  return u_foot_color * base * (max(dot(n, d), 0.0) * inversesqrt(d2) / (1.0 + d2));\n"
    "}\n"
    "void main() {\n"
    "  vec3 base = u_color.rgb;\n"
    "#if !MR_SCENERY\n"
    "  if (u_textured != 0) base *= texture(u_texture, v_uv).rgb;\n"
    "#endif\n"
    "#if MR_SCENERY == 2\n"
    "  base = boards(base);\n"
    "#endif\n"
    "#if MR_SCENERY == 2\n"
    "  vec3 n = vec3(0.0, 1.0, 0.0);\n"
    "#elif MR_SCENERY == 1\n"
    "  vec3 n = vec3(0.0, 0.0, 1.0);\n"
    "#else\n"
    "  vec3 n = normalize(v_normal);\n"
    "#endif\n"
    "  if (gl_FrontFacing == u_mirrored) n = -n;\n"
    "  vec3 v = normalize(u_eye - v_world);\n"
    "#if MR_SCENERY\n"
    "  float shin = 1.0;\n"
    "#else\n"
    "  float r = clamp(u_roughness, 0.05, 1.0);\n"
    "  float shin = clamp(2.0 / (r * r) - 2.0, 1.0, 1024.0);\n"
    "#endif\n"
    "  vec3 f0 = mix(vec3(0.04), base, METALLIC);\n"
    "#if MR_SCENERY\n"
    "  vec3 c = u_ambient * base;\n"
    "#else\n"
    "  vec3 c = u_ambient * base + u_emissive;\n"
    "#endif\n"
    "  float ndl = max(dot(n, u_sun_dir), 0.0);\n"
    "  c += u_sun_color * light(n, v, u_sun_dir, base, f0, shin) * sun_shadow(ndl);\n"
    "  for (int i = 0; i < MR_N_SPOTS; i++) {\n"
    "    vec3 d = u_spot_pos[i] - v_world;\n"
    "    float d2 = dot(d, d);\n"
    "    vec3 l = d * inversesqrt(d2);\n"
    "    float cone = smoothstep(u_spot_cos[i].x, u_spot_cos[i].y, dot(-l, u_spot_dir[i]));\n"
    "    c += u_spot_color[i] * (cone / (1.0 + 0.05 * d2)) * light(n, v, l, base, f0, shin);\n"
    "  }\n"
    "#if MR_FOOTLIGHTS\n"
    "  c += footlight(n, base);\n"
    "#endif\n"
    "  o_color = vec4(mr_to_srgb(c), 1.0);\n"
    "}\n";

int mr_src_mesh_vs_make(char *buf, size_t size, int skinned) {
  int n = snprintf(buf, size, "%s#define MR_SKINNED %d\n%s", MR_GLSL_VERSION, skinned ? 1 : 0,
                   mesh_vs_body);
  return n > 0 && (size_t)n < size ? 0 : -1;
}

int mr_src_mesh_fs_make(char *buf, size_t size, int n_spots, int shadow_taps,
                        mr_src_surface surface, int footlights) {
  int n = snprintf(buf, size,
                   "%s#define MR_N_SPOTS %d\n#define MR_SHADOW_TAPS %d\n#define MR_SCENERY %d\n"
                   "#define MR_FOOTLIGHTS %d\n%s",
                   MR_GLSL_VERSION, n_spots, shadow_taps, (int)surface, footlights ? 1 : 0,
                   mesh_fs_body);
  return n > 0 && (size_t)n < size ? 0 : -1;
}

/* The shadow pass writes depth only. */
const char mr_src_depth_fs[] = MR_GLSL_VERSION "void main() {}\n";

/* The rigging's lines, each a quad already in clip space (lines.c); the
 * line on screen (a point, its unit normal, in pixels) comes flat, and a
 * pixel's coverage is the share of it a line u_width pixels wide covers,
 * from its distance to the line (a box filter a pixel wide). */
const char mr_src_line_vs[] = MR_GLSL_VERSION "layout(location = 0) in vec4 a_clip;\n"
                                              "layout(location = 1) in vec3 a_color;\n"
                                              "layout(location = 2) in vec4 a_line;\n"
                                              "out vec3 v_color;\n"
                                              "flat out vec4 v_line;\n"
                                              "void main() {\n"
                                              "  v_color = a_color;\n"
                                              "  v_line = a_line;\n"
                                              "  gl_Position = a_clip;\n"
                                              "}\n";

const char mr_src_line_fs[] =
    MR_GLSL_VERSION MR_GLSL_SRGB "in vec3 v_color;\n"
                                 "flat in vec4 v_line;\n"
                                 "uniform float u_width;\n"
                                 "out vec4 o_color;\n"
                                 "void main() {\n"
                                 "  float d = abs(dot(gl_FragCoord.xy - v_line.xy, v_line.zw));\n"
                                 "  float cover = clamp(0.5 * u_width + 0.5 - d, 0.0, 1.0);\n"
                                 "  cover = min(cover, u_width);\n"
                                 "  if (cover <= 0.0) discard;\n"
                                 "  o_color = vec4(mr_to_srgb(v_color), cover);\n"
                                 "}\n";

/* Stars: points on a sphere about the eye, inside the far plane, so the
 * floor and the backdrop hide them; they fade in as the sun sets. The
 * edge-smoothing pass draws them again, u_point_pad pixels wider, with
 * its own fragment shader (post.c). A star
 * whose centre is outside the view is dropped (sent past the far plane):
 * desktop GL discards such a point, but ES clips points only at the near
 * and far planes and would draw the part that reaches into the frame. */
const char mr_src_star_vs[] = MR_GLSL_VERSION
    "layout(location = 0) in vec3 a_dir;\n"
    "layout(location = 1) in float a_bright;\n"
    "uniform mat4 u_view_proj;\n"
    "uniform vec3 u_eye;\n"
    "uniform float u_night, u_point_scale, u_point_pad;\n"
    "out float v_alpha;\n"
    "void main() {\n"
    "  v_alpha = clamp(a_bright, 0.0, 1.0) * u_night;\n"
    "  gl_PointSize = (1.5 + 2.5 * clamp(a_bright, 0.0, 1.0)) * u_point_scale + u_point_pad;\n"
    "  vec4 p = u_view_proj * vec4(u_eye + normalize(a_dir) * 50.0, 1.0);\n"
    "  if (any(greaterThan(abs(p.xy), vec2(p.w)))) p.z = 2.0 * p.w;\n"
    "  gl_Position = p;\n"
    "}\n";

const char mr_src_star_fs[] =
    MR_GLSL_VERSION "in float v_alpha;\n"
                    "out vec4 o_color;\n"
                    "void main() {\n"
                    "  float r = length(gl_PointCoord * 2.0 - 1.0);\n"
                    "  o_color = vec4(1.0, 1.0, 0.95, v_alpha * (1.0 - smoothstep(0.5, 1.0, r)));\n"
                    "}\n";

/* The post pass: the regions where an edge can be (post.c), in
 * normalised device coordinates. */
const char mr_src_post_vs[] =
    MR_GLSL_VERSION "layout(location = 0) in vec2 a_pos;\n"
                    "void main() { gl_Position = vec4(a_pos, 0.0, 1.0); }\n";

/* Edge smoothing, for frames drawn with one sample (software GL, where
 * multisampling costs most of a frame). The luma of the pixel and its
 * four neighbours gives the contrast and the gradient; where the contrast
 * is high, the pixel is blended with two bilinear reads along the edge
 * (across the gradient), 1.5 pixels either way, so the steps of a
 * slanted edge are spread along it. Flat areas and 1-pixel lines (whose
 * gradient is nil) are left as they are. Its input is already sRGB. */
const char mr_src_smooth_fs[] =
    MR_GLSL_VERSION "uniform sampler2D u_frame;\n"
                    "uniform vec2 u_texel;\n"
                    "out vec4 o_color;\n"
                    "float luma(ivec2 p, ivec2 hi) {\n"
                    "  vec3 c = texelFetch(u_frame, clamp(p, ivec2(0), hi), 0).rgb;\n"
                    "  return dot(c, vec3(0.299, 0.587, 0.114));\n"
                    "}\n"
                    "void main() {\n"
                    "  ivec2 p = ivec2(gl_FragCoord.xy), hi = textureSize(u_frame, 0) - 1;\n"
                    "  vec3 c = texelFetch(u_frame, p, 0).rgb;\n"
                    "  float m = dot(c, vec3(0.299, 0.587, 0.114));\n"
                    "  float n = luma(p + ivec2(0, 1), hi), s = luma(p - ivec2(0, 1), hi);\n"
                    "  float e = luma(p + ivec2(1, 0), hi), w = luma(p - ivec2(1, 0), hi);\n"
                    "  float lo = min(m, min(min(n, s), min(e, w)));\n"
                    "  float top = max(m, max(max(n, s), max(e, w)));\n"
                    "  float amount = smoothstep(0.03, 0.12, top - lo);\n"
                    "  vec2 g = vec2(e - w, n - s);\n"
                    "  float len = length(g);\n"
                    "  vec2 t = len > 0.0001 ? vec2(-g.y, g.x) * (1.5 / len) : vec2(0.0);\n"
                    "  vec2 uv = gl_FragCoord.xy * u_texel;\n"
                    "  vec3 a = texture(u_frame, uv + t * u_texel).rgb;\n"
                    "  vec3 b = texture(u_frame, uv - t * u_texel).rgb;\n"
                    "  o_color = vec4(mix(c, 0.5 * (a + b), 0.5 * amount), 1.0);\n"
                    "}\n";

/* The on-screen display: pixel coordinates, top left origin; glyphs take
 * their coverage from the font atlas, the box behind them is solid. Its
 * colours are already sRGB. */
const char mr_src_text_vs[] = MR_GLSL_VERSION "layout(location = 0) in vec2 a_pos;\n"
                                              "layout(location = 1) in vec2 a_uv;\n"
                                              "uniform vec2 u_screen;\n"
                                              "out vec2 v_uv;\n"
                                              "void main() {\n"
                                              "  v_uv = a_uv;\n"
                                              "  vec2 p = a_pos / u_screen * 2.0 - 1.0;\n"
                                              "  gl_Position = vec4(p.x, -p.y, 0.0, 1.0);\n"
                                              "}\n";

const char mr_src_text_fs[] =
    MR_GLSL_VERSION "in vec2 v_uv;\n"
                    "uniform vec4 u_color;\n"
                    "uniform int u_solid;\n"
                    "uniform sampler2D u_font;\n"
                    "out vec4 o_color;\n"
                    "void main() {\n"
                    "  float a = u_solid != 0 ? 1.0 : texture(u_font, v_uv).r;\n"
                    "  o_color = vec4(u_color.rgb, u_color.a * a);\n"
                    "}\n";
