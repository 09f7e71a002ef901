/*
 * fuzz_mesh.c: fuzz target for meshes from files (src/io/mesh_import.c and
 * src/mesh/): the bytes go through the real loader (assimp, then unroll's
 * checks of the header counts, coordinates and transforms), then through
 * what `unroll mesh` does next: clean at its weld tolerance, check, cut
 * into disks (mesh_check.h).
 *
 * The first byte picks the format, known to the loader by the extension:
 * OBJ, STL (ASCII or binary), PLY, glTF, Collada or 3MF (byte modulo 6,
 * so that the seeds of the first four formats kept theirs); the rest is
 * the file.  Assimp
 * itself is not instrumented, so coverage guides the fuzzer through
 * unroll's code only.
 */
#include "mesh_check.h"

#include "unroll/io.h"

static const char *const names[] = {"mesh.obj",  "mesh.stl", "mesh.ply",
                                    "mesh.gltf", "mesh.dae", "mesh.3mf"};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    ur_mesh mesh;
    ur_error error;
    if (ur_mesh_import_buffer(names[data[0] % 6], data + 1, size - 1, NULL, &mesh, NULL, &error) !=
        UR_OK) {
        FUZZ_CHECK(strstr(error.message, "mesh.") != NULL);
        return 0;
    }
    for (size_t v = 0; v < mesh.vertex_count; v++) {
        ur_vec3 p = mesh.vertices[v];
        FUZZ_CHECK(fabs(p.x) <= UR_MESH_IMPORT_MAX_COORDINATE &&
                   fabs(p.y) <= UR_MESH_IMPORT_MAX_COORDINATE &&
                   fabs(p.z) <= UR_MESH_IMPORT_MAX_COORDINATE);
    }
    /* As src/cli/meshes.c welds: well below any detail, above float rounding. */
    double size_mm = mesh.vertex_count ? ur_mesh_size(&mesh) : 0.0;
    clean_and_cut(&mesh, 1e-6 * size_mm);
    ur_mesh_free(&mesh);
    return 0;
}
