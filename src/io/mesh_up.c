/*
 * mesh_up.c: which axis of a mesh file points up, guessed from what wrote
 * it, for drawings of the model (the assembly guide).
 *
 * A mesh file does not say which way is up, but its format or its writer
 * often does: glTF is +y up by its specification, a Collada file comes
 * out of assimp +y up (assimp turns the <up_axis> the file declares to
 * +y), and Blender writes OBJ files +y up unless told otherwise (and says
 * so in the comment it puts on the first line).  Everything else is taken
 * as +z up, as CAD programs, STL and 3MF files (Blender's STL export
 * included) and this project's samples are.
 */
#include "io_internal.h"

#include <stdio.h>
#include <string.h>

/* Enough of a file's start for the comment lines a writer puts there. */
#define HEAD_SIZE 1024

/* Whether the OBJ's leading comment lines name Blender (its exporter writes "# Blender ..."). */
static bool obj_written_by_blender(const char *head, size_t size)
{
    size_t at = 0;
    while (at < size && head[at] == '#') {
        size_t end = at;
        while (end < size && head[end] != '\n')
            end++;
        /* "# Blender v3.4.1 OBJ File" (the legacy exporter) or "# Blender 4.0.2". */
        if (end - at >= 9 && strncmp(head + at, "# Blender", 9) == 0)
            return true;
        at = end + 1;
    }
    return false;
}

ur_up_axis ur_mesh_up_axis(const char *name, const void *head, size_t size)
{
    if (io_has_extension(name, "gltf") || io_has_extension(name, "glb") ||
        io_has_extension(name, "dae"))
        return UR_UP_Y;
    if (io_has_extension(name, "obj") && head && obj_written_by_blender(head, size))
        return UR_UP_Y;
    return UR_UP_Z;
}

ur_up_axis ur_mesh_file_up_axis(const char *path)
{
    char head[HEAD_SIZE];
    size_t size = 0;
    FILE *file = io_has_extension(path, "obj") ? fopen(path, "rb") : NULL;
    if (file) {
        size = fread(head, 1, sizeof head, file);
        fclose(file);
    }
    return ur_mesh_up_axis(path, size ? head : NULL, size);
}
