/*
 * mesh_polygons.c: the file's faces of four corners or more, marked on
 * assimp's raw scene and found again once assimp has triangulated it; and
 * the flat ones of five corners or more triangulated again, without
 * slivers.
 *
 * assimp cuts a polygon into triangles by clipping ears, and where the
 * polygon has corners almost in line that leaves long thin triangles.  A
 * flat polygon is flat only to the rounding of the file's coordinates, and
 * across a sliver a few thousandths of a millimetre out of plane become a
 * fold of more than the flat angle: each six-sided facet of Blender's
 * brilliant-cut gem (three corners almost in line along its girdle) came
 * out with a 0.55 degree valley fold inside it, on a convex gem.  The
 * constrained Delaunay triangulation of the same corners (GEOS) makes
 * triangles as little thin as the polygon allows: 0.06 degrees there.
 * Quads keep assimp's split, or mesh_quads.c's.
 */
#include "io_internal.h"
#include "../geom/geos_polygon.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <assimp/scene.h>

/* How many faces a face of n corners becomes once triangulated (points and lines stay). */
static size_t faces_after(unsigned corners)
{
    return corners > 3 ? corners - 2 : 1;
}

/* The marks of one raw mesh, or NULL when it has no face of more than three corners. */
static ur_status mark_mesh(const struct aiMesh *mesh, size_t count, unsigned **marks,
                           ur_error *error)
{
    *marks = NULL;
    bool any = false;
    for (unsigned f = 0; f < mesh->mNumFaces && !any; f++)
        any = mesh->mFaces[f].mNumIndices > 3;
    if (!any)
        return UR_OK;
    *marks = calloc(count ? count : 1, sizeof **marks);
    if (!*marks)
        return ur_error_out_of_memory(error);
    size_t at = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        unsigned corners = mesh->mFaces[f].mNumIndices;
        if (corners > 3)
            (*marks)[at] = corners;
        at += faces_after(corners);
    }
    return UR_OK;
}

ur_status io_polygon_marks_read(const struct aiScene *raw, io_polygon_marks *marks, ur_error *error)
{
    *marks = (io_polygon_marks){0};
    if (raw->mNumMeshes == 0)
        return UR_OK;
    marks->corners = calloc(raw->mNumMeshes, sizeof *marks->corners);
    marks->face_counts = ur_alloc_array(raw->mNumMeshes, sizeof *marks->face_counts, error);
    if (!marks->corners || !marks->face_counts) {
        io_polygon_marks_free(marks);
        return ur_error_out_of_memory(error);
    }
    marks->mesh_count = raw->mNumMeshes;
    for (unsigned m = 0; m < raw->mNumMeshes; m++) {
        const struct aiMesh *mesh = raw->mMeshes[m];
        size_t count = 0;
        for (unsigned f = 0; f < mesh->mNumFaces; f++)
            count += faces_after(mesh->mFaces[f].mNumIndices);
        marks->face_counts[m] = count;
        ur_status status = mark_mesh(mesh, count, &marks->corners[m], error);
        if (status != UR_OK) {
            io_polygon_marks_free(marks);
            return status;
        }
    }
    return UR_OK;
}

void io_polygon_marks_match(io_polygon_marks *marks, const struct aiScene *triangulated)
{
    for (unsigned m = 0; m < marks->mesh_count; m++)
        if (m >= triangulated->mNumMeshes ||
            triangulated->mMeshes[m]->mNumFaces != marks->face_counts[m]) {
            free(marks->corners[m]);
            marks->corners[m] = NULL;
        }
}

const unsigned *io_polygon_marks_of(const io_polygon_marks *marks, unsigned mesh)
{
    return mesh < marks->mesh_count ? marks->corners[mesh] : NULL;
}

void io_polygon_marks_free(io_polygon_marks *marks)
{
    for (unsigned m = 0; marks->corners && m < marks->mesh_count; m++)
        free(marks->corners[m]);
    free(marks->corners);
    free(marks->face_counts);
    *marks = (io_polygon_marks){0};
}

/* ---- A polygon's outline, from its triangles --------------------------- */

/* An edge of one of the polygon's triangles, from vertex to vertex. */
typedef struct directed_edge {
    size_t from, to;
} directed_edge;

/* Edges by their ends, whichever way they run. */
static int compare_by_ends(const void *a, const void *b)
{
    const directed_edge *p = a, *q = b;
    size_t p_low = p->from < p->to ? p->from : p->to, p_high = p->from < p->to ? p->to : p->from;
    size_t q_low = q->from < q->to ? q->from : q->to, q_high = q->from < q->to ? q->to : q->from;
    if (p_low != q_low)
        return p_low < q_low ? -1 : 1;
    return (p_high > q_high) - (p_high < q_high);
}

static int compare_by_start(const void *a, const void *b)
{
    const directed_edge *p = a, *q = b;
    return (p->from > q->from) - (p->from < q->from);
}

static bool same_ends(const directed_edge *p, const directed_edge *q)
{
    return (p->from == q->to && p->to == q->from) || (p->from == q->from && p->to == q->to);
}

/*
 * The outline of the polygon whose triangles are given, in their order
 * round it (the edges that only one triangle has): count corners in
 * outline; false unless it is one loop through that many corners.
 * edges has room for three per triangle.
 */
static bool outline_of(size_t (*triangles)[3], size_t triangle_count, directed_edge *edges,
                       size_t *outline, size_t count)
{
    size_t edge_count = 0;
    for (size_t t = 0; t < triangle_count; t++)
        for (int k = 0; k < 3; k++)
            edges[edge_count++] = (directed_edge){triangles[t][k], triangles[t][(k + 1) % 3]};
    qsort(edges, edge_count, sizeof *edges, compare_by_ends);
    size_t kept = 0;
    for (size_t i = 0; i < edge_count;) {
        size_t j = i + 1;
        while (j < edge_count && same_ends(&edges[i], &edges[j]))
            j++;
        if (j == i + 1)
            edges[kept++] = edges[i];
        i = j;
    }
    if (kept != count)
        return false;
    qsort(edges, kept, sizeof *edges, compare_by_start);
    for (size_t i = 1; i < kept; i++)
        if (edges[i].from == edges[i - 1].from)
            return false; /* a corner the outline passes twice */
    size_t at = 0;
    for (size_t step = 0; step < count; step++) {
        outline[step] = edges[at].from;
        directed_edge key = {edges[at].to, 0};
        const directed_edge *next = bsearch(&key, edges, kept, sizeof *edges, compare_by_start);
        if (!next)
            return false;
        at = (size_t)(next - edges);
        if (at == 0 && step + 1 < count)
            return false; /* closed early: more than one loop */
    }
    return at == 0;
}

/* ---- Flat polygons, triangulated again ----------------------------------- */

/*
 * A polygon is flat when every corner lies within this share of its size
 * (its longest distance from its centre) of its plane: far less than the
 * flat angle (0.5 degrees is 0.0087), far more than an OBJ's rounding.
 */
#define FLAT_WITHIN 1e-3

/* A corner seen in the polygon's plane, and its vertex. */
typedef struct plane_corner {
    double x, y;
    size_t vertex;
} plane_corner;

static int compare_plane_corners(const void *a, const void *b)
{
    const plane_corner *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    return (p->y > q->y) - (p->y < q->y);
}

/*
 * The outline's corners in its own plane, counter-clockwise seen from the
 * side it turns round (its triangles' outside); false unless it is flat.
 */
static bool lay_in_plane(const ur_vec3 *vertices, const size_t *outline, size_t count,
                         ur_vec2 *points)
{
    ur_vec3 normal = {0, 0, 0}, centre = {0, 0, 0};
    for (size_t i = 0; i < count; i++) {
        ur_vec3 a = vertices[outline[i]], b = vertices[outline[(i + 1) % count]];
        normal = ur_vec3_add(normal, ur_vec3_cross(a, b));
        centre = ur_vec3_add(centre, a);
    }
    double length = ur_vec3_length(normal);
    if (!(length > 0))
        return false;
    normal = ur_vec3_scale(normal, 1.0 / length);
    centre = ur_vec3_scale(centre, 1.0 / (double)count);
    double size = 0, off_plane = 0;
    for (size_t i = 0; i < count; i++) {
        ur_vec3 d = ur_vec3_sub(vertices[outline[i]], centre);
        size = fmax(size, ur_vec3_length(d));
        off_plane = fmax(off_plane, fabs(ur_vec3_dot(d, normal)));
    }
    if (!(off_plane <= FLAT_WITHIN * size))
        return false;
    /* x along the axis the normal leans least on, then y = normal x x: x, y, normal turn
     * right-handed. */
    ur_vec3 axis = fabs(normal.x) < 0.5 ? (ur_vec3){1, 0, 0} : (ur_vec3){0, 1, 0};
    ur_vec3 x = ur_vec3_cross(ur_vec3_cross(normal, axis), normal);
    x = ur_vec3_scale(x, 1.0 / ur_vec3_length(x));
    ur_vec3 y = ur_vec3_cross(normal, x);
    for (size_t i = 0; i < count; i++) {
        ur_vec3 d = ur_vec3_sub(vertices[outline[i]], centre);
        points[i] = (ur_vec2){ur_vec3_dot(d, x), ur_vec3_dot(d, y)};
    }
    return true;
}

/* The vertex at (x, y) among the sorted corners; SIZE_MAX if none. */
static size_t vertex_at(const plane_corner *sorted, size_t count, double x, double y)
{
    plane_corner key = {x, y, 0};
    const plane_corner *found = bsearch(&key, sorted, count, sizeof *sorted, compare_plane_corners);
    return found ? found->vertex : SIZE_MAX;
}

/*
 * Writes the triangulation's triangles (corners found by their exact
 * coordinates, which GEOS copies from its input) over the polygon's, each
 * counter-clockwise, made first in made (room for count - 2); false,
 * leaving them, unless there are as many and each has three different
 * corners.
 */
static bool take_triangulation(GEOSContextHandle_t geos, const GEOSGeometry *triangulation,
                               const plane_corner *sorted, size_t count, size_t (*made)[3],
                               size_t (*triangles)[3])
{
    int found = GEOSGetNumGeometries_r(geos, triangulation);
    if (found < 0 || (size_t)found != count - 2)
        return false;
    bool ok = true;
    for (int t = 0; ok && t < found; t++) {
        const GEOSGeometry *ring =
            GEOSGetExteriorRing_r(geos, GEOSGetGeometryN_r(geos, triangulation, t));
        const GEOSCoordSequence *points = ring ? GEOSGeom_getCoordSeq_r(geos, ring) : NULL;
        double x[3], y[3];
        for (unsigned k = 0; ok && k < 3; k++) {
            ok = points && GEOSCoordSeq_getXY_r(geos, points, k, &x[k], &y[k]);
            made[t][k] = ok ? vertex_at(sorted, count, x[k], y[k]) : SIZE_MAX;
            ok = ok && made[t][k] != SIZE_MAX;
        }
        ok = ok && made[t][0] != made[t][1] && made[t][1] != made[t][2] && made[t][0] != made[t][2];
        if (ok && (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]) < 0) {
            size_t swap = made[t][1];
            made[t][1] = made[t][2], made[t][2] = swap;
        }
    }
    if (ok)
        memcpy(triangles, made, (count - 2) * sizeof *made);
    return ok;
}

/* Room for one polygon's work, grown as larger polygons come. */
typedef struct polygon_work {
    directed_edge *edges; /* three per triangle */
    size_t *outline;      /* the corners' vertices in order round the polygon */
    ur_vec2 *points;      /* the corners in the polygon's plane, in that order */
    plane_corner *sorted; /* the same by position, with their vertices */
    size_t (*made)[3];    /* the new triangles */
    size_t room;          /* corners */
} polygon_work;

static void work_free(polygon_work *work)
{
    free(work->edges), free(work->outline), free(work->points), free(work->sorted);
    free(work->made);
    *work = (polygon_work){0};
}

static bool work_room(polygon_work *work, size_t count)
{
    if (count <= work->room)
        return true;
    work_free(work);
    work->edges = ur_alloc_array(3 * count, sizeof *work->edges, NULL);
    work->outline = ur_alloc_array(count, sizeof *work->outline, NULL);
    work->points = ur_alloc_array(count, sizeof *work->points, NULL);
    work->sorted = ur_alloc_array(count, sizeof *work->sorted, NULL);
    work->made = ur_alloc_array(count, sizeof *work->made, NULL);
    work->room =
        work->edges && work->outline && work->points && work->sorted && work->made ? count : 0;
    return work->room > 0;
}

/* One polygon of count corners, its triangles at triangles; false only when out of memory. */
static bool triangulate_again(GEOSContextHandle_t geos, const ur_vec3 *vertices,
                              size_t (*triangles)[3], size_t count, polygon_work *work)
{
    if (!work_room(work, count))
        return false;
    if (!outline_of(triangles, count - 2, work->edges, work->outline, count) ||
        !lay_in_plane(vertices, work->outline, count, work->points))
        return true;
    for (size_t i = 0; i < count; i++)
        work->sorted[i] = (plane_corner){work->points[i].x, work->points[i].y, work->outline[i]};
    qsort(work->sorted, count, sizeof *work->sorted, compare_plane_corners);
    for (size_t i = 1; i < count; i++)
        if (compare_plane_corners(&work->sorted[i - 1], &work->sorted[i]) == 0)
            return true; /* two corners at one point: a triangle's corners could not be told */
    GEOSGeometry *polygon = geos_polygon_of_ring(geos, work->points, count);
    GEOSGeometry *triangulation =
        polygon ? GEOSConstrainedDelaunayTriangulation_r(geos, polygon) : NULL;
    if (triangulation) {
        take_triangulation(geos, triangulation, work->sorted, count, work->made, triangles);
        GEOSGeom_destroy_r(geos, triangulation);
    }
    if (polygon)
        GEOSGeom_destroy_r(geos, polygon);
    return true;
}

ur_status io_triangulate_flat_polygons(const ur_vec3 *vertices, size_t (*triangles)[3],
                                       size_t triangle_count, const size_t *starts,
                                       const size_t *corners, size_t polygon_count, ur_error *error)
{
    if (polygon_count == 0)
        return UR_OK;
    GEOSContextHandle_t geos = GEOS_init_r();
    if (!geos)
        return ur_error_set(error, UR_ERROR_INTERNAL, "GEOS could not be started");
    polygon_work work = {0};
    bool ok = true;
    for (size_t p = 0; ok && p < polygon_count; p++)
        if (corners[p] >= 5 && starts[p] + corners[p] - 2 <= triangle_count)
            ok = triangulate_again(geos, vertices, triangles + starts[p], corners[p], &work);
    work_free(&work);
    GEOS_finish_r(geos);
    return ok ? UR_OK : ur_error_out_of_memory(error);
}
