/*
 * lscm.c: least-squares conformal maps (Levy, Petitjean, Ray, Maillot 2002).
 *
 * In the plane of triangle t, with complex corners z_k and W_k = z_(k+2) -
 * z_(k+1), the flat map U = u + i v is conformal on t when dU/dz-bar = 0,
 * which for the linear interpolant is sum_k W_k U_k = 0.  LSCM minimises
 * sum_t |sum_k W_k U_k|^2 / A_t over the 2n unknowns, two vertices pinned to
 * remove the similarities that leave it unchanged.  The normal matrix is
 * assembled per vertex and per edge rather than per triangle: with the
 * real rows (a_k, -b_k) and (b_k, a_k) of W_k = a_k + i b_k, an edge ij
 * contributes the same "sym" to (u_i, u_j) and (v_i, v_j), and "skew" and
 * -skew to (u_i, v_j) and (v_i, u_j), so that summing there first gives
 * CHOLMOD a third of the triplets.
 *
 * The skew part is the signed area of the layout (LSCM is the Dirichlet
 * energy minus the area, Mullen et al. 2008), and the area only depends
 * on the boundary: on an inner edge the two triangles' skew terms cancel
 * exactly, leaving rounding (about 1e-12 of sym).  So u and v are coupled
 * on boundary edges only, and the matrix is two cotangent Laplacians tied
 * at the boundary: half the fill of the full pattern.
 *
 * LSCM only keeps angles, so its layout is then scaled to the 3D area.
 */
#include "flatten_internal.h"

#include <math.h>
#include <stdlib.h>

#define NOT_FREE ((size_t)-1)

/* The normal matrix, summed per vertex (diagonal) and per edge (lower, higher vertex). */
typedef struct lscm_sums {
    double *diagonal;    /* V: (u_i, u_i) = (v_i, v_i); (u_i, v_i) is 0 */
    double *sym;         /* E: (u_lo, u_hi) = (v_lo, v_hi) */
    double *skew;        /* E: (u_lo, v_hi) = -(v_lo, u_hi) */
    unsigned char *uses; /* E: triangles on the edge (1 or 2) */
    size_t *index;       /* V: number among the free vertices, or NOT_FREE */
    size_t free_count;
} lscm_sums;

static void sums_free(lscm_sums *s)
{
    free(s->diagonal);
    free(s->sym);
    free(s->skew);
    free(s->uses);
    free(s->index);
}

static ur_status sums_alloc(lscm_sums *s, size_t vertices, size_t edges, ur_error *error)
{
    s->diagonal = ur_alloc_array(vertices, sizeof *s->diagonal, error);
    s->sym = ur_alloc_array(edges, sizeof *s->sym, error);
    s->skew = ur_alloc_array(edges, sizeof *s->skew, error);
    s->uses = ur_alloc_array(edges, sizeof *s->uses, error);
    s->index = ur_alloc_array(vertices, sizeof *s->index, error);
    if (!s->diagonal || !s->sym || !s->skew || !s->uses || !s->index) {
        sums_free(s);
        return UR_ERROR_MEMORY;
    }
    return UR_OK;
}

static void number_free_vertices(lscm_sums *s, size_t vertices, const size_t pins[2])
{
    s->free_count = 0;
    for (size_t v = 0; v < vertices; v++)
        s->index[v] = v == pins[0] || v == pins[1] ? NOT_FREE : s->free_count++;
}

/* Adds triangle t's |sum W_k U_k|^2 / A to the sums. */
static void add_triangle(lscm_sums *s, const ur_mesh *mesh, const flat_frame *frame,
                         const flat_topology *topology, size_t t)
{
    double a[3], b[3];
    for (int k = 0; k < 3; k++) {
        ur_vec2 w = ur_vec2_sub(frame->corner[(k + 2) % 3], frame->corner[(k + 1) % 3]);
        a[k] = w.x;
        b[k] = w.y;
    }
    double weight = 1 / frame->area;
    for (int k = 0; k < 3; k++) {
        int l = (k + 1) % 3;
        size_t e = topology->edge_of[3 * t + k];
        bool k_low = mesh->triangles[t][k] == topology->edges[e][0];
        int lo = k_low ? k : l, hi = k_low ? l : k;
        s->diagonal[mesh->triangles[t][k]] += weight * (a[k] * a[k] + b[k] * b[k]);
        s->sym[e] += weight * (a[lo] * a[hi] + b[lo] * b[hi]);
        s->skew[e] += weight * (b[lo] * a[hi] - a[lo] * b[hi]);
        s->uses[e]++;
    }
}

/* The triplets of the free-free entries. */
static void fill_matrix(const lscm_sums *s, const flat_topology *topology, size_t vertices,
                        cholmod_triplet *m)
{
    size_t n = s->free_count;
    for (size_t v = 0; v < vertices; v++) {
        size_t i = s->index[v];
        if (i != NOT_FREE) {
            flat_triplet_add(m, i, i, s->diagonal[v]);
            flat_triplet_add(m, n + i, n + i, s->diagonal[v]);
        }
    }
    for (size_t e = 0; e < topology->edge_count; e++) {
        size_t i = s->index[topology->edges[e][0]], j = s->index[topology->edges[e][1]];
        if (i == NOT_FREE || j == NOT_FREE)
            continue;
        flat_triplet_add(m, i, j, s->sym[e]);
        flat_triplet_add(m, n + i, n + j, s->sym[e]);
        if (s->uses[e] == 1) {
            flat_triplet_add(m, i, n + j, s->skew[e]);
            flat_triplet_add(m, n + i, j, -s->skew[e]);
        }
    }
}

/* Moves the pinned vertices' terms to the right-hand side: rhs = -M_free,pinned x_pinned. */
static void fill_rhs(const lscm_sums *s, const flat_topology *topology, const ur_vec2 *layout,
                     double *rhs)
{
    size_t n = s->free_count;
    for (size_t e = 0; e < topology->edge_count; e++) {
        for (int side = 0; side < 2; side++) {
            size_t v = topology->edges[e][side], w = topology->edges[e][1 - side];
            size_t i = s->index[v];
            if (i == NOT_FREE || s->index[w] != NOT_FREE)
                continue;
            /* (u_v, v_w) is skew when v is the lower end, -skew when it is the higher. */
            double skew = s->uses[e] == 2 ? 0 : side == 0 ? s->skew[e] : -s->skew[e];
            rhs[i] -= s->sym[e] * layout[w].x + skew * layout[w].y;
            rhs[n + i] -= -skew * layout[w].x + s->sym[e] * layout[w].y;
        }
    }
}

static ur_status solve(const lscm_sums *s, const flat_topology *topology, size_t vertices,
                       ur_vec2 *layout, ur_error *error)
{
    flat_solver solver;
    ur_status status = flat_solver_start(&solver, error);
    if (status)
        return status;
    size_t n = s->free_count;
    cholmod_triplet *m = NULL;
    cholmod_dense *rhs = NULL;
    const double *x = NULL;
    bool definite = false;
    status =
        flat_solver_triplets(&solver, 2 * n, 2 * vertices + 4 * topology->edge_count, &m, error);
    if (!status) {
        fill_matrix(s, topology, vertices, m);
        status = flat_solver_factor(&solver, &m, &definite, error);
    }
    if (!status && !definite)
        status = ur_error_set(error, UR_ERROR_INTERNAL,
                              "LSCM: the conformal system is singular (a degenerate piece?)");
    if (!status)
        status = flat_solver_rhs(&solver, 1, &rhs, error);
    if (!status) {
        fill_rhs(s, topology, layout, rhs->x);
        status = flat_solver_solve(&solver, rhs, &x, error);
    }
    if (!status)
        for (size_t v = 0; v < vertices; v++)
            if (s->index[v] != NOT_FREE)
                layout[v] = ur_vec2_make(x[s->index[v]], x[n + s->index[v]]);
    if (m)
        cholmod_l_free_triplet(&m, &solver.common);
    if (rhs)
        cholmod_l_free_dense(&rhs, &solver.common);
    flat_solver_finish(&solver);
    return status;
}

/* Scales about the origin (pins[0]) so that the flat area is the 3D area. */
static ur_status scale_to_area(const ur_mesh *mesh, const flat_frame *frames, ur_vec2 *layout,
                               ur_error *error)
{
    double flat = 0, area = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const size_t *c = mesh->triangles[t];
        flat += 0.5 * ur_vec2_cross(ur_vec2_sub(layout[c[1]], layout[c[0]]),
                                    ur_vec2_sub(layout[c[2]], layout[c[0]]));
        area += frames[t].area;
    }
    if (!(flat > 0))
        return ur_error_set(error, UR_ERROR_INTERNAL, "LSCM: the layout has no area (%g)", flat);
    double scale = sqrt(area / flat);
    for (size_t v = 0; v < mesh->vertex_count; v++)
        layout[v] = ur_vec2_scale(layout[v], scale);
    return UR_OK;
}

ur_status flat_lscm(const ur_mesh *mesh, const flat_frame *frames, const flat_topology *topology,
                    ur_vec2 *layout, ur_error *error)
{
    const size_t *pins = topology->pins;
    lscm_sums s;
    ur_status status = sums_alloc(&s, mesh->vertex_count, topology->edge_count, error);
    if (status)
        return status;
    number_free_vertices(&s, mesh->vertex_count, pins);
    for (size_t t = 0; t < mesh->triangle_count; t++)
        add_triangle(&s, mesh, &frames[t], topology, t);
    /* The pins as far apart as in space; the scale is fixed afterwards anyway. */
    layout[pins[0]] = ur_vec2_make(0, 0);
    layout[pins[1]] =
        ur_vec2_make(ur_vec3_distance(mesh->vertices[pins[0]], mesh->vertices[pins[1]]), 0);
    status = solve(&s, topology, mesh->vertex_count, layout, error);
    sums_free(&s);
    return status ? status : scale_to_area(mesh, frames, layout, error);
}
