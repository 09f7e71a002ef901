/*
 * fuzz_mesh_clean.c: fuzz target for unroll's own mesh repair (src/mesh/):
 * welding, dropping degenerate triangles and unused vertices, orienting,
 * refusing non-manifold edges, then cutting into disks, on meshes made
 * straight from the fuzzer's bytes rather than through a file format, so
 * that every input is a mesh and coincident points, repeated corners,
 * folds and fans are common.
 *
 * Bytes: [0] the vertex count n (1..64), [1] the scale and weld tolerance,
 * then 3 n signed bytes, the coordinates on a grid, then 4 bytes a
 * triangle: three corners (mod n) and a group (mod 4).
 */
#include "mesh_check.h"

#include <stdint.h>

#define FUZZ_MAX_VERTICES 64

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 2)
        return 0;
    size_t n = (size_t)(data[0] % FUZZ_MAX_VERTICES) + 1;
    /* Grid steps from a micrometre to a metre: welding and area tests at every size. */
    static const double steps[] = {1e-3, 1e-1, 1.0, 10.0, 1000.0};
    double step = steps[(data[1] & 0x0f) % 5];
    /* Weld tolerances: identical points only, under a step, about a step. */
    static const double welds[] = {0.0, 1e-6, 0.3, 1.0};
    double weld = welds[(data[1] >> 4) % 4] * step;
    size_t offset = 2;
    if (size < offset + 3 * n)
        return 0;
    ur_vec3 vertices[FUZZ_MAX_VERTICES];
    for (size_t v = 0; v < n; v++) {
        const uint8_t *c = data + offset + 3 * v;
        vertices[v] = ur_vec3_make((int8_t)c[0] * step, (int8_t)c[1] * step, (int8_t)c[2] * step);
    }
    offset += 3 * n;
    size_t triangle_count = (size - offset) / 4;
    if (triangle_count == 0)
        return 0;
    size_t(*triangles)[3] = malloc(triangle_count * sizeof *triangles);
    size_t *groups = malloc(triangle_count * sizeof *groups);
    FUZZ_CHECK(triangles && groups);
    for (size_t t = 0; t < triangle_count; t++) {
        const uint8_t *c = data + offset + 4 * t;
        for (int k = 0; k < 3; k++)
            triangles[t][k] = c[k] % n;
        groups[t] = c[3] % 4;
    }
    ur_mesh mesh;
    ur_error error;
    if (ur_mesh_new(vertices, n, (const size_t(*)[3])triangles, triangle_count, groups, &mesh,
                    &error) == UR_OK) {
        clean_and_cut(&mesh, weld);
        ur_mesh_free(&mesh);
    }
    free(triangles);
    free(groups);
    return 0;
}
