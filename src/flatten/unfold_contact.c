/*
 * unfold_contact.c: how two flat triangles touch, and the hash grid that
 * finds the triangles of a piece near a new one.
 *
 * Two convex polygons have disjoint interiors exactly when a line
 * separates them, and for polygons one of their edges' lines does
 * (the separating axis theorem).  With a tolerance: the triangles overlap
 * when, along the normal of each of their six edges, their shadows
 * overlap by more than eps; they are apart when along one of them the
 * shadows are more than eps apart.  A thinner overlap is a contact, which unfold.c
 * judges by the corners near the other triangle: the ends of a contact
 * segment are always among them.
 *
 * The grid keeps a join's cost independent of the pieces' sizes: cells of
 * about a mean edge (a triangle covers a few), keyed by piece and cell and
 * hashed into at least eight slots per triangle of the mesh, so that a
 * query reads a few short chains.  Slots remember the run they were filled
 * in, so starting a new run is free.
 */
#include "unfold_internal.h"

#include "../base/tables.h"

#include <stdint.h>
#include <stdlib.h>

/* A triangle whose box covers more cells than this goes on its piece's list of big ones. */
#define BIG_CELLS 64

/* The cell of that list (no box reaches it). */
#define BIG_KEY INT64_MIN

/*
 * How far apart the shadows of t and q are along the normal of edge ab
 * (negative where they overlap).
 */
static double gap_along(ur_vec2 a, ur_vec2 b, const ur_vec2 t[3], const ur_vec2 q[3])
{
    ur_vec2 d = ur_vec2_sub(b, a);
    double length = sqrt(ur_vec2_dot(d, d));
    ur_vec2 normal = ur_vec2_make(-d.y / length, d.x / length);
    double t_low = INFINITY, t_high = -INFINITY, q_low = INFINITY, q_high = -INFINITY;
    for (int k = 0; k < 3; k++) {
        double s = ur_vec2_dot(normal, t[k]), r = ur_vec2_dot(normal, q[k]);
        t_low = s < t_low ? s : t_low;
        t_high = s > t_high ? s : t_high;
        q_low = r < q_low ? r : q_low;
        q_high = r > q_high ? r : q_high;
    }
    double one = q_low - t_high, other = t_low - q_high;
    return one > other ? one : other;
}

static ur_vec2 nearest_on_segment(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    ur_vec2 d = ur_vec2_sub(b, a);
    double squared_length = ur_vec2_dot(d, d);
    if (squared_length == 0) /* a point (the far end of a wedge's side, unfold_lay.c) */
        return a;
    double s = ur_vec2_dot(ur_vec2_sub(p, a), d) / squared_length;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    return ur_vec2_add_scaled(a, d, s);
}

static double squared_segment_distance(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    ur_vec2 e = ur_vec2_sub(p, nearest_on_segment(p, a, b));
    return ur_vec2_dot(e, e);
}

/*
 * Whether p is within eps of the counter-clockwise triangle q (or inside
 * it).  A point more than eps outside the line of an edge is further than
 * eps from the whole triangle, which lies on the line's inner side: most
 * points a join asks about are, and need no distance to a segment.
 */
static bool near_triangle(ur_vec2 p, const ur_vec2 q[3], double eps)
{
    bool inside = true;
    for (int k = 0; k < 3; k++) {
        ur_vec2 a = q[k], d = ur_vec2_sub(q[(k + 1) % 3], a);
        double cross = ur_vec2_cross(d, ur_vec2_sub(p, a));
        if (cross < 0) {
            if (cross * cross > eps * eps * ur_vec2_dot(d, d))
                return false;
            inside = false;
        }
    }
    if (inside)
        return true;
    for (int k = 0; k < 3; k++)
        if (squared_segment_distance(p, q[k], q[(k + 1) % 3]) <= eps * eps)
            return true;
    return false;
}

/*
 * Whether the boxes of t and q are more than eps apart: then so are the
 * triangles, and no corner comes near.  Most of the triangles a join looks
 * at are (it looks as far as the options' gap), and this costs no root.
 */
static bool boxes_apart(const ur_vec2 t[3], const ur_vec2 q[3], double eps)
{
    ur_box a = unfold_box_of(t, 3), b = unfold_box_of(q, 3);
    return a.min.x - b.max.x > eps || b.min.x - a.max.x > eps || a.min.y - b.max.y > eps ||
           b.min.y - a.max.y > eps;
}

unfold_contact unfold_triangle_contact(const ur_vec2 t[3], const ur_vec2 q[3], double eps)
{
    if (boxes_apart(t, q, eps))
        return (unfold_contact){false, 0, 0};
    unfold_contact contact = {true, 0, 0};
    double widest = -INFINITY;
    for (int k = 0; k < 3; k++) {
        double a = gap_along(t[k], t[(k + 1) % 3], t, q);
        double b = gap_along(q[k], q[(k + 1) % 3], t, q);
        widest = a > widest ? a : widest;
        widest = b > widest ? b : widest;
    }
    if (widest > eps) /* apart by more than eps: no corner comes near */
        return (unfold_contact){false, 0, 0};
    if (!(widest >= -eps))
        return contact;
    contact.overlap = false;
    for (int k = 0; k < 3; k++) {
        if (near_triangle(t[k], q, eps))
            contact.t_near |= 1u << k;
        if (near_triangle(q[k], t, eps))
            contact.q_near |= 1u << k;
    }
    return contact;
}

double unfold_edge_gap(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d, ur_vec2 *on_ab, ur_vec2 *on_cd)
{
    /* Segments that do not cross are nearest at an end of one of them. */
    ur_vec2 ends[4] = {a, b, c, d};
    ur_vec2 nearest[4] = {nearest_on_segment(a, c, d), nearest_on_segment(b, c, d),
                          nearest_on_segment(c, a, b), nearest_on_segment(d, a, b)};
    int best = 0;
    double squared[4];
    for (int k = 0; k < 4; k++) {
        ur_vec2 e = ur_vec2_sub(ends[k], nearest[k]);
        squared[k] = ur_vec2_dot(e, e);
        if (squared[k] < squared[best])
            best = k;
    }
    *on_ab = best < 2 ? ends[best] : nearest[best];
    *on_cd = best < 2 ? nearest[best] : ends[best];
    return sqrt(squared[best]);
}

bool unfold_point_near_triangle(ur_vec2 p, const ur_vec2 q[3], double eps)
{
    return near_triangle(p, q, eps);
}

/* ---- the grid ---- */

typedef struct cell_range {
    int64_t x0, y0, x1, y1;
} cell_range;

/* The cells box covers; false when they are more than BIG_CELLS. */
static bool cells_of(const unfold_grid *grid, ur_box box, cell_range *range)
{
    double x0 = floor(box.min.x / grid->cell), x1 = floor(box.max.x / grid->cell);
    double y0 = floor(box.min.y / grid->cell), y1 = floor(box.max.y / grid->cell);
    if (!((x1 - x0 + 1) * (y1 - y0 + 1) <= BIG_CELLS))
        return false;
    *range = (cell_range){(int64_t)x0, (int64_t)y0, (int64_t)x1, (int64_t)y1};
    return true;
}

static size_t slot_of(const unfold_grid *grid, size_t piece, int64_t x, int64_t y)
{
    uint64_t h = (uint64_t)x * UINT64_C(0x9E3779B97F4A7C15) ^
                 (uint64_t)y * UINT64_C(0xC2B2AE3D27D4EB4F) ^
                 (uint64_t)piece * UINT64_C(0x165667B19E3779F9);
    h ^= h >> 29;
    h *= UINT64_C(0xBF58476D1CE4E5B9);
    h ^= h >> 32;
    return (size_t)(h & grid->mask);
}

ur_status unfold_grid_init(unfold_grid *grid, size_t triangle_count, double cell, ur_error *error)
{
    *grid = (unfold_grid){0};
    size_t slots = 64;
    while (slots < 8 * triangle_count)
        slots *= 2;
    grid->cell = cell;
    grid->mask = slots - 1;
    grid->slots = table_alloc(slots, sizeof *grid->slots, error);
    grid->entry_capacity = 8 * triangle_count + 16;
    grid->entries = ur_alloc_array(grid->entry_capacity, sizeof *grid->entries, error);
    grid->seen = ur_alloc_array(triangle_count, sizeof *grid->seen, error);
    grid->found = ur_alloc_array(triangle_count, sizeof *grid->found, error);
    if (!grid->slots || !grid->entries || !grid->seen || !grid->found)
        return UR_ERROR_MEMORY;
    grid->stamp = 1;
    return UR_OK;
}

void unfold_grid_free(unfold_grid *grid)
{
    free(grid->slots);
    free(grid->entries);
    free(grid->seen);
    free(grid->found);
    *grid = (unfold_grid){0};
}

void unfold_grid_restart(unfold_grid *grid)
{
    grid->stamp++;
    grid->entry_count = 0;
}

static ur_status grow_entries(unfold_grid *grid, ur_error *error)
{
    size_t capacity = 2 * grid->entry_capacity;
    unfold_grid_entry *grown = realloc(grid->entries, capacity * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    grid->entries = grown;
    grid->entry_capacity = capacity;
    return UR_OK;
}

static ur_status add_to_cell(unfold_grid *grid, size_t piece, int64_t x, int64_t y, size_t triangle,
                             ur_error *error)
{
    ur_status status =
        grid->entry_count == grid->entry_capacity ? grow_entries(grid, error) : UR_OK;
    if (status != UR_OK)
        return status;
    unfold_grid_slot *slot = &grid->slots[slot_of(grid, piece, x, y)];
    size_t entry = grid->entry_count++;
    if (slot->stamp != grid->stamp) {
        slot->stamp = grid->stamp;
        slot->head = UNFOLD_NONE;
    }
    grid->entries[entry] = (unfold_grid_entry){triangle, piece, slot->head};
    slot->head = entry;
    return UR_OK;
}

ur_status unfold_grid_add(unfold_grid *grid, ur_box box, size_t piece, size_t triangle,
                          ur_error *error)
{
    cell_range r;
    if (!cells_of(grid, box, &r))
        return add_to_cell(grid, piece, BIG_KEY, BIG_KEY, triangle, error);
    for (int64_t x = r.x0; x <= r.x1; x++)
        for (int64_t y = r.y0; y <= r.y1; y++)
            if (add_to_cell(grid, piece, x, y, triangle, error) != UR_OK)
                return UR_ERROR_MEMORY; /* the only way add_to_cell fails */
    return UR_OK;
}

/* Adds the live triangles of the piece in the cell's slot to what the query found. */
static void read_cell(unfold_grid *grid, size_t piece, int64_t x, int64_t y, const size_t *piece_of)
{
    const unfold_grid_slot *slot = &grid->slots[slot_of(grid, piece, x, y)];
    if (slot->stamp != grid->stamp)
        return;
    for (size_t e = slot->head; e != UNFOLD_NONE; e = grid->entries[e].next) {
        size_t t = grid->entries[e].item;
        if (grid->entries[e].piece != piece || piece_of[t] != piece || grid->seen[t] == grid->query)
            continue;
        grid->seen[t] = grid->query;
        grid->found[grid->found_count++] = t;
    }
}

bool unfold_grid_query(unfold_grid *grid, ur_box box, size_t piece, const size_t *piece_of)
{
    cell_range r;
    if (!cells_of(grid, box, &r))
        return false;
    grid->query++;
    grid->found_count = 0;
    read_cell(grid, piece, BIG_KEY, BIG_KEY, piece_of);
    for (int64_t x = r.x0; x <= r.x1; x++)
        for (int64_t y = r.y0; y <= r.y1; y++)
            read_cell(grid, piece, x, y, piece_of);
    return true;
}
