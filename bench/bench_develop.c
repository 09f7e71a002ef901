/*
 * bench_develop.c: exact development plus SVG writing of a tangent
 * developable with 100,000 rulings (the target: under 0.2 s on one core).
 *
 * The edge of regression is samples/spiral.csv; the surface is developed
 * with -n 100000 (every ruling is a sample of the net) and written with its
 * outline to an SVG in a temporary directory.  Prints the best of 5 runs,
 * per phase.
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "unroll/allow.h"
#include "unroll/develop.h"
#include "unroll/io.h"
#include "unroll/nest.h"
#include "unroll/out.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void die(const ur_error *error)
{
    fprintf(stderr, "bench_develop: %s\n", error->message);
    exit(1);
}

int main(void)
{
    enum { RULINGS = 100000, RUNS = 5 };
    ur_vec3 *points;
    size_t count;
    bool closed;
    ur_error error;
    ur_machine machine;
    if (ur_curve_csv_read("samples/spiral.csv", &points, &count, &closed, &error) ||
        ur_machine_load("co2-60w", &machine, &error))
        die(&error);
    char directory[] = "/tmp/unroll-bench-XXXXXX";
    if (!mkdtemp(directory))
        return 1;
    char output[256];
    snprintf(output, sizeof output, "%s/net.svg", directory);
    double best_develop = 1e9, best_write = 1e9;
    size_t samples = 0;
    for (int run = 0; run < RUNS; run++) {
        ur_curve *curve;
        ur_ruled ruled;
        if (ur_curve_new_interpolating(points, count, closed, &curve, &error) ||
            ur_ruled_tangent(curve, 0, 20, &ruled, &error))
            die(&error);
        ur_develop_options options;
        ur_develop_options_default(&options);
        options.rulings = RULINGS;
        ur_net_list nets;
        double start = now();
        if (ur_develop(&ruled, &options, &nets, &error))
            die(&error);
        double developed = now();
        ur_piece *pieces = calloc(nets.count, sizeof *pieces);
        ur_allowance_options allowances = {false};
        for (size_t k = 0; k < nets.count; k++)
            if (ur_piece_from_net(&nets.nets[k], &allowances, &pieces[k], &error))
                die(&error);
        ur_layout_options sheet = {2000, 2000, 5, 0.5};
        ur_layout layout;
        ur_output_options svg = {"bench"};
        if (ur_layout_rows(pieces, nets.count, &sheet, &layout, &error) ||
            ur_write_svg(output, &layout, pieces, &machine, &svg, &error))
            die(&error);
        double written = now();
        best_develop = developed - start < best_develop ? developed - start : best_develop;
        best_write = written - developed < best_write ? written - developed : best_write;
        samples = nets.nets[0].outline_count;
        for (size_t k = 0; k < nets.count; k++)
            ur_piece_free(&pieces[k]);
        free(pieces);
        ur_layout_free(&layout);
        ur_net_list_free(&nets);
        ur_ruled_free(&ruled);
    }
    unlink(output);
    rmdir(directory);
    free(points);
    printf("tangent developable, %d rulings (%zu outline points): develop %.3f s, place and "
           "write SVG %.3f s, total %.3f s (target 0.2 s)\n",
           RULINGS, samples, best_develop, best_write, best_develop + best_write);
    return 0;
}
