/*
 * bench_flatten.c: LSCM and ARAP on a hyperbolic paraboloid z = x y / c
 * over a 1000 mm square (c = 2000 mm, corners 125 mm out of plane),
 * triangulated as a regular grid of about 10,000, 100,000 and 1,000,000
 * triangles (the target: ARAP to convergence or 50 iterations on 100,000
 * triangles under 3 s, in under 500 MB).
 *
 * Each size is flattened by LSCM alone, by ARAP stopped after one
 * iteration and by ARAP made to do 50, so that the figures split into
 * LSCM, the Laplacian's factorisation and the time per iteration; the two
 * smaller sizes also by ARAP as it runs by default (to convergence) but for
 * at most 50 iterations.  Prints the best of a few runs for the smaller
 * sizes, one run for the largest, and the process's peak memory.
 */
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

#include "unroll/flatten.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void die(const char *what)
{
    fprintf(stderr, "bench_flatten: %s\n", what);
    exit(1);
}

/* An n x n grid over the saddle, each square cut into two triangles. */
static ur_mesh saddle(size_t n)
{
    const double side = 1000, c = 2000;
    ur_mesh mesh = {0};
    mesh.vertex_count = (n + 1) * (n + 1);
    mesh.triangle_count = 2 * n * n;
    mesh.vertices = malloc(mesh.vertex_count * sizeof *mesh.vertices);
    mesh.triangles = malloc(mesh.triangle_count * sizeof *mesh.triangles);
    if (!mesh.vertices || !mesh.triangles)
        die("out of memory");
    for (size_t j = 0; j <= n; j++)
        for (size_t i = 0; i <= n; i++) {
            double x = side * ((double)i / n - 0.5), y = side * ((double)j / n - 0.5);
            mesh.vertices[j * (n + 1) + i] = ur_vec3_make(x, y, x * y / c);
        }
    size_t t = 0;
    for (size_t j = 0; j < n; j++)
        for (size_t i = 0; i < n; i++) {
            size_t a = j * (n + 1) + i, b = a + 1, d = a + n + 1, e = d + 1;
            mesh.triangles[t][0] = a, mesh.triangles[t][1] = b, mesh.triangles[t++][2] = e;
            mesh.triangles[t][0] = a, mesh.triangles[t][1] = e, mesh.triangles[t++][2] = d;
        }
    mesh.group_count = 1;
    return mesh;
}

/* Seconds to flatten; *flat is the result, the caller's to free. */
static double time_flatten(const ur_mesh *mesh, const ur_flatten_options *options,
                           ur_flat_piece *flat)
{
    ur_error error;
    double start = now();
    if (ur_flatten(mesh, options, flat, &error))
        die(error.message);
    return now() - start;
}

/* The best of runs times with these options; the last result is kept in *flat. */
static double best_of(int runs, const ur_mesh *mesh, ur_flatten_method method, size_t iterations,
                      double tolerance, ur_flat_piece *flat)
{
    ur_flatten_options options = {
        .method = method, .iterations = iterations, .tolerance = tolerance};
    double best = 1e300;
    for (int run = 0; run < runs; run++) {
        if (run > 0)
            ur_flat_piece_free(flat);
        double seconds = time_flatten(mesh, &options, flat);
        best = seconds < best ? seconds : best;
    }
    return best;
}

static double peak_megabytes(void)
{
    struct rusage usage;
    return getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss / 1024.0 : -1;
}

static void print_result(const ur_mesh *mesh, const ur_flat_piece *lscm, const ur_flat_piece *arap)
{
    double energy_lscm, energy_arap;
    if (ur_flatten_energy(mesh, lscm->flat, &energy_lscm, NULL) ||
        ur_flatten_energy(mesh, arap->flat, &energy_arap, NULL))
        die("energy");
    printf("  energy LSCM %.3g, ARAP %.3g; stretch %.4f, compression %.4f, coverage %.6f%s\n",
           energy_lscm, energy_arap, arap->max_stretch, arap->max_compression, arap->coverage,
           arap->flipped ? ", FLIPPED" : "");
}

/*
 * LSCM alone, ARAP stopped after 1 iteration, ARAP made to do 50
 * (tolerance 0), and unless skipped ARAP as ur_flatten does it by default
 * (tolerance 1e-9) but for at most 50 iterations.
 */
static void bench(size_t n, int runs, bool to_convergence)
{
    ur_mesh mesh = saddle(n);
    ur_flat_piece lscm, one, fifty, converged;
    double t_lscm = best_of(runs, &mesh, UR_FLATTEN_LSCM, 0, 0, &lscm);
    double t_one = best_of(runs, &mesh, UR_FLATTEN_ARAP, 1, 0, &one);
    double t_fifty = best_of(runs, &mesh, UR_FLATTEN_ARAP, 50, 0, &fifty);
    double per_iteration = (t_fifty - t_one) / 49;
    printf("saddle, %zu triangles, %zu vertices:\n", mesh.triangle_count, mesh.vertex_count);
    printf("  LSCM %.3f s; ARAP factorisation about %.3f s, %.4f s per iteration; LSCM and 50 "
           "ARAP iterations %.3f s\n",
           t_lscm, t_one - t_lscm - per_iteration, per_iteration, t_fifty);
    if (to_convergence) {
        double t_converged = best_of(runs, &mesh, UR_FLATTEN_ARAP, 50, 1e-9, &converged);
        printf("  to convergence (tolerance 1e-9) or 50 iterations: %.3f s, %zu iterations\n",
               t_converged, converged.iterations);
        print_result(&mesh, &lscm, &converged);
        ur_flat_piece_free(&converged);
    } else
        print_result(&mesh, &lscm, &fifty);
    printf("  peak memory so far %.0f MB\n", peak_megabytes());
    ur_flat_piece_free(&lscm);
    ur_flat_piece_free(&one);
    ur_flat_piece_free(&fifty);
    free(mesh.vertices);
    free(mesh.triangles);
}

int main(void)
{
    bench(71, 5, true);   /* 10,082 triangles */
    bench(224, 3, true);  /* 100,352 triangles: the target, 3 s and 500 MB */
    bench(707, 1, false); /* 999,698 triangles: one run of each, 50 iterations only */
    return 0;
}
