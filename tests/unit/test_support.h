/*
 * test_support.h: what several unit tests share, header-only.
 *
 * The Makefile builds each tests/unit/test_*.c as a program of its own, so
 * there is no test library to link: everything here is a macro or a static
 * inline function, and a test that leaves one unused still builds with
 * -Werror.  It includes cmocka itself, so it may come before or after it.
 */
#ifndef UNROLL_TEST_SUPPORT_H
#define UNROLL_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "unroll/develop.h"
#include "unroll/flatten.h"
#include "unroll/io.h"
#include "unroll/mesh.h"

/* actual within tolerance * |expected| of expected; the message names the expression. */
#define assert_relative(actual, expected, tolerance)                                               \
    do {                                                                                           \
        double a_ = (actual), e_ = (expected);                                                     \
        if (!(fabs(a_ - e_) <= (tolerance)*fabs(e_)))                                              \
            fail_msg("%s = %.12g, expected %.12g within %g", #actual, a_, e_,                      \
                     (double)(tolerance));                                                         \
    } while (0)

/* The nets of ruled by method with n parts (rulings drawn for the exact method); fails on error. */
static inline ur_net_list develop(ur_ruled *ruled, ur_method method, size_t n, double tolerance)
{
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.method = method;
    options.rulings = n;
    options.tolerance = tolerance;
    ur_net_list nets;
    ur_error error;
    if (ur_develop(ruled, &options, &nets, &error) != UR_OK)
        fail_msg("develop: %s", error.message);
    return nets;
}

/* A piece whose outline is the ring (a cut), with its flat area. */
static inline ur_piece polygon_piece(const char *name, const ur_vec2 *ring, size_t count)
{
    ur_piece piece;
    memset(&piece, 0, sizeof piece);
    snprintf(piece.name, sizeof piece.name, "%s", name);
    assert_int_equal(ur_piece_add_path(&piece, UR_OP_CUT, ring, count, true, NULL), UR_OK);
    piece.measures.flat_area = fabs(ur_polygon_signed_area(ring, count));
    return piece;
}

/* The box of points turned by angle about the origin. */
static inline ur_box turned_box_of(const ur_vec2 *points, size_t count, double angle)
{
    double c = cos(angle), s = sin(angle);
    ur_box box = ur_box_empty();
    for (size_t k = 0; k < count; k++)
        ur_box_add(&box, ur_vec2_make(c * points[k].x - s * points[k].y,
                                      s * points[k].x + c * points[k].y));
    return box;
}

/* ---- A test directory under /tmp ---------------------------------------- */

/* directory/name into path; fails the test rather than cut it short. */
static inline void path_in(const char *directory, const char *name, char *path, size_t size)
{
    int length = snprintf(path, size, "%s/%s", directory, name);
    assert_true(length > 0 && (size_t)length < size);
}

/* Whether anything, file or directory, is at path. */
static inline bool exists(const char *path)
{
    struct stat info;
    return stat(path, &info) == 0;
}

/*
 * Calls f (unless NULL) on each entry of directory but . and .., hidden
 * ones included; returns how many there are, -1 if it cannot be read.
 */
static inline int each_entry(const char *directory, int (*f)(const char *path))
{
    DIR *dir = opendir(directory);
    if (!dir)
        return -1;
    int count = 0;
    struct dirent *entry;
    char path[512];
    while ((entry = readdir(dir)) != NULL) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
            continue;
        count++;
        snprintf(path, sizeof path, "%s/%s", directory, entry->d_name);
        if (f)
            f(path);
    }
    closedir(dir);
    return count;
}

/* How many entries directory holds: temporaries a writer left behind count too. */
static inline int entries_in(const char *directory)
{
    int count = each_entry(directory, NULL);
    assert_true(count >= 0);
    return count;
}

/* Removes directory and the files in it (tests write no subdirectories); 0 on success. */
static inline int remove_test_directory(const char *directory)
{
    each_entry(directory, unlink);
    return rmdir(directory);
}

/* ---- Unfolded meshes as nets ---------------------------------------------- */

/* A mesh file read and cleaned as the command line does (welded to 1e-6 mm). */
static inline ur_mesh cleaned_mesh_file(const char *path)
{
    ur_mesh mesh;
    ur_error error;
    if (ur_mesh_import(path, NULL, &mesh, NULL, &error) != UR_OK)
        fail_msg("import: %s", error.message);
    ur_mesh_repairs repairs;
    assert_int_equal(ur_mesh_clean(&mesh, 1e-6, &repairs, &error), UR_OK);
    return mesh;
}

/*
 * The nets of the mesh file unfolded along its edges, as the command line
 * makes them (outline, 3D points, names P1, P2, ...), seams not yet found;
 * *seams receives how many edges the unfolding cut.  Free with
 * ur_net_list_free.
 */
static inline ur_net_list unfolded_nets(const char *path, size_t *seams)
{
    ur_mesh mesh = cleaned_mesh_file(path);
    ur_error error;
    ur_unfolding unfolding;
    assert_int_equal(ur_unfold(&mesh, NULL, 0, &unfolding, &error), UR_OK);
    ur_net_list nets = {calloc(unfolding.count, sizeof(ur_net)), unfolding.count};
    assert_non_null(nets.nets);
    for (size_t k = 0; k < unfolding.count; k++) {
        const ur_unfolded_piece *piece = &unfolding.pieces[k];
        ur_net *net = &nets.nets[k];
        snprintf(net->name, sizeof net->name, "P%zu", k + 1);
        net->outline_count = piece->outline_count;
        net->outline = malloc(piece->outline_count * sizeof *net->outline);
        net->outline_3d = malloc(piece->outline_count * sizeof *net->outline_3d);
        assert_true(net->outline && net->outline_3d);
        for (size_t i = 0; i < piece->outline_count; i++) {
            net->outline[i] = piece->outline[i];
            net->outline_3d[i] = mesh.vertices[piece->outline_vertices[i]];
        }
        net->flat_area = piece->flat_area;
    }
    *seams = unfolding.seams;
    ur_unfolding_free(&unfolding);
    ur_mesh_free(&mesh);
    return nets;
}

#endif
