/*
 * unfold_lay.c: joining two pieces across an edge: the smaller moved
 * rigidly onto the larger so that the edge meets, the edges that land on
 * each other next to it joined too, and the join kept only if the result
 * is still a disk laid flat without overlap.
 *
 * A piece is a disk whose flat vertices are classes of triangle corners
 * (union-find over corners, joined across every edge the piece joins).
 * Two disks joined along a path of their outlines make a disk, so the
 * join follows the outlines away from the edge at both its ends for as
 * long as the next edges are twins that land on each other (closing the
 * ring of triangles round a vertex whose angles add to 2 pi, or following
 * a straight crease), and joins those too, but never the whole outline of
 * either piece (that would close a hole).  Everywhere else the pieces may
 * touch only at the flat vertices the join makes one: two triangles may
 * share one such vertex, not two (an edge they meet along without being
 * joined across it would be a slit, or a hole).  Inside a flat face, which
 * is rigid, a slit is allowed: a face round a hole can only be laid flat
 * in one piece with a cut from its hole to its outside, and both sides of
 * that cut lie on each other.
 */
#include "unfold_internal.h"

#include "../geom/hull.h"

#include "../base/tables.h"
#include "../base/union_find.h"

#include <stdlib.h>
#include <string.h>

static ur_vec2 corner_at(const unfolder *u, size_t corner)
{
    return u->flat[corner / 3][corner % 3];
}

/* The motion that lays half-edge small_half on its twin large_half, midpoint on midpoint. */
static unfold_motion hinge_motion(const unfolder *u, size_t small_half, size_t large_half)
{
    ur_vec2 xs = corner_at(u, small_half), ys = corner_at(u, unfold_next(small_half));
    ur_vec2 yl = corner_at(u, large_half), xl = corner_at(u, unfold_next(large_half));
    /* small_half runs from x to y, its twin from y to x: turn x to y onto x to y. */
    ur_vec2 ds = ur_vec2_sub(ys, xs), dl = ur_vec2_sub(yl, xl);
    double angle = atan2(ur_vec2_cross(ds, dl), ur_vec2_dot(ds, dl));
    return (unfold_motion){cos(angle), sin(angle), ur_vec2_scale(ur_vec2_add(xs, ys), 0.5),
                           ur_vec2_scale(ur_vec2_add(xl, yl), 0.5)};
}

static bool lands_on(const unfolder *u, const unfold_motion *m, size_t small_corner,
                     size_t large_corner)
{
    return unfold_within(unfold_move(m, corner_at(u, small_corner)), corner_at(u, large_corner),
                         u->eps);
}

static void add_pair(unfolder *u, size_t small_half, size_t large_half)
{
    u->pair_small[u->pair_count] = small_half;
    u->pair_large[u->pair_count] = large_half;
    u->pair_count++;
}

/* Whether s and l are twins that may be joined, and there is room for one more pair. */
static bool zips(const unfolder *u, size_t s, size_t l, size_t most)
{
    return s != UNFOLD_NONE && l != UNFOLD_NONE && u->edges.twins[s] == l && !u->edges.cut[s] &&
           u->pair_count + 1 < most;
}

/*
 * The pairs of half-edges the join joins: the hinge, then along the
 * outlines from its two ends while the next edges land on each other.
 */
static void find_pairs(unfolder *u, const unfold_motion *m, size_t hinge_small, size_t hinge_large,
                       size_t most)
{
    u->pair_count = 0;
    add_pair(u, hinge_small, hinge_large);
    /* From the hinge's end y: on, round the small piece; back, round the large one. */
    for (size_t s = hinge_small, l = hinge_large;;) {
        size_t s2 = unfold_outline_next(u, s), l2 = unfold_outline_previous(u, l);
        if (!zips(u, s2, l2, most) || !lands_on(u, m, unfold_next(s2), l2))
            break;
        add_pair(u, s2, l2);
        s = s2, l = l2;
    }
    /* From its start x: back round the small piece, on round the large one. */
    for (size_t s = hinge_small, l = hinge_large;;) {
        size_t s2 = unfold_outline_previous(u, s), l2 = unfold_outline_next(u, l);
        if (!zips(u, s2, l2, most) || !lands_on(u, m, s2, unfold_next(l2)))
            break;
        add_pair(u, s2, l2);
        s = s2, l = l2;
    }
    /* The flat vertices each pair makes one: its start's and its end's. */
    for (size_t i = 0; i < u->pair_count; i++) {
        size_t s = u->pair_small[i], l = u->pair_large[i];
        u->roots[4 * i] = unfold_find(u, s);
        u->roots[4 * i + 1] = unfold_find(u, unfold_next(l));
        u->roots[4 * i + 2] = unfold_find(u, unfold_next(s));
        u->roots[4 * i + 3] = unfold_find(u, l);
    }
}

static bool is_pair(const unfolder *u, size_t small_half)
{
    for (size_t i = 0; i < u->pair_count; i++)
        if (u->pair_small[i] == small_half)
            return true;
    return false;
}

/*
 * Inside a face: the edges of the small piece that land on their twins in
 * the large one without being joined, slits, after the pairs (slit_count
 * of them), with the flat vertices at their ends as if they were made one.
 */
static void find_slits(unfolder *u, const unfold_motion *m, size_t small, size_t large)
{
    size_t end = u->pair_count;
    for (size_t t = u->islands[small].first; t != UNFOLD_NONE; t = u->next_member[t])
        for (size_t h = 3 * t; h < 3 * t + 3; h++) {
            size_t g = u->edges.twins[h];
            if (g == UR_NO_EDGE || u->piece[g / 3] != large || is_pair(u, h) ||
                !lands_on(u, m, h, unfold_next(g)) || !lands_on(u, m, unfold_next(h), g))
                continue;
            u->pair_small[end] = h;
            u->pair_large[end] = g;
            u->roots[4 * end] = unfold_find(u, h);
            u->roots[4 * end + 1] = unfold_find(u, unfold_next(g));
            u->roots[4 * end + 2] = unfold_find(u, unfold_next(h));
            u->roots[4 * end + 3] = unfold_find(u, g);
            end++;
        }
    u->slit_count = end - u->pair_count;
}

/* Whether corner cs of the small piece and cl of the large become one flat vertex (or a slit's
 * end). */
static bool made_one(unfolder *u, size_t cs, size_t cl)
{
    size_t rs = unfold_find(u, cs), rl = unfold_find(u, cl);
    for (size_t i = 0; i < 2 * (u->pair_count + u->slit_count); i++)
        if (u->roots[2 * i] == rs && u->roots[2 * i + 1] == rl)
            return true;
    return false;
}

static bool paired(const unfolder *u, size_t s, size_t q)
{
    for (size_t i = 0; i < u->pair_count + u->slit_count; i++)
        if (u->pair_small[i] / 3 == s && u->pair_large[i] / 3 == q)
            return true;
    return false;
}

/* The bit of corner j of q if it is one with corner i of moved small triangle s; else 0. */
static unsigned shared_corner(unfolder *u, size_t s, const ur_vec2 moved[3], int i, size_t q, int j)
{
    if (!unfold_within(moved[i], u->flat[q][j], u->eps))
        return 0;
    return made_one(u, 3 * s + (size_t)i, 3 * q + (size_t)j) ? 1u << j : 0;
}

/* Whether joins keep the options' gap: between pieces of faces, not inside a face. */
static bool keeps_gap(const unfolder *u)
{
    return u->options.min_gap > 0 && !u->slits && !u->gap_waived;
}

/* Whether moved small triangle s and large triangle q meet at most at one flat vertex made one. */
static bool touches_well(unfolder *u, size_t s, const ur_vec2 moved[3], size_t q)
{
    unfold_contact contact = unfold_triangle_contact(moved, u->flat[q], u->eps);
    if (contact.overlap)
        return false;
    unsigned shared = 0;
    for (int i = 0; i < 3; i++) {
        if (!(contact.t_near & (1u << i)))
            continue;
        unsigned bit = 0;
        for (int j = 0; j < 3 && !bit; j++)
            bit = shared_corner(u, s, moved, i, q, j);
        if (!bit)
            return false;
        shared |= bit;
    }
    for (int j = 0; j < 3; j++) {
        if (!(contact.q_near & (1u << j)))
            continue;
        unsigned bit = 0;
        for (int i = 0; i < 3 && !bit; i++)
            bit = shared_corner(u, s, moved, i, q, j);
        if (!bit)
            return false;
        shared |= bit;
    }
    return (shared & (shared - 1)) == 0;
}

/* Whether half-edge h stays on its piece's outline: joined neither before nor by this join. */
static bool stays_outline(const unfolder *u, size_t h)
{
    if (u->joined[h])
        return false;
    for (size_t i = 0; i < u->pair_count + u->slit_count; i++)
        if (u->pair_small[i] == h || u->pair_large[i] == h)
            return false;
    return true;
}

/*
 * Whether point p (where the join puts it) lies on a triangle of piece
 * (the small one moved by m, or the large one as it lies), or within
 * tolerance of one.
 */
static bool covered(unfolder *u, size_t piece, const unfold_motion *m, ur_vec2 p, double tolerance)
{
    ur_vec2 at = m ? unfold_move_back(m, p) : p;
    ur_box box = {ur_vec2_make(at.x - tolerance, at.y - tolerance),
                  ur_vec2_make(at.x + tolerance, at.y + tolerance)};
    unfold_grid *grid = &u->grid;
    if (unfold_grid_query(grid, box, piece, u->piece)) {
        for (size_t i = 0; i < grid->found_count; i++)
            if (unfold_point_near_triangle(at, u->flat[grid->found[i]], tolerance))
                return true;
        return false;
    }
    for (size_t t = u->islands[piece].first; t != UNFOLD_NONE; t = u->next_member[t])
        if (unfold_point_near_triangle(at, u->flat[t], tolerance))
            return true;
    return false;
}

/*
 * How far apart edges ab and cd are, and their nearest points; edges that
 * meet at an end (round a flat vertex the join makes one) are as far apart
 * as the nearer of their other ends is from the other edge: the width of
 * the wedge between them.
 */
static double edge_gap(const unfolder *u, ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d,
                       ur_vec2 *on_ab, ur_vec2 *on_cd)
{
    ur_vec2 ab[2] = {a, b}, cd[2] = {c, d};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) {
            if (!unfold_within(ab[i], cd[j], u->eps))
                continue;
            ur_vec2 far_ab = ab[1 - i], far_cd = cd[1 - j], near_cd, near_ab, unused;
            double from_ab = unfold_edge_gap(far_ab, far_ab, c, d, &unused, &near_cd);
            double from_cd = unfold_edge_gap(a, b, far_cd, far_cd, &near_ab, &unused);
            *on_ab = from_ab < from_cd ? far_ab : near_ab;
            *on_cd = from_ab < from_cd ? near_cd : far_cd;
            return fmin(from_ab, from_cd);
        }
    return unfold_edge_gap(a, b, c, d, on_ab, on_cd);
}

/*
 * Whether the boxes of edges ab and cd come within gap of each other: if
 * not, neither do the edges, nor the wedge between them (most pairs of
 * edges a join looks at).
 */
static bool boxes_within(ur_vec2 a, ur_vec2 b, ur_vec2 c, ur_vec2 d, double gap)
{
    return fmin(c.x, d.x) - fmax(a.x, b.x) < gap && fmin(a.x, b.x) - fmax(c.x, d.x) < gap &&
           fmin(c.y, d.y) - fmax(a.y, b.y) < gap && fmin(a.y, b.y) - fmax(c.y, d.y) < gap;
}

/*
 * Whether outline edges ab (of the moved small piece) and cd (of the large
 * one) come closer than the gap with the outside between them: a slit.
 * Where the middle of the shortest way between them is on a piece, it is
 * a narrow part of the piece, or the way runs along its outline (edges of
 * a straight or convex stretch apart by less than the gap), not a slit.
 */
static bool slit_between(unfolder *u, const unfold_motion *m, size_t small, size_t large, ur_vec2 a,
                         ur_vec2 b, ur_vec2 c, ur_vec2 d, double gap)
{
    ur_vec2 on_ab, on_cd;
    if (!boxes_within(a, b, c, d, gap) || !(edge_gap(u, a, b, c, d, &on_ab, &on_cd) < gap))
        return false;
    ur_vec2 middle = ur_vec2_scale(ur_vec2_add(on_ab, on_cd), 0.5);
    return !covered(u, large, NULL, middle, u->eps) && !covered(u, small, m, middle, u->eps);
}

/*
 * The gap edges hs (ab) and hq (cd) must keep.  Two sides of one seam that
 * meet at an end make a wedge that must hold that seam's tab itself,
 * which stands clear of the wedge's point, where the wedge is narrow:
 * half as much again at its open end.  With the gap there, tabs a third
 * of the way along found 1.5 to 2.2 mm, and 10 of the 15 seam edges of
 * Blender's monkey head (A3, 6 mm tabs) left without a tab were such
 * wedges; with 1.5 gaps 4 edges are left, in 20 pieces instead of 17
 * (with 2 gaps, 3 in 29).
 */
static double wedge_gap(const unfolder *u, size_t hs, size_t hq, ur_vec2 a, ur_vec2 b, ur_vec2 c,
                        ur_vec2 d)
{
    double gap = u->options.min_gap;
    if (u->edges.twins[hs] != hq)
        return gap;
    bool meet = ur_vec2_distance(a, d) <= u->eps || ur_vec2_distance(b, c) <= u->eps;
    return meet ? 1.5 * gap : gap;
}

static bool marked_by_join(const unfolder *u, size_t h)
{
    for (size_t i = 0; i < u->slit_side_count; i++)
        if (u->slit_sides[i] == h)
            return true;
    return false;
}

/*
 * Whether outline edge h may lie in a narrow slit beside outline edge
 * other: it needs no tab (the mesh's boundary), or its seam's tab can go
 * on its twin instead, which is neither the other side of the slit nor in
 * a slit itself.
 */
static bool tab_may_go_to_twin(const unfolder *u, size_t h, size_t other)
{
    size_t g = u->edges.twins[h];
    if (g == UR_NO_EDGE)
        return true;
    return g != other && !u->tab_on_twin[g] && !marked_by_join(u, g);
}

static void mark_for_join(unfolder *u, size_t h)
{
    if (u->edges.twins[h] != UR_NO_EDGE && !u->tab_on_twin[h] && !marked_by_join(u, h))
        u->slit_sides[u->slit_side_count++] = h;
}

/*
 * Whether outline edges hs of moved s and hq of q leave a slit between
 * them that no tab can use: a slit whose two edges both hand their tabs
 * to their twins is kept (the tabs of a seam go on one side only, as in
 * Blender's paper model), and the two edges are marked so when the join is
 * made.
 */
static bool blocking_slit(unfolder *u, const unfold_motion *m, size_t hs, ur_vec2 a, ur_vec2 b,
                          size_t hq, ur_vec2 c, ur_vec2 d)
{
    size_t s = hs / 3, q = hq / 3;
    if (!slit_between(u, m, u->piece[s], u->piece[q], a, b, c, d, wedge_gap(u, hs, hq, a, b, c, d)))
        return false;
    if (!u->tabs_to_twins || !tab_may_go_to_twin(u, hs, hq) || !tab_may_go_to_twin(u, hq, hs))
        return true;
    mark_for_join(u, hs);
    mark_for_join(u, hq);
    return false;
}

/* Whether an outline edge of moved s and one of q leave a slit between them. */
static bool leaves_slit(unfolder *u, const unfold_motion *m, size_t s, const ur_vec2 moved[3],
                        size_t q)
{
    for (int i = 0; i < 3; i++) {
        size_t hs = 3 * s + (size_t)i;
        if (!stays_outline(u, hs))
            continue;
        for (int j = 0; j < 3; j++) {
            size_t hq = 3 * q + (size_t)j;
            if (stays_outline(u, hq) && blocking_slit(u, m, hs, moved[i], moved[(i + 1) % 3], hq,
                                                      u->flat[q][j], u->flat[q][(j + 1) % 3]))
                return true;
        }
    }
    return false;
}

/*
 * Whether moved small triangle s may lie where it is beside large triangle
 * q: joined to it, or touching it well, and, when the options ask for a
 * gap, leaving no slit narrower than it between their outlines (nor a
 * narrower wedge at a flat vertex the join makes one).
 */
static bool lies_well(unfolder *u, const unfold_motion *m, size_t s, const ur_vec2 moved[3],
                      size_t q)
{
    if (paired(u, s, q))
        return true;
    if (!touches_well(u, s, moved, q))
        return false;
    return !keeps_gap(u) || !leaves_slit(u, m, s, moved, q);
}

static ur_box padded_box(const ur_vec2 corners[3], double eps)
{
    ur_box box = unfold_box_of(corners, 3);
    box.min = ur_vec2_sub(box.min, ur_vec2_make(eps, eps));
    box.max = ur_vec2_add(box.max, ur_vec2_make(eps, eps));
    return box;
}

static bool boxes_meet(ur_box box, const ur_vec2 q[3])
{
    for (int axis = 0; axis < 2; axis++) {
        double low = axis ? box.min.y : box.min.x, high = axis ? box.max.y : box.max.x;
        double a = axis ? q[0].y : q[0].x, b = axis ? q[1].y : q[1].x, c = axis ? q[2].y : q[2].x;
        if ((a < low && b < low && c < low) || (a > high && b > high && c > high))
            return false;
    }
    return true;
}

/*
 * Whether moved small triangle s lies well beside the large piece.  What
 * the grid found is copied first: looking for slits asks it again.
 */
static bool fits_large(unfolder *u, const unfold_motion *m, size_t s, const ur_vec2 moved[3],
                       size_t large)
{
    unfold_grid *grid = &u->grid;
    ur_box box = padded_box(moved, keeps_gap(u) ? fmax(u->eps, u->options.min_gap) : u->eps);
    if (unfold_grid_query(grid, box, large, u->piece)) {
        size_t count = grid->found_count;
        memcpy(u->nearby, grid->found, count * sizeof *u->nearby);
        for (size_t i = 0; i < count; i++) {
            size_t q = u->nearby[i];
            if (boxes_meet(box, u->flat[q]) && !lies_well(u, m, s, moved, q)) {
                u->blocker = q;
                return false;
            }
        }
        return true;
    }
    for (size_t q = u->islands[large].first; q != UNFOLD_NONE; q = u->next_member[q])
        if (boxes_meet(box, u->flat[q]) && !lies_well(u, m, s, moved, q)) {
            u->blocker = q;
            return false;
        }
    return true;
}

static void move_triangle(const unfold_motion *m, const ur_vec2 in[3], ur_vec2 out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = unfold_move(m, in[k]);
}

static bool fits_one(unfolder *u, const unfold_motion *m, size_t s, size_t large)
{
    ur_vec2 moved[3];
    move_triangle(m, u->flat[s], moved);
    if (fits_large(u, m, s, moved, large))
        return true;
    /* Remember it: the next try of these pieces, across a neighbouring edge, fails there too. */
    memmove(u->culprits + 1, u->culprits, (UNFOLD_CULPRITS - 1) * sizeof *u->culprits);
    u->culprits[0] = s;
    return false;
}

/*
 * Whether the moved small piece fits the large.  Two large pieces that do
 * not fit are tried across every edge between them, and most of their
 * triangles would overlap: the triangles that stopped the last tries go
 * first, then every 16th, then all, so that a join that fails fails early.
 */
static bool fits(unfolder *u, const unfold_motion *m, size_t small, size_t large)
{
    for (size_t i = 0; i < UNFOLD_CULPRITS; i++) {
        size_t s = u->culprits[i];
        if (s != UNFOLD_NONE && u->piece[s] == small && !fits_one(u, m, s, large))
            return false;
    }
    size_t stride = u->islands[small].triangle_count > 64 ? 16 : 1;
    for (size_t pass = stride; pass >= 1; pass = pass == 1 ? 0 : 1) {
        size_t i = 0;
        for (size_t s = u->islands[small].first; s != UNFOLD_NONE; s = u->next_member[s], i++)
            if (i % pass == 0 && !fits_one(u, m, s, large))
                return false;
    }
    return true;
}

/* Whether moved small triangle s lies well beside large triangle q (lies_well, s moved first). */
static bool lies_well_moved(unfolder *u, const unfold_motion *m, size_t s, size_t q)
{
    ur_vec2 moved[3];
    move_triangle(m, u->flat[s], moved);
    return lies_well(u, m, s, moved, q);
}

/*
 * Whether the two triangles that stopped the last join across this hinge
 * (one of each piece) stop this one too: the join is then refused after a
 * test or two.  Most joins a step judges afresh are joins of pieces that
 * changed away from the hinge (a seam moved elsewhere gave them new keys)
 * and still overlap where they did: of the 23,600 joins a 48 x 24
 * sphere's two searches judged overlapping, 18,000 were refused so.
 * Whatever triangle is tested first, a join the test refuses is one that
 * fits() refuses.  Not in the last run, whose slits depend on the order
 * of its tests.
 */
static bool stopped_as_before(unfolder *u, const unfold_motion *m, size_t small, size_t large,
                              size_t hinge)
{
    if (u->last_run)
        return false;
    const size_t *pair = u->hinge_culprits[hinge];
    for (int i = 0; i < 2; i++) {
        size_t s = pair[i], q = pair[1 - i];
        if (s == UNFOLD_NONE || u->piece[s] != small)
            continue;
        if (q != UNFOLD_NONE && u->piece[q] == large && !lies_well_moved(u, m, s, q))
            return true; /* as before: the grid would have found q near s */
        if (!fits_one(u, m, s, large))
            return true;
    }
    return false;
}

/* Remembers what stopped the join across hinge, after fits said it does not fit. */
static void remember_stop(unfolder *u, size_t hinge)
{
    u->hinge_culprits[hinge][0] = u->culprits[0];
    u->hinge_culprits[hinge][1] = u->blocker;
}

/* The hull of both pieces into u->hull_points; its count. */
static size_t joined_hull(unfolder *u, const unfold_motion *m, size_t small, size_t large)
{
    const unfold_island *a = &u->islands[small], *b = &u->islands[large];
    size_t count = 0;
    for (size_t i = 0; i < a->hull_count; i++)
        u->hull_points[count++] = unfold_move(m, a->hull[i]);
    for (size_t i = 0; i < b->hull_count; i++)
        u->hull_points[count++] = b->hull[i];
    /* Two convex hulls: joined in linear time, not sorted again (the search does this often). */
    size_t k = geom_convex_hull_of_two(u->hull_points, a->hull_count, b->hull_count,
                                       u->hull_chain + count + 1, u->hull_chain);
    for (size_t i = 0; i < k; i++)
        u->hull_points[i] = u->hull_chain[i];
    return k;
}

/* A circle round both pieces, the small one moved by m. */
static unfold_circle joined_circle(const unfolder *u, const unfold_motion *m, size_t small,
                                   size_t large)
{
    unfold_circle moved = u->islands[small].circle;
    moved.center = unfold_move(m, moved.center);
    return unfold_circle_join(u, moved, u->islands[large].circle);
}

/* Sets piece p's hull to count points (room made for them as needed). */
static ur_status set_hull(unfold_island *island, const ur_vec2 *points, size_t count,
                          ur_error *error)
{
    if (count > island->hull_capacity) {
        ur_vec2 *grown = realloc(island->hull, 2 * count * sizeof *grown);
        if (!grown)
            return ur_error_out_of_memory(error);
        island->hull = grown;
        island->hull_capacity = 2 * count;
    }
    memcpy(island->hull, points, count * sizeof *points);
    island->hull_count = count;
    island->hull_set = true;
    return UR_OK;
}

static ur_status keep_hull(unfolder *u, size_t large, size_t count, ur_error *error)
{
    return set_hull(&u->islands[large], u->hull_points, count, error);
}

/* ---- the outcomes of joins, remembered over the runs ---- */

/* How a join came out, kept in the low two bits of its slot (0: no entry). */
enum { OUTCOME_NONE, OUTCOME_TOO_LARGE, OUTCOME_OVERLAPS, OUTCOME_FITS };
#define OUTCOME_BITS UINT64_C(3)

/*
 * The search runs the joins again and again in orders that differ by one
 * edge, and most of a run's joins are joins of the same two pieces across
 * the same edge as in an earlier run: their outcome is looked up instead
 * of tested again.  A piece's key is the sum (exclusive or) of keys of
 * its triangles, of the edges it was joined across (each hinge) and of
 * the edges those joins zipped: pieces with the same key were laid
 * through the same hinges, so that they are the same up to a motion
 * (and rounding), with the same outline.  A join is then fixed by the two
 * keys, its hinge in the smaller piece and what the phase allows; whether
 * it fits does not depend on where the pieces lie, on which triangles were
 * tried first (the culprits) nor on the grid.  Only the last run, whose
 * slits depend on the order of its tests, judges everything itself.
 */
ur_status unfold_outcomes_init(unfolder *u, ur_error *error)
{
    size_t slots = 1024, wanted = 64 * u->mesh->triangle_count;
    while (slots < wanted && slots < ((size_t)1 << 23))
        slots *= 2;
    u->outcomes = table_alloc(slots, sizeof *u->outcomes, error);
    if (!u->outcomes)
        return UR_ERROR_MEMORY;
    u->outcome_mask = slots - 1;
    return UR_OK;
}

/* The key the pairs of the join under way add to the large piece's. */
static uint64_t joined_key(const unfolder *u)
{
    uint64_t key = 0;
    for (size_t i = 0; i < u->pair_count; i++) {
        size_t s = u->pair_small[i], l = u->pair_large[i];
        size_t lower = s < l ? s : l;
        key ^= unfold_mix(4 * (uint64_t)lower + (i == 0 ? 2 : 3)); /* the hinge, then the zipped */
    }
    return key;
}

static uint64_t join_key(const unfolder *u, size_t small, size_t large, size_t hinge_small,
                         bool turned_room)
{
    uint64_t phase = (uint64_t)u->slits | (uint64_t)u->room_binds << 1 |
                     (uint64_t)u->gap_waived << 2 | (uint64_t)turned_room << 3;
    uint64_t pieces = unfold_mix(unfold_mix(u->islands[small].layout) + u->islands[large].layout);
    return pieces ^ unfold_mix(16 * (uint64_t)hinge_small + phase);
}

static bool remembers(const unfolder *u)
{
    return !u->last_run;
}

static unsigned recalled(const unfolder *u, uint64_t key)
{
    uint64_t slot = u->outcomes[(key >> 2) & u->outcome_mask];
    return (slot & ~OUTCOME_BITS) == (key & ~OUTCOME_BITS) ? (unsigned)(slot & OUTCOME_BITS)
                                                           : OUTCOME_NONE;
}

/*
 * The outcome of a join, if one was judged before: with the room turned,
 * also one judged with it level that holds turned as well.  A join that
 * fits the level room fits the turned one (a piece that fits at its
 * least-area rectangle's turn fits at some turn), and an overlap does not
 * depend on the room; only "too large" may change.  The turned search
 * starts from the level one's first order and walks much as it did (the
 * same random choices), so that most of its joins were judged level.
 *
 * Most runs try the same join across a hinge as the run before, so each
 * hinge keeps the last join judged or looked up across it, looked at
 * first: a table of three entries per triangle, which stays in the
 * processor's cache, where the large one is read from memory (the bench's
 * 48 x 24 sphere: a tenth of its search's time went in reading it).  A
 * join found there that the large table has since forgotten is not
 * judged again: its outcome is the same.
 */
static unsigned recalled_join(unfolder *u, size_t small, size_t large, size_t hinge_small,
                              size_t hinge, uint64_t *key)
{
    *key = join_key(u, small, large, hinge_small, u->turned_room);
    uint64_t last = u->hinge_outcomes[hinge];
    if ((last & ~OUTCOME_BITS) == (*key & ~OUTCOME_BITS) && (last & OUTCOME_BITS))
        return (unsigned)(last & OUTCOME_BITS);
    unsigned outcome = recalled(u, *key);
    if (outcome != OUTCOME_NONE)
        u->hinge_outcomes[hinge] = (*key & ~OUTCOME_BITS) | outcome;
    if (outcome != OUTCOME_NONE || !u->turned_room)
        return outcome;
    unsigned level = recalled(u, join_key(u, small, large, hinge_small, false));
    return level == OUTCOME_FITS || level == OUTCOME_OVERLAPS ? level : OUTCOME_NONE;
}

/* Kept in its slot, in place of what was there: a forgotten outcome is only judged again. */
static void remember(unfolder *u, uint64_t key, size_t hinge, unsigned outcome)
{
    u->outcomes[(key >> 2) & u->outcome_mask] = (key & ~OUTCOME_BITS) | outcome;
    u->hinge_outcomes[hinge] = (key & ~OUTCOME_BITS) | outcome;
}

ur_status unfold_grid_piece(unfolder *u, size_t p, ur_error *error)
{
    unfold_island *island = &u->islands[p];
    size_t from =
        island->grid_last != UNFOLD_NONE ? u->next_member[island->grid_last] : island->first;
    for (size_t t = from; t != UNFOLD_NONE; t = u->next_member[t]) {
        ur_status status = unfold_grid_add(&u->grid, unfold_box_of(u->flat[t], 3), p, t, error);
        if (status != UR_OK)
            return status;
        island->grid_last = t;
    }
    return UR_OK;
}

/* Joins the moved small piece to the large: its triangles go in the grid when a join tests it. */
static void commit(unfolder *u, const unfold_motion *m, size_t small, size_t large)
{
    for (size_t i = 0; i < u->slit_side_count; i++)
        u->tab_on_twin[u->slit_sides[i]] = true;
    for (size_t i = 0; i < u->pair_count; i++) {
        size_t s = u->pair_small[i], l = u->pair_large[i];
        u->joined[s] = u->joined[l] = true;
        union_find_join(u->parent, s, unfold_next(l));
        union_find_join(u->parent, unfold_next(s), l);
    }
    unfold_island *a = &u->islands[small], *b = &u->islands[large];
    for (size_t s = a->first; s != UNFOLD_NONE; s = u->next_member[s]) {
        move_triangle(m, u->flat[s], u->flat[s]);
        u->piece[s] = large;
    }
    b->layout ^= a->layout ^ joined_key(u);
    b->lowest = a->lowest < b->lowest ? a->lowest : b->lowest;
    if (u->room)
        b->circle = joined_circle(u, m, small, large);
    u->next_member[b->last] = a->first;
    b->last = a->last;
    b->triangle_count += a->triangle_count;
    b->face_count += a->face_count;
    b->area += a->area;
    b->failures = 0;
    b->outline_count = b->outline_count + a->outline_count - 2 * u->pair_count;
    a->triangle_count = 0;
    a->first = a->last = UNFOLD_NONE;
}

/* ---- hulls kept over the runs ---- */

/*
 * Bringing a piece's hull up to date merges in turn the hulls of the
 * pieces it took in (unfold_update_hull), and most runs make the same
 * pieces as the last: a quarter of the bench's 48 x 24 sphere's run
 * without tabs went in merging the same hulls again.  A piece's hull is kept under its layout key,
 * which fixes the piece up to a motion (see join_key), with where its lowest triangle lay; found
 * again, it is moved to where that triangle lies now. A slot holds the last hull kept there.  Not
 * in the last run, which judges everything itself.
 */
#define KEPT_HULLS_MOST ((size_t)1 << 14)

typedef struct unfold_kept_hull {
    uint64_t layout;
    ur_vec2 at[2]; /* two corners of the piece's lowest triangle, as the hull was kept */
    ur_vec2 *points;
    size_t count, capacity; /* count 0: an empty slot */
} unfold_kept_hull;

ur_status unfold_kept_hulls_init(unfolder *u, ur_error *error)
{
    if (!u->room)
        return UR_OK;
    size_t slots = 1024; /* a piece's hull is kept when brought up to date: a few per join */
    while (slots < 4 * u->mesh->triangle_count && slots < KEPT_HULLS_MOST)
        slots *= 2;
    u->kept_hulls = table_alloc(slots, sizeof *u->kept_hulls, error);
    if (!u->kept_hulls)
        return UR_ERROR_MEMORY;
    u->kept_mask = slots - 1;
    return UR_OK;
}

void unfold_kept_hulls_free(unfolder *u)
{
    for (size_t k = 0; u->kept_hulls && k <= u->kept_mask; k++)
        free(u->kept_hulls[k].points);
    free(u->kept_hulls);
    u->kept_hulls = NULL;
}

static unfold_kept_hull *kept_slot(const unfolder *u, uint64_t layout)
{
    return &u->kept_hulls[(layout >> 3) & u->kept_mask];
}

/* Keeps piece p's hull, up to date, for the runs to come. */
static ur_status keep_for_later(unfolder *u, size_t p, ur_error *error)
{
    if (!u->kept_hulls || u->last_run)
        return UR_OK;
    const unfold_island *island = &u->islands[p];
    unfold_kept_hull *slot = kept_slot(u, island->layout);
    if (island->hull_count > slot->capacity) {
        ur_vec2 *grown = realloc(slot->points, 2 * island->hull_count * sizeof *grown);
        if (!grown)
            return ur_error_out_of_memory(error);
        slot->points = grown;
        slot->capacity = 2 * island->hull_count;
    }
    memcpy(slot->points, island->hull, island->hull_count * sizeof *slot->points);
    slot->count = island->hull_count;
    slot->layout = island->layout;
    slot->at[0] = u->flat[island->lowest][0];
    slot->at[1] = u->flat[island->lowest][1];
    return UR_OK;
}

/* The motion that takes a to b and the direction a0 -> a1 to b0 -> b1. */
static unfold_motion motion_between(const ur_vec2 a[2], ur_vec2 b0, ur_vec2 b1)
{
    ur_vec2 d = ur_vec2_sub(a[1], a[0]), e = ur_vec2_sub(b1, b0);
    double lengths = ur_vec2_length(d) * ur_vec2_length(e);
    return (unfold_motion){.cos = ur_vec2_dot(d, e) / lengths,
                           .sin = ur_vec2_cross(d, e) / lengths,
                           .from = a[0],
                           .to = b0};
}

/*
 * Sets piece p's hull from the one kept under its layout key, moved to
 * where the piece lies, and forgets the hulls still to merge; *found says
 * whether one was kept.
 */
static ur_status recall_hull(unfolder *u, size_t p, bool *found, ur_error *error)
{
    *found = false;
    unfold_island *island = &u->islands[p];
    const unfold_kept_hull *slot =
        u->kept_hulls && !u->last_run ? kept_slot(u, island->layout) : NULL;
    if (!slot || slot->count == 0 || slot->layout != island->layout)
        return UR_OK;
    const ur_vec2 *now = u->flat[island->lowest];
    unfold_motion m = motion_between(slot->at, now[0], now[1]);
    for (size_t i = 0; i < slot->count; i++)
        u->hull_points[i] = unfold_move(&m, slot->points[i]);
    ur_status status = set_hull(island, u->hull_points, slot->count, error);
    if (status == UR_OK) {
        island->absorbed_first = island->absorbed_last = UNFOLD_NONE;
        *found = true;
    }
    return status;
}

/*
 * The hulls of the pieces, when the room is limited, are kept up to date
 * only where a join needs them: a join that is looked up, or whose
 * pieces' circle shows that they fit the room, leaves the hull of the
 * smaller piece, and the motion that moved it, on a list of the larger
 * one, and the hulls on the list are merged into its own in turn, each
 * brought up to date first, when a join of the larger piece needs its
 * hull: the same hulls of two, in the same order, as if each had been
 * merged when its join was made.
 */
static void defer_hull(unfolder *u, const unfold_motion *m, size_t small, size_t large)
{
    unfold_island *a = &u->islands[small], *b = &u->islands[large];
    a->absorbed_motion = *m;
    a->absorbed_next = UNFOLD_NONE;
    if (b->absorbed_last == UNFOLD_NONE)
        b->absorbed_first = small;
    else
        u->islands[b->absorbed_last].absorbed_next = small;
    b->absorbed_last = small;
}

/*
 * Merges the hulls on piece p's list into its own, each brought up to
 * date first.  Each piece on the list is at most half as large as the
 * piece it joined, so that the lists nest at most log2(triangles) deep.
 */
static ur_status merge_absorbed(unfolder *u, size_t p, ur_error *error)
{
    while (u->islands[p].absorbed_first != UNFOLD_NONE) {
        size_t a = u->islands[p].absorbed_first;
        ur_status status = merge_absorbed(u, a, error);
        if (status != UR_OK)
            return status;
        u->islands[p].absorbed_first = u->islands[a].absorbed_next;
        size_t count = joined_hull(u, &u->islands[a].absorbed_motion, a, p);
        status = keep_hull(u, p, count, error);
        if (status != UR_OK)
            return status;
    }
    u->islands[p].absorbed_last = UNFOLD_NONE;
    return UR_OK;
}

ur_status unfold_update_hull(unfolder *u, size_t p, ur_error *error)
{
    if (u->islands[p].absorbed_first == UNFOLD_NONE)
        return UR_OK;
    bool found;
    ur_status status = recall_hull(u, p, &found, error);
    if (status == UR_OK && !found)
        status = merge_absorbed(u, p, error);
    if (status == UR_OK && !found)
        status = keep_for_later(u, p, error);
    return status;
}

/* The pairs the join joins, and inside a face its slits. */
static void find_all_pairs(unfolder *u, const unfold_motion *m, size_t small, size_t hinge_small,
                           size_t large, size_t hinge_large)
{
    size_t most = u->islands[small].outline_count < u->islands[large].outline_count
                      ? u->islands[small].outline_count
                      : u->islands[large].outline_count;
    find_pairs(u, m, hinge_small, hinge_large, most);
    u->slit_count = 0;
    if (u->slits)
        find_slits(u, m, small, large);
}

/*
 * How the join of the moved small piece to the large comes out: the tests
 * a remembered outcome spares.  Leaves the pairs found, and the hull of
 * both pieces in u->hull_points (*hull_count points) if it was needed
 * (the room is limited, and the circle round both pieces does not show
 * that they fit it); else *hull_count is 0.
 */
static ur_status judge(unfolder *u, const unfold_motion *m, size_t small, size_t hinge_small,
                       size_t large, size_t hinge_large, size_t *hull_count, unsigned *outcome,
                       ur_error *error)
{
    *hull_count = 0;
    ur_status status = UR_OK;
    if (u->room && u->room_binds && !unfold_circle_fits(u, joined_circle(u, m, small, large))) {
        status = unfold_update_hull(u, small, error);
        if (status == UR_OK)
            status = unfold_update_hull(u, large, error);
        if (status != UR_OK)
            return status;
        *hull_count = joined_hull(u, m, small, large);
        if (!unfold_hull_fits(u, u->hull_points, *hull_count)) {
            *outcome = OUTCOME_TOO_LARGE;
            /* Only whether there is one matters (to search turned): one test is enough. */
            if (!u->turned_room && u->turnable_refusals == 0 &&
                unfold_hull_fits_turned(u, u->hull_points, *hull_count))
                u->turnable_refusals++;
            return UR_OK;
        }
    }
    find_all_pairs(u, m, small, hinge_small, large, hinge_large);
    status = unfold_grid_piece(u, small, error); /* the slits' test asks about both pieces */
    if (status == UR_OK)
        status = unfold_grid_piece(u, large, error);
    if (status != UR_OK)
        return status;
    size_t hinge = hinge_small < hinge_large ? hinge_small : hinge_large;
    if (stopped_as_before(u, m, small, large, hinge)) {
        *outcome = OUTCOME_OVERLAPS;
        return UR_OK;
    }
    bool fit = fits(u, m, small, large);
    if (!fit)
        remember_stop(u, hinge);
    *outcome = fit ? OUTCOME_FITS : OUTCOME_OVERLAPS;
    return UR_OK;
}

/* Whether two pieces of several faces have failed to join too often (not inside faces). */
static bool given_up(const unfolder *u, size_t small, size_t large)
{
    const unfold_island *a = &u->islands[small];
    return !u->slits && a->face_count > 1 && u->islands[large].face_count > 1 &&
           a->failed_with == large && a->failed_size == u->islands[large].triangle_count &&
           a->failures >= UNFOLD_MOST_FAILURES;
}

static void count_failure(unfolder *u, size_t small, size_t large)
{
    unfold_island *a = &u->islands[small];
    size_t size = u->islands[large].triangle_count;
    if (a->failed_with == large && a->failed_size == size) {
        a->failures++;
        return;
    }
    a->failed_with = large;
    a->failed_size = size;
    a->failures = 1;
}

ur_status unfold_try_join(unfolder *u, size_t h, bool *joined, ur_error *error)
{
    *joined = false;
    u->slit_side_count = 0;
    size_t g = u->edges.twins[h];
    if (g == UR_NO_EDGE || u->edges.cut[h] || u->joined[h])
        return UR_OK;
    size_t a = u->piece[h / 3], b = u->piece[g / 3];
    if (a == b)
        return UR_OK;
    size_t na = u->islands[a].triangle_count, nb = u->islands[b].triangle_count;
    bool a_small = na < nb || (na == nb && a > b);
    size_t small = a_small ? a : b, large = a_small ? b : a;
    if (given_up(u, small, large))
        return UR_OK;
    size_t hinge_small = a_small ? h : g, hinge_large = a_small ? g : h;
    uint64_t key = 0;
    unsigned outcome = remembers(u)
                           ? recalled_join(u, small, large, hinge_small, h < g ? h : g, &key)
                           : OUTCOME_NONE;
    if (outcome == OUTCOME_TOO_LARGE)
        return UR_OK;
    if (outcome == OUTCOME_OVERLAPS) {
        count_failure(u, small, large);
        return UR_OK;
    }
    unfold_motion m = hinge_motion(u, hinge_small, hinge_large);
    size_t hull_count = 0;
    if (outcome == OUTCOME_NONE) {
        ur_status status =
            judge(u, &m, small, hinge_small, large, hinge_large, &hull_count, &outcome, error);
        if (status != UR_OK)
            return status;
        if (remembers(u))
            remember(u, key, h < g ? h : g, outcome);
    } else
        find_all_pairs(u, &m, small, hinge_small, large, hinge_large);
    if (outcome == OUTCOME_OVERLAPS)
        count_failure(u, small, large);
    if (outcome != OUTCOME_FITS)
        return UR_OK;
    bool judged_hull = u->room && hull_count > 0;
    if (judged_hull) {
        ur_status status = keep_hull(u, large, hull_count, error);
        if (status != UR_OK)
            return status;
    } else if (u->room)
        defer_hull(u, &m, small, large);
    *joined = true;
    commit(u, &m, small, large);
    /* the joined piece's hull, under its new key */
    return judged_hull ? keep_for_later(u, large, error) : UR_OK;
}
