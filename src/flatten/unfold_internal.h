/*
 * unfold_internal.h: what the files of the exact unfolding share: the
 * mesh's edges with their bends and what may never be folded
 * (unfold_edges.c), its flat faces laid in their planes (unfold_faces.c),
 * how two flat triangles touch and a hash grid to find the triangles of a
 * piece near a point (unfold_contact.c), joining two pieces across an edge
 * (unfold_lay.c), whether a piece fits the room (unfold_room.c), one run
 * of joins in a given order (unfold.c), the search over orders
 * (unfold_search.c) and turning the pieces into outlines and folds
 * (unfold_piece.c).
 */
#ifndef UNROLL_UNFOLD_INTERNAL_H
#define UNROLL_UNFOLD_INTERNAL_H

#include "unroll/flatten.h"

#include <geos_c.h>

/*
 * Flat points closer than this fraction of the mesh's size meet: edges
 * that land within it of each other are joined, triangles that come within
 * it touch.  Coordinates read from files are often 32-bit floats (7
 * digits), so that the triangles round a flat vertex or along a straight
 * crease of a modelled mesh close up only to about 1e-7 of its size; a
 * millionth is still far below what a cutter can tell (0.1 um on 100 mm).
 */
#define UNFOLD_CONTACT 1e-6

/* No piece, no corner, no entry. */
#define UNFOLD_NONE ((size_t)-1)

/* Half-edge k of triangle t runs from corner k to corner k + 1 and is numbered 3 t + k. */
static inline size_t unfold_next(size_t half)
{
    return half - half % 3 + (half % 3 + 1) % 3;
}

static inline size_t unfold_previous(size_t half)
{
    return half - half % 3 + (half % 3 + 2) % 3;
}

static inline size_t unfold_from(const ur_mesh *mesh, size_t half)
{
    return mesh->triangles[half / 3][half % 3];
}

static inline size_t unfold_to(const ur_mesh *mesh, size_t half)
{
    return mesh->triangles[half / 3][(half % 3 + 1) % 3];
}

static inline double unfold_edge_length(const ur_mesh *mesh, size_t half)
{
    return ur_vec3_distance(mesh->vertices[unfold_from(mesh, half)],
                            mesh->vertices[unfold_to(mesh, half)]);
}

/*
 * The box round points, as ur_box_of_points but inline: the runs of the
 * search take the box of every triangle they move or test, and a call per
 * point and per min and max was a tenth of their time.  (Points are
 * finite, so a comparison picks what fmin and fmax would.)
 */
static inline ur_box unfold_box_of(const ur_vec2 *points, size_t count)
{
    ur_box box = {{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
    for (size_t i = 0; i < count; i++) {
        ur_vec2 p = points[i];
        box.min.x = p.x < box.min.x ? p.x : box.min.x;
        box.min.y = p.y < box.min.y ? p.y : box.min.y;
        box.max.x = p.x > box.max.x ? p.x : box.max.x;
        box.max.y = p.y > box.max.y ? p.y : box.max.y;
    }
    return box;
}

/*
 * hypot(x, y) <= limit, asked of nearly every pair of points and every
 * join the search tries: the squares decide unless they are within
 * rounding of the limit, where hypot (what ur_vec2_distance uses) has the
 * last word, so that the answer is always hypot's.
 */
static inline bool unfold_hypot_within(double x, double y, double limit)
{
    double squared = x * x + y * y, limit_squared = limit * limit;
    if (squared < limit_squared * (1 - 1e-9))
        return true;
    if (squared > limit_squared * (1 + 1e-9))
        return false;
    return hypot(x, y) <= limit;
}

/* ur_vec2_distance(a, b) <= limit. */
static inline bool unfold_within(ur_vec2 a, ur_vec2 b, double limit)
{
    return unfold_hypot_within(a.x - b.x, a.y - b.y, limit);
}

/* The mesh's edges, per half-edge. */
typedef struct unfold_edges {
    size_t *twins; /* ur_mesh_twins */
    double *bend;  /* signed turn of the surface across the edge: > 0 convex, 0 on the boundary */
    bool *cut;     /* never folded: the boundary, a group boundary, a user seam */
    double scale;  /* the diagonal of the mesh's bounding box */
    double mean_edge;
} unfold_edges;

/*
 * Checks the mesh (see ur_unfold for what is refused), pairs its edges and
 * measures their bends.  Free with unfold_edges_free, also on failure.
 */
ur_status unfold_edges_build(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                             unfold_edges *edges, ur_error *error);
void unfold_edges_free(unfold_edges *edges);

/*
 * The flat faces: per triangle its face (the number of the face's first
 * triangle) and its corners in the face's plane, every face's points
 * projected on one plane so that its triangles meet exactly.  flat[h]:
 * half-edge h draws no fold when joined (inside a face, or turning less
 * than the flat angle).  slack: the most an edge's length changes by the
 * projection.
 */
typedef struct unfold_faces {
    size_t *face;
    ur_vec2 (*home)[3];
    bool *flat;
    double slack;
    size_t *order; /* the edges inside faces (lower halves) in the order to join them */
    size_t order_count;
} unfold_faces;

ur_status unfold_faces_build(const ur_mesh *mesh, const unfold_edges *edges, double flat_angle,
                             unfold_faces *faces, ur_error *error);
void unfold_faces_free(unfold_faces *faces);

/*
 * How a candidate triangle t touches a laid one q, both counter-clockwise:
 * overlap when their interiors overlap deeper than eps; otherwise the bits
 * of t_near (q_near) are the corners of t (q) within eps of the other
 * triangle.  Where two triangles touch without overlapping, the contact is
 * a point or a segment whose ends are among those corners.
 */
typedef struct unfold_contact {
    bool overlap;
    unsigned t_near, q_near;
} unfold_contact;

unfold_contact unfold_triangle_contact(const ur_vec2 t[3], const ur_vec2 q[3], double eps);

/*
 * How far apart segments ab and cd are (they do not cross), and their
 * nearest points.
 */
double unfold_edge_gap(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d, ur_vec2 *on_ab, ur_vec2 *on_cd);

/* Whether p is within eps of the counter-clockwise triangle q (or inside it). */
bool unfold_point_near_triangle(ur_vec2 p, const ur_vec2 q[3], double eps);

/*
 * The triangles of every piece, bucketed by piece and by the square cells
 * their boxes cover (cells of about a mean edge, hashed into slots), so
 * that a join looks at the triangles near the moved ones only.  A triangle
 * is added again under its new piece when it moves; an entry whose
 * triangle has left its piece is stale and skipped.  A triangle whose box
 * covers many cells is kept on its piece's list of big ones, which every
 * query reads.
 */
typedef struct unfold_grid_slot {
    size_t head;  /* the first entry */
    size_t stamp; /* the run head belongs to (else the slot is empty) */
} unfold_grid_slot;

/* What a query reads of an entry side by side: one cache line, not three arrays. */
typedef struct unfold_grid_entry {
    size_t item; /* a triangle */
    size_t piece;
    size_t next; /* the next in its slot */
} unfold_grid_entry;

typedef struct unfold_grid {
    double cell;
    size_t mask; /* slots - 1, a power of two less one */
    unfold_grid_slot *slots;
    size_t stamp; /* the run */
    unfold_grid_entry *entries;
    size_t entry_count, entry_capacity;
    size_t *seen; /* per triangle: the last query that found it */
    size_t query;
    size_t *found; /* what the last query found */
    size_t found_count;
} unfold_grid;

ur_status unfold_grid_init(unfold_grid *grid, size_t triangle_count, double cell, ur_error *error);
void unfold_grid_free(unfold_grid *grid);

/* Empties the grid for a new run. */
void unfold_grid_restart(unfold_grid *grid);

ur_status unfold_grid_add(unfold_grid *grid, ur_box box, size_t piece, size_t triangle,
                          ur_error *error);

/*
 * Fills grid->found with every triangle of the piece (piece_of[t] ==
 * piece) whose box may meet box, once each; false when the box covers too
 * many cells, and the caller reads the piece's triangles itself.
 */
bool unfold_grid_query(unfold_grid *grid, ur_box box, size_t piece, const size_t *piece_of);

/* p -> to + R (p - from), R the turn by (cos, sin). */
typedef struct unfold_motion {
    double cos, sin;
    ur_vec2 from, to;
} unfold_motion;

static inline ur_vec2 unfold_move(const unfold_motion *m, ur_vec2 p)
{
    ur_vec2 d = ur_vec2_sub(p, m->from);
    return ur_vec2_add(m->to,
                       ur_vec2_make(m->cos * d.x - m->sin * d.y, m->sin * d.x + m->cos * d.y));
}

/* A circle: round a piece, not the least one, kept as pieces join at no cost. */
typedef struct unfold_circle {
    ur_vec2 center;
    double radius;
} unfold_circle;

/* A piece of a run: its triangles in a list through unfolder.next_member. */
typedef struct unfold_island {
    size_t first, last;
    size_t triangle_count;
    size_t outline_count; /* half-edges not joined */
    ur_vec2 *hull;        /* its convex hull, counter-clockwise, when the room is limited */
    size_t hull_count, hull_capacity;
    bool hull_set;        /* hull is no longer its first triangle's, as it lay at home (unfold.c) */
    unfold_circle circle; /* round the piece, when the room is limited */
    size_t face_count;    /* flat faces, once the faces are joined (1 before) */
    double area;          /* of its triangles, mm2 */
    /* the piece it last failed to join as the smaller one, that piece's size then, how often */
    size_t failed_with, failed_size, failures;
    uint64_t layout;  /* what the piece is made of (see unfold_lay.c's join_key) */
    size_t lowest;    /* its triangle of the lowest number: where a kept hull is laid from */
    size_t grid_last; /* its last member in the grid (later ones joined since); UNFOLD_NONE: none */
    /* the pieces whose hulls are still to be merged into hull (unfold_lay.c's defer_hull) */
    size_t absorbed_first, absorbed_last;
    size_t absorbed_next;          /* once joined to a larger piece: the next on its list */
    unfold_motion absorbed_motion; /* and the motion that moved it there */
} unfold_island;

/*
 * Two pieces of several faces that failed to join this often, across as
 * many edges, are not tried again while neither changes: two large pieces
 * that do not fit would otherwise be tried across every edge between them.
 * A piece of one face is always tried.
 */
#define UNFOLD_MOST_FAILURES 8

/* The point that m moves to p. */
static inline ur_vec2 unfold_move_back(const unfold_motion *m, ur_vec2 p)
{
    ur_vec2 d = ur_vec2_sub(p, m->to);
    return ur_vec2_add(m->from,
                       ur_vec2_make(m->cos * d.x + m->sin * d.y, -m->sin * d.x + m->cos * d.y));
}

/* How many of the triangles that stopped the last joins are tried first (unfold_lay.c). */
#define UNFOLD_CULPRITS 8

/* The mesh, its edges and faces, and the state of the current run of joins. */
typedef struct unfolder {
    const ur_mesh *mesh;
    const ur_seam *seams; /* the caller's, for a search beside this one (unfold.c) */
    size_t seam_count;
    ur_unfold_options options;
    unfold_edges edges;
    unfold_faces faces;
    double eps;       /* points closer than this meet */
    bool room;        /* options.room_* limit the pieces: hulls are kept */
    bool room_binds;  /* joins that do not fit the room are refused (not inside faces) */
    bool turned_room; /* a piece fits the room at any turn, not only level (unfold_room.c) */
    size_t turnable_refusals; /* 0, or 1 once the level room refused a join it would take turned */
    /*
     * the share of the whole search the part under way reports
     * ("improving"), from..from + span; of which a first part of
     * search_in_two given progress_given steps (0: none) reports in the
     * share unfold_first_part_share gives
     */
    double progress_from, progress_span;
    size_t progress_given;
    /* the run: */
    size_t *piece;      /* per triangle: its piece (an island's number) */
    ur_vec2 (*flat)[3]; /* per triangle: its corners on its piece */
    bool *joined;       /* per half-edge: joined to its twin inside a piece */
    size_t *parent;     /* union-find over corners 3 t + k: the flat vertices of pieces */
    size_t *next_member;
    unfold_island *islands; /* per triangle number: the piece it started */
    unfold_grid grid;
    size_t *nearby; /* a copy of what a grid query found, while the join asks it again */
    size_t *pair_small, *pair_large; /* the half-edges a join joins, in the two pieces */
    size_t pair_count, slit_count;   /* slits follow the pairs */
    bool slits;                      /* allowed: inside faces */
    bool gap_waived;                 /* options.min_gap not kept: single faces joined last */
    size_t gap_breaks;               /* the run's joins made so */
    size_t *roots; /* 2 per pair: the flat vertices it makes one, small's then large's */
    ur_vec2 *hull_points, *hull_chain; /* room for the hull of every corner */
    unfold_circle *home_circles;       /* per triangle: a circle round it as it lies at home */
    size_t culprits[UNFOLD_CULPRITS];  /* the triangles that stopped the last joins */
    size_t blocker;                    /* the large triangle that stopped the last one */
    size_t (*hinge_culprits)[2]; /* per lower half-edge: the two triangles that stopped its join */
    uint64_t *outcomes;       /* joins already judged, by join_key (unfold_lay.c), over all runs */
    uint64_t *hinge_outcomes; /* per lower half-edge: the last join judged or found across it */
    size_t outcome_mask;      /* slots - 1 */
    struct unfold_kept_hull *kept_hulls; /* pieces' hulls by their layout keys, over all runs */
    size_t kept_mask;                    /* slots - 1 */
    /*
     * The last pass of the last run (tabs_to_twins): a join may leave a
     * slit narrower than the gap when both its edges can give their tabs to
     * their twins; per half-edge on an outline, whether it lies in such a
     * slit, so that its seam's tab goes on its twin, which must have the
     * room.
     */
    bool last_run, tabs_to_twins;
    bool *tab_on_twin;
    size_t *slit_sides; /* the half-edges the join under way puts in slits, to mark */
    size_t slit_side_count;
    struct unfold_faces_joined *faces_joined; /* the run's state once its faces are joined */
} unfolder;

/* A well-mixed 64-bit number for x (splitmix64's finisher): keys of triangles and edges. */
static inline uint64_t unfold_mix(uint64_t x)
{
    x ^= x >> 30;
    x *= UINT64_C(0xBF58476D1CE4E5B9);
    x ^= x >> 27;
    x *= UINT64_C(0x94D049BB133111EB);
    x ^= x >> 31;
    return x;
}

/* The layout key of a piece of triangle t alone. */
static inline uint64_t unfold_triangle_key(size_t t)
{
    return unfold_mix(4 * (uint64_t)t + 1);
}

/* Room for the outcomes of joins, the slots of unfolder.outcomes. */
ur_status unfold_outcomes_init(unfolder *u, ur_error *error);

/* Room for the hulls kept over the runs when the room is limited (unfold_lay.c); and its end. */
ur_status unfold_kept_hulls_init(unfolder *u, ur_error *error);
void unfold_kept_hulls_free(unfolder *u);

/* The union-find root of corner c (with path halving). */
size_t unfold_find(unfolder *u, size_t corner);

/*
 * Puts the triangles of piece p in the grid unless they are there: a join
 * whose outcome is remembered (unfold_lay.c) looks at no triangle, so
 * that the pieces are put in the grid when a join first tests them, and
 * the triangles that join a piece in the grid when a join tests it next
 * (of the 2,200 joins a step of the bench's 48 x 24 sphere tries, about
 * 150 are judged; the others are looked up and test nothing).
 * They are put in in the order they joined it, as they were when each
 * join put them in at once, so that a query finds a piece's triangles in
 * the same order: the last run's slits depend on the order of its tests.
 */
ur_status unfold_grid_piece(unfolder *u, size_t p, ur_error *error);

/* Merges the hulls of the pieces joined to piece p into its hull (see unfold_lay.c). */
ur_status unfold_update_hull(unfolder *u, size_t p, ur_error *error);

/* Joins the pieces on either side of half-edge h if they fit together (unfold_lay.c). */
ur_status unfold_try_join(unfolder *u, size_t h, bool *joined, ur_error *error);

/* ---- the room (unfold_room.c) ---- */

/*
 * The convex hull of points (count of them, sorted in place),
 * counter-clockwise, into hull (which may be points); chain: room for
 * count + 1 points.
 */
size_t unfold_hull(ur_vec2 *points, size_t count, ur_vec2 *chain, ur_vec2 *hull);

/* The sides of the smallest rectangle round a convex hull, longer first. */
void unfold_hull_size(const ur_vec2 *hull, size_t count, double *length, double *width);

/* Whether a convex hull fits the room of the options. */
bool unfold_hull_fits(const unfolder *u, const ur_vec2 *hull, size_t count);

/* Whether the hull fits the room at some turn (whatever u->turned_room says). */
bool unfold_hull_fits_turned(const unfolder *u, const ur_vec2 *hull, size_t count);

/* A circle round triangle corners (count of them). */
unfold_circle unfold_circle_round(const unfolder *u, const ur_vec2 *corners, size_t count);

/* A circle round circles a and b. */
unfold_circle unfold_circle_join(const unfolder *u, unfold_circle a, unfold_circle b);

/*
 * Whether whatever lies in the circle fits the room for sure, as
 * unfold_hull_fits would find of its hull: then the hull is not needed.
 */
bool unfold_circle_fits(const unfolder *u, unfold_circle circle);

/* ---- one run (unfold.c) ---- */

/* The outcome of a run, compared: fewer pieces, then fewer of one face, then less cut. */
typedef struct unfold_score {
    size_t pieces, single_face;
    size_t gap_breaks; /* joins made without the options' gap */
    double seam_length;
    double cost; /* the pieces and the gap's breaks, each at options.gap_break_cost */
} unfold_score;

/* What a run costs the maker: a piece, and a seam whose tab may find no room. */
static inline double unfold_score_cost(unfold_score score)
{
    return score.cost;
}

/* -1, 0, 1 as a is better than, as good as or worse than b. */
int unfold_score_compare(unfold_score a, unfold_score b);

/*
 * The faces laid (every triangle a piece, joined across the flat edges
 * inside faces), then the pieces joined across order[0..count) in turn.
 */
ur_status unfold_run(unfolder *u, const size_t *order, size_t count, unfold_score *score,
                     ur_error *error);

/* The half-edge leaving the end of h (arriving at the start of h) on its piece's outline. */
size_t unfold_outline_next(const unfolder *u, size_t h);
size_t unfold_outline_previous(const unfolder *u, size_t h);

/* ---- the search (unfold_search.c) ---- */

/*
 * Improves order (count edges; the best found is left in it) while the
 * budget lasts, then runs it again so that u holds its pieces; *steps the
 * steps done, *best the score of that run.
 */
ur_status unfold_search(unfolder *u, size_t *order, size_t count, size_t *steps, unfold_score *best,
                        ur_error *error);

/* The share of its window a search reports in, its best so far being best (unfold.c). */
double unfold_first_part_share(const unfolder *u, unfold_score best);

/*
 * Turns piece p of the last run into *piece: triangles and their flat
 * corners, the folds, the outline (walked along the edges not joined)
 * checked to be a simple polygon with GEOS, and the areas.  index numbers
 * it in messages.  Frees what it made on failure.
 */
ur_status unfold_piece_build(const unfolder *u, size_t p, size_t index, GEOSContextHandle_t geos,
                             ur_unfolded_piece *piece, ur_error *error);

void unfold_piece_free(ur_unfolded_piece *piece);

#endif
