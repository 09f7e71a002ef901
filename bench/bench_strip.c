/*
 * bench_strip.c: a developable strip of 10,000 rulings between two
 * 10,000-point rails, paired, analysed and developed (the target: under 1 s
 * in all on one core).
 *
 * Both rails lie on the tangent developable of a helix (radius 30 mm, rise
 * 10 mm per radian): rail 1 at distance 5 along the tangents, rail 2 at
 * 25 + 4 sin(3 t) and running a little past rail 1 at both ends, so that the
 * strip between them is that developable everywhere but its rulings meet
 * rail 2 at unevenly spaced points.  The phases are those of the command:
 * the rails and their pairing (ur_ruled_strip), ur_analyze with 10,000
 * rulings, and ur_ruled_area plus the exact ur_develop with 10,000 rulings
 * at the default tolerance.  Each run checks that the result is sane (no
 * gaps, developable, net area equal to the 3D area within 1e-4) so that the
 * bench cannot time a failure.  Prints the best of 3 runs, per phase.
 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "unroll/analyze.h"
#include "unroll/develop.h"

enum { POINTS = 10000, RULINGS = 10000, RUNS = 3 };

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void die(const char *what, const ur_error *error)
{
    fprintf(stderr, "bench_strip: %s: %s\n", what, error ? error->message : "wrong result");
    exit(1);
}

/* The point at distance `along` on the helix's tangent at t. */
static ur_vec3 on_tangent(double t, double along)
{
    double r = 30, c = 10, s = sqrt(r * r + c * c);
    ur_vec3 point = ur_vec3_make(r * cos(t), r * sin(t), c * t);
    ur_vec3 tangent = ur_vec3_make(-r * sin(t) / s, r * cos(t) / s, c / s);
    return ur_vec3_add_scaled(point, tangent, along);
}

static void make_rails(ur_vec3 *near, ur_vec3 *far)
{
    for (int i = 0; i < POINTS; i++) {
        double t = 2.0 * i / (POINTS - 1), t2 = -0.2 + 2.4 * i / (POINTS - 1);
        near[i] = on_tangent(t, 5);
        far[i] = on_tangent(t2, 25 + 4 * sin(3 * t2));
    }
}

static void pair(const ur_vec3 *near, const ur_vec3 *far, ur_ruled *ruled)
{
    ur_curve *rail1, *rail2;
    ur_error error;
    if (ur_curve_new_interpolating(near, POINTS, false, &rail1, &error) ||
        ur_curve_new_interpolating(far, POINTS, false, &rail2, &error))
        die("rails", &error);
    if (ur_ruled_strip(rail1, rail2, ruled, &error))
        die("strip", &error);
    const ur_interval *gaps;
    if (ur_ruled_gaps(ruled, &gaps) != 0)
        die("strip has gaps", NULL);
}

static void analyze(ur_ruled *ruled)
{
    ur_analysis_options options;
    ur_analysis_options_default(&options);
    options.rulings = RULINGS;
    ur_analysis analysis;
    ur_error error;
    if (ur_analyze(ruled, &options, &analysis, &error))
        die("analyze", &error);
    if (!analysis.developable)
        die("analysis finds the strip not developable", NULL);
    ur_analysis_free(&analysis);
}

/* Develops the strip; returns the 3D area and the nets' total flat area. */
static size_t develop(ur_ruled *ruled, double *area, double *flat)
{
    ur_develop_options options;
    ur_develop_options_default(&options);
    options.rulings = RULINGS;
    ur_net_list nets;
    ur_error error;
    if (ur_ruled_area(ruled, ur_ruled_start(ruled), ur_ruled_end(ruled), area, &error))
        die("area", &error);
    if (ur_develop(ruled, &options, &nets, &error))
        die("develop", &error);
    *flat = 0.0;
    for (size_t k = 0; k < nets.count; k++)
        *flat += nets.nets[k].flat_area;
    size_t pieces = nets.count;
    ur_net_list_free(&nets);
    if (!(fabs(*flat - *area) <= 1e-4 * *area))
        die("net area differs from the 3D area", NULL);
    return pieces;
}

int main(void)
{
    ur_vec3 *near = malloc(POINTS * sizeof *near), *far = malloc(POINTS * sizeof *far);
    if (!near || !far)
        return 1;
    make_rails(near, far);
    double best[3] = {1e9, 1e9, 1e9}, best_total = 1e9, area = 0.0, flat = 0.0;
    size_t pieces = 0;
    for (int run = 0; run < RUNS; run++) {
        ur_ruled ruled;
        double times[4];
        times[0] = now();
        pair(near, far, &ruled);
        times[1] = now();
        analyze(&ruled);
        times[2] = now();
        pieces = develop(&ruled, &area, &flat);
        times[3] = now();
        ur_ruled_free(&ruled);
        for (int k = 0; k < 3; k++)
            best[k] = fmin(best[k], times[k + 1] - times[k]);
        best_total = fmin(best_total, times[3] - times[0]);
    }
    free(near);
    free(far);
    printf("strip of %d rulings between two %d-point rails: pairing %.3f s, analysis %.3f s, "
           "area and net %.3f s, total %.3f s (target 1 s); %zu piece(s), surface %.2f mm2, "
           "net %.2f mm2 (relative difference %.1e)\n",
           RULINGS, POINTS, best[0], best[1], best[2], best_total, pieces, area, flat,
           (flat - area) / area);
    return 0;
}
