/*
 * clean.c: ur_mesh_clean: welding, dropping zero-area triangles, flaps of
 * no thickness and faces given twice (flaps.c) and unused vertices,
 * refusing non-manifold edges (after un-welding the vertices whose
 * welding made them, or taking apart surfaces that touch along them) and
 * orienting each part.
 *
 * Every step writes new arrays; the mesh gets them only once all have
 * succeeded, so that a refused mesh is left as it was.  Messages name input
 * vertices and triangles (1-based), the numbers the user's file has.
 */
#include "mesh_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct cleaning {
    const ur_mesh *mesh; /* the input */
    size_t *map;         /* input vertex -> kept input vertex, then -> cleaned vertex */
    size_t (*triangles)[3];
    size_t *groups;
    size_t *source; /* input triangle of each kept triangle */
    size_t triangle_count;
    ur_vec3 *vertices;
    size_t *original; /* input vertex of each cleaned vertex */
    size_t vertex_count;
    ur_mesh_repairs repairs;
    mesh_bad_edge bad; /* the non-manifold edge found, in cleaned vertices */
} cleaning;

static void cleaning_free(cleaning *c)
{
    free(c->map);
    free(c->triangles);
    free(c->groups);
    free(c->source);
    free(c->vertices);
    free(c->original);
}

/* Frees what a try made and starts again with none of it. */
static void cleaning_reset(cleaning *c)
{
    const ur_mesh *mesh = c->mesh;
    cleaning_free(c);
    *c = (cleaning){.mesh = mesh};
}

static ur_status check_input(const ur_mesh *mesh, double tolerance, ur_error *error)
{
    if (!isfinite(tolerance) || tolerance < 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the weld tolerance must be a finite length, 0 or more (not %g)",
                            tolerance);
    if (mesh->triangle_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "the mesh has no triangles");
    ur_status status = ur_mesh_check_vertices(mesh->vertices, mesh->vertex_count, error);
    if (status == UR_OK)
        status = mesh_check_triangles((const size_t(*)[3])mesh->triangles, mesh->triangle_count,
                                      mesh->vertex_count, error);
    return status;
}

static bool is_degenerate(const ur_vec3 *vertices, const size_t c[3], double smallest)
{
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
        return true;
    ur_vec3 ab = ur_vec3_sub(vertices[c[1]], vertices[c[0]]);
    ur_vec3 ac = ur_vec3_sub(vertices[c[2]], vertices[c[0]]);
    return 0.5 * ur_vec3_length(ur_vec3_cross(ab, ac)) <= smallest;
}

/* Keeps the triangles with area once their corners are welded. */
static ur_status drop_degenerate(cleaning *c, ur_error *error)
{
    const ur_mesh *mesh = c->mesh;
    c->triangles = ur_alloc_array(mesh->triangle_count, sizeof *c->triangles, error);
    c->groups = ur_alloc_array(mesh->triangle_count, sizeof *c->groups, error);
    c->source = ur_alloc_array(mesh->triangle_count, sizeof *c->source, error);
    if (!c->triangles || !c->groups || !c->source)
        return UR_ERROR_MEMORY;
    double size = ur_mesh_size(mesh), smallest = UR_MESH_ZERO_AREA * size * size;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        size_t welded[3];
        for (int k = 0; k < 3; k++)
            welded[k] = c->map[mesh->triangles[t][k]];
        if (is_degenerate(mesh->vertices, welded, smallest)) {
            c->repairs.degenerate++;
            continue;
        }
        memcpy(c->triangles[c->triangle_count], welded, sizeof welded);
        c->groups[c->triangle_count] = mesh->groups ? mesh->groups[t] : 0;
        c->source[c->triangle_count++] = t;
    }
    if (c->triangle_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the mesh has no triangles left: all %zu have zero area",
                            mesh->triangle_count);
    return UR_OK;
}

/* Drops, among the kept triangles, flaps of no thickness and faces given twice (flaps.c). */
static ur_status drop_repeated(cleaning *c, ur_error *error)
{
    bool *drop = ur_alloc_array(c->triangle_count, sizeof *drop, error);
    if (!drop)
        return UR_ERROR_MEMORY;
    size_t flaps = 0, duplicates = 0;
    ur_status status = mesh_find_repeated((const size_t(*)[3])c->triangles, c->triangle_count, drop,
                                          &flaps, &duplicates, error);
    bool any = status == UR_OK && flaps + duplicates > 0;
    size_t kept = 0;
    for (size_t t = 0; any && t < c->triangle_count; t++) {
        if (drop[t])
            continue;
        memmove(c->triangles[kept], c->triangles[t], sizeof c->triangles[t]);
        c->groups[kept] = c->groups[t];
        c->source[kept++] = c->source[t];
    }
    if (any) {
        c->triangle_count = kept;
        c->repairs.flaps = flaps;
        c->repairs.duplicates = duplicates;
    }
    free(drop);
    return status;
}

/*
 * Numbers the vertices the kept triangles use, in input order, and drops
 * the rest; c->map then goes from input vertex to cleaned vertex.
 */
static ur_status renumber(cleaning *c, ur_error *error)
{
    const ur_mesh *mesh = c->mesh;
    size_t *index = ur_alloc_array(mesh->vertex_count, sizeof *index, error);
    if (!index)
        return UR_ERROR_MEMORY;
    for (size_t v = 0; v < mesh->vertex_count; v++)
        index[v] = UR_NO_VERTEX;
    for (size_t t = 0; t < c->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            index[c->triangles[t][k]] = 0; /* used; numbered below */
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        if (index[v] != UR_NO_VERTEX)
            index[v] = c->vertex_count++;
        else if (c->map[v] == v)
            c->repairs.isolated++;
    }
    c->vertices = ur_alloc_array(c->vertex_count, sizeof *c->vertices, error);
    c->original = ur_alloc_array(c->vertex_count, sizeof *c->original, error);
    if (!c->vertices || !c->original) {
        free(index);
        return UR_ERROR_MEMORY;
    }
    for (size_t v = 0; v < mesh->vertex_count; v++)
        if (index[v] != UR_NO_VERTEX) {
            c->vertices[index[v]] = mesh->vertices[v];
            c->original[index[v]] = v;
        }
    for (size_t t = 0; t < c->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            c->triangles[t][k] = index[c->triangles[t][k]];
    for (size_t v = 0; v < mesh->vertex_count; v++)
        c->map[v] = index[c->map[v]];
    free(index);
    return UR_OK;
}

/* Pairs the half-edges, refusing an edge of three or more triangles (kept in c->bad). */
static ur_status pair_edges(cleaning *c, size_t *twins, ur_error *error)
{
    mesh_bad_edge bad = {0, 0, 0};
    ur_status status = mesh_pair_edges((const size_t(*)[3])c->triangles, c->triangle_count,
                                       c->vertex_count, twins, &bad, error);
    if (status == UR_ERROR_INPUT) {
        c->bad = bad;
        return ur_error_set(error, status,
                            "non-manifold edge between vertices %zu and %zu (%zu triangles)",
                            c->original[bad.a] + 1, c->original[bad.b] + 1, bad.count);
    }
    return status;
}

/* Refuses non-manifold edges and orients each part, counting the triangles turned. */
static ur_status orient(cleaning *c, ur_error *error)
{
    size_t *twins = ur_alloc_array(3 * c->triangle_count, sizeof *twins, error);
    bool *flipped = ur_alloc_array(c->triangle_count, sizeof *flipped, error);
    ur_status status = twins && flipped ? pair_edges(c, twins, error) : UR_ERROR_MEMORY;
    mesh_conflict conflict = {0, 0, 0, 0};
    if (status == UR_OK) {
        status = mesh_orient(c->triangles, c->triangle_count, twins, c->vertices, flipped,
                             &conflict, error);
        if (status == UR_ERROR_INPUT)
            ur_error_set(error, status,
                         "the surface cannot be oriented: a Mobius strip? Going around it from "
                         "triangle %zu to triangle %zu across the edge between vertices %zu and "
                         "%zu turns it over",
                         c->source[conflict.first] + 1, c->source[conflict.second] + 1,
                         c->original[conflict.a] + 1, c->original[conflict.b] + 1);
    }
    for (size_t t = 0; t < c->triangle_count && status == UR_OK; t++)
        c->repairs.flipped += flipped[t];
    free(twins);
    free(flipped);
    return status;
}

/* Gives the mesh the cleaned arrays (and c the old ones, to free). */
static void commit(cleaning *c, ur_mesh *mesh)
{
    ur_vec3 *vertices = mesh->vertices;
    size_t(*triangles)[3] = mesh->triangles;
    size_t *groups = mesh->groups;
    mesh->vertices = c->vertices;
    mesh->vertex_count = c->vertex_count;
    mesh->triangles = c->triangles;
    mesh->groups = c->groups;
    mesh->triangle_count = c->triangle_count;
    c->vertices = vertices;
    c->triangles = triangles;
    c->groups = groups;
}

/* The steps of a cleaning, with the vertices marked apart left unwelded. */
static ur_status clean_once(cleaning *c, double weld_tolerance, const bool *apart, ur_error *error)
{
    const ur_mesh *mesh = c->mesh;
    c->map = ur_alloc_array(mesh->vertex_count, sizeof *c->map, error);
    ur_status status = c->map ? mesh_weld(mesh->vertices, mesh->vertex_count, weld_tolerance,
                                          c->map, &c->repairs.welded, error)
                              : UR_ERROR_MEMORY;
    for (size_t v = 0; status == UR_OK && apart && v < mesh->vertex_count; v++)
        if (c->map[v] != v && (apart[v] || apart[c->map[v]])) {
            c->map[v] = v;
            c->repairs.welded--;
            c->repairs.kept_apart++;
        }
    if (status == UR_OK)
        status = drop_degenerate(c, error);
    if (status == UR_OK)
        status = drop_repeated(c, error);
    if (status == UR_OK)
        status = renumber(c, error);
    if (status == UR_OK)
        status = orient(c, error);
    return status;
}

/*
 * Marks apart the input vertices welded into either end of the bad edge;
 * false when none was (the edge was non-manifold in the input).
 */
static bool mark_welded_ends(const cleaning *c, bool *apart)
{
    bool marked = false;
    for (size_t v = 0; v < c->mesh->vertex_count; v++) {
        size_t cleaned = c->map[v];
        if (cleaned == UR_NO_VERTEX || (cleaned != c->bad.a && cleaned != c->bad.b))
            continue;
        if (c->original[cleaned] != v && !apart[v]) {
            apart[v] = apart[c->original[cleaned]] = true;
            marked = true;
        }
    }
    return marked;
}

/*
 * Takes apart, at both ends of the bad edge, the fans of triangles round
 * them (fans.c); *split says whether any vertex was copied.  Only an edge
 * of an even count of triangles: two surfaces that touch; of three, one
 * is a fin that no copy can tell from the surface it stands on.
 */
static ur_status split_bad_edge(cleaning *c, bool *split, ur_error *error)
{
    *split = false;
    if (c->bad.count % 2 != 0)
        return UR_OK;
    size_t ends[2] = {c->bad.a, c->bad.b};
    for (int e = 0; e < 2; e++) {
        size_t copies = 0;
        ur_status status = mesh_split_fans(c->triangles, c->triangle_count, ends[e],
                                           c->vertex_count, &copies, error);
        if (status != UR_OK)
            return status;
        if (copies == 0)
            continue;
        ur_vec3 *vertices = realloc(c->vertices, (c->vertex_count + copies) * sizeof *vertices);
        if (vertices)
            c->vertices = vertices;
        size_t *original = realloc(c->original, (c->vertex_count + copies) * sizeof *original);
        if (original)
            c->original = original;
        if (!vertices || !original)
            return ur_error_out_of_memory(error);
        for (size_t k = 0; k < copies; k++) {
            c->vertices[c->vertex_count + k] = c->vertices[ends[e]];
            c->original[c->vertex_count + k] = c->original[ends[e]];
        }
        c->vertex_count += copies;
        c->repairs.split += copies;
        *split = true;
    }
    return UR_OK;
}

/* At most this many edges made non-manifold by welding are taken apart again. */
#define MOST_UNWELDS 1000

ur_status ur_mesh_clean_map(ur_mesh *mesh, double weld_tolerance, ur_mesh_repairs *repairs,
                            size_t **vertex_map, ur_error *error)
{
    cleaning c = {0};
    c.mesh = mesh;
    if (repairs)
        memset(repairs, 0, sizeof *repairs);
    if (vertex_map)
        *vertex_map = NULL;
    ur_status status = check_input(mesh, weld_tolerance, error);
    /*
     * Welding can join two parts that only touch (a modeller's eyes set
     * into a head) along an edge of four triangles: the ends of such an
     * edge are welded no more, and the mesh cleaned again.  When the input
     * itself joins them there, the surfaces round the edge's ends are
     * given their own vertices (split_bad_edge).
     */
    bool *apart = NULL;
    if (status == UR_OK)
        status = clean_once(&c, weld_tolerance, NULL, error);
    for (size_t round = 0; status == UR_ERROR_INPUT && c.bad.count > 2 && round < MOST_UNWELDS;
         round++) {
        if (!apart) {
            apart = ur_alloc_array(mesh->vertex_count, sizeof *apart, error);
            if (!apart) {
                status = UR_ERROR_MEMORY;
                break;
            }
            memset(apart, 0, mesh->vertex_count * sizeof *apart);
        }
        if (mark_welded_ends(&c, apart)) {
            cleaning_reset(&c);
            status = clean_once(&c, weld_tolerance, apart, error);
            continue;
        }
        bool split;
        ur_error refused = {0}; /* the bad edge's message, if nothing is split */
        if (error)
            refused = *error;
        ur_status splitting = split_bad_edge(&c, &split, error);
        if (splitting != UR_OK || !split) {
            if (splitting == UR_OK && error)
                *error = refused;
            status = splitting == UR_OK ? status : splitting;
            break;
        }
        status = orient(&c, error);
    }
    free(apart);
    if (status == UR_OK) {
        commit(&c, mesh);
        if (repairs)
            *repairs = c.repairs;
        if (vertex_map) {
            *vertex_map = c.map;
            c.map = NULL;
        }
    }
    cleaning_free(&c);
    return status;
}

ur_status ur_mesh_clean(ur_mesh *mesh, double weld_tolerance, ur_mesh_repairs *repairs,
                        ur_error *error)
{
    return ur_mesh_clean_map(mesh, weld_tolerance, repairs, NULL, error);
}
