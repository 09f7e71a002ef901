/*
 * mesh_check.h: what fuzz_mesh.c and fuzz_mesh_clean.c share, header-only:
 * the path a mesh takes in unroll after it is read (src/cli/meshes.c):
 * welding and repair (ur_mesh_clean), the manifold check (ur_mesh_twins)
 * and the cut into topological disks (ur_mesh_pieces), each result checked
 * against what unroll/mesh.h promises.
 */
#ifndef UNROLL_FUZZ_MESH_CHECK_H
#define UNROLL_FUZZ_MESH_CHECK_H

#include "fuzz_support.h"

#include <math.h>

#include "unroll/mesh.h"

/* Finite vertices, indices in range, groups below group_count. */
static inline void check_mesh(const ur_mesh *mesh)
{
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        ur_vec3 p = mesh->vertices[v];
        FUZZ_CHECK(isfinite(p.x) && isfinite(p.y) && isfinite(p.z));
    }
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        for (int k = 0; k < 3; k++)
            FUZZ_CHECK(mesh->triangles[t][k] < mesh->vertex_count);
        FUZZ_CHECK(mesh->groups == NULL || mesh->groups[t] < mesh->group_count);
    }
}

/* Every piece is a disk of the cleaned mesh's vertices. */
static inline void check_pieces(const ur_mesh *mesh, const ur_mesh_piece *pieces, size_t count)
{
    size_t triangles = 0;
    for (size_t k = 0; k < count; k++) {
        const ur_mesh_piece *piece = &pieces[k];
        check_mesh(&piece->mesh);
        FUZZ_CHECK(piece->mesh.triangle_count > 0);
        for (size_t v = 0; v < piece->mesh.vertex_count; v++)
            FUZZ_CHECK(piece->original[v] < mesh->vertex_count);
        for (size_t t = 0; t < piece->mesh.triangle_count; t++)
            FUZZ_CHECK(piece->source_triangles[t] < mesh->triangle_count);
        size_t *loop = NULL, loop_count = 0;
        ur_error error;
        if (ur_mesh_boundary(&piece->mesh, &loop, &loop_count, &error) != UR_OK) {
            fprintf(stderr, "piece %zu is no disk: %s\n", k + 1, error.message);
            FUZZ_CHECK(!"every piece is a disk");
        }
        FUZZ_CHECK(loop_count >= 3);
        free(loop);
        triangles += piece->mesh.triangle_count;
    }
    /* The pieces share out the triangles, none lost or doubled. */
    FUZZ_CHECK(triangles == mesh->triangle_count);
}

/* What unroll does with a mesh it has read: clean (welding at its tolerance), check, cut. */
static inline void clean_and_cut(ur_mesh *mesh, double weld)
{
    check_mesh(mesh);
    ur_mesh_repairs repairs;
    ur_error error;
    if (ur_mesh_clean(mesh, weld, &repairs, &error) != UR_OK) {
        FUZZ_CHECK(error.message[0] != '\0');
        return;
    }
    check_mesh(mesh);
    FUZZ_CHECK(mesh->triangle_count > 0);
    size_t *twins = NULL;
    FUZZ_CHECK(ur_mesh_twins(mesh, &twins, &error) == UR_OK); /* clean refuses non-manifold */
    free(twins);
    ur_mesh_piece *pieces = NULL;
    size_t count = 0;
    if (ur_mesh_pieces(mesh, NULL, 0, &pieces, &count, &error) != UR_OK) {
        fprintf(stderr, "cut into pieces: %s\n", error.message);
        FUZZ_CHECK(!"a clean mesh is cut into pieces");
    }
    check_pieces(mesh, pieces, count);
    ur_mesh_pieces_free(pieces, count);
}

#endif
