/*
 * unfold_lay.c: laying one triangle on a growing piece: placing it rigidly
 * on the edge it shares with a laid triangle, joining it to laid twins it
 * meets edge to edge, and deciding whether it fits.
 *
 * The piece is a disk whose flat vertices are classes of triangle corners
 * (union-find over corners, joined across every edge the piece joins).  A
 * new triangle keeps it a disk when it meets the piece along a path of
 * edges it is joined across, and nowhere else but at those edges' flat
 * vertices.  So a laid triangle it touches must touch it only at a flat
 * vertex the two share, at one corner: two shared corners would be an edge
 * they meet along without being joined across it (a slit, or a hole when
 * the edge is elsewhere on the border).  Across its entry edge the new
 * triangle is joined to its parent; where it closes the ring around a
 * flat vertex of the mesh (the angles there add to 2 pi) it lands on the
 * laid twin of another of its edges too and is joined there as well.
 */
#include "unfold_internal.h"

/* Corner k + 2 of triangle t, when corner k lies at p0 and corner k + 1 at p1. */
static ur_vec2 third_corner(const ur_mesh *mesh, size_t t, size_t k, ur_vec2 p0, ur_vec2 p1)
{
    ur_vec3 a = mesh->vertices[mesh->triangles[t][k]];
    ur_vec3 b = mesh->vertices[mesh->triangles[t][(k + 1) % 3]];
    ur_vec3 c = mesh->vertices[mesh->triangles[t][(k + 2) % 3]];
    ur_vec3 side = ur_vec3_sub(b, a), other = ur_vec3_sub(c, a);
    double length = ur_vec3_length(side);
    double along = ur_vec3_dot(other, side) / length;
    double across = ur_vec3_length(ur_vec3_cross(side, other)) / length;
    ur_vec2 d = ur_vec2_sub(p1, p0);
    d = ur_vec2_scale(d, 1.0 / ur_vec2_length(d));
    /* The triangle runs counter-clockwise, so its third corner is left of p0 -> p1. */
    return ur_vec2_add_scaled(ur_vec2_add_scaled(p0, d, along), ur_vec2_make(-d.y, d.x), across);
}

static void candidate_start(unfold_candidate *c, size_t triangle, size_t entry)
{
    c->triangle = triangle;
    c->entry = entry;
    for (int k = 0; k < 3; k++)
        c->join[k] = c->root[k][0] = c->root[k][1] = UNFOLD_NONE;
}

void unfold_seed(const unfolder *u, size_t triangle, unfold_candidate *c)
{
    candidate_start(c, triangle, UNFOLD_NONE);
    const ur_mesh *mesh = u->mesh;
    double length = ur_vec3_distance(mesh->vertices[mesh->triangles[triangle][0]],
                                     mesh->vertices[mesh->triangles[triangle][1]]);
    c->corner[0] = ur_vec2_make(0, 0);
    c->corner[1] = ur_vec2_make(length, 0);
    c->corner[2] = third_corner(mesh, triangle, 0, c->corner[0], c->corner[1]);
}

/* Records that corner k of the candidate is flat vertex root; false if it already is another. */
static bool add_root(unfold_candidate *c, size_t k, size_t root)
{
    if (c->root[k][0] == UNFOLD_NONE || c->root[k][0] == root) {
        c->root[k][0] = root;
        return true;
    }
    if (c->root[k][1] == UNFOLD_NONE || c->root[k][1] == root) {
        c->root[k][1] = root;
        return true;
    }
    return false;
}

/*
 * Half-edge k of the candidate runs from its corner k to corner k + 1; its
 * twin q runs from corner q % 3 of its triangle (the same mesh vertex as
 * corner k + 1) to the next.  The twin's corners for the candidate's k and
 * k + 1 are stored in *mine and *next.
 */
static void twin_corners(size_t q, size_t *mine, size_t *next)
{
    *mine = 3 * (q / 3) + (q % 3 + 1) % 3;
    *next = q;
}

/* Joins half-edge k to its twin when the twin is laid in this piece, edge on edge. */
static bool try_join(unfolder *u, unfold_candidate *c, size_t k)
{
    size_t half = 3 * c->triangle + k, q = u->edges.twins[half];
    if (q == UR_NO_EDGE || u->edges.cut[half] || u->piece[q / 3] != u->current)
        return false;
    size_t mine, next, k1 = (k + 1) % 3;
    twin_corners(q, &mine, &next);
    const ur_vec2 *laid = u->flat[q / 3];
    if (ur_vec2_distance(c->corner[k], laid[mine % 3]) > u->eps ||
        ur_vec2_distance(c->corner[k1], laid[next % 3]) > u->eps)
        return false;
    /* The shared corner must be the same flat vertex, or the join would pinch the disk. */
    size_t root_mine = unfold_find(u, mine), root_next = unfold_find(u, next);
    if ((c->root[k][0] != UNFOLD_NONE && c->root[k][0] != root_mine) ||
        (c->root[k1][0] != UNFOLD_NONE && c->root[k1][0] != root_next))
        return false;
    add_root(c, k, root_mine);
    add_root(c, k1, root_next);
    c->join[k] = q;
    return true;
}

bool unfold_prepare(unfolder *u, size_t entry, unfold_candidate *c)
{
    size_t t = entry / 3, k = entry % 3, h = u->edges.twins[entry];
    size_t mine, next;
    twin_corners(h, &mine, &next);
    candidate_start(c, t, entry);
    c->corner[k] = u->flat[h / 3][mine % 3];
    c->corner[(k + 1) % 3] = u->flat[h / 3][next % 3];
    c->corner[(k + 2) % 3] = third_corner(u->mesh, t, k, c->corner[k], c->corner[(k + 1) % 3]);
    c->join[k] = h;
    add_root(c, k, unfold_find(u, mine));
    add_root(c, (k + 1) % 3, unfold_find(u, next));
    bool first = try_join(u, c, (k + 1) % 3);
    bool second = try_join(u, c, (k + 2) % 3);
    /* Joined on all three edges it would fill a hole, which a disk has not: rounding. */
    return !(first && second);
}

/* Whether corner i of the candidate and corner j of laid triangle q are one flat vertex. */
static bool same_vertex(unfolder *u, const unfold_candidate *c, int i, size_t q, int j)
{
    if (ur_vec2_distance(c->corner[i], u->flat[q][j]) > u->eps)
        return false;
    size_t root = unfold_find(u, 3 * q + (size_t)j);
    return root == c->root[i][0] || root == c->root[i][1];
}

/* The bit of the candidate's corner that corner j of laid triangle q is one with; 0 if none. */
static unsigned corner_of_laid(unfolder *u, const unfold_candidate *c, size_t q, int j)
{
    for (int i = 0; i < 3; i++)
        if (same_vertex(u, c, i, q, j))
            return 1u << i;
    return 0;
}

/* The bit of the candidate's corner i if it is one with a corner of laid triangle q; else 0. */
static unsigned corner_if_shared(unfolder *u, const unfold_candidate *c, int i, size_t q)
{
    for (int j = 0; j < 3; j++)
        if (same_vertex(u, c, i, q, j))
            return 1u << i;
    return 0;
}

/* Whether the candidate and laid triangle q meet at most at one flat vertex they share. */
static bool touches_well(unfolder *u, const unfold_candidate *c, size_t q)
{
    unfold_contact contact = unfold_triangle_contact(c->corner, u->flat[q], u->eps);
    if (contact.overlap)
        return false;
    unsigned shared = 0;
    for (int k = 0; k < 3; k++) {
        if (contact.t_near & (1u << k)) {
            unsigned s = corner_if_shared(u, c, k, q);
            if (!s)
                return false;
            shared |= s;
        }
        if (contact.q_near & (1u << k)) {
            unsigned s = corner_of_laid(u, c, q, k);
            if (!s)
                return false;
            shared |= s;
        }
    }
    return shared == 0 || (shared & (shared - 1)) == 0;
}

static bool joined_to(const unfold_candidate *c, size_t q)
{
    for (int k = 0; k < 3; k++)
        if (c->join[k] != UNFOLD_NONE && c->join[k] / 3 == q)
            return true;
    return false;
}

static ur_box candidate_box(const unfold_candidate *c, double eps)
{
    ur_box box = ur_box_of_points(c->corner, 3);
    box.min = ur_vec2_sub(box.min, ur_vec2_make(eps, eps));
    box.max = ur_vec2_add(box.max, ur_vec2_make(eps, eps));
    return box;
}

bool unfold_fits(unfolder *u, unfold_grid *grid, const unfold_candidate *c)
{
    unfold_grid_query(grid, candidate_box(c, u->eps));
    for (size_t i = 0; i < grid->found_count; i++) {
        size_t q = grid->found[i];
        if (!joined_to(c, q) && !touches_well(u, c, q))
            return false;
    }
    return true;
}

static void join(unfolder *u, size_t a, size_t b)
{
    a = unfold_find(u, a);
    b = unfold_find(u, b);
    if (a != b)
        u->parent[a] = b;
}

ur_status unfold_commit(unfolder *u, unfold_grid *grid, const unfold_candidate *c, ur_error *error)
{
    size_t t = c->triangle;
    u->piece[t] = u->current;
    for (int k = 0; k < 3; k++) {
        u->flat[t][k] = c->corner[k];
        size_t q = c->join[k];
        if (q == UNFOLD_NONE)
            continue;
        size_t mine, next;
        twin_corners(q, &mine, &next);
        u->joined[3 * t + (size_t)k] = u->joined[q] = true;
        join(u, 3 * t + (size_t)k, mine);
        join(u, 3 * t + (size_t)(k + 1) % 3, next);
    }
    u->members[u->member_count++] = t;
    ur_box box = ur_box_of_points(c->corner, 3);
    return unfold_grid_add(grid, box, t, error);
}
