/*
 * mesh_repeats.c: a face given twice triangulated as it was the first
 * time, so that the mesh's cleaning finds the copy's triangles on the
 * same corners as the first's and drops them (flaps.c).
 *
 * A modeller's extrusion of no length, or a face filled again over one
 * that was there, leaves a face given twice, often the other way round.
 * assimp splits a quad from its first corner, and the other way round
 * that is the other diagonal; a regular polygon (a cylinder's cap) has
 * its corners on a circle, where the Delaunay triangulation
 * (mesh_polygons.c) may take any of its ties.  Either way the copy's
 * triangles repeated none of the first's, its sides carried three
 * triangles, and the mesh was refused or kept apart there.
 *
 * Faces are told by the points of their corners.  A face on the same
 * corners as an earlier one, with a side on an odd number of triangles
 * besides those of the faces on those corners (a face doubled, or given
 * three times, in a surface: one neighbour across), takes the earlier
 * one's triangles, on its own vertices and running its own way round.  A
 * sheet with a face on each side has two neighbours across each side, or
 * none on its rim, and keeps its two triangulations: the same one would
 * join its sides round their rim, and taking them apart would then cut
 * each in pieces.
 */
#include "io_internal.h"
#include "../geom/points.h"

#include <stdlib.h>
#include <string.h>

/* A face of the file: its triangles (corners - 2 from start) and its corners' points, sorted. */
typedef struct face {
    size_t start, corners;
    size_t *points; /* in repeats.points */
} face;

typedef struct repeats {
    size_t (*triangles)[3];
    size_t *point;      /* per vertex: the number of its point */
    io_surface surface; /* the triangles' edges by position: made once a face is found twice */
    bool surface_made;
    face *faces;
    size_t face_count;
    size_t *points; /* the faces' points, one face after the other */
} repeats;

/* By their corners' points, then in the file's order. */
static int compare_faces(const void *a, const void *b)
{
    const face *f = a, *g = b;
    if (f->corners != g->corners)
        return f->corners < g->corners ? -1 : 1;
    for (size_t k = 0; k < f->corners; k++)
        if (f->points[k] != g->points[k])
            return f->points[k] < g->points[k] ? -1 : 1;
    return (f->start > g->start) - (f->start < g->start);
}

static bool same_points(const face *f, const face *g)
{
    return f->corners == g->corners &&
           memcmp(f->points, g->points, f->corners * sizeof *f->points) == 0;
}

static int compare_numbers(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

/*
 * The points of a face's corners, sorted, into f->points; false when two
 * corners are at one point (or a triangle's corner is none of the face's),
 * and the face cannot be told by them.
 */
static bool take_points(const repeats *r, face *f)
{
    size_t count = 0;
    for (size_t t = f->start; t < f->start + f->corners - 2; t++)
        for (int k = 0; k < 3; k++) {
            size_t p = r->point[r->triangles[t][k]];
            bool seen = false;
            for (size_t i = 0; i < count && !seen; i++)
                seen = f->points[i] == p;
            if (!seen && count == f->corners)
                return false;
            if (!seen)
                f->points[count++] = p;
        }
    qsort(f->points, count, sizeof *f->points, compare_numbers);
    return count == f->corners;
}

/* Whether side (a, b) of triangle t is a side of the face: no other of its triangles has it. */
static bool on_outline(const repeats *r, const face *f, size_t t, size_t a, size_t b)
{
    for (size_t u = f->start; u < f->start + f->corners - 2; u++) {
        if (u == t)
            continue;
        for (int k = 0; k < 3; k++) {
            size_t c = r->point[r->triangles[u][k]], d = r->point[r->triangles[u][(k + 1) % 3]];
            if ((c == a && d == b) || (c == b && d == a))
                return false;
        }
    }
    return true;
}

/* Whether the points a, b are the ends of one of face f's sides. */
static bool side_of(const repeats *r, const face *f, size_t a, size_t b)
{
    for (size_t t = f->start; t < f->start + f->corners - 2; t++)
        for (int k = 0; k < 3; k++) {
            size_t c = r->point[r->triangles[t][k]], d = r->point[r->triangles[t][(k + 1) % 3]];
            if (((c == a && d == b) || (c == b && d == a)) && on_outline(r, f, t, c, d))
                return true;
        }
    return false;
}

/*
 * Whether face g is a copy of face f: on the same corners, with the same
 * sides (not a bow tie drawn through them), one of which carries an odd
 * number of triangles besides those of the copies faces on those corners
 * (each has one on each side).
 */
static bool copy_to_split_alike(const repeats *r, const face *f, const face *g, size_t copies)
{
    bool odd = false;
    for (size_t t = g->start; t < g->start + g->corners - 2; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = r->point[r->triangles[t][k]], b = r->point[r->triangles[t][(k + 1) % 3]];
            if (!on_outline(r, g, t, a, b))
                continue;
            if (!side_of(r, f, a, b))
                return false;
            size_t on =
                io_surface_count(&r->surface, r->triangles[t][k], r->triangles[t][(k + 1) % 3]);
            odd = odd || (on > copies && (on - copies) % 2 == 1);
        }
    return odd;
}

/* Twice the triangle's area vector: which way it faces. */
static ur_vec3 facing(const ur_vec3 *vertices, const size_t triangle[3])
{
    ur_vec3 a = vertices[triangle[0]];
    return ur_vec3_cross(ur_vec3_sub(vertices[triangle[1]], a),
                         ur_vec3_sub(vertices[triangle[2]], a));
}

static ur_vec3 face_facing(const ur_vec3 *vertices, size_t (*triangles)[3], const face *f)
{
    ur_vec3 sum = {0, 0, 0};
    for (size_t t = f->start; t < f->start + f->corners - 2; t++)
        sum = ur_vec3_add(sum, facing(vertices, triangles[t]));
    return sum;
}

/* The vertex of face f's triangles at point p (there is one: f has its corners' points). */
static size_t vertex_at(const repeats *r, const face *f, size_t p)
{
    for (size_t t = f->start; t < f->start + f->corners - 2; t++)
        for (int k = 0; k < 3; k++)
            if (r->point[r->triangles[t][k]] == p)
                return r->triangles[t][k];
    return r->triangles[f->start][0];
}

/* Gives copy the triangles of first, on its own vertices, turned over if it faces the other way. */
static ur_status triangulate_alike(const repeats *r, const ur_vec3 *vertices, const face *first,
                                   const face *copy, ur_error *error)
{
    bool turned = ur_vec3_dot(face_facing(vertices, r->triangles, first),
                              face_facing(vertices, r->triangles, copy)) < 0;
    size_t count = first->corners - 2;
    size_t(*made)[3] = ur_alloc_array(count, sizeof *made, error);
    if (!made)
        return UR_ERROR_MEMORY;
    for (size_t k = 0; k < count; k++)
        for (int c = 0; c < 3; c++) {
            int from = turned ? (3 - c) % 3 : c; /* 0, 2, 1 when turned */
            made[k][c] = vertex_at(r, copy, r->point[r->triangles[first->start + k][from]]);
        }
    memcpy(r->triangles + copy->start, made, count * sizeof *made);
    free(made);
    return UR_OK;
}

static ur_status repeats_make(repeats *r, const ur_vec3 *vertices, size_t vertex_count,
                              size_t face_count, size_t corner_count, ur_error *error)
{
    r->point = ur_alloc_array(vertex_count, sizeof *r->point, error);
    r->faces = ur_alloc_array(face_count, sizeof *r->faces, error);
    r->points = ur_alloc_array(corner_count, sizeof *r->points, error);
    if (!r->point || !r->faces || !r->points)
        return UR_ERROR_MEMORY;
    return geom_number_points(vertices, vertex_count, r->point, error);
}

static void repeats_free(repeats *r)
{
    free(r->point);
    io_surface_free(&r->surface);
    free(r->faces);
    free(r->points);
}

/* Adds the face of corners corners from triangle start, if it can be told by its points. */
static void add_face(repeats *r, size_t start, size_t corners, size_t triangle_count, size_t *used)
{
    if (corners < 4 || start + corners - 2 > triangle_count)
        return;
    face *f = &r->faces[r->face_count];
    *f = (face){start, corners, r->points + *used};
    if (take_points(r, f)) {
        r->face_count++;
        *used += corners;
    }
}

ur_status io_repeated_faces_alike(const ur_vec3 *vertices, size_t vertex_count,
                                  size_t (*triangles)[3], size_t triangle_count,
                                  const size_t *quads, size_t quad_count,
                                  const size_t *polygon_starts, const size_t *polygon_corners,
                                  size_t polygon_count, ur_error *error)
{
    size_t face_count = quad_count + polygon_count, corner_count = 4 * quad_count;
    if (face_count < 2)
        return UR_OK;
    for (size_t p = 0; p < polygon_count; p++)
        corner_count += polygon_corners[p];
    repeats r = {.triangles = triangles};
    ur_status status = repeats_make(&r, vertices, vertex_count, face_count, corner_count, error);
    size_t used = 0;
    for (size_t k = 0; status == UR_OK && k < quad_count; k++)
        add_face(&r, quads[k], 4, triangle_count, &used);
    for (size_t p = 0; status == UR_OK && p < polygon_count; p++)
        add_face(&r, polygon_starts[p], polygon_corners[p], triangle_count, &used);
    if (status == UR_OK)
        qsort(r.faces, r.face_count, sizeof *r.faces, compare_faces);
    for (size_t i = 0, j; status == UR_OK && i < r.face_count; i = j) {
        for (j = i + 1; j < r.face_count && same_points(&r.faces[j], &r.faces[i]); j++)
            ;
        if (j - i > 1 && !r.surface_made) { /* most files give no face twice: no edges to list */
            r.surface_made = true;
            status = io_surface_make(&r.surface, vertices, vertex_count, triangles, triangle_count,
                                     error);
        }
        for (size_t k = i + 1; status == UR_OK && k < j; k++)
            if (copy_to_split_alike(&r, &r.faces[i], &r.faces[k], j - i))
                status = triangulate_alike(&r, vertices, &r.faces[i], &r.faces[k], error);
    }
    repeats_free(&r);
    return status;
}
