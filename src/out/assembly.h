/*
 * assembly.h: what the files of the assembly guide (--assembly) share,
 * private to src/out: the model drawn, every piece's faces with their
 * edges told apart and the seams' places (assembly_model.c); the four
 * views of it, what each shows and where (assembly_view.c); and the
 * picture, labels and files (assembly.c).
 */
#ifndef UNROLL_OUT_ASSEMBLY_H
#define UNROLL_OUT_ASSEMBLY_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/out.h"

/* The picture in pixels of the PNG (the PDF draws the same, scaled to its page). */
enum {
    CELL = 1150,  /* one view's square */
    MARGIN = 24,  /* round and between the views */
    HEADER = 184, /* title, key and swatches above the views */
    CAPTION = 44, /* a view's caption, at the top of its square */
    INSET = 16,   /* between a view's square and its drawing */
    COLUMNS = 2,
    ROWS = 2,
    VIEWS = COLUMNS * ROWS,
    CANVAS_WIDTH = COLUMNS * CELL + (COLUMNS + 1) * MARGIN,
    CANVAS_HEIGHT = HEADER + ROWS * CELL + ROWS * MARGIN,
    NAME_SIZE = 24, /* a piece's name, pixels */
};

/* No face (of a view, or at a place). */
#define NO_FACE ((size_t)-1)

/* ---- The model (assembly_model.c) ---------------------------------------- */

typedef struct face {
    ur_vec3 corner[3];
    ur_vec3 normal; /* unit, toward the outside */
    size_t piece;
    unsigned char border; /* bit k: the edge from corner k to k + 1 is on its piece's outline */
    unsigned char fold;   /* bit k: that edge is a fold inside the piece */
} face;

/* Where a seam is: the middle of its run, by length, in 3D. */
typedef struct seam_mark {
    int seam;
    ur_vec3 point;
} seam_mark;

typedef struct model {
    face *faces;
    size_t face_count;
    size_t piece_count;   /* the nets, drawn or not */
    size_t pieces_drawn;  /* nets with faces */
    bool *outlined;       /* per piece: its net has faces and its outline in 3D */
    const char **names;   /* per piece, borrowed */
    double (*colours)[3]; /* per piece, sRGB 0..1 */
    seam_mark *seams;
    size_t seam_count;
    bool closed; /* every edge has a face on both sides */
    ur_vec3 centre;
    double size; /* the diagonal of the box round it */
} model;

/*
 * The model of the nets' faces (the nets with none are not drawn but keep
 * their colour), their edges marked, the seams placed and the pieces'
 * colours chosen.  UR_ERROR_INPUT when no net has a face; free with
 * assembly_model_free, whole or not.
 */
ur_status assembly_model_build(const ur_net_list *nets, const ur_assembly_options *options,
                               model *m, ur_error *error);
void assembly_model_free(model *m);

/* ---- The views (assembly_view.c) ----------------------------------------- */

typedef struct camera {
    const char *caption;
    ur_vec3 toward; /* from the model to the viewer, unit */
    ur_vec3 right, up;
} camera;

/* The faces drawn in a view, indexed by where they fall on it. */
typedef struct grid {
    double left, top, cell; /* pixels */
    size_t columns, rows;
    size_t *start; /* columns * rows + 1: the faces of cell c are faces[start[c] .. start[c + 1]) */
    size_t *faces;
} grid;

typedef struct view {
    camera camera;
    double left, top, width, height; /* the drawing area, pixels */
    double scale;                    /* pixels a model unit */
    ur_vec2 middle;                  /* the model point drawn at the area's middle (view plane) */
    ur_vec2 (*points)[3];            /* per face: its corners on the picture */
    double (*depth)[3];              /* per face: its corners' depths, larger nearer */
    size_t *order;                   /* the faces drawn, far to near */
    size_t drawn;
    grid grid;
    double *seen_area;   /* per piece: pixels^2 seen */
    ur_vec2 *name_point; /* per piece: where its name goes */
} view;

/*
 * The four views in their squares of the picture, at one scale: the faces
 * drawn far to near, indexed, and what each shows of each piece.  Free
 * each with assembly_view_free, whole or not.
 */
ur_status assembly_views_prepare(view views[VIEWS], const model *m, bool y_up, ur_error *error);
void assembly_view_free(view *v);

/* Where a model point is drawn in the view, and its depth (larger nearer the viewer). */
ur_vec2 assembly_picture_point(const view *v, const model *m, ur_vec3 p);
double assembly_depth(const view *v, const model *m, ur_vec3 p);

/*
 * Whether the model point drawn at q with that depth is in sight: no face
 * drawn over q lies nearer the viewer by more than tolerance.
 */
bool assembly_in_sight(const view *v, ur_vec2 q, double depth, double tolerance);

/* Whether the face turns toward the viewer. */
bool assembly_faces_viewer(const view *v, const face *f);

/* The area of a triangle on the picture, pixels^2. */
double assembly_face_area(const ur_vec2 p[3]);

#endif
