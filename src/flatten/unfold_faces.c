/*
 * unfold_faces.c: the flat faces of a mesh to be unfolded, each laid in
 * its own plane.
 *
 * A face grows from its first triangle across edges that are not cut and
 * turn by less than the flat angle, taking a triangle only while its normal
 * stays within that angle of the first triangle's: so a finely divided
 * curved surface, whose every edge turns a little, is not taken for one
 * flat face.  The face's points are projected on the plane through its
 * first point square to its mean normal (its triangles' normals weighted
 * by area), so that its triangles meet exactly and lie as one rigid
 * polygon; no triangle turns over, since none leans by more than twice the
 * flat angle.  A triangle alone is its own face, laid congruent.
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

static ur_vec3 unit(ur_vec3 v)
{
    return ur_vec3_scale(v, 1.0 / ur_vec3_length(v));
}

/* ---- a heap of edges, longest first ---- */

typedef struct edge_heap {
    size_t *half;
    double *length;
    size_t count;
} edge_heap;

static bool above(const edge_heap *heap, size_t i, size_t j)
{
    if (heap->length[i] != heap->length[j])
        return heap->length[i] > heap->length[j];
    return heap->half[i] < heap->half[j];
}

static void swap_entries(edge_heap *heap, size_t i, size_t j)
{
    size_t half = heap->half[i];
    double length = heap->length[i];
    heap->half[i] = heap->half[j], heap->length[i] = heap->length[j];
    heap->half[j] = half, heap->length[j] = length;
}

static void heap_push(edge_heap *heap, size_t half, double length)
{
    size_t i = heap->count++;
    heap->half[i] = half, heap->length[i] = length;
    while (i > 0 && above(heap, i, (i - 1) / 2)) {
        swap_entries(heap, i, (i - 1) / 2);
        i = (i - 1) / 2;
    }
}

static size_t heap_pop(edge_heap *heap)
{
    size_t top = heap->half[0];
    swap_entries(heap, 0, --heap->count);
    for (size_t i = 0;;) {
        size_t child = 2 * i + 1;
        if (child >= heap->count)
            break;
        if (child + 1 < heap->count && above(heap, child + 1, child))
            child++;
        if (!above(heap, child, i))
            break;
        swap_entries(heap, i, child);
        i = child;
    }
    return top;
}

/* ---- gathering a face ---- */

/* Whether triangle t may join the face whose first triangle has the given normal. */
static bool joins_face(const ur_mesh *mesh, const unfold_edges *edges, double flat_angle,
                       ur_vec3 normal, size_t h)
{
    size_t g = edges->twins[h];
    return g != UR_NO_EDGE && !edges->cut[h] && fabs(edges->bend[h]) < flat_angle &&
           ur_vec3_dot(unit(area_vector(mesh, g / 3)), normal) > cos(flat_angle);
}

static void push_edges(const ur_mesh *mesh, edge_heap *heap, size_t t)
{
    for (size_t h = 3 * t; h < 3 * t + 3; h++)
        heap_push(heap, h, unfold_edge_length(mesh, h));
}

/*
 * Gathers the face of triangle seed into members (seed first, then in the
 * order reached) and returns how many; face[] marks them.  It grows as
 * Prim's algorithm does, across the longest edge on its border first, and
 * appends each edge it grows across to faces->order: joined in that order
 * each triangle meets the face along its edge, so that the face never
 * touches itself at a point.
 */
static size_t gather(const ur_mesh *mesh, const unfold_edges *edges, double flat_angle, size_t seed,
                     unfold_faces *faces, edge_heap *heap, size_t *members)
{
    ur_vec3 normal = unit(area_vector(mesh, seed));
    size_t count = 0;
    faces->face[seed] = seed;
    members[count++] = seed;
    heap->count = 0;
    push_edges(mesh, heap, seed);
    while (heap->count > 0) {
        size_t h = heap_pop(heap), g = edges->twins[h];
        if (g == UR_NO_EDGE || faces->face[g / 3] != UNFOLD_NONE ||
            !joins_face(mesh, edges, flat_angle, normal, h))
            continue;
        faces->face[g / 3] = seed;
        members[count++] = g / 3;
        faces->order[faces->order_count++] = h < g ? h : g;
        push_edges(mesh, heap, g / 3);
    }
    return count;
}

/* The face's edges it did not grow across, longest first, after the others in faces->order. */
static void add_other_edges(const ur_mesh *mesh, const unfold_edges *edges, const size_t *members,
                            size_t count, unfold_faces *faces, edge_heap *heap, bool *grown)
{
    heap->count = 0;
    for (size_t i = 0; i < count; i++)
        for (size_t h = 3 * members[i]; h < 3 * members[i] + 3; h++) {
            size_t g = edges->twins[h];
            if (g != UR_NO_EDGE && h < g && !edges->cut[h] &&
                faces->face[g / 3] == faces->face[h / 3])
                heap_push(heap, h, unfold_edge_length(mesh, h));
        }
    for (size_t i = faces->order_count - (count - 1); i < faces->order_count; i++)
        grown[faces->order[i]] = true;
    while (heap->count > 0) {
        size_t h = heap_pop(heap);
        if (!grown[h])
            faces->order[faces->order_count++] = h;
    }
}

/* Lays the face's triangles in its plane; returns the most an edge's length changed. */
static double lay_face(const ur_mesh *mesh, const size_t *members, size_t count, ur_vec2 (*home)[3])
{
    ur_vec3 sum = ur_vec3_make(0, 0, 0);
    for (size_t i = 0; i < count; i++)
        sum = ur_vec3_add(sum, area_vector(mesh, members[i]));
    ur_vec3 normal = unit(sum);
    const size_t *first = mesh->triangles[members[0]];
    ur_vec3 origin = mesh->vertices[first[0]];
    ur_vec3 side = ur_vec3_sub(mesh->vertices[first[1]], origin);
    ur_vec3 e1 = unit(ur_vec3_sub(side, ur_vec3_scale(normal, ur_vec3_dot(side, normal))));
    ur_vec3 e2 = ur_vec3_cross(normal, e1);
    double slack = 0.0;
    for (size_t i = 0; i < count; i++) {
        size_t t = members[i];
        for (int k = 0; k < 3; k++) {
            ur_vec3 d = ur_vec3_sub(mesh->vertices[mesh->triangles[t][k]], origin);
            home[t][k] = ur_vec2_make(ur_vec3_dot(d, e1), ur_vec3_dot(d, e2));
        }
        if (count == 1)
            continue;
        for (int k = 0; k < 3; k++) {
            double plane = ur_vec2_distance(home[t][k], home[t][(k + 1) % 3]);
            slack = fmax(slack, fabs(plane - unfold_edge_length(mesh, 3 * t + (size_t)k)));
        }
    }
    return slack;
}

ur_status unfold_faces_build(const ur_mesh *mesh, const unfold_edges *edges, double flat_angle,
                             unfold_faces *faces, ur_error *error)
{
    *faces = (unfold_faces){0};
    size_t n = mesh->triangle_count;
    faces->face = ur_alloc_array(n, sizeof *faces->face, error);
    faces->home = ur_alloc_array(n, sizeof *faces->home, error);
    faces->flat = ur_alloc_array(3 * n, sizeof *faces->flat, error);
    faces->order = ur_alloc_array(3 * n, sizeof *faces->order, error);
    size_t *members = ur_alloc_array(n, sizeof *members, error);
    bool *grown = ur_alloc_array(3 * n, sizeof *grown, error);
    edge_heap heap = {ur_alloc_array(3 * n, sizeof *heap.half, error),
                      ur_alloc_array(3 * n, sizeof *heap.length, error), 0};
    ur_status status = UR_OK;
    if (!faces->face || !faces->home || !faces->flat || !faces->order || !members || !grown ||
        !heap.half || !heap.length)
        status = UR_ERROR_MEMORY;
    for (size_t t = 0; t < n && status == UR_OK; t++)
        faces->face[t] = UNFOLD_NONE;
    for (size_t t = 0; t < n && status == UR_OK; t++) {
        if (faces->face[t] != UNFOLD_NONE)
            continue;
        size_t count = gather(mesh, edges, flat_angle, t, faces, &heap, members);
        add_other_edges(mesh, edges, members, count, faces, &heap, grown);
        faces->slack = fmax(faces->slack, lay_face(mesh, members, count, faces->home));
    }
    for (size_t h = 0; h < 3 * n && status == UR_OK; h++) {
        size_t g = edges->twins[h];
        faces->flat[h] =
            g != UR_NO_EDGE && !edges->cut[h] &&
            (faces->face[h / 3] == faces->face[g / 3] || fabs(edges->bend[h]) < flat_angle);
    }
    free(members);
    free(grown);
    free(heap.half);
    free(heap.length);
    return status;
}

void unfold_faces_free(unfold_faces *faces)
{
    free(faces->face);
    free(faces->home);
    free(faces->flat);
    free(faces->order);
    *faces = (unfold_faces){0};
}
