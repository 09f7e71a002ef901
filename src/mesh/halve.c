/*
 * halve.c: cutting a piece in two along its length (ur_mesh_halve), for a
 * flattened piece whose outline crosses itself, or into as many as it
 * takes to fit a sheet (ur_mesh_split_along).
 *
 * A long piece that winds round (a ribbon of more than a turn) lies over
 * itself when flat; cutting it across its middle makes two pieces that each
 * wind half as far.  Planes in space cannot do that: a plane cuts a helix
 * at every turn.  So the cut follows the surface: the distance from one end
 * of the piece, measured along its edges (the far end of a double sweep:
 * the vertex farthest from anywhere, then the one farthest from that), and
 * the cut is the line where that distance splits the piece's area in two
 * (or in as many equal parts as asked).  ur_mesh_split_by cuts the same
 * way at the levels of a field the caller gives, such as the position
 * along a flat piece's length, for straight cuts across it.
 */
#include "cutter.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The vertex of the cut surface farthest from source along the edges. */
static ur_status farthest(const cutter *c, size_t source, size_t *far, double **distance,
                          ur_error *error)
{
    static const bool cutting[1] = {true};
    mesh_paths paths = {NULL, NULL};
    ur_status status = mesh_paths_from(c, cutting, &source, 1, &paths, error);
    if (status == UR_OK) {
        *far = source;
        for (size_t v = 0; v < c->vertex_count; v++)
            if (isfinite(paths.distance[v]) && paths.distance[v] > paths.distance[*far])
                *far = v;
    }
    if (status == UR_OK && distance) {
        *distance = paths.distance;
        paths.distance = NULL;
    }
    mesh_paths_free(&paths);
    return status;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A triangle as the field sees it: its corners' values in order, and its area. */
typedef struct field_span {
    double s[3], area;
} field_span;

/* The area where the field lies below x: each triangle's share exact, the field linear on it. */
static double area_below(const field_span *spans, size_t n, double x)
{
    double area = 0;
    for (size_t t = 0; t < n; t++)
        area += spans[t].area * mesh_fraction_below(spans[t].s, x);
    return area;
}

/* Halvings of the field's range that find a level: far below any rounding of the area. */
enum { LEVEL_HALVINGS = 64 };

/*
 * The parts - 1 levels of the field below which 1/parts, 2/parts, ... of
 * the area lies, found by halving.  Taken exactly, not triangle by
 * triangle, so that they increase even where one large triangle holds
 * several shares (a coarse piece cut into many parts).
 */
static ur_status area_levels(const ur_mesh *mesh, const double *field, double *levels, size_t parts,
                             ur_error *error)
{
    size_t n = mesh->triangle_count;
    field_span *spans = ur_alloc_array(n, sizeof *spans, error);
    if (!spans)
        return UR_ERROR_MEMORY;
    double total = 0, low = INFINITY, high = -INFINITY;
    for (size_t t = 0; t < n; t++) {
        const size_t *v = mesh->triangles[t];
        ur_vec3 a = mesh->vertices[v[0]];
        ur_vec3 normal = ur_vec3_cross(ur_vec3_sub(mesh->vertices[v[1]], a),
                                       ur_vec3_sub(mesh->vertices[v[2]], a));
        for (int k = 0; k < 3; k++)
            spans[t].s[k] = field[v[k]];
        qsort(spans[t].s, 3, sizeof spans[t].s[0], compare_doubles);
        spans[t].area = ur_vec3_length(normal) / 2;
        total += spans[t].area;
        low = fmin(low, spans[t].s[0]);
        high = fmax(high, spans[t].s[2]);
    }
    for (size_t j = 1; j < parts; j++) {
        double target = total * (double)j / (double)parts, below = low, above = high;
        for (int h = 0; h < LEVEL_HALVINGS && below < above; h++) {
            double middle = below + 0.5 * (above - below);
            if (area_below(spans, n, middle) < target)
                below = middle;
            else
                above = middle;
        }
        levels[j - 1] = above;
        if (j > 1 && !(levels[j - 1] > levels[j - 2])) /* rounding: a sliver of a part */
            levels[j - 1] = nextafter(levels[j - 2], INFINITY);
    }
    free(spans);
    return UR_OK;
}

/* Each mesh vertex's distance: the least of its corners' cut-surface vertices. */
static ur_status vertex_field(const cutter *c, const double *distance, double **field,
                              ur_error *error)
{
    const ur_mesh *mesh = c->mesh;
    *field = ur_alloc_array(mesh->vertex_count, sizeof **field, error);
    if (!*field)
        return UR_ERROR_MEMORY;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        (*field)[v] = INFINITY;
    for (size_t h = 0; h < c->half_edge_count; h++) {
        size_t v = mesh->triangles[h / 3][h % 3];
        (*field)[v] = fmin((*field)[v], distance[c->corner[h]]);
    }
    for (size_t v = 0; v < mesh->vertex_count; v++)
        if (!isfinite((*field)[v]))
            (*field)[v] = 0; /* unused, or cut off from the rest: it makes no crossing */
    return UR_OK;
}

/* The cut at the levels of field that part the area evenly (parts checked by the caller). */
static ur_status split_by_levels(const ur_mesh *mesh, const double *field, size_t parts,
                                 ur_mesh *split, ur_error *error)
{
    double *levels = ur_alloc_array(parts, sizeof *levels, error);
    if (!levels)
        return UR_ERROR_MEMORY;
    ur_status status = area_levels(mesh, field, levels, parts, error);
    if (status == UR_OK)
        status = mesh_bands_of_field(mesh, field, levels, parts, split, error);
    free(levels);
    return status;
}

static ur_status check_parts(size_t parts, ur_error *error)
{
    if (parts < 2)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "a piece is cut into 2 parts or more along its length, not %zu", parts);
    return UR_OK;
}

ur_status ur_mesh_split_along(const ur_mesh *mesh, size_t parts, ur_mesh *split, ur_error *error)
{
    memset(split, 0, sizeof *split);
    ur_status status = check_parts(parts, error);
    if (status != UR_OK)
        return status;
    cutter c;
    double *distance = NULL, *field = NULL;
    size_t start, end;
    status = cutter_init(&c, mesh, error);
    if (status == UR_OK) {
        c.part_count = 1;
        c.part_size[0] = mesh->triangle_count;
        status = cutter_corners(&c, error);
    }
    if (status == UR_OK)
        status = farthest(&c, c.corner[0], &start, NULL, error);
    if (status == UR_OK)
        status = farthest(&c, start, &end, &distance, error);
    if (status == UR_OK)
        status = vertex_field(&c, distance, &field, error);
    if (status == UR_OK)
        status = split_by_levels(mesh, field, parts, split, error);
    free(distance);
    free(field);
    cutter_free(&c);
    return status;
}

ur_status ur_mesh_split_by(const ur_mesh *mesh, const double *field, size_t parts, ur_mesh *split,
                           ur_error *error)
{
    memset(split, 0, sizeof *split);
    ur_status status = check_parts(parts, error);
    if (status != UR_OK)
        return status;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        if (!isfinite(field[v]))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "the value at vertex %zu, by which a piece is cut, is not finite",
                                v + 1);
    return split_by_levels(mesh, field, parts, split, error);
}

ur_status ur_mesh_halve(const ur_mesh *mesh, ur_mesh *halves, ur_error *error)
{
    return ur_mesh_split_along(mesh, 2, halves, error);
}
