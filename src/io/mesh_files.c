/*
 * mesh_files.c: the files assimp may open while it reads a mesh
 * (mesh_import.c): the mesh itself, from disk or from a buffer, and for a
 * glTF the files beside it (its buffers); never a material library.
 *
 * unroll needs no materials, and assimp 5.2's OBJ reader crashes on a
 * material library with a texture line before its first material ("map_Kd
 * x.png" above "newmtl"): from disk when the OBJ names such a file, and
 * from a buffer on any OBJ that names a library at all, since assimp then
 * reads the OBJ itself as the library (fuzz_mesh).  Refusing to open any
 * file but the mesh makes assimp go on with its default material.
 */
#include "io_internal.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Whether assimp may open path: the mesh, or a file beside a glTF. */
static bool may_open(const io_mesh_files *files, const char *path)
{
    if (strcmp(path, files->name) == 0)
        return true;
    if (files->data) /* a buffer has nothing beside it */
        return false;
    struct stat mesh, other;
    if (stat(files->name, &mesh) == 0 && stat(path, &other) == 0 && mesh.st_dev == other.st_dev &&
        mesh.st_ino == other.st_ino)
        return true; /* the mesh under another spelling of its path */
    return io_has_extension(files->name, "gltf") && !io_has_extension(path, "mtl");
}

static FILE *stream_of(struct aiFile *file)
{
    return (FILE *)(void *)file->UserData;
}

static size_t read_file(struct aiFile *file, char *buffer, size_t size, size_t count)
{
    return fread(buffer, size, count, stream_of(file));
}

static size_t write_file(struct aiFile *file, const char *buffer, size_t size, size_t count)
{
    (void)file, (void)buffer, (void)size, (void)count;
    return 0; /* opened for reading only */
}

static size_t tell_file(struct aiFile *file)
{
    long at = ftell(stream_of(file));
    return at < 0 ? 0 : (size_t)at;
}

static size_t size_of_file(struct aiFile *file)
{
    FILE *stream = stream_of(file);
    long at = ftell(stream);
    if (at < 0 || fseek(stream, 0, SEEK_END) != 0)
        return 0;
    long end = ftell(stream);
    if (fseek(stream, at, SEEK_SET) != 0 || end < 0)
        return 0;
    return (size_t)end;
}

static enum aiReturn seek_file(struct aiFile *file, size_t offset, enum aiOrigin origin)
{
    int whence = origin == aiOrigin_SET ? SEEK_SET : origin == aiOrigin_CUR ? SEEK_CUR : SEEK_END;
    if (offset > (size_t)LONG_MAX)
        return aiReturn_FAILURE;
    return fseek(stream_of(file), (long)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static void flush_file(struct aiFile *file)
{
    (void)file; /* nothing is written */
}

static struct aiFile *open_file(struct aiFileIO *io, const char *path, const char *mode)
{
    const io_mesh_files *files = (const io_mesh_files *)(void *)io->UserData;
    if (!path || !mode || strchr(mode, 'w') || strchr(mode, 'a') || !may_open(files, path))
        return NULL;
    struct aiFile *file = calloc(1, sizeof *file);
    if (!file)
        return NULL;
    /* "r": the buffer is only read */
    FILE *stream =
        files->data ? fmemopen((void *)files->data, files->size, "r") : fopen(path, "rb");
    if (!stream) {
        free(file);
        return NULL;
    }
    *file = (struct aiFile){.ReadProc = read_file,
                            .WriteProc = write_file,
                            .TellProc = tell_file,
                            .FileSizeProc = size_of_file,
                            .SeekProc = seek_file,
                            .FlushProc = flush_file,
                            .UserData = (aiUserData)(void *)stream};
    return file;
}

static void close_file(struct aiFileIO *io, struct aiFile *file)
{
    (void)io;
    if (!file)
        return;
    fclose(stream_of(file));
    free(file);
}

void io_mesh_files_init(io_mesh_files *files, const char *name, const void *data, size_t size)
{
    files->name = name;
    files->data = data;
    files->size = size;
    files->io = (struct aiFileIO){
        .OpenProc = open_file, .CloseProc = close_file, .UserData = (aiUserData)(void *)files};
}
