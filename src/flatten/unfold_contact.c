/*
 * unfold_contact.c: how two flat triangles touch, and the hash grid that
 * finds the triangles of a piece near a new one.
 *
 * Two convex polygons have disjoint interiors exactly when a line
 * separates them, and for polygons one of their edges' lines does
 * (the separating axis theorem).  With a tolerance: the triangles overlap
 * when, along the normal of each of their six edges, their shadows
 * overlap by more than eps.  A thinner overlap is a contact, which unfold.c
 * judges by the corners near the other triangle: the ends of a contact
 * segment are always among them.
 *
 * The grid keeps laying a triangle independent of the piece's size: cells
 * of about a mean edge (a triangle covers a few), hashed into at least
 * four slots per triangle of the mesh, so that a query reads a few short
 * chains.  Slots remember the piece they were filled for, so starting a
 * new piece is free.
 */
#include "unfold_internal.h"

#include <stdint.h>
#include <stdlib.h>

/* A triangle whose box covers more cells than this goes on the list every query reads. */
#define BIG_CELLS 64

/* Whether the normal of edge ab separates t and q, allowing an overlap of eps. */
static bool separates(ur_vec2 a, ur_vec2 b, const ur_vec2 t[3], const ur_vec2 q[3], double eps)
{
    ur_vec2 d = ur_vec2_sub(b, a);
    ur_vec2 normal = ur_vec2_scale(ur_vec2_make(-d.y, d.x), 1.0 / ur_vec2_length(d));
    double t_low = INFINITY, t_high = -INFINITY, q_low = INFINITY, q_high = -INFINITY;
    for (int k = 0; k < 3; k++) {
        double s = ur_vec2_dot(normal, t[k]), r = ur_vec2_dot(normal, q[k]);
        t_low = fmin(t_low, s);
        t_high = fmax(t_high, s);
        q_low = fmin(q_low, r);
        q_high = fmax(q_high, r);
    }
    return t_high <= q_low + eps || q_high <= t_low + eps;
}

static double segment_distance(ur_vec2 p, ur_vec2 a, ur_vec2 b)
{
    ur_vec2 d = ur_vec2_sub(b, a);
    double s = ur_vec2_dot(ur_vec2_sub(p, a), d) / ur_vec2_dot(d, d);
    s = fmin(1.0, fmax(0.0, s));
    return ur_vec2_distance(p, ur_vec2_add_scaled(a, d, s));
}

/* Distance from p to the counter-clockwise triangle q, 0 inside. */
static double triangle_distance(ur_vec2 p, const ur_vec2 q[3])
{
    bool inside = true;
    double nearest = INFINITY;
    for (int k = 0; k < 3; k++) {
        ur_vec2 a = q[k], b = q[(k + 1) % 3];
        if (ur_vec2_cross(ur_vec2_sub(b, a), ur_vec2_sub(p, a)) < 0)
            inside = false;
        nearest = fmin(nearest, segment_distance(p, a, b));
    }
    return inside ? 0.0 : nearest;
}

unfold_contact unfold_triangle_contact(const ur_vec2 t[3], const ur_vec2 q[3], double eps)
{
    unfold_contact contact = {true, 0, 0};
    for (int k = 0; k < 3 && contact.overlap; k++)
        if (separates(t[k], t[(k + 1) % 3], t, q, eps) ||
            separates(q[k], q[(k + 1) % 3], t, q, eps))
            contact.overlap = false;
    if (contact.overlap)
        return contact;
    for (int k = 0; k < 3; k++) {
        if (triangle_distance(t[k], q) <= eps)
            contact.t_near |= 1u << k;
        if (triangle_distance(q[k], t) <= eps)
            contact.q_near |= 1u << k;
    }
    return contact;
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

static size_t slot_of(const unfold_grid *grid, int64_t x, int64_t y)
{
    uint64_t h =
        (uint64_t)x * UINT64_C(0x9E3779B97F4A7C15) ^ (uint64_t)y * UINT64_C(0xC2B2AE3D27D4EB4F);
    h ^= h >> 31;
    return (size_t)(h & grid->mask);
}

ur_status unfold_grid_init(unfold_grid *grid, size_t triangle_count, double cell, ur_error *error)
{
    *grid = (unfold_grid){0};
    size_t slots = 64;
    while (slots < 4 * triangle_count)
        slots *= 2;
    grid->cell = cell;
    grid->mask = slots - 1;
    grid->head = ur_alloc_array(slots, sizeof *grid->head, error);
    grid->head_piece = ur_alloc_array(slots, sizeof *grid->head_piece, error);
    grid->entry_capacity = 4 * triangle_count;
    grid->entry_item = ur_alloc_array(grid->entry_capacity, sizeof *grid->entry_item, error);
    grid->entry_next = ur_alloc_array(grid->entry_capacity, sizeof *grid->entry_next, error);
    grid->big = ur_alloc_array(triangle_count, sizeof *grid->big, error);
    grid->seen = ur_alloc_array(triangle_count, sizeof *grid->seen, error);
    grid->found = ur_alloc_array(triangle_count, sizeof *grid->found, error);
    if (!grid->head || !grid->head_piece || !grid->entry_item || !grid->entry_next || !grid->big ||
        !grid->seen || !grid->found)
        return UR_ERROR_INTERNAL;
    for (size_t s = 0; s < slots; s++)
        grid->head_piece[s] = UNFOLD_NONE;
    return UR_OK;
}

void unfold_grid_free(unfold_grid *grid)
{
    free(grid->head);
    free(grid->head_piece);
    free(grid->entry_item);
    free(grid->entry_next);
    free(grid->big);
    free(grid->seen);
    free(grid->found);
    *grid = (unfold_grid){0};
}

void unfold_grid_restart(unfold_grid *grid)
{
    grid->piece++;
    grid->entry_count = 0;
    grid->big_count = 0;
}

static ur_status grow_entries(unfold_grid *grid, ur_error *error)
{
    size_t capacity = 2 * grid->entry_capacity + 16;
    size_t *item = realloc(grid->entry_item, capacity * sizeof *item);
    if (item)
        grid->entry_item = item;
    size_t *next = item ? realloc(grid->entry_next, capacity * sizeof *next) : NULL;
    if (!next)
        return ur_error_out_of_memory(error);
    grid->entry_next = next;
    grid->entry_capacity = capacity;
    return UR_OK;
}

static ur_status add_to_cell(unfold_grid *grid, int64_t x, int64_t y, size_t triangle,
                             ur_error *error)
{
    if (grid->entry_count == grid->entry_capacity && grow_entries(grid, error) != UR_OK)
        return UR_ERROR_INTERNAL;
    size_t slot = slot_of(grid, x, y), entry = grid->entry_count++;
    if (grid->head_piece[slot] != grid->piece) {
        grid->head_piece[slot] = grid->piece;
        grid->head[slot] = UNFOLD_NONE;
    }
    grid->entry_item[entry] = triangle;
    grid->entry_next[entry] = grid->head[slot];
    grid->head[slot] = entry;
    return UR_OK;
}

ur_status unfold_grid_add(unfold_grid *grid, ur_box box, size_t triangle, ur_error *error)
{
    cell_range r;
    if (!cells_of(grid, box, &r)) {
        grid->big[grid->big_count++] = triangle;
        return UR_OK;
    }
    for (int64_t x = r.x0; x <= r.x1; x++)
        for (int64_t y = r.y0; y <= r.y1; y++)
            if (add_to_cell(grid, x, y, triangle, error) != UR_OK)
                return UR_ERROR_INTERNAL;
    return UR_OK;
}

static void found_add(unfold_grid *grid, size_t triangle)
{
    if (grid->seen[triangle] == grid->query)
        return;
    grid->seen[triangle] = grid->query;
    grid->found[grid->found_count++] = triangle;
}

void unfold_grid_query(unfold_grid *grid, ur_box box)
{
    grid->query++;
    grid->found_count = 0;
    for (size_t i = 0; i < grid->big_count; i++)
        found_add(grid, grid->big[i]);
    cell_range r;
    if (!cells_of(grid, box, &r)) {
        for (size_t e = 0; e < grid->entry_count; e++)
            found_add(grid, grid->entry_item[e]);
        return;
    }
    for (int64_t x = r.x0; x <= r.x1; x++)
        for (int64_t y = r.y0; y <= r.y1; y++) {
            size_t slot = slot_of(grid, x, y);
            if (grid->head_piece[slot] != grid->piece)
                continue;
            for (size_t e = grid->head[slot]; e != UNFOLD_NONE; e = grid->entry_next[e])
                found_add(grid, grid->entry_item[e]);
        }
}
