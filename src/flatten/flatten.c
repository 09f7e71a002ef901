/*
 * flatten.c: ur_flatten and its options: check the piece, lay it out by
 * LSCM, improve the layout by ARAP, and measure the strain of the result.
 */
#include "flatten_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *const method_names[] = {[UR_FLATTEN_ARAP] = "arap", [UR_FLATTEN_LSCM] = "lscm"};

#define METHOD_COUNT (sizeof method_names / sizeof method_names[0])

const char *ur_flatten_method_name(ur_flatten_method method)
{
    return (size_t)method < METHOD_COUNT ? method_names[method] : "unknown";
}

int ur_flatten_method_from_name(const char *name)
{
    for (size_t m = 0; name && m < METHOD_COUNT; m++)
        if (strcmp(name, method_names[m]) == 0)
            return (int)m;
    return -1;
}

void ur_flatten_options_default(ur_flatten_options *options)
{
    options->method = UR_FLATTEN_ARAP;
    options->iterations = 100;
    options->tolerance = 1e-9;
    options->progress = NULL;
    options->progress_context = NULL;
    options->context = NULL;
}

/*
 * bench_flatten measures about 1.3 kB per triangle at the peak of ARAP (127
 * MB for 100,352 triangles, growing linearly); the pipeline around it
 * (pieces, nets, the strain shading, the writers) keeps copies, so allow
 * 2 kB, and 32 MB for the program itself.
 */
size_t ur_flatten_memory_estimate(size_t triangle_count)
{
    const size_t per_triangle = 2048, base = (size_t)32 << 20;
    if (triangle_count > (SIZE_MAX - base) / per_triangle)
        return SIZE_MAX;
    return base + per_triangle * triangle_count;
}

static ur_status check_options(const ur_flatten_options *options, ur_error *error)
{
    if ((size_t)options->method >= METHOD_COUNT)
        return ur_error_set(error, UR_ERROR_INPUT, "unknown flattening method %d",
                            (int)options->method);
    if (!(options->tolerance >= 0) || !isfinite(options->tolerance))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the flattening tolerance must be a number >= 0, not %g",
                            options->tolerance);
    return UR_OK;
}

void ur_flat_piece_free(ur_flat_piece *flat)
{
    if (!flat)
        return;
    free(flat->flat);
    free(flat->strain);
    memset(flat, 0, sizeof *flat);
}

/* Twice the signed area of flat triangle t: > 0 when it keeps its 3D orientation. */
static double twice_flat_area(const ur_mesh *mesh, const ur_vec2 *layout, size_t t)
{
    const size_t *c = mesh->triangles[t];
    return ur_vec2_cross(ur_vec2_sub(layout[c[1]], layout[c[0]]),
                         ur_vec2_sub(layout[c[2]], layout[c[0]]));
}

/* Fills everything but flat->flat (already there) and iterations. */
static ur_status measure(const ur_mesh *mesh, const flat_frame *frames, ur_flat_piece *flat,
                         ur_error *error)
{
    flat->strain = ur_alloc_array(mesh->triangle_count, sizeof *flat->strain, error);
    if (!flat->strain)
        return UR_ERROR_MEMORY;
    flat->vertex_count = mesh->vertex_count;
    flat->triangle_count = mesh->triangle_count;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        ur_strain s = flat_strain(flat_triangle_jacobian(mesh, frames, flat->flat, t));
        double twice = twice_flat_area(mesh, flat->flat, t);
        flat->strain[t] = s;
        flat->area_3d += frames[t].area;
        flat->flat_area += 0.5 * twice;
        flat->flipped = flat->flipped || twice < 0;
        flat->max_stretch = fmax(flat->max_stretch, s.sigma1 - 1);
        flat->max_compression = fmax(flat->max_compression, 1 - s.sigma2);
    }
    flat->coverage = flat->flat_area / flat->area_3d;
    return UR_OK;
}

/* Whether some triangle of the layout has no area or is turned over. */
static bool any_turned(const ur_mesh *mesh, const ur_vec2 *layout)
{
    for (size_t t = 0; t < mesh->triangle_count; t++)
        if (!(twice_flat_area(mesh, layout, t) > 0))
            return true;
    return false;
}

/*
 * A first layout with no triangle turned over: LSCM's, or where it turns
 * one over (a piece curved far from any flat shape), Tutte's embedding.
 * A piece with holes has no Tutte embedding here and keeps LSCM's; *tutte
 * says which was taken.
 */
static ur_status first_layout(const ur_mesh *mesh, const flat_frame *frames,
                              const flat_topology *topology, ur_vec2 *layout, bool *tutte,
                              ur_error *error)
{
    *tutte = false;
    ur_status status = flat_lscm(mesh, frames, topology, layout, error);
    if (status == UR_ERROR_INTERNAL || (!status && any_turned(mesh, layout))) {
        ur_error ignored;
        if (flat_tutte(mesh, frames, topology, layout, &ignored) == UR_OK) {
            *tutte = true;
            return UR_OK;
        }
    }
    return status;
}

/*
 * Lays the piece out with its frames and topology: LSCM, then ARAP if
 * asked, or always when LSCM turned a triangle over and Tutte's layout
 * was taken instead (it keeps no lengths).
 */
static ur_status lay_out(const ur_mesh *mesh, const flat_frame *frames,
                         const flat_topology *topology, const ur_flatten_options *options,
                         ur_flat_piece *flat, ur_error *error)
{
    flat->flat = ur_alloc_array(mesh->vertex_count, sizeof *flat->flat, error);
    if (!flat->flat)
        return UR_ERROR_MEMORY;
    bool tutte = false;
    ur_status status = first_layout(mesh, frames, topology, flat->flat, &tutte, error);
    if (!status && (options->method == UR_FLATTEN_ARAP || tutte)) {
        ur_flatten_options arap = *options;
        if (arap.iterations == 0)
            arap.iterations = 1;
        status = flat_arap(mesh, frames, topology, topology->pins[0], &arap, flat->flat,
                           &flat->iterations, error);
    }
    return status ? status : measure(mesh, frames, flat, error);
}

ur_status ur_flatten(const ur_mesh *piece, const ur_flatten_options *options, ur_flat_piece *flat,
                     ur_error *error)
{
    memset(flat, 0, sizeof *flat);
    ur_flatten_options defaults;
    ur_flatten_options_default(&defaults);
    if (!options)
        options = &defaults;
    flat_frame *frames = NULL;
    flat_topology topology;
    memset(&topology, 0, sizeof topology);
    ur_status status = check_options(options, error);
    if (!status)
        status = flat_frames(piece, &frames, error);
    if (!status)
        status = flat_topology_of(piece, &topology, error);
    if (!status)
        status = lay_out(piece, frames, &topology, options, flat, error);
    flat_topology_free(&topology);
    free(frames);
    if (status)
        ur_flat_piece_free(flat);
    return status;
}

ur_status ur_flat_piece_measure(const ur_mesh *piece, const ur_vec2 *layout, ur_flat_piece *flat,
                                ur_error *error)
{
    memset(flat, 0, sizeof *flat);
    if (!layout)
        return ur_error_set(error, UR_ERROR_INPUT, "no layout to measure");
    flat_frame *frames = NULL;
    ur_status status = flat_frames(piece, &frames, error);
    if (status)
        return status;
    flat->flat = ur_alloc_array(piece->vertex_count, sizeof *flat->flat, error);
    if (!flat->flat)
        status = UR_ERROR_MEMORY;
    if (!status) {
        memcpy(flat->flat, layout, piece->vertex_count * sizeof *flat->flat);
        status = measure(piece, frames, flat, error);
    }
    free(frames);
    if (status)
        ur_flat_piece_free(flat);
    return status;
}

ur_status ur_flatten_energy(const ur_mesh *piece, const ur_vec2 *layout, double *energy,
                            ur_error *error)
{
    if (!layout)
        return ur_error_set(error, UR_ERROR_INPUT, "no layout to measure");
    flat_frame *frames = NULL;
    ur_status status = flat_frames(piece, &frames, error);
    if (status)
        return status;
    *energy = flat_energy(piece, frames, layout);
    free(frames);
    return UR_OK;
}

/* The factor that brings sigma in [low, high] within the limits, nearest 1. */
static double fitting_scale(double low, double high, const ur_strip_limits *limits)
{
    double stretch = limits->max_stretch, compression = limits->max_compression;
    double smallest = (1 - compression) / low, largest = (1 + stretch) / high;
    if (smallest <= largest)
        return fmin(fmax(1.0, smallest), largest);
    /* Over both ways: s high - 1 and 1 - s low the same share of their limits. */
    if (stretch + compression > 0)
        return (stretch + compression) / (compression * high + stretch * low);
    return 2 / (low + high);
}

void ur_flat_piece_fit_limits(ur_flat_piece *flat, const ur_strip_limits *limits)
{
    if (!flat->strain || flat->triangle_count == 0)
        return;
    double low = INFINITY, high = 0;
    for (size_t t = 0; t < flat->triangle_count; t++) {
        low = fmin(low, flat->strain[t].sigma2);
        high = fmax(high, flat->strain[t].sigma1);
    }
    if (!(low > 0) || !isfinite(high))
        return;
    double scale = fitting_scale(low, high, limits);
    if (scale == 1.0)
        return;
    for (size_t v = 0; v < flat->vertex_count; v++)
        flat->flat[v] = ur_vec2_scale(flat->flat[v], scale);
    flat->max_stretch = flat->max_compression = 0;
    for (size_t t = 0; t < flat->triangle_count; t++) {
        flat->strain[t].sigma1 *= scale;
        flat->strain[t].sigma2 *= scale;
        flat->max_stretch = fmax(flat->max_stretch, flat->strain[t].sigma1 - 1);
        flat->max_compression = fmax(flat->max_compression, 1 - flat->strain[t].sigma2);
    }
    flat->flat_area *= scale * scale;
    flat->coverage = flat->flat_area / flat->area_3d;
}
