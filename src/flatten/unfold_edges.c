/*
 * unfold_edges.c: the edges of a mesh to be unfolded: checking that it can
 * be (finite, no triangle of no area, manifold, consistently oriented),
 * pairing its half-edges, how far the surface turns across each edge and
 * which edges may never be folded (the boundary, group boundaries and the
 * user's seams).
 *
 * The turn across an edge is the signed angle between the two faces'
 * normals about the edge: with n1 and n2 the unit normals of the triangles
 * on either side and e the edge's direction as the first runs it,
 * atan2((n1 x n2) . e, n1 . n2).  It is positive where the surface is
 * convex (the second face turns away from the outside) and the same seen
 * from either face, since swapping them turns both n1 x n2 and e around.
 */
#include "unfold_internal.h"

#include <stdlib.h>

/* Twice the triangle's area as a vector along its normal. */
static ur_vec3 area_vector(const ur_mesh *mesh, size_t t)
{
    ur_vec3 a = mesh->vertices[mesh->triangles[t][0]];
    ur_vec3 b = mesh->vertices[mesh->triangles[t][1]];
    ur_vec3 c = mesh->vertices[mesh->triangles[t][2]];
    return ur_vec3_cross(ur_vec3_sub(b, a), ur_vec3_sub(c, a));
}

/* The bounding box's diagonal, the mean edge, and a refusal of triangles of no area. */
static ur_status measure(const ur_mesh *mesh, unfold_edges *edges, ur_error *error)
{
    ur_vec3 low = mesh->vertices[0], high = low;
    for (size_t v = 1; v < mesh->vertex_count; v++) {
        ur_vec3 p = mesh->vertices[v];
        low = ur_vec3_make(fmin(low.x, p.x), fmin(low.y, p.y), fmin(low.z, p.z));
        high = ur_vec3_make(fmax(high.x, p.x), fmax(high.y, p.y), fmax(high.z, p.z));
    }
    edges->scale = ur_vec3_distance(low, high);
    double total = 0.0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        if (0.5 * ur_vec3_length(area_vector(mesh, t)) <=
            UR_MESH_ZERO_AREA * edges->scale * edges->scale)
            return ur_error_set(error, UR_ERROR_INPUT, "triangle %zu has no area", t + 1);
        for (size_t k = 0; k < 3; k++)
            total += ur_vec3_distance(mesh->vertices[unfold_from(mesh, 3 * t + k)],
                                      mesh->vertices[unfold_to(mesh, 3 * t + k)]);
    }
    edges->mean_edge = total / (3.0 * (double)mesh->triangle_count);
    return UR_OK;
}

/* Neighbours must run their shared edge in opposite directions. */
static ur_status check_orientation(const ur_mesh *mesh, const size_t *twins, ur_error *error)
{
    for (size_t h = 0; h < 3 * mesh->triangle_count; h++) {
        size_t g = twins[h];
        if (g != UR_NO_EDGE && unfold_from(mesh, h) == unfold_from(mesh, g))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "triangles %zu and %zu run their shared edge (vertices %zu and "
                                "%zu) the same way: the mesh is not consistently oriented",
                                h / 3 + 1, g / 3 + 1, unfold_from(mesh, h) + 1,
                                unfold_to(mesh, h) + 1);
    }
    return UR_OK;
}

static double bend_across(const ur_mesh *mesh, size_t h, size_t g)
{
    ur_vec3 n1 = area_vector(mesh, h / 3), n2 = area_vector(mesh, g / 3);
    n1 = ur_vec3_scale(n1, 1.0 / ur_vec3_length(n1));
    n2 = ur_vec3_scale(n2, 1.0 / ur_vec3_length(n2));
    ur_vec3 e =
        ur_vec3_sub(mesh->vertices[unfold_to(mesh, h)], mesh->vertices[unfold_from(mesh, h)]);
    e = ur_vec3_scale(e, 1.0 / ur_vec3_length(e));
    return atan2(ur_vec3_dot(ur_vec3_cross(n1, n2), e), ur_vec3_dot(n1, n2));
}

/* Bends, and the boundary and group boundaries marked as cut. */
static void classify(const ur_mesh *mesh, unfold_edges *edges)
{
    for (size_t h = 0; h < 3 * mesh->triangle_count; h++) {
        size_t g = edges->twins[h];
        if (g == UR_NO_EDGE) {
            edges->cut[h] = true;
            continue;
        }
        edges->bend[h] = bend_across(mesh, h, g);
        if (mesh->groups && mesh->groups[h / 3] != mesh->groups[g / 3])
            edges->cut[h] = true;
    }
}

/* A seam by its ends in increasing order, and its place in the caller's array. */
typedef struct seam_key {
    size_t low, high, index;
} seam_key;

static int compare_ends(const void *a, const void *b)
{
    const seam_key *x = a, *y = b;
    if (x->low != y->low)
        return x->low < y->low ? -1 : 1;
    return (x->high > y->high) - (x->high < y->high);
}

static ur_status seam_keys(const ur_seam *seams, size_t count, size_t vertex_count, seam_key *keys,
                           ur_error *error)
{
    for (size_t i = 0; i < count; i++) {
        size_t a = seams[i].a, b = seams[i].b, far = a > b ? a : b;
        if (far >= vertex_count)
            return ur_error_set(error, UR_ERROR_INPUT,
                                "seam %zu names vertex %zu, but the mesh has %zu vertices", i + 1,
                                far + 1, vertex_count);
        if (a == b)
            return ur_error_set(error, UR_ERROR_INPUT, "seam %zu joins vertex %zu to itself", i + 1,
                                a + 1);
        keys[i] = (seam_key){a < b ? a : b, a < b ? b : a, i};
    }
    qsort(keys, count, sizeof *keys, compare_ends);
    return UR_OK;
}

/* The first seam (in the caller's order) that found[] says is no edge of the mesh, or UR_OK. */
static ur_status report_missing(const ur_seam *seams, const seam_key *keys, const bool *found,
                                size_t count, ur_error *error)
{
    size_t missing = UNFOLD_NONE;
    for (size_t i = 0; i < count; i++)
        if (!found[i] && (missing == UNFOLD_NONE || keys[i].index < missing))
            missing = keys[i].index;
    if (missing == UNFOLD_NONE)
        return UR_OK;
    return ur_error_set(error, UR_ERROR_INPUT,
                        "seam %zu (vertices %zu and %zu) is not an edge of the mesh", missing + 1,
                        seams[missing].a + 1, seams[missing].b + 1);
}

/*
 * Marks every half-edge on a user seam as cut; each seam must be an edge.
 * Repeated seams share one edge: bsearch finds one of them, and the others
 * are then found by their neighbours in the sorted keys.
 */
static ur_status mark_user_seams(const ur_mesh *mesh, const ur_seam *seams, size_t count,
                                 unfold_edges *edges, ur_error *error)
{
    seam_key *keys = ur_alloc_array(count, sizeof *keys, error);
    bool *found = ur_alloc_array(count, sizeof *found, error);
    ur_status status = keys && found ? UR_OK : UR_ERROR_MEMORY;
    if (status == UR_OK)
        status = seam_keys(seams, count, mesh->vertex_count, keys, error);
    for (size_t h = 0; h < 3 * mesh->triangle_count && status == UR_OK && count > 0; h++) {
        size_t a = unfold_from(mesh, h), b = unfold_to(mesh, h);
        seam_key key = {a < b ? a : b, a < b ? b : a, 0};
        seam_key *hit = bsearch(&key, keys, count, sizeof *keys, compare_ends);
        if (!hit)
            continue;
        edges->cut[h] = true;
        size_t i = (size_t)(hit - keys), j = i;
        while (i > 0 && compare_ends(&keys[i - 1], &key) == 0)
            i--;
        while (j + 1 < count && compare_ends(&keys[j + 1], &key) == 0)
            j++;
        for (size_t k = i; k <= j; k++)
            found[k] = true;
    }
    if (status == UR_OK)
        status = report_missing(seams, keys, found, count, error);
    free(keys);
    free(found);
    return status;
}

ur_status unfold_edges_build(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                             unfold_edges *edges, ur_error *error)
{
    *edges = (unfold_edges){0};
    if (!mesh || mesh->triangle_count == 0 || mesh->vertex_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "the mesh has no triangles to unfold");
    if (seam_count > 0 && !seams)
        return ur_error_set(error, UR_ERROR_INTERNAL, "ur_unfold: seam_count without seams");
    ur_status status = ur_mesh_check_vertices(mesh->vertices, mesh->vertex_count, error);
    if (status == UR_OK)
        status = ur_mesh_twins(mesh, &edges->twins, error);
    if (status == UR_OK)
        status = measure(mesh, edges, error);
    if (status == UR_OK)
        status = check_orientation(mesh, edges->twins, error);
    if (status != UR_OK)
        return status;
    size_t halves = 3 * mesh->triangle_count;
    edges->bend = ur_alloc_array(halves, sizeof *edges->bend, error);
    edges->cut = ur_alloc_array(halves, sizeof *edges->cut, error);
    if (!edges->bend || !edges->cut)
        return UR_ERROR_MEMORY;
    classify(mesh, edges);
    return mark_user_seams(mesh, seams, seam_count, edges, error);
}

void unfold_edges_free(unfold_edges *edges)
{
    free(edges->twins);
    free(edges->bend);
    free(edges->cut);
    *edges = (unfold_edges){0};
}
