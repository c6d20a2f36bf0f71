/* mr_stage: what the stage shows, and where, without a line of GL.
 *
 * A scene's `models:`, `lights:`, `stage:` and `camera:` sections are read
 * (host/scene) into an mr_stage_def: models bound to particles in one of
 * the paper's four display modes (§3.3), lights, scenery, the day knob and
 * cameras. Each frame, an mr_stage turns the particles' positions (world
 * ids index them: scene particles first, then control points) into a draw
 * list of poses: this is all the renderer (mr_render.h) ever sees, so the
 * renderer never links the physics and the physics never links GL.
 *
 * Manners as elsewhere: definition structs from default makers, one
 * prefix, no printing, no aborting. */
#ifndef MR_STAGE_H
#define MR_STAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "mr_def.h"
#include "mr_pose.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { MR_STAGE_NAME_MAX = 48, MR_STAGE_PATH_MAX = 512 };
/* How far the stage's front edge stands in front of the proscenium's
 * plane, m (see mr_stage_def's set). */
#define MR_SET_APRON 0.35f
/* The proscenium's opening and plane when nothing sized them (m). */
#define MR_SET_WIDTH  3.0
#define MR_SET_HEIGHT 2.2
#define MR_SET_FRONT  1.0

/* Where an item starts in its scene file (0, 0: not from a file). */
typedef struct mr_stage_pos {
  int line, column;
} mr_stage_pos;

/* A surface. base_color and roughness are the metal-rough model (glTF);
 * a Phong material (OBJ, 3DS, FBX) is kept as diffuse -> base_color and
 * shininess s -> roughness sqrt(2 / (s + 2)). Colours are linear RGB(A). */
typedef struct mr_material_def {
  uint32_t cookie;     /* MR_DEF_COOKIE, set by mr_default_material_def() */
  float base_color[4]; /* default (0.8, 0.8, 0.8, 1) */
  float roughness;     /* 0..1, default 0.6 */
  float metallic;      /* 0..1, default 0 */
  float emissive[3];   /* default 0 */
} mr_material_def;
mr_material_def mr_default_material_def(void);

/* The mesh a model draws: a file through the model loader, or a built-in
 * shape of unit size (sphere and capsule radius 0.5; box and cylinder 1 m
 * across; link shapes run from y = 0 to y = 1, see below). */
typedef enum mr_shape {
  MR_SHAPE_FILE = 0,
  MR_SHAPE_SPHERE,
  MR_SHAPE_BOX,
  MR_SHAPE_CYLINDER, /* axis y, from y = 0 to y = 1, radius 0.5 */
  MR_SHAPE_CAPSULE,  /* axis y, from y = 0 to y = 1, radius 0.5, caps inside */
  MR_SHAPE_CONE      /* axis y, base at y = 0, tip at y = 1, radius 0.5 */
} mr_shape;
const char *mr_shape_name(mr_shape s);
int mr_shape_parse(const char *name, mr_shape *out);

/* The paper's display modes (§3.3). */
typedef enum mr_display_mode {
  /* A model at one particle, unturned: its origin on the particle. */
  MR_DISPLAY_PARTICLE = 0,
  /* A model stretched between two particles: its +y axis from y = 0 to
   * y = 1 (after placement) is laid from the first particle to the second,
   * and scaled along y to their distance; x and z keep their size. */
  MR_DISPLAY_LINK,
  /* A model oriented by three particles (a rigid group). */
  MR_DISPLAY_RIGID,
  /* A skinned mesh deformed by many particles (linear blend skinning). */
  MR_DISPLAY_FREEFORM
} mr_display_mode;
const char *mr_display_mode_name(mr_display_mode m);
int mr_display_mode_parse(const char *name, mr_display_mode *out);

/* How a rigid-group model is turned (§3.3). */
typedef enum mr_rigid_orient {
  /* From the three particles' configuration: the model's axes are the
   * frame x = unit(p1 - p0), y = unit of p2 - p0 made normal to x,
   * z = x × y, its origin on p0. The model is authored in that frame. */
  MR_RIGID_CONFIGURATION = 0,
  /* From the initial orientation: the model is placed in world
   * coordinates at the start and moves with the rotation and translation
   * that take the three particles' start frame to their frame now. */
  MR_RIGID_INITIAL
} mr_rigid_orient;

enum { MR_STAGE_MAX_MATERIALS = 8, MR_SKIN_MAX_INFLUENCES = 4 };

typedef struct mr_model_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_model_def() */
  char name[MR_STAGE_NAME_MAX];
  mr_shape shape;
  char path[MR_STAGE_PATH_MAX];       /* MR_SHAPE_FILE: the model file, as the
                                   scene resolved it (host/scenes/FORMAT.md,
                                   "Where models are found") */
  char looked[2 * MR_STAGE_PATH_MAX]; /* when no place had the file: the
                                         places tried after path, ", "-
                                         separated (else empty) */
  /* Placement, applied to the mesh at load: scale first, then the turn,
   * then the move. */
  double scale[3]; /* default (1, 1, 1) */
  mr_pose place;   /* default identity */
  /* The materials it can wear; materials[0] at the start. None: the
   * file's own materials (a shape then wears the default material). The
   * material worn can change while the show runs (mr_stage_set_material). */
  mr_material_def materials[MR_STAGE_MAX_MATERIALS];
  int n_materials;
  mr_display_mode display;
  int particles[3]; /* world ids: PARTICLE [0], LINK [0] [1], RIGID [0..2] */
  mr_rigid_orient orient;
  /* FREEFORM: the particles the mesh follows (world ids) and where they
   * were when the mesh was placed (3 n, world coordinates): each vertex is
   * bound at load to at most `influences` of the nearest, weighted by
   * distance (mr_stage_skin_bind). The mesh's placement is in world
   * coordinates. Both arrays belong to the def's owner. */
  const int *bones;
  const double *bones_rest;
  int n_bones;
  int influences;   /* 1..MR_SKIN_MAX_INFLUENCES, default 4 */
  bool cast_shadow; /* default true */
  /* A collision sphere (`stage: spheres`): drawn only while the stage
   * shows them (show_spheres, mr_stage_show_spheres). Default false. */
  bool collision;
  mr_stage_pos pos;
} mr_model_def;
mr_model_def mr_default_model_def(void);

typedef struct mr_spot_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_spot_def() */
  double position[3], target[3];
  double angle_deg; /* half-angle of the cone, default 25 */
  float color[3];   /* default white */
  double intensity; /* default 1 */
  mr_stage_pos pos;
} mr_spot_def;
mr_spot_def mr_default_spot_def(void);

enum { MR_STAGE_MAX_SPOTS = 8, MR_STAGE_MAX_CAMERAS = 8 };

typedef struct mr_lights_def {
  float ambient[3];     /* default (0.25, 0.25, 0.3) at noon; the day knob dims it */
  float sun_color[3];   /* default (1, 0.96, 0.9) */
  double sun_intensity; /* default 1 */
  bool shadows;         /* the sun casts shadows through a shadow map; default true */
  /* Shadow map texels a side; 0 (default): sized to the frame, the
   * smallest power of two at least half its longer side, 256 to 2048. */
  int shadow_size;
  /* Reads of the shadow map a pixel (each a bilinear 2 x 2 compare): 1, 4
   * or 9; 0 (default): 9 where a GPU draws, 1 in software. */
  int shadow_filter;
  mr_spot_def spots[MR_STAGE_MAX_SPOTS];
  int n_spots;
} mr_lights_def;

/* A camera the scene names: `marionette render --camera NAME`, and the
 * window's number keys. */
typedef struct mr_camera_def {
  uint32_t cookie; /* MR_DEF_COOKIE, set by mr_default_camera_def() */
  char name[MR_STAGE_NAME_MAX];
  double position[3], target[3];
  double fov_deg; /* vertical, default 45 */
  mr_stage_pos pos;
} mr_camera_def;
mr_camera_def mr_default_camera_def(void);

/* How a control frame is drawn. */
typedef enum mr_frame_style {
  /* A wooden control, as a puppeteer holds one (the paper's Fig. 2, 3
   * and 8): the scene (host/scene) lays a bar, a link-mode capsule
   * frame_thickness across, along each edge of the tree that joins the
   * frame's points by the least wood (mr_frame_bars); the stage draws no
   * lines for it. */
  MR_FRAMES_SOLID = 0,
  /* Thin lines between its points, in order, closed round. */
  MR_FRAMES_WIRE
} mr_frame_style;
const char *mr_frame_style_name(mr_frame_style s);
int mr_frame_style_parse(const char *name, mr_frame_style *out);

/* The bars of a wooden control through n points (3 n): the tree joining
 * them whose bars are shortest in all (Prim's; a tie goes to the lower
 * index), so a bar never doubles another. Writes n - 1 pairs of local
 * indices into pairs (2 (n - 1)) and returns how many: 0 for n < 2, -1
 * out of memory. */
int mr_frame_bars(const double *xyz, int n, int *pairs);

/* A star of the night sky: a direction (need not be unit; y up) and a
 * brightness 0..1. */
typedef struct mr_star {
  float dir[3];
  float brightness;
} mr_star;

/* The front curtain (`stage: curtain:`): two halves of red velvet, hung
 * just upstage of the stage's front edge across the opening, that part
 * and gather to the sides as the show starts and close over its last
 * seconds. How open it is is a pure function of the show's time
 * (mr_curtain_openness), so a frame drawn alone (`marionette render
 * --frame T`) shows what the same moment of a run shows. */
typedef struct mr_curtain_def {
  bool show;       /* default true */
  float color[3];  /* linear RGB, default a deep red (0.42, 0.02, 0.04) */
  double open_s;   /* seconds it takes to open from t = 0, default 1.5 */
  double close_s;  /* seconds it takes to close before the show's end, default 1.5 */
  double distance; /* m in front of the stage's middle, towards the audience
                       (camera.facing); 0 (default): just upstage of the
                       floor's front edge, and no nearer the audience's
                       camera than 40 % of its distance to what it looks at */
  double width;    /* m across; 0 (default): a little wider than the
                       audience's view where it hangs (open, its gathered
                       halves frame the picture's sides), at most the
                       floor's size (8 m without one) */
  double height;   /* m from the floor up; 0 (default): past the top of the
                       audience's view where it hangs, at least 2.4 m */
} mr_curtain_def;

/* The follow spot (`stage: follow_spot:`): a spot hung in front of and
 * above the stage that aims, every frame, at the middle of the box
 * around the puppets' points (the points their models are drawn on,
 * without the control bars'). Aimed anew each frame from the frame's
 * points alone, it is reproducible like the curtain. It takes one of
 * the MR_STAGE_MAX_SPOTS slots. */
typedef struct mr_follow_spot_def {
  bool show;          /* default false: its moving pool is lit again every
                         frame, which software GL pays for */
  double position[3]; /* where it hangs in the audience's frame (turned by
                         camera.facing): x to their right, y up, z towards
                         them; default (0, 3.2, 4) */
  double angle_deg;   /* half-angle of its cone, default 8 */
  float color[3];     /* default a warm white (1, 0.93, 0.8) */
  double intensity;   /* default 1.5 */
} mr_follow_spot_def;

typedef struct mr_stage_def {
  uint32_t cookie;      /* MR_DEF_COOKIE, set by mr_default_stage_def() */
  mr_model_def *models; /* belongs to the def's owner */
  size_t n_models;
  mr_lights_def lights;
  /* Scenery: a floor at floor_height (boards of board_width, each a tone
   * between floor_color and floor_color2, floor_size m a side) and a
   * backdrop wall behind the stage. */
  bool floor;          /* default true */
  double floor_height; /* default 0 */
  double floor_size;   /* default 8 */
  float floor_color[3], floor_color2[3];
  bool backdrop;            /* default true */
  double backdrop_distance; /* m behind the origin along -z, default 3 */
  float backdrop_color[3];
  /* The theater's set, drawn with the scenery (and kept with it where
   * that is kept): built-in boxes and spheres made in C (set.c). It stands
   * on the floor, turned to face the audience (facing_deg). The
   * proscenium is an arch around the stage's opening, set_width x
   * set_height m, its middle set_middle m to the audience's right of the
   * origin, its plane set_front m in front of the origin; the stage's
   * front edge is MR_SET_APRON m in front of it, and the boards end there
   * (the footlights stand along it). 0 (the
   * default) for the size or the plane: from the show (a scene sizes
   * them so that the opening holds every puppet and bar over the whole
   * show; with nothing sized, 3 x 2.2 m at 1 m). */
  bool proscenium;           /* default true */
  float proscenium_color[3]; /* default dark red */
  float trim_color[3];       /* the arch's edging, default gold */
  double set_width, set_height, set_front, set_middle;
  bool wings;          /* two pairs of legs (flats) either side, behind the arch; default true */
  float wing_color[3]; /* default near black */
  /* A row of small lamps along the stage's front edge, glowing, and a
   * warm light from them (a line light at the row) on what is above. */
  bool footlights;            /* default true */
  float footlight_color[3];   /* default warm (1, 0.72, 0.42) */
  double footlight_intensity; /* default 1 */
  bool bridge;        /* the puppeteer's walkway, above and behind the backdrop; default false */
  double board_width; /* the floor's boards, m across, default 0.16 */
  /* Day and night (§3.3: "day can turn into night at the turn of a knob").
   * time_of_day 0..1: 0 and 1 midnight, 0.5 noon. It sets the sun's
   * height, the sky's colour between sky_day and sky_night, and how
   * bright the stars are. */
  double time_of_day; /* default 0.5 */
  float sky_day[3], sky_night[3];
  /* The constellations: the scene's, or none (n_stars 0, stars true): the
   * built-in ones (mr_stage_builtin_stars). */
  bool stars;               /* default true */
  const mr_star *star_list; /* belongs to the def's owner */
  size_t n_stars;
  /* Rigging: strings as thin lines from their control point to their
   * particle, and each control frame (frame_style below). */
  bool show_strings; /* default true */
  float string_color[3];
  const int *strings; /* 2 n_strings world ids: from, to */
  size_t n_strings;
  bool show_frames; /* default true */
  float frame_color[3];
  const int *frame_points; /* per control frame, its points' world ids,
                              frame_point_count[k] of them in order */
  const int *frame_point_count;
  size_t n_frames;
  /* Puppets that read as puppets: the frames' look (default solid, bars
   * frame_thickness m across, default 0.025, wearing frame_color as
   * rough wood), and the collision spheres (models marked collision),
   * drawn only when asked (default false). */
  mr_frame_style frame_style;
  double frame_thickness;
  bool show_spheres;
  /* Cameras: the orbit camera's start, and the scene's named ones. */
  double orbit_target[3];                        /* default (0, 0.6, 0) */
  double orbit_distance;                         /* default 2.5 */
  double orbit_azimuth_deg, orbit_elevation_deg; /* default 0, 12 */
  double fov_deg;                                /* default 45 */
  /* `camera: follow`: the orbit's target follows the middle of the
   * puppets' and bars' box, critically damped (mr_follow), default false. */
  bool follow;
  /* `camera.facing`: the side the puppets face at their start, degrees
   * about +y from +z; the audience's camera sits there. Default 0. */
  double facing_deg;
  mr_camera_def cameras[MR_STAGE_MAX_CAMERAS];
  int n_cameras;
  /* The front curtain and the follow spot (the moving part of the set). */
  mr_curtain_def curtain;
  mr_follow_spot_def follow_spot;
  /* The picture (the scene's `stage.size`): default 1280 x 720. */
  int width, height;
  mr_stage_pos pos;
} mr_stage_def;
mr_stage_def mr_default_stage_def(void);

/* The orbit camera: it looks at a target from `distance` metres, standing
 * at an azimuth about the vertical (0 looks from +z towards -z, the
 * backdrop) and an elevation above the target. The window drags and
 * zooms it; leaving a scene's camera starts it where that camera stood. */
typedef struct mr_orbit {
  double target[3], distance, azimuth_deg, elevation_deg;
  double fov_deg; /* vertical */
} mr_orbit;
/* The stage's own orbit (its orbit_* and fov_deg). */
mr_orbit mr_orbit_of_stage(const mr_stage_def *def);
/* The orbit whose eye is where camera c stands, looking at its target;
 * start untouched when the two coincide (no direction to stand in). */
mr_orbit mr_orbit_of_camera(const mr_camera_def *c, const mr_orbit *start);
/* Turned by d_azimuth, d_elevation degrees: the azimuth wraps at 360, the
 * elevation stays within +-89 (the view never flips over the top). */
void mr_orbit_turn(mr_orbit *o, double d_azimuth_deg, double d_elevation_deg);
/* Each step 10 % nearer (positive, the wheel up) or farther, from 5 cm to
 * 100 m. */
void mr_orbit_zoom(mr_orbit *o, double steps);
/* Where the eye stands. */
void mr_orbit_eye(const mr_orbit *o, double eye[3]);

/* Where p falls in the picture of a camera at eye looking at target (up
 * +y, vertical field of view fov_deg, width / height = aspect), as the
 * renderer projects it: ndc in -1..1 across the view, x to the right, y
 * up. Returns p's depth in front of the eye (m); ndc is meaningless when
 * that is not above 0. */
double mr_view_project(const double eye[3], const double target[3], double fov_deg, double aspect,
                       const double p[3], double ndc[2]);

/* A critically damped follower (`camera: follow`): pos is pulled towards
 * a goal with time constant `time` s and never overshoots a goal that
 * stands still; its velocity never jumps, so a camera on it does not
 * jitter with the goal. mr_follow_step advances it by dt exactly (the
 * closed form for a goal held over dt); the first step jumps to the goal. */
typedef struct mr_follow {
  double pos[3], vel[3];
  double time; /* s, default MR_FOLLOW_TIME */
  bool started;
} mr_follow;
#define MR_FOLLOW_TIME 0.3
mr_follow mr_follow_start(double time);
void mr_follow_step(mr_follow *f, const double goal[3], double dt);
/* The middle of the box around n points (3 n), what `camera: follow`
 * follows; (0, 0, 0) for none. */
void mr_box_middle(const double *xyz, size_t n, double mid[3]);

/* The on-screen display (the window's overlay): at most MR_OSD_ROWS lines
 * of MR_OSD_COLUMNS characters, in a monospaced font MR_OSD_FONT_PX(height)
 * pixels high, in the picture's bottom left corner over a translucent box.
 * mr_osd_rect gives that box for rows lines of at most columns characters
 * in a picture width x height: x, y (top), w, h in pixels, y down. The
 * renderer draws it there; the audience's camera frames the show clear
 * of it. */
enum { MR_OSD_ROWS = 5, MR_OSD_COLUMNS = 44 };
double mr_osd_font_px(int height);
void mr_osd_rect(int width, int height, int rows, int columns, double rect[4]);

/* The built-in constellations: a few recognisable patterns and a field of
 * faint stars, fixed (no randomness at run time), so frames are
 * reproducible. */
const mr_star *mr_stage_builtin_stars(size_t *count);

/* The star at azimuth (degrees from straight ahead, -z, towards +x) and
 * elevation (degrees above the horizon; 90 overhead): a unit direction,
 * brightness clamped to 0..1. The scene's constellations use it. */
mr_star mr_stage_star_at(double azimuth_deg, double elevation_deg, double brightness);

/* ------------------------------------------------------------ draw list */

/* One model drawn: its mesh as loaded (placement applied), scaled in its
 * own axes, then moved by pose. */
typedef struct mr_draw_item {
  int model; /* index into the stage's models */
  mr_pose pose;
  double scale[3];
  int material; /* index into the model's materials; -1: the file's own */
} mr_draw_item;

/* A freeform model's bones this frame: bone i moves the points bound to
 * it by pose[i] (world at rest -> world now), and the vertices blend the
 * moves by their weights. */
typedef struct mr_draw_skin {
  int model;
  const mr_pose *bones;
  int n_bones;
  int material;
} mr_draw_skin;

typedef struct mr_draw_line {
  double a[3], b[3];
  float rgb[3];
} mr_draw_line;

/* The follow spot this frame: on (its def's show, and points to aim
 * at), where it stands and the point it aims at, world coordinates. */
typedef struct mr_draw_follow_spot {
  bool on;
  double position[3], target[3];
} mr_draw_follow_spot;

typedef struct mr_draw_list {
  const mr_draw_item *items;
  size_t n_items;
  const mr_draw_skin *skins;
  size_t n_skins;
  const mr_draw_line *lines; /* strings and control frames */
  size_t n_lines;
  /* How far the curtain is closed this frame, 1 - its openness
   * (mr_stage_set_time): 0 open (a stage not told the time, and a list
   * made by hand and zeroed), 1 closed. */
  double curtain_closed;
  mr_draw_follow_spot follow_spot;
} mr_draw_list;

/* ------------------------------------------------------ curtain and spot */

/* How open the curtain is at show time t of a show that ends at `end`
 * (end < 0 or not finite: not known, a live show still running): 0
 * before the show (t <= 0), opening over the first open_s seconds to 1,
 * and closing over the last close_s seconds before end to 0 at end and
 * after, each with a smooth start and stop (3x^2 - 2x^3). When opening
 * and closing overlap (a show shorter than open_s + close_s) the lesser
 * wins. A curtain not shown is always open (1). */
double mr_curtain_openness(const mr_curtain_def *c, double t, double end);

/* Where the curtain hangs: its bottom middle (on the floor), the unit
 * axis across it to the audience's right, the unit normal towards the
 * audience, its width and height (def's, or the defaults worked out
 * from the floor and the audience's orbit camera). */
typedef struct mr_curtain_place {
  double origin[3], right[3], normal[3];
  double width, height;
} mr_curtain_place;
mr_curtain_place mr_curtain_place_of(const mr_stage_def *def);

/* Where the follow spot hangs, in world coordinates. */
void mr_follow_spot_position(const mr_stage_def *def, double out[3]);

/* ---------------------------------------------------------------- stage */

typedef enum mr_stage_status {
  MR_STAGE_OK = 0,
  MR_STAGE_ERR_ARG = -1,   /* NULL, def not from its maker, a world id out of range */
  MR_STAGE_ERR_VALUE = -2, /* NaN or coincident particles where a frame is needed */
  MR_STAGE_ERR_NOMEM = -3
} mr_stage_status;

typedef struct mr_stage mr_stage;

/* A stage for def over n points whose start positions are rest_xyz (3 n):
 * the rest frames of rigid groups and skins are taken from them. def is
 * copied, with every array it points to. msg names what is wrong. */
mr_stage_status mr_stage_create(const mr_stage_def *def, const double *rest_xyz, size_t n,
                                mr_stage **out, char *msg, size_t msg_size);
void mr_stage_destroy(mr_stage *s);
const mr_stage_def *mr_stage_get_def(const mr_stage *s);

/* The draw list for points at xyz (3 n, the same n as at create). The list
 * and what it points to belong to the stage and stay valid until the next
 * call. Points that are not finite leave their models where they were
 * last drawn, so a bad frame never reaches the GPU. */
mr_stage_status mr_stage_update(mr_stage *s, const double *xyz, size_t n, const mr_draw_list **out);

/* The collision spheres (models marked collision) drawn from the next
 * draw list on, or not. */
mr_stage_status mr_stage_show_spheres(mr_stage *s, bool show);
/* The show's time t (s) and its end (s; < 0: not known yet) for the next
 * draw lists (and the current one): the curtain's openness,
 * mr_curtain_openness. A live show that is asked to stop gives as end
 * the moment its curtain will have closed. */
mr_stage_status mr_stage_set_time(mr_stage *s, double t, double end);

/* Model `model` wears its material k from now on (§3.3). */
mr_stage_status mr_stage_set_material(mr_stage *s, size_t model, int k);

/* Binds n_vertices vertices (3 n, world coordinates at rest) to the n_bones
 * bones at bones_rest (3 n_bones): per vertex, the `influences` nearest
 * bones, weighted by inverse square distance and normalised to sum 1 (a
 * vertex on a bone takes it alone). Writes influences entries per vertex
 * into index and weight (unused entries: index 0, weight 0). */
mr_stage_status mr_stage_skin_bind(const float *vertices, size_t n_vertices,
                                   const double *bones_rest, int n_bones, int influences,
                                   int *index, float *weight);

#ifdef __cplusplus
}
#endif

#endif /* MR_STAGE_H */
