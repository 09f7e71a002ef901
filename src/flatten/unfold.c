/*
 * unfold.c: ur_unfold: the exact unfolding of a polyhedral mesh along its
 * edges.
 *
 * A run starts from every triangle a piece of its own, laid in its flat
 * face's plane (unfold_faces.c), and joins pieces across edges in turn
 * (unfold_lay.c): first the edges inside flat faces, longest first, so
 * that each face becomes one piece and a face round a hole is cut at one
 * of its shortest edges; then the edges between faces in the order given.
 * A join that does not fit is left cut.  Every later join only adds to
 * pieces, so an edge refused once would be refused again: each edge is
 * tried once.  The first order is Blender's paper model's: flat edges,
 * then convex ones by turn, concave last, longer first; the search
 * (unfold_search.c) then changes it.
 */
#include "unfold_internal.h"

#include "../base/union_find.h"

#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

/* ---- the orders of the edges ---- */

/*
 * What folding across an edge costs: flat, then convex by turn, then
 * concave; or (by_length) flat, then every other edge alike, so that the
 * longer go first.
 */
static double fold_weight(const unfolder *u, size_t h, bool by_length)
{
    double bend = u->edges.bend[h];
    if (u->faces.flat[h])
        return 0.0;
    if (by_length)
        return 1.0;
    return bend > 0 ? bend : M_PI - bend;
}

typedef struct ranked_edge {
    double weight, length;
    size_t half;
} ranked_edge;

/* Cheapest first; at equal weight the longer edge, so that short edges are cut. */
static int compare_ranked(const void *a, const void *b)
{
    const ranked_edge *x = a, *y = b;
    if (x->weight != y->weight)
        return x->weight < y->weight ? -1 : 1;
    if (x->length != y->length)
        return x->length > y->length ? -1 : 1;
    return (x->half > y->half) - (x->half < y->half);
}

/* The edges between faces that may be joined, by their lower halves, in a first order. */
static ur_status rank_edges(const unfolder *u, bool by_length, size_t **order, size_t *count,
                            ur_error *error)
{
    size_t halves = 3 * u->mesh->triangle_count, n = 0;
    ranked_edge *ranked = ur_alloc_array(halves, sizeof *ranked, error);
    *order = ur_alloc_array(halves, sizeof **order, error);
    if (!ranked || !*order) {
        free(ranked);
        return UR_ERROR_MEMORY;
    }
    for (size_t h = 0; h < halves; h++) {
        size_t g = u->edges.twins[h];
        if (g == UR_NO_EDGE || g < h || u->edges.cut[h] ||
            u->faces.face[h / 3] == u->faces.face[g / 3])
            continue;
        ranked[n++] =
            (ranked_edge){fold_weight(u, h, by_length), unfold_edge_length(u->mesh, h), h};
    }
    qsort(ranked, n, sizeof *ranked, compare_ranked);
    for (size_t i = 0; i < n; i++)
        (*order)[i] = ranked[i].half;
    *count = n;
    free(ranked);
    return UR_OK;
}

/* ---- a run ---- */

size_t unfold_find(unfolder *u, size_t corner)
{
    return union_find_root(u->parent, corner);
}

size_t unfold_outline_next(const unfolder *u, size_t h)
{
    size_t n = unfold_next(h), limit = 3 * u->mesh->triangle_count;
    for (size_t turns = 0; u->joined[n]; turns++) {
        if (turns > limit)
            return UNFOLD_NONE;
        n = unfold_next(u->edges.twins[n]);
    }
    return n;
}

size_t unfold_outline_previous(const unfolder *u, size_t h)
{
    size_t p = unfold_previous(h), limit = 3 * u->mesh->triangle_count;
    for (size_t turns = 0; u->joined[p]; turns++) {
        if (turns > limit)
            return UNFOLD_NONE;
        p = unfold_previous(u->edges.twins[p]);
    }
    return p;
}

/* Every triangle a piece of its own, in its face's plane. */
static ur_status restart(unfolder *u, ur_error *error)
{
    size_t n = u->mesh->triangle_count;
    unfold_grid_restart(&u->grid);
    for (size_t i = 0; i < UNFOLD_CULPRITS; i++)
        u->culprits[i] = UNFOLD_NONE;
    for (size_t t = 0; t < n; t++) {
        u->piece[t] = t;
        u->next_member[t] = UNFOLD_NONE;
        unfold_island *island = &u->islands[t];
        island->first = island->last = t;
        island->triangle_count = 1;
        island->outline_count = 3;
        island->face_count = 1;
        island->area =
            0.5 * fabs(ur_vec2_cross(ur_vec2_sub(u->faces.home[t][1], u->faces.home[t][0]),
                                     ur_vec2_sub(u->faces.home[t][2], u->faces.home[t][0])));
        island->failed_with = UNFOLD_NONE;
        island->failures = 0;
        island->layout = unfold_triangle_key(t);
        island->lowest = t;
        for (int k = 0; k < 3; k++) {
            u->flat[t][k] = u->faces.home[t][k];
            u->joined[3 * t + (size_t)k] = false;
            u->tab_on_twin[3 * t + (size_t)k] = false;
            u->parent[3 * t + (size_t)k] = 3 * t + (size_t)k;
            if (u->room)
                island->hull[k] = u->flat[t][k];
        }
        if (u->room)
            island->circle = u->home_circles[t];
        island->hull_count = u->room ? 3 : 0;
        island->hull_set = false;
        island->grid_last = UNFOLD_NONE;
        island->absorbed_first = island->absorbed_last = UNFOLD_NONE;
        ur_status status = u->last_run ? unfold_grid_piece(u, t, error) : UR_OK;
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

static ur_status join_all(unfolder *u, const size_t *order, size_t count, ur_error *error)
{
    for (size_t i = 0; i < count; i++) {
        bool joined;
        ur_status status = unfold_try_join(u, order[i], &joined, error);
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

/* The arrays of a run that are copied whole (the islands are copied apart: each keeps its hull). */
typedef struct run_arrays {
    size_t *piece, *parent, *next_member;
    ur_vec2 (*flat)[3];
    bool *joined, *tab_on_twin;
} run_arrays;

static run_arrays arrays_of(const unfolder *u)
{
    return (run_arrays){u->piece, u->parent, u->next_member, u->flat, u->joined, u->tab_on_twin};
}

static void copy_arrays(run_arrays to, run_arrays from, size_t n)
{
    memcpy(to.piece, from.piece, n * sizeof *to.piece);
    memcpy(to.parent, from.parent, 3 * n * sizeof *to.parent);
    memcpy(to.next_member, from.next_member, n * sizeof *to.next_member);
    memcpy(to.flat, from.flat, n * sizeof *to.flat);
    memcpy(to.joined, from.joined, 3 * n * sizeof *to.joined);
    memcpy(to.tab_on_twin, from.tab_on_twin, 3 * n * sizeof *to.tab_on_twin);
}

/*
 * Every run joins the edges inside flat faces first, in the same order
 * and with the same outcomes (the room does not bind there), so the state
 * they leave is kept after the first run and put back in the runs after
 * it: a seventh of the search's time on the bench's 48 x 24 sphere, whose
 * quads are two triangles each.  The pieces' hulls are then still their
 * first triangles' (a face's joins never bring a hull up to date), and the
 * grid is filled again as joins need it, as after restart.  The last run,
 * which judges every join itself, joins its faces anew.
 */
typedef struct unfold_faces_joined {
    run_arrays arrays;
    unfold_island *islands;
    size_t culprits[UNFOLD_CULPRITS];
} unfold_faces_joined;

static void faces_joined_free(unfold_faces_joined *f)
{
    if (!f)
        return;
    free(f->arrays.piece);
    free(f->arrays.parent);
    free(f->arrays.next_member);
    free(f->arrays.flat);
    free(f->arrays.joined);
    free(f->arrays.tab_on_twin);
    free(f->islands);
    free(f);
}

/* Keeps the run's state as its faces left it; nothing kept when memory is short (only slower). */
static void keep_faces_joined(unfolder *u)
{
    size_t n = u->mesh->triangle_count;
    unfold_faces_joined *f = calloc(1, sizeof *f);
    if (f) {
        run_arrays *a = &f->arrays;
        a->piece = malloc(n * sizeof *a->piece);
        a->parent = malloc(3 * n * sizeof *a->parent);
        a->next_member = malloc(n * sizeof *a->next_member);
        a->flat = malloc(n * sizeof *a->flat);
        a->joined = malloc(3 * n * sizeof *a->joined);
        a->tab_on_twin = malloc(3 * n * sizeof *a->tab_on_twin);
        f->islands = malloc(n * sizeof *f->islands);
    }
    if (!f || !f->arrays.piece || !f->arrays.parent || !f->arrays.next_member || !f->arrays.flat ||
        !f->arrays.joined || !f->arrays.tab_on_twin || !f->islands) {
        faces_joined_free(f);
        return;
    }
    copy_arrays(f->arrays, arrays_of(u), n);
    memcpy(f->islands, u->islands, n * sizeof *f->islands);
    memcpy(f->culprits, u->culprits, sizeof f->culprits);
    u->faces_joined = f;
}

/* The state kept by keep_faces_joined, each piece keeping its own hull's room. */
static void put_back_faces_joined(unfolder *u)
{
    const unfold_faces_joined *f = u->faces_joined;
    size_t n = u->mesh->triangle_count;
    unfold_grid_restart(&u->grid);
    copy_arrays(arrays_of(u), f->arrays, n);
    memcpy(u->culprits, f->culprits, sizeof u->culprits);
    for (size_t t = 0; t < n; t++) {
        unfold_island *island = &u->islands[t];
        ur_vec2 *hull = island->hull;
        size_t capacity = island->hull_capacity;
        bool set = island->hull_set;
        *island = f->islands[t];
        island->hull = hull;
        island->hull_capacity = capacity;
        island->grid_last = UNFOLD_NONE;
        /* Most hulls are still their first triangles': left, not written again (a miss each). */
        for (int k = 0; u->room && set && k < 3; k++)
            hull[k] = u->faces.home[t][k];
    }
}

/* Every triangle a piece of its own, then the edges inside flat faces joined. */
static ur_status join_faces(unfolder *u, ur_error *error)
{
    if (u->faces_joined && !u->last_run) {
        put_back_faces_joined(u);
        return UR_OK;
    }
    ur_status status = restart(u, error);
    if (status == UR_OK)
        status = join_all(u, u->faces.order, u->faces.order_count, error);
    if (status == UR_OK && !u->faces_joined && !u->last_run)
        keep_faces_joined(u);
    return status;
}

/*
 * Tries every edge again, a slit narrower than the gap now allowed where
 * the tabs of both its edges can go on their twins (unfold_lay.c): the
 * gap keeps room for a tab on both sides of a slit, where one side is
 * enough.  Only in the last run: the joins it adds to the search's best
 * are free (no tab loses its room), and a pass more in every step of the
 * search would slow it for no better choice of the order.  The failures
 * counted before are forgotten: the joins they gave up may fit now.
 */
static ur_status join_with_tabs_on_twins(unfolder *u, const size_t *order, size_t count,
                                         ur_error *error)
{
    for (size_t t = 0; t < u->mesh->triangle_count; t++)
        u->islands[t].failures = 0;
    u->tabs_to_twins = true;
    ur_status status = join_all(u, order, count, error);
    u->tabs_to_twins = false;
    return status;
}

/* Whether the gap may be broken for piece p: a single face, or less than small_piece_area. */
static bool is_small(const unfolder *u, size_t p)
{
    return u->islands[p].face_count == 1 || u->islands[p].area < u->options.small_piece_area;
}

/*
 * Joins the pieces of a single face the gap left (a sphere's thin pole
 * triangles, which no join lays clear of their neighbours), and those
 * smaller than options.small_piece_area, to a neighbour without it,
 * counting the joins: a stray face or a scrap smaller than a tab costs
 * the maker more than a seam whose tab may find no room (the tabs then
 * say so), and the search weighs such joins as pieces.  With
 * options.gap_break_cost below one, pieces of any size are joined so,
 * each join costing less than the piece it saves.  Every edge was tried
 * with the gap before and joins only add to pieces, so each join here
 * breaks it.
 */
static ur_status join_strays(unfolder *u, const size_t *order, size_t count, size_t *joins,
                             ur_error *error)
{
    u->gap_waived = true;
    bool any_piece = u->options.gap_break_cost < 1.0;
    ur_status status = UR_OK;
    for (size_t i = 0; i < count && status == UR_OK; i++) {
        size_t h = order[i], g = u->edges.twins[h];
        if (!any_piece && !is_small(u, u->piece[h / 3]) && !is_small(u, u->piece[g / 3]))
            continue;
        bool joined;
        status = unfold_try_join(u, h, &joined, error);
        *joins += joined;
    }
    u->gap_waived = false;
    return status;
}

static bool one_face(const unfolder *u, size_t p)
{
    size_t first = u->islands[p].first;
    for (size_t t = first; t != UNFOLD_NONE; t = u->next_member[t])
        if (u->faces.face[t] != u->faces.face[first])
            return false;
    return true;
}

static unfold_score score_of(const unfolder *u)
{
    unfold_score score = {0, 0, 0, 0.0, 0.0};
    size_t n = u->mesh->triangle_count;
    for (size_t p = 0; p < n; p++) {
        if (u->islands[p].triangle_count == 0)
            continue;
        score.pieces++;
        score.single_face += one_face(u, p);
    }
    for (size_t h = 0; h < 3 * n; h++) {
        size_t g = u->edges.twins[h];
        if (g != UR_NO_EDGE && h < g && !u->joined[h])
            score.seam_length += unfold_edge_length(u->mesh, h);
    }
    return score;
}

int unfold_score_compare(unfold_score a, unfold_score b)
{
    if (unfold_score_cost(a) != unfold_score_cost(b))
        return unfold_score_cost(a) < unfold_score_cost(b) ? -1 : 1;
    if (a.single_face != b.single_face)
        return a.single_face < b.single_face ? -1 : 1;
    if (a.gap_breaks != b.gap_breaks) /* a seam with room for its tab before a shorter cut */
        return a.gap_breaks < b.gap_breaks ? -1 : 1;
    if (a.seam_length != b.seam_length)
        return a.seam_length < b.seam_length ? -1 : 1;
    return 0;
}

ur_status unfold_run(unfolder *u, const size_t *order, size_t count, unfold_score *score,
                     ur_error *error)
{
    u->room_binds = false; /* a face is never cut: one too large is refused before */
    u->slits = true;
    ur_status status = join_faces(u, error);
    for (size_t t = 0; t < u->mesh->triangle_count; t++)
        u->islands[t].face_count = 1; /* each piece now a face (or part of one) */
    u->room_binds = u->room;
    u->slits = false;
    if (status == UR_OK)
        status = join_all(u, order, count, error);
    u->gap_breaks = 0;
    if (status == UR_OK && u->options.min_gap > 0 && !u->options.gap_strands_faces)
        status = join_strays(u, order, count, &u->gap_breaks, error);
    if (status == UR_OK && u->last_run && u->options.min_gap > 0)
        status = join_with_tabs_on_twins(u, order, count, error);
    if (status == UR_OK) {
        *score = score_of(u);
        score->gap_breaks = u->gap_breaks;
        score->cost = (double)score->pieces + u->options.gap_break_cost * (double)score->gap_breaks;
    }
    return status;
}

/* ---- the unfolder ---- */

static ur_status check_options(const ur_unfold_options *o, ur_error *error)
{
    if (!(o->flat_angle >= 0 && o->flat_angle < M_PI / 2))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the flat angle must be at least 0 and less than 90 degrees");
    if (!(o->time_budget >= 0 && isfinite(o->time_budget)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the unfolding's time budget must be a number of seconds >= 0");
    if (!(o->room_length >= 0 && isfinite(o->room_length) && o->room_width >= 0 &&
          isfinite(o->room_width)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the room for a piece must be two lengths >= 0 (0 x 0: no limit)");
    if (!(o->min_gap >= 0 && isfinite(o->min_gap)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the narrowest gap between a piece's edges must be a length >= 0");
    if (!(o->small_piece_area >= 0 && isfinite(o->small_piece_area)))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the area below which a piece is joined without the gap must be "
                            "an area >= 0");
    if (!(o->gap_break_cost >= 0 && o->gap_break_cost <= 1))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "what a join without the gap costs must be from 0 to 1 piece");
    return UR_OK;
}

static ur_status alloc_run(unfolder *u, ur_error *error)
{
    size_t n = u->mesh->triangle_count;
    u->piece = ur_alloc_array(n, sizeof *u->piece, error);
    u->flat = ur_alloc_array(n, sizeof *u->flat, error);
    u->joined = ur_alloc_array(3 * n, sizeof *u->joined, error);
    u->parent = ur_alloc_array(3 * n, sizeof *u->parent, error);
    u->next_member = ur_alloc_array(n, sizeof *u->next_member, error);
    u->islands = ur_alloc_array(n, sizeof *u->islands, error);
    u->pair_small = ur_alloc_array(3 * n + 2, sizeof *u->pair_small, error);
    u->pair_large = ur_alloc_array(3 * n + 2, sizeof *u->pair_large, error);
    u->roots = ur_alloc_array(4 * (3 * n + 2), sizeof *u->roots, error);
    u->nearby = ur_alloc_array(n, sizeof *u->nearby, error);
    u->tab_on_twin = ur_alloc_array(3 * n, sizeof *u->tab_on_twin, error);
    u->slit_sides = ur_alloc_array(3 * n, sizeof *u->slit_sides, error);
    u->hinge_culprits = ur_alloc_array(3 * n, sizeof *u->hinge_culprits, error);
    u->hinge_outcomes = ur_alloc_array(3 * n, sizeof *u->hinge_outcomes, error);
    if (!u->piece || !u->flat || !u->joined || !u->parent || !u->next_member || !u->islands ||
        !u->pair_small || !u->pair_large || !u->roots || !u->nearby || !u->tab_on_twin ||
        !u->slit_sides || !u->hinge_culprits || !u->hinge_outcomes)
        return UR_ERROR_MEMORY;
    for (size_t h = 0; h < 3 * n; h++)
        u->hinge_culprits[h][0] = u->hinge_culprits[h][1] = UNFOLD_NONE;
    if (!u->room)
        return UR_OK;
    u->hull_points = ur_alloc_array(3 * n + 1, sizeof *u->hull_points, error);
    u->hull_chain = ur_alloc_array(6 * n + 2, sizeof *u->hull_chain, error);
    u->home_circles = ur_alloc_array(n, sizeof *u->home_circles, error);
    if (!u->hull_points || !u->hull_chain || !u->home_circles)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < n; t++)
        u->home_circles[t] = unfold_circle_round(u, u->faces.home[t], 3);
    for (size_t t = 0; t < n; t++) {
        u->islands[t].hull = ur_alloc_array(3, sizeof *u->islands[t].hull, error);
        if (!u->islands[t].hull)
            return UR_ERROR_MEMORY;
        u->islands[t].hull_capacity = 3;
    }
    return UR_OK;
}

static ur_status unfolder_init(unfolder *u, const ur_mesh *mesh, const ur_seam *seams,
                               size_t seam_count, const ur_unfold_options *options, ur_error *error)
{
    *u = (unfolder){.mesh = mesh, .seams = seams, .seam_count = seam_count, .progress_span = 1.0};
    if (options)
        u->options = *options;
    else
        ur_unfold_options_default(&u->options);
    ur_status status = check_options(&u->options, error);
    if (status == UR_OK)
        status = unfold_edges_build(mesh, seams, seam_count, &u->edges, error);
    if (status == UR_OK)
        status = unfold_faces_build(mesh, &u->edges, u->options.flat_angle, &u->faces, error);
    if (status != UR_OK)
        return status;
    /* Faces laid in their planes meet their neighbours only to the projection's slack. */
    u->eps = fmax(UNFOLD_CONTACT * u->edges.scale, 2.0 * u->faces.slack);
    u->room = u->options.room_length > 0 && u->options.room_width > 0;
    status = alloc_run(u, error);
    if (status == UR_OK)
        status = unfold_grid_init(&u->grid, mesh->triangle_count, u->edges.mean_edge, error);
    if (status == UR_OK)
        status = unfold_outcomes_init(u, error);
    if (status == UR_OK)
        status = unfold_kept_hulls_init(u, error);
    return status;
}

static void unfolder_free(unfolder *u)
{
    unfold_edges_free(&u->edges);
    unfold_faces_free(&u->faces);
    if (u->islands)
        for (size_t t = 0; t < u->mesh->triangle_count; t++)
            free(u->islands[t].hull);
    free(u->piece);
    free(u->flat);
    free(u->joined);
    free(u->parent);
    free(u->next_member);
    free(u->islands);
    free(u->pair_small);
    free(u->pair_large);
    free(u->roots);
    free(u->nearby);
    free(u->tab_on_twin);
    free(u->slit_sides);
    free(u->hinge_culprits);
    free(u->hinge_outcomes);
    free(u->hull_points);
    free(u->hull_chain);
    free(u->home_circles);
    free(u->outcomes);
    faces_joined_free(u->faces_joined);
    unfold_kept_hulls_free(u);
    unfold_grid_free(&u->grid);
}

/* ---- the result ---- */

/* A flat face (one piece after the faces are joined) larger than the room, refused. */
static ur_status check_faces_fit(unfolder *u, ur_error *error)
{
    unfold_score score;
    ur_status status = unfold_run(u, NULL, 0, &score, error);
    if (status != UR_OK)
        return status;
    for (size_t t = 0; t < u->mesh->triangle_count; t++) {
        const unfold_island *island = &u->islands[t];
        if (island->triangle_count == 0)
            continue;
        status = unfold_update_hull(u, t, error);
        if (status != UR_OK)
            return status;
        if (unfold_hull_fits(u, island->hull, island->hull_count))
            continue;
        double length, width;
        unfold_hull_size(island->hull, island->hull_count, &length, &width);
        size_t first = island->first;
        for (size_t s = island->first; s != UNFOLD_NONE; s = u->next_member[s])
            first = s < first ? s : first;
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the flat face of triangle %zu (%zu triangle%s) is %.1f x %.1f mm, "
                            "larger than the room of %.1f x %.1f mm a piece may take, and a face "
                            "is never cut",
                            first + 1, island->triangle_count,
                            island->triangle_count == 1 ? "" : "s", length, width,
                            fmax(u->options.room_length, u->options.room_width),
                            fmin(u->options.room_length, u->options.room_width));
    }
    return UR_OK;
}

/* Folds, flat joins, seams and boundary edges, each edge counted once. */
static void count_edges(const unfolder *u, ur_unfolding *out)
{
    for (size_t h = 0; h < 3 * u->mesh->triangle_count; h++) {
        size_t g = u->edges.twins[h];
        if (g == UR_NO_EDGE)
            out->boundary++;
        else if (h > g)
            continue;
        else if (!u->joined[h]) {
            out->seams++;
            out->seam_length += unfold_edge_length(u->mesh, h);
        } else if (u->faces.flat[h])
            out->flat++;
        else {
            out->folds++;
            out->valleys += u->edges.bend[h] < 0;
        }
    }
}

/* The pieces of the last run, in the order of their first triangle. */
static ur_status build_pieces(const unfolder *u, GEOSContextHandle_t geos, ur_unfolding *out,
                              ur_error *error)
{
    size_t n = u->mesh->triangle_count, count = 0;
    for (size_t p = 0; p < n; p++)
        count += u->islands[p].triangle_count > 0;
    out->pieces = ur_alloc_array(count, sizeof *out->pieces, error);
    bool *done = ur_alloc_array(n, sizeof *done, error);
    ur_status status = out->pieces && done ? UR_OK : UR_ERROR_MEMORY;
    for (size_t t = 0; t < n && status == UR_OK; t++) {
        size_t p = u->piece[t];
        if (done[p])
            continue;
        done[p] = true;
        status = unfold_piece_build(u, p, out->count, geos, &out->pieces[out->count], error);
        if (status == UR_OK) {
            out->single_face += out->pieces[out->count].face_count == 1;
            out->count++;
        }
    }
    free(done);
    return status;
}

/*
 * The pieces of order, after the search: its last run (which joins across
 * slits where both tabs can go to their twins), then each piece laid out
 * and counted.
 */
static ur_status finish_unfolding(unfolder *u, const size_t *order, size_t count, ur_unfolding *out,
                                  ur_error *error)
{
    ur_status status = UR_OK;
    if (u->options.min_gap > 0 && !u->options.gap_both_sides) {
        unfold_score last;
        u->last_run = true;
        status = unfold_run(u, order, count, &last, error);
    }
    out->gap_breaks = u->gap_breaks;
    GEOSContextHandle_t geos = status == UR_OK ? GEOS_init_r() : NULL;
    if (status == UR_OK && !geos)
        status = ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not be started");
    if (status == UR_OK)
        status = build_pieces(u, geos, out, error);
    if (status == UR_OK)
        count_edges(u, out);
    if (geos)
        GEOS_finish_r(geos);
    return status;
}

/*
 * The order the search starts from: Blender's paper model's (by bend), or
 * longer edges first whatever their bend when its run costs at least a
 * fifth less (fewer pieces and single faces joined without the gap).  On
 * a mesh of regular quads the bends decide between whole rows of edges:
 * a torus's edges round the tube turn less than those along it, and
 * joining them first makes rings round the torus that do not lie flat
 * (Blender's torus with tabs on A3: 43 pieces before the search and 16
 * after it by bend, 32 and 9 by length; its monkey 58 and 23, 44 and 19).
 * Runs that cost about the same say little about where the search ends
 * (UV spheres: 26 against 24 before it, 7 against 9 after; 23 against
 * 22, 6 against 7; the sample head: 25 against 22, 9 against 8 but with a
 * seam left without room for its tab), so there the bends keep their
 * say.  The fifth is what these meshes showed, not a law.
 */
static ur_status first_order(unfolder *u, size_t **order, size_t *count, unfold_score *first,
                             ur_error *error)
{
    size_t *by_length = NULL, by_length_count = 0;
    unfold_score bend_score = {0}, length_score = {0};
    ur_status status = rank_edges(u, false, order, count, error);
    if (status == UR_OK)
        status = rank_edges(u, true, &by_length, &by_length_count, error);
    if (status == UR_OK)
        status = unfold_run(u, *order, *count, &bend_score, error);
    if (status == UR_OK)
        status = unfold_run(u, by_length, by_length_count, &length_score, error);
    if (status == UR_OK &&
        5 * unfold_score_cost(length_score) <= 4 * unfold_score_cost(bend_score)) {
        size_t *swap = *order;
        *order = by_length;
        by_length = swap;
        bend_score = length_score;
    }
    *first = bend_score;
    free(by_length);
    return status;
}

static void report(const unfolder *u, const char *phase, double fraction)
{
    if (u->options.progress)
        u->options.progress(u->options.progress_context, phase, fraction);
}

/* The score of the last run (unfold) on order: its joins across slits are not in the search's. */
static ur_status last_run_score(unfolder *u, const size_t *order, size_t count, unfold_score *score,
                                ur_error *error)
{
    u->last_run = true;
    ur_status status = unfold_run(u, order, count, score, error);
    u->last_run = false;
    return status;
}

/*
 * The search in two parts: UNFOLD_FIRST_STEPS steps (or max_steps if
 * fewer), then the rest of the steps on from the best of those, each part
 * within the time budget.  The steps in all are max_steps, or
 * steps_per_piece for each piece the first part left when that is more
 * (up to UNFOLD_MOST_BY_PIECES; Blender's monkey head subdivided once,
 * 3,936 triangles: 132 pieces after 200 steps, 106 after 1,000, and its
 * nesting 6 s shorter).  The longer search finds fewer pieces on some
 * meshes (Blender's monkey head: 31 -> 17 in 723 steps) and, scored
 * without the last run's joins, more on others (a 48 x 24 sphere in 452
 * steps: 10 -> 12, with more seams joined without the gap), so it is kept
 * only when, after the last run, it is better (fewer pieces and joins
 * without the gap together, then as unfold_score_compare goes on) with no
 * more pieces.  A few more such joins for many fewer pieces are worth it:
 * the subdivided monkey with 3,000 steps, 88 pieces and 3 such joins
 * against 132 and 1 (the rule that also wanted no more such joins kept
 * the 132).  u is left with the pieces of the order kept.
 */
enum { UNFOLD_FIRST_STEPS = 200, UNFOLD_MOST_BY_PIECES = 1000 };

/* The steps of both parts, after a first part that left best. */
static size_t steps_in_all(const unfolder *u, size_t given, unfold_score best)
{
    if (given == 0) /* time alone: one part */
        return 0;
    size_t by_pieces = u->options.steps_per_piece * best.pieces;
    if (by_pieces > UNFOLD_MOST_BY_PIECES)
        by_pieces = UNFOLD_MOST_BY_PIECES;
    return by_pieces > given ? by_pieces : given;
}

/*
 * The share of its window the first part of search_in_two reports in,
 * when the steps given were u->progress_given and its best so far is
 * best: its steps' share of both parts' as the best's pieces would ask
 * for them.  The share only grows as the pieces fall, so that the line
 * moves forward; it is the first part's share in the end.  (Half the
 * window, kept for steps the pieces might ask for, left the line at half
 * when they did not: a 48 x 24 sphere's went from 48 % to done.)
 */
double unfold_first_part_share(const unfolder *u, unfold_score best)
{
    size_t given = u->progress_given;
    if (given == 0) /* a part whose window is fixed, or time alone: one part */
        return 1.0;
    size_t first = given < UNFOLD_FIRST_STEPS ? given : UNFOLD_FIRST_STEPS;
    size_t total = steps_in_all(u, given, best);
    size_t second = total > UNFOLD_FIRST_STEPS ? total - UNFOLD_FIRST_STEPS : 0;
    return (double)first / (double)(first + second);
}

static ur_status search_in_two(unfolder *u, size_t **order, size_t count, size_t *steps,
                               unfold_score *best, ur_error *error)
{
    size_t given = u->options.max_steps;
    double from = u->progress_from, span = u->progress_span;
    if (given > UNFOLD_FIRST_STEPS)
        u->options.max_steps = UNFOLD_FIRST_STEPS;
    u->progress_given = given;
    ur_status status = unfold_search(u, *order, count, steps, best, error);
    size_t total = status == UR_OK ? steps_in_all(u, given, *best) : 0;
    double first_span = status == UR_OK ? span * unfold_first_part_share(u, *best) : span;
    u->progress_given = 0;
    u->options.max_steps = given;
    u->progress_from = from + first_span; /* the second part, if any, goes on from there */
    u->progress_span = span - first_span;
    if (status != UR_OK || total <= UNFOLD_FIRST_STEPS)
        return status;
    size_t *more = ur_alloc_array(count ? count : 1, sizeof *more, error);
    if (!more)
        return UR_ERROR_MEMORY;
    memcpy(more, *order, count * sizeof *more);
    u->options.max_steps = total - UNFOLD_FIRST_STEPS;
    size_t more_steps = 0;
    unfold_score further;
    status = unfold_search(u, more, count, &more_steps, &further, error);
    u->options.max_steps = given;
    *steps += more_steps;
    bool last = u->options.min_gap > 0 && !u->options.gap_both_sides;
    bool keep = status == UR_OK && unfold_score_compare(further, *best) < 0;
    if (keep && last) {
        unfold_score first_last, further_last;
        status = last_run_score(u, *order, count, &first_last, error);
        if (status == UR_OK)
            status = last_run_score(u, more, count, &further_last, error);
        keep = status == UR_OK && further_last.pieces <= first_last.pieces &&
               unfold_score_compare(further_last, first_last) < 0;
    }
    if (keep) {
        size_t *swap = *order;
        *order = more;
        more = swap;
        *best = further;
    }
    if (status == UR_OK && (last || !keep)) /* the pieces of the order kept */
        status = unfold_run(u, *order, count, best, error);
    free(more);
    return status;
}

/* The turned search's options: half the level one's steps and time budget. */
static ur_unfold_options turned_options(const ur_unfold_options *level)
{
    ur_unfold_options o = *level;
    o.time_budget /= 2;
    o.max_steps = (level->max_steps + 1) / 2;
    o.steps_per_piece = (level->steps_per_piece + 1) / 2;
    return o;
}

/*
 * The search for fewer pieces, with the room taken level (as nesting first
 * turns a piece); then, if the room refused joins it would have taken
 * turned, again from the same order with the room taken at any turn (a
 * piece that fits only between level and on end, as nesting then turns
 * it), keeping the better (the level one when as good).  Neither always wins: the freer room lets
 * the search grow pieces that later block others (the project's torus sample: 5 pieces level, 7
 * turned; Blender's torus: 10 level, 5 turned).  The turned search takes half the steps and half
 * the time budget (a 48 x 24 sphere, whose turned search finds nothing better, pays 100 steps for
 * it; Blender's torus finds its 5 pieces so too).  u is left with the pieces kept, *order with its
 * order.
 */
static ur_status search_level_then_turned(unfolder *u, size_t **order, size_t count, size_t *steps,
                                          ur_error *error)
{
    size_t *turned = NULL;
    if (u->room) {
        turned = ur_alloc_array(count ? count : 1, sizeof *turned, error);
        if (!turned)
            return UR_ERROR_MEMORY;
        memcpy(turned, *order, count * sizeof *turned);
    }
    unfold_score level, best;
    size_t more = 0;
    u->turned_room = false;
    u->turnable_refusals = 0;
    /* The turned search, if any, takes half the level one's steps: the last third of the report. */
    double level_share = u->room ? 2.0 / 3.0 : 1.0;
    u->progress_from = 0;
    u->progress_span = level_share;
    ur_status status = search_in_two(u, order, count, steps, &level, error);
    if (status == UR_OK && u->room && u->turnable_refusals > 0) {
        u->turned_room = true;
        u->progress_from = level_share;
        u->progress_span = 1 - level_share;
        ur_unfold_options given = u->options;
        u->options = turned_options(&given);
        status = search_in_two(u, &turned, count, &more, &best, error);
        u->options = given;
        *steps += more;
        if (status == UR_OK && unfold_score_compare(best, level) < 0) {
            size_t *swap = *order;
            *order = turned;
            turned = swap;
        } else if (status == UR_OK) {
            u->turned_room = false;
            status = unfold_run(u, *order, count, &level, error);
        }
    }
    free(turned);
    return status;
}

/*
 * The turned search beside the level one (search_side_by_side): a state
 * of its own, made from the level search's mesh, seams and options, and
 * what it found.  When it ends while the level search still runs, it
 * builds its pieces too (finish_unfolding), which the level search then
 * need not make again should the turned one win: the same pieces, built
 * on a core that would wait (the bench's 48 x 24 sphere, whose turned
 * search wins, ends it at about the level search's 140th step of 200).
 */
typedef struct turned_aside {
    const ur_mesh *mesh;
    const ur_seam *seams;
    size_t seam_count;
    ur_unfold_options options; /* copied: the level search changes its own as it goes */
    unfolder u;
    size_t *order; /* the first order, then the best found (owned) */
    size_t count, steps;
    unfold_score best;
    ur_status status;
    ur_error error;
    atomic_bool level_ended; /* set by the level search: too late to build ahead */
    bool built;              /* pieces holds the pieces of order */
    ur_unfolding pieces;     /* owned until handed on */
} turned_aside;

static int search_turned_aside(void *data)
{
    turned_aside *a = data;
    a->status = unfolder_init(&a->u, a->mesh, a->seams, a->seam_count, &a->options, &a->error);
    if (a->status == UR_OK) {
        a->u.turned_room = true;
        a->status = search_in_two(&a->u, &a->order, a->count, &a->steps, &a->best, &a->error);
    }
    if (a->status == UR_OK && !atomic_load(&a->level_ended)) {
        /* A failure here is no failure of the search: the level search builds them itself. */
        ur_error ignored;
        a->built = finish_unfolding(&a->u, a->order, a->count, &a->pieces, &ignored) == UR_OK;
        if (!a->built)
            ur_unfolding_free(&a->pieces);
    }
    return 0;
}

/*
 * search_level_then_turned with both searches side by side: the turned
 * one starts at once in a thread of its own, before the level one has
 * shown whether it is wanted, and is dropped when it is not.  Each search
 * keeps its own outcomes and hulls over its runs.  When no thread can
 * start, the turned search runs after the level one, still on a state of
 * its own, so that the pieces are the same.  When the turned search wins
 * and built its pieces ahead, they are handed on in *out (*built).
 */
static ur_status search_side_by_side(unfolder *u, size_t **order, size_t count, size_t *steps,
                                     ur_unfolding *out, bool *built, ur_error *error)
{
    turned_aside aside = {.mesh = u->mesh,
                          .seams = u->seams,
                          .seam_count = u->seam_count,
                          .options = turned_options(&u->options),
                          .count = count,
                          .status = UR_OK};
    atomic_init(&aside.level_ended, false);
    aside.options.progress = NULL; /* the level search reports for both */
    aside.options.threads = 1;
    aside.options.started = NULL;
    aside.order = ur_alloc_array(count ? count : 1, sizeof *aside.order, error);
    if (!aside.order)
        return UR_ERROR_MEMORY;
    memcpy(aside.order, *order, count * sizeof *aside.order);
    thrd_t thread;
    bool beside = thrd_create(&thread, search_turned_aside, &aside) == thrd_success;
    unfold_score level;
    u->turned_room = false;
    u->turnable_refusals = 0;
    u->progress_from = 0;
    u->progress_span = 1;
    ur_status status = search_in_two(u, order, count, steps, &level, error);
    atomic_store(&aside.level_ended, true);
    bool wanted = status == UR_OK && u->turnable_refusals > 0;
    if (beside)
        thrd_join(thread, NULL);
    else if (wanted)
        search_turned_aside(&aside);
    if (wanted && aside.status != UR_OK) {
        status = aside.status;
        *error = aside.error;
    }
    if (wanted && status == UR_OK) {
        *steps += aside.steps;
        if (unfold_score_compare(aside.best, level) < 0) {
            size_t *swap = *order;
            *order = aside.order;
            aside.order = swap;
            u->turned_room = true;
            if (aside.built) { /* its pieces, built ahead */
                *out = aside.pieces;
                aside.pieces = (ur_unfolding){0};
                *built = true;
            } else /* u is given its pieces */
                status = unfold_run(u, *order, count, &level, error);
        }
    }
    ur_unfolding_free(&aside.pieces);
    unfolder_free(&aside.u);
    free(aside.order);
    return status;
}

static ur_status unfold(unfolder *u, ur_unfolding *out, ur_error *error)
{
    size_t *order = NULL, count = 0;
    report(u, "unfolding", 0.0);
    u->turned_room = true; /* a face too large level may still fit turned */
    ur_status status = u->room ? check_faces_fit(u, error) : UR_OK;
    u->turned_room = false;
    unfold_score first = {0};
    if (status == UR_OK)
        status = first_order(u, &order, &count, &first, error);
    if (status == UR_OK && u->options.started &&
        !u->options.started(u->options.started_context, unfold_score_cost(first),
                            &u->options.threads))
        status = ur_error_set(error, UR_ERROR_CANCELLED,
                              "the unfolding was stopped after its first run");
    size_t steps = 0;
    bool built = false;
    if (status == UR_OK && u->room && u->options.threads >= 2)
        status = search_side_by_side(u, &order, count, &steps, out, &built, error);
    else if (status == UR_OK)
        status = search_level_then_turned(u, &order, count, &steps, error);
    if (status == UR_OK && !built)
        status = finish_unfolding(u, order, count, out, error);
    out->steps = steps;
    free(order);
    report(u, "unfolding", 1.0);
    return status;
}

void ur_unfold_options_default(ur_unfold_options *options)
{
    *options = (ur_unfold_options){
        .flat_angle = UR_UNFOLD_FLAT_ANGLE,
        .time_budget = 1.0,
        .seed = 1,
        .gap_break_cost = 1.0,
        .threads = 1,
    };
}

ur_status ur_unfold_with_options(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                                 const ur_unfold_options *options, ur_unfolding *out,
                                 ur_error *error)
{
    *out = (ur_unfolding){0};
    unfolder u;
    ur_status status = unfolder_init(&u, mesh, seams, seam_count, options, error);
    if (status == UR_OK)
        status = unfold(&u, out, error);
    unfolder_free(&u);
    if (status != UR_OK)
        ur_unfolding_free(out);
    return status;
}

ur_status ur_unfold(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count, ur_unfolding *out,
                    ur_error *error)
{
    return ur_unfold_with_options(mesh, seams, seam_count, NULL, out, error);
}

void ur_unfolding_free(ur_unfolding *unfolding)
{
    if (!unfolding)
        return;
    for (size_t i = 0; i < unfolding->count; i++)
        unfold_piece_free(&unfolding->pieces[i]);
    free(unfolding->pieces);
    *unfolding = (ur_unfolding){0};
}
