/*
 * pieces.c: ur_mesh_pieces: the parts of a mesh between its seams (user
 * seams, group boundaries, the boundary), each cut open into a topological
 * disk (cut.c) and made a mesh of its own, then checked to be a disk.
 *
 * The mesh must be manifold and consistently oriented, as ur_mesh_clean
 * leaves it: a one-sided or tangled mesh is refused, not repaired here.
 */
#include "cutter.h"

#include <stdlib.h>
#include <string.h>

/* A triangle no part has reached yet. */
#define NO_PART ((size_t)-1)

void cutter_free(cutter *c)
{
    free(c->twins);
    free(c->seam);
    free(c->tree);
    free(c->part);
    free(c->part_size);
    free(c->corner);
}

/* Refuses what cutting cannot work on: corners at one vertex, triangles turned opposite ways. */
static ur_status check_mesh(const cutter *c, ur_error *error)
{
    const size_t(*triangles)[3] = c->triangles;
    for (size_t t = 0; t < c->mesh->triangle_count; t++) {
        const size_t *v = triangles[t];
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
            return ur_error_set(error, UR_ERROR_INPUT,
                                "triangle %zu has two corners at one vertex: clean the mesh first",
                                t + 1);
    }
    for (size_t h = 0; h < c->half_edge_count; h++) {
        size_t g = c->twins[h];
        if (g != UR_NO_EDGE && mesh_from(triangles, h) != mesh_to(triangles, g))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "the mesh is not consistently oriented: triangles %zu and %zu run "
                                "the edge between vertices %zu and %zu the same way; clean it "
                                "first",
                                h / 3 + 1, g / 3 + 1, mesh_from(triangles, h) + 1,
                                mesh_to(triangles, h) + 1);
    }
    return UR_OK;
}

ur_status cutter_init(cutter *c, const ur_mesh *mesh, ur_error *error)
{
    memset(c, 0, sizeof *c);
    c->mesh = mesh;
    c->triangles = (const size_t(*)[3])mesh->triangles;
    c->half_edge_count = 3 * mesh->triangle_count;
    ur_status status = ur_mesh_twins(mesh, &c->twins, error);
    if (status != UR_OK)
        return status;
    c->seam = ur_alloc_array(c->half_edge_count, sizeof *c->seam, error);
    c->tree = ur_alloc_array(c->half_edge_count, sizeof *c->tree, error);
    c->part = ur_alloc_array(mesh->triangle_count, sizeof *c->part, error);
    c->part_size = ur_alloc_array(mesh->triangle_count, sizeof *c->part_size, error);
    c->corner = ur_alloc_array(c->half_edge_count, sizeof *c->corner, error);
    if (!c->seam || !c->tree || !c->part || !c->part_size || !c->corner)
        return UR_ERROR_MEMORY;
    return check_mesh(c, error);
}

static ur_status check_seam(const ur_seam *seam, size_t index, size_t vertex_count, ur_error *error)
{
    size_t far = seam->a > seam->b ? seam->a : seam->b;
    if (far >= vertex_count)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "seam %zu names vertex %zu, but the mesh has %zu vertices", index + 1,
                            far + 1, vertex_count);
    if (seam->a == seam->b)
        return ur_error_set(error, UR_ERROR_INPUT, "seam %zu joins vertex %zu to itself", index + 1,
                            seam->a + 1);
    return UR_OK;
}

/* The user's seams, checked, sorted and without repeats; *count is updated. */
static ur_status sort_seams(const ur_seam *seams, size_t *count, size_t vertex_count,
                            mesh_edge_key **keys, ur_error *error)
{
    *keys = ur_alloc_array(*count, sizeof **keys, error);
    if (!*keys)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < *count; i++) {
        ur_status status = check_seam(&seams[i], i, vertex_count, error);
        if (status != UR_OK)
            return status;
        /* A user seam and its place in the caller's array. */
        (*keys)[i] = mesh_edge_key_of(seams[i].a, seams[i].b, i);
    }
    qsort(*keys, *count, sizeof **keys, mesh_compare_edge_keys);
    size_t kept = 0;
    for (size_t i = 0; i < *count; i++)
        if (kept == 0 || mesh_compare_edge_ends(&(*keys)[i], &(*keys)[kept - 1]) != 0)
            (*keys)[kept++] = (*keys)[i];
    *count = kept;
    return UR_OK;
}

/* Unglues the user's seams; each must be an edge of the mesh. */
static ur_status mark_user_seams(cutter *c, const ur_seam *seams, size_t count, ur_error *error)
{
    mesh_edge_key *keys = NULL;
    bool *found = NULL;
    ur_status status = sort_seams(seams, &count, c->mesh->vertex_count, &keys, error);
    if (status == UR_OK && !(found = ur_alloc_array(count, sizeof *found, error)))
        status = UR_ERROR_MEMORY;
    for (size_t h = 0; h < c->half_edge_count && status == UR_OK && count > 0; h++) {
        if (c->twins[h] != UR_NO_EDGE && c->twins[h] < h)
            continue;
        size_t a = mesh_from(c->triangles, h), b = mesh_to(c->triangles, h);
        mesh_edge_key key = mesh_edge_key_of(a, b, 0);
        mesh_edge_key *hit = bsearch(&key, keys, count, sizeof *keys, mesh_compare_edge_ends);
        if (hit) {
            found[hit - keys] = true;
            cutter_unglue(c, h);
        }
    }
    /* Name the first missing seam in the caller's order. */
    size_t missing = count;
    for (size_t i = 0; i < count && status == UR_OK; i++)
        if (!found[i] && (missing == count || keys[i].index < keys[missing].index))
            missing = i;
    if (status == UR_OK && missing < count)
        status = ur_error_set(error, UR_ERROR_INPUT,
                              "seam %zu (vertices %zu and %zu) is not an edge of the mesh",
                              keys[missing].index + 1, seams[keys[missing].index].a + 1,
                              seams[keys[missing].index].b + 1);
    free(keys);
    free(found);
    return status;
}

/* The boundary and the edges between groups never join two triangles of one piece. */
static void mark_seams(cutter *c)
{
    const size_t *groups = c->mesh->groups;
    for (size_t h = 0; h < c->half_edge_count; h++) {
        size_t g = c->twins[h];
        if (g == UR_NO_EDGE || (groups && groups[h / 3] != groups[g / 3]))
            c->seam[h] = true;
    }
}

/* Parts: triangles reached across glued edges, breadth first. */
static ur_status find_parts(cutter *c, ur_error *error)
{
    size_t triangle_count = c->mesh->triangle_count;
    size_t *queue = ur_alloc_array(triangle_count, sizeof *queue, error);
    if (!queue)
        return UR_ERROR_MEMORY;
    for (size_t t = 0; t < triangle_count; t++)
        c->part[t] = NO_PART;
    size_t head = 0, tail = 0;
    for (size_t seed = 0; seed < triangle_count; seed++) {
        if (c->part[seed] != NO_PART)
            continue;
        size_t p = c->part_count++;
        c->part[seed] = p;
        queue[tail++] = seed;
        while (head < tail) {
            size_t t = queue[head++];
            c->part_size[p]++;
            for (size_t h = 3 * t; h < 3 * t + 3; h++) {
                if (c->seam[h] || c->part[c->twins[h] / 3] != NO_PART)
                    continue;
                size_t s = c->twins[h] / 3;
                c->part[s] = p;
                queue[tail++] = s;
            }
        }
    }
    free(queue);
    return UR_OK;
}

/* Cutting relies on every vertex of the cut surface having one boundary edge out at most. */
static ur_status check_manifold(const cutter *c, const part_shape *shapes, ur_error *error)
{
    for (size_t p = 0; p < c->part_count; p++)
        if (shapes[p].broken)
            return ur_error_set(error, UR_ERROR_INTERNAL,
                                "piece %zu: a vertex has two boundary edges leaving it (a bug)",
                                p + 1);
    return UR_OK;
}

/* Seams, slits, parts, cuts: leaves c->corner numbering the vertices of disks. */
static ur_status cut_open(cutter *c, const ur_seam *seams, size_t seam_count, part_shape **shapes,
                          ur_error *error)
{
    mark_seams(c);
    ur_status status = mark_user_seams(c, seams, seam_count, error);
    if (status == UR_OK)
        status = cutter_corners(c, error);
    if (status == UR_OK)
        status = cutter_open_slits(c, error);
    if (status == UR_OK)
        status = find_parts(c, error);
    if (status == UR_OK && !(*shapes = ur_alloc_array(c->part_count, sizeof **shapes, error)))
        status = UR_ERROR_MEMORY;
    if (status == UR_OK)
        status = cutter_shapes(c, *shapes, error);
    if (status == UR_OK)
        status = check_manifold(c, *shapes, error);
    if (status == UR_OK)
        status = cutter_cut(c, *shapes, error);
    if (status == UR_OK)
        status = cutter_corners(c, error);
    if (status == UR_OK)
        status = cutter_shapes(c, *shapes, error);
    return status;
}

static ur_status alloc_piece(ur_mesh_piece *piece, const part_shape *shape, ur_error *error)
{
    ur_mesh *mesh = &piece->mesh;
    mesh->vertices = ur_alloc_array(shape->vertices, sizeof *mesh->vertices, error);
    mesh->triangles = ur_alloc_array(shape->triangles, sizeof *mesh->triangles, error);
    mesh->groups = ur_alloc_array(shape->triangles, sizeof *mesh->groups, error);
    piece->original = ur_alloc_array(shape->vertices, sizeof *piece->original, error);
    piece->source_triangles =
        ur_alloc_array(shape->triangles, sizeof *piece->source_triangles, error);
    if (!mesh->vertices || !mesh->triangles || !mesh->groups || !piece->original ||
        !piece->source_triangles)
        return UR_ERROR_MEMORY;
    return UR_OK;
}

/* Adds triangle t to its piece, numbering the piece's vertices as they first appear. */
static void add_triangle(const cutter *c, size_t t, ur_mesh_piece *piece, size_t *local)
{
    const ur_mesh *mesh = c->mesh;
    ur_mesh *out = &piece->mesh;
    size_t i = out->triangle_count++;
    for (int k = 0; k < 3; k++) {
        size_t v = c->corner[3 * t + k];
        if (local[v] == UR_NO_VERTEX) {
            local[v] = out->vertex_count++;
            out->vertices[local[v]] = mesh->vertices[mesh->triangles[t][k]];
            piece->original[local[v]] = mesh->triangles[t][k];
        }
        out->triangles[i][k] = local[v];
    }
    out->groups[i] = mesh->groups ? mesh->groups[t] : 0;
    piece->source_triangles[i] = t;
}

static ur_status build_pieces(const cutter *c, const part_shape *shapes, ur_mesh_piece *pieces,
                              ur_error *error)
{
    for (size_t p = 0; p < c->part_count; p++) {
        ur_status status = alloc_piece(&pieces[p], &shapes[p], error);
        if (status != UR_OK)
            return status;
        pieces[p].mesh.group_count = c->mesh->group_count;
    }
    size_t *local = ur_alloc_array(c->vertex_count, sizeof *local, error);
    if (!local)
        return UR_ERROR_MEMORY;
    for (size_t v = 0; v < c->vertex_count; v++)
        local[v] = UR_NO_VERTEX;
    for (size_t t = 0; t < c->mesh->triangle_count; t++)
        add_triangle(c, t, &pieces[c->part[t]], local);
    free(local);
    return UR_OK;
}

/* Each piece, seen as a mesh of its own, must be a disk; anything else is a bug here. */
static ur_status verify_pieces(const ur_mesh_piece *pieces, size_t count, ur_error *error)
{
    for (size_t p = 0; p < count; p++) {
        ur_status status = mesh_check_disk(&pieces[p].mesh, error);
        if (status == UR_ERROR_INPUT) {
            ur_error_prefix(error, "piece %zu did not come out a disk (a bug): ", p + 1);
            if (error)
                error->status = UR_ERROR_INTERNAL;
            return UR_ERROR_INTERNAL;
        }
        if (status != UR_OK)
            return status;
    }
    return UR_OK;
}

ur_status ur_mesh_pieces(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                         ur_mesh_piece **pieces, size_t *piece_count, ur_error *error)
{
    *pieces = NULL;
    *piece_count = 0;
    cutter c;
    part_shape *shapes = NULL;
    ur_status status = cutter_init(&c, mesh, error);
    if (status == UR_OK)
        status = cut_open(&c, seams, seam_count, &shapes, error);
    if (status == UR_OK && !(*pieces = ur_alloc_array(c.part_count, sizeof **pieces, error)))
        status = UR_ERROR_MEMORY;
    if (status == UR_OK) {
        *piece_count = c.part_count;
        status = build_pieces(&c, shapes, *pieces, error);
    }
    if (status == UR_OK)
        status = verify_pieces(*pieces, *piece_count, error);
    if (status != UR_OK) {
        ur_mesh_pieces_free(*pieces, *piece_count);
        *pieces = NULL;
        *piece_count = 0;
    }
    free(shapes);
    cutter_free(&c);
    return status;
}

void ur_mesh_pieces_free(ur_mesh_piece *pieces, size_t piece_count)
{
    if (!pieces)
        return;
    for (size_t p = 0; p < piece_count; p++) {
        ur_mesh_free(&pieces[p].mesh);
        free(pieces[p].original);
        free(pieces[p].source_triangles);
    }
    free(pieces);
}
