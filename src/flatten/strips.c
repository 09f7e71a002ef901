/*
 * strips.c: flattening a surface in strips when one piece would strain too
 * much: a ruled surface cut along its rulings into strips of equal width in
 * u, a mesh cut by parallel planes into bands (mesh/bands.c), each strip
 * cut into disks and flattened by ur_flatten, and the search for the fewest
 * strips that stay within the allowed strain.
 */
#include "unroll/flatten.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "../base/c_locale.h"

/*
 * Triangulation of a ruled surface: the CLI flattens a whole one with 96
 * parts along and 24 across; strips share the 96 out, but each keeps at
 * least 8 so that a narrow one still bends smoothly.
 */
enum { WHOLE_ALONG = 96, LEAST_ALONG = 8, ACROSS = 24 };

/* Welding of a strip's mesh, times its size: a cone's apex, a closed surface's seam. */
#define WELD 1e-6

/* A ruling's ends lie within this times the strip's size of a vertex of its piece. */
#define SEAM_MATCH 1e-5

/* What a count of strips is made and flattened from. */
typedef struct strip_job {
    ur_ruled *ruled;      /* a ruled surface, or */
    const ur_mesh *mesh;  /* a mesh, cut across */
    ur_vec3 direction;    /* this unit direction */
    double low, high;     /* the mesh's extent along it */
    const ur_seam *seams; /* the user's seams on the mesh, cut in every band */
    size_t seam_count;
    const ur_flatten_options *options;
    const ur_strip_limits *limits; /* NULL: flatten every strip whatever its strain */
} strip_job;

/* The first piece that broke the limits, for the message. */
typedef struct strip_failure {
    bool failed;
    size_t band;
    double stretch, compression;
    bool flipped;
} strip_failure;

/* Frees what one piece owns (ur_mesh_pieces_free frees whole arrays). */
static void piece_free(ur_mesh_piece *piece)
{
    ur_mesh_free(&piece->mesh);
    free(piece->original);
    free(piece->source_triangles);
    memset(piece, 0, sizeof *piece);
}

void ur_strips_free(ur_strips *strips)
{
    if (!strips)
        return;
    for (size_t i = 0; i < strips->count; i++) {
        piece_free(&strips->strips[i].piece);
        ur_flat_piece_free(&strips->strips[i].flat);
    }
    free(strips->strips);
    memset(strips, 0, sizeof *strips);
}

static bool within(const ur_strip_limits *limits, const ur_flat_piece *flat)
{
    return !flat->flipped && flat->max_stretch <= limits->max_stretch &&
           flat->max_compression <= limits->max_compression;
}

/* Moves the piece and its layout to the end of the strips (zeroing them); grows the array. */
static ur_status append(ur_strips *strips, ur_mesh_piece *piece, ur_flat_piece *flat, size_t band,
                        double start, double end, ur_error *error)
{
    ur_strip *grown = realloc(strips->strips, (strips->count + 1) * sizeof *grown);
    if (!grown)
        return ur_error_out_of_memory(error);
    strips->strips = grown;
    ur_strip *strip = &grown[strips->count++];
    memset(strip, 0, sizeof *strip);
    strip->piece = *piece;
    strip->flat = *flat;
    strip->band = band;
    strip->start = start;
    strip->end = end;
    memset(piece, 0, sizeof *piece);
    memset(flat, 0, sizeof *flat);
    strips->max_stretch = fmax(strips->max_stretch, strip->flat.max_stretch);
    strips->max_compression = fmax(strips->max_compression, strip->flat.max_compression);
    strips->flipped = strips->flipped || strip->flat.flipped;
    return UR_OK;
}

/*
 * Flattens a piece of strip band and moves it, with its layout, into the
 * strips.  A piece out of the limits (when the job has limits) is the
 * failure: that count of strips does not fit, and the caller need flatten
 * no more of them.
 */
static ur_status flatten_piece(const strip_job *job, ur_mesh_piece *piece, size_t band,
                               double start, double end, ur_strips *strips, strip_failure *failure,
                               ur_error *error)
{
    ur_flat_piece flat;
    ur_status status = ur_flatten(&piece->mesh, job->options, &flat, error);
    if (status != UR_OK)
        return status;
    if (job->limits && !within(job->limits, &flat))
        *failure =
            (strip_failure){true, band, flat.max_stretch, flat.max_compression, flat.flipped};
    status = append(strips, piece, &flat, band, start, end, error);
    ur_flat_piece_free(&flat); /* zeroed when moved */
    return status;
}

/* ---- Ruled surfaces ------------------------------------------------------ */

/* The vertex of the mesh nearest to point, if within tolerance. */
static bool nearest_vertex(const ur_mesh *mesh, ur_vec3 point, double tolerance, size_t *vertex)
{
    double best = INFINITY;
    for (size_t v = 0; v < mesh->vertex_count; v++) {
        double distance = ur_vec3_distance(mesh->vertices[v], point);
        if (distance < best) {
            best = distance;
            *vertex = v;
        }
    }
    return best <= tolerance;
}

/* Adds the flat ruling at u to the strip's seams when both its ends are vertices of the piece. */
static void add_seam(ur_ruled *ruled, double u, ur_strip *strip)
{
    const ur_mesh *mesh = &strip->piece.mesh;
    ur_vec3 rails[4];
    ur_ruled_rails(ruled, u, rails);
    double tolerance = SEAM_MATCH * ur_mesh_size(mesh);
    size_t a, b;
    if (nearest_vertex(mesh, rails[0], tolerance, &a) &&
        nearest_vertex(mesh, rails[2], tolerance, &b))
        strip->seams[strip->seam_count++] = (ur_segment){strip->flat.flat[a], strip->flat.flat[b]};
}

/* The disks of the part of the surface in use: triangulated, cleaned, cut. */
static ur_status ruled_pieces(ur_ruled *ruled, size_t along, ur_mesh_piece **pieces, size_t *count,
                              ur_error *error)
{
    ur_mesh mesh;
    ur_status status = ur_mesh_from_ruled(ruled, along, ACROSS, &mesh, error);
    if (status != UR_OK)
        return status;
    status = ur_mesh_clean(&mesh, WELD * ur_mesh_size(&mesh), NULL, error);
    if (status == UR_OK)
        status = ur_mesh_pieces(&mesh, NULL, 0, pieces, count, error);
    ur_mesh_free(&mesh);
    return status;
}

/*
 * Strip band of count, u in [start, end] of a surface that is closed or
 * not: restricts the surface to it (the caller puts the restriction back),
 * flattens its pieces and gives them the rulings shared with the
 * neighbours as seams.
 */
static ur_status ruled_strip(const strip_job *job, size_t band, size_t count, bool closed,
                             double start, double end, ur_strips *strips, strip_failure *failure,
                             ur_error *error)
{
    ur_ruled_restrict(job->ruled, start, end);
    size_t along = (WHOLE_ALONG + count - 1) / count;
    ur_mesh_piece *pieces = NULL;
    size_t piece_count = 0, first = strips->count;
    ur_status status = ruled_pieces(job->ruled, along > LEAST_ALONG ? along : LEAST_ALONG, &pieces,
                                    &piece_count, error);
    for (size_t p = 0; status == UR_OK && !failure->failed && p < piece_count; p++)
        status = flatten_piece(job, &pieces[p], band, start, end, strips, failure, error);
    ur_mesh_pieces_free(pieces, piece_count); /* what was not moved */
    bool shared_start = count > 1 && (band > 0 || closed);
    bool shared_end = count > 1 && (band + 1 < count || closed);
    for (size_t i = first; status == UR_OK && i < strips->count; i++) {
        if (shared_start)
            add_seam(job->ruled, ur_ruled_start(job->ruled), &strips->strips[i]);
        if (shared_end)
            add_seam(job->ruled, ur_ruled_end(job->ruled), &strips->strips[i]);
    }
    return status;
}

/*
 * count strips of equal width in u over the part of the surface in use,
 * which is put back afterwards, also on failure, for the next count.
 */
static ur_status ruled_trial(const strip_job *job, size_t count, ur_strips *strips,
                             strip_failure *failure, ur_error *error)
{
    ur_ruled *ruled = job->ruled;
    bool restricted = ruled->restricted;
    double u_min = ruled->u_min, u_max = ruled->u_max;
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    bool closed = ur_ruled_is_closed(ruled); /* before restricting, which opens it */
    ur_status status = UR_OK;
    for (size_t band = 0; status == UR_OK && !failure->failed && band < count; band++) {
        double start = u0 + (u1 - u0) * (double)band / (double)count;
        double end = band + 1 == count ? u1 : u0 + (u1 - u0) * (double)(band + 1) / (double)count;
        status = ruled_strip(job, band, count, closed, start, end, strips, failure, error);
    }
    ruled->restricted = restricted;
    ruled->u_min = u_min;
    ruled->u_max = u_max;
    return status;
}

/* ---- Meshes -------------------------------------------------------------- */

/* Where band b of count lies along the direction. */
static void band_range(const strip_job *job, const double *planes, size_t count, size_t band,
                       double *start, double *end)
{
    *start = band > 0 ? planes[band - 1] : job->low;
    *end = band + 1 < count ? planes[band] : job->high;
}

/* Every vertex's neighbours along the banded mesh's edges (compressed rows). */
typedef struct neighbours {
    size_t *start; /* vertex v's neighbours are list[start[v] .. start[v + 1] - 1] */
    size_t *list;
} neighbours;

static void neighbours_free(neighbours *n)
{
    free(n->start);
    free(n->list);
}

static ur_status neighbours_build(const ur_mesh *mesh, neighbours *n, ur_error *error)
{
    size_t v_count = mesh->vertex_count, t_count = mesh->triangle_count;
    n->start = calloc(v_count + 1, sizeof *n->start);
    n->list = ur_alloc_array(6 * t_count + 1, sizeof *n->list, error);
    if (!n->start || !n->list) {
        neighbours_free(n);
        return ur_error_out_of_memory(error);
    }
    for (size_t t = 0; t < t_count; t++)
        for (int k = 0; k < 3; k++)
            n->start[mesh->triangles[t][k] + 1] += 2;
    for (size_t v = 0; v < v_count; v++)
        n->start[v + 1] += n->start[v];
    size_t *fill = ur_alloc_array(v_count + 1, sizeof *fill, error);
    if (!fill) {
        neighbours_free(n);
        return UR_ERROR_MEMORY;
    }
    memcpy(fill, n->start, (v_count + 1) * sizeof *fill);
    for (size_t t = 0; t < t_count; t++)
        for (int k = 0; k < 3; k++) {
            size_t a = mesh->triangles[t][k];
            n->list[fill[a]++] = mesh->triangles[t][(k + 1) % 3];
            n->list[fill[a]++] = mesh->triangles[t][(k + 2) % 3];
        }
    free(fill);
    return UR_OK;
}

/*
 * The next vertex on the way along the user's seam from `from` to b: b
 * itself when it is a neighbour, else the point where a plane cut the seam
 * edge (a new vertex of the banded mesh, on the segment, further along).
 */
static size_t seam_step(const ur_mesh *banded, const neighbours *n, size_t original_count, size_t a,
                        size_t b, size_t from)
{
    ur_vec3 pa = banded->vertices[a], pb = banded->vertices[b];
    ur_vec3 along = ur_vec3_sub(pb, pa);
    double length2 = ur_vec3_dot(along, along);
    double at = ur_vec3_dot(ur_vec3_sub(banded->vertices[from], pa), along) / length2;
    size_t best = SIZE_MAX;
    double best_at = INFINITY;
    for (size_t k = n->start[from]; k < n->start[from + 1]; k++) {
        size_t x = n->list[k];
        if (x == b)
            return b;
        if (x < original_count)
            continue;
        ur_vec3 offset = ur_vec3_sub(banded->vertices[x], pa);
        double t = ur_vec3_dot(offset, along) / length2;
        ur_vec3 off_line = ur_vec3_add_scaled(offset, along, -t);
        if (t > at && t < best_at && ur_vec3_dot(off_line, off_line) <= 1e-18 * length2) {
            best = x;
            best_at = t;
        }
    }
    return best;
}

/*
 * The user's seams on the banded mesh: its first original_count vertices
 * are the mesh's, with their numbers (ur_mesh_bands), and a seam edge that
 * a plane crosses is followed through the crossing points.
 */
static ur_status band_seams(const strip_job *job, const ur_mesh *banded, ur_seam **seams,
                            size_t *count, ur_error *error)
{
    *seams = NULL;
    *count = 0;
    if (job->seam_count == 0)
        return UR_OK;
    neighbours n = {0};
    ur_status status = neighbours_build(banded, &n, error);
    size_t capacity = 0;
    for (size_t s = 0; status == UR_OK && s < job->seam_count; s++) {
        size_t a = job->seams[s].a, b = job->seams[s].b, from = a;
        while (status == UR_OK && from != b) {
            size_t next = seam_step(banded, &n, job->mesh->vertex_count, a, b, from);
            if (next == SIZE_MAX) {
                status =
                    ur_error_set(error, UR_ERROR_INTERNAL,
                                 "seam %zu-%zu is lost where the strips are cut", a + 1, b + 1);
                break;
            }
            if (*count == capacity) {
                capacity = capacity ? 2 * capacity : 16;
                ur_seam *grown = realloc(*seams, capacity * sizeof *grown);
                if (!grown) {
                    status = ur_error_out_of_memory(error);
                    break;
                }
                *seams = grown;
            }
            (*seams)[(*count)++] = (ur_seam){from, next};
            from = next;
        }
    }
    neighbours_free(&n);
    if (status != UR_OK) {
        free(*seams);
        *seams = NULL;
        *count = 0;
    }
    return status;
}

/* Flattens the pieces of the banded mesh, which come band by band. */
static ur_status flatten_bands(const strip_job *job, const ur_mesh *banded, const double *planes,
                               size_t count, ur_strips *strips, strip_failure *failure,
                               ur_error *error)
{
    ur_mesh_piece *pieces = NULL;
    size_t piece_count = 0;
    ur_seam *seams;
    size_t seam_count;
    ur_status status = band_seams(job, banded, &seams, &seam_count, error);
    if (status == UR_OK)
        status = ur_mesh_pieces(banded, seams, seam_count, &pieces, &piece_count, error);
    free(seams);
    size_t groups = job->mesh->group_count > 0 ? job->mesh->group_count : 1;
    for (size_t p = 0; status == UR_OK && !failure->failed && p < piece_count; p++) {
        size_t band = pieces[p].mesh.groups[0] / groups; /* see ur_mesh_bands */
        double start, end;
        band_range(job, planes, count, band, &start, &end);
        status = flatten_piece(job, &pieces[p], band, start, end, strips, failure, error);
    }
    ur_mesh_pieces_free(pieces, piece_count); /* what was not moved */
    return status;
}

static ur_status mesh_trial(const strip_job *job, size_t count, ur_strips *strips,
                            strip_failure *failure, ur_error *error)
{
    double *planes = ur_alloc_array(count - 1, sizeof *planes, error);
    if (!planes)
        return UR_ERROR_MEMORY;
    ur_mesh banded;
    ur_status status = ur_mesh_band_planes(job->mesh, job->direction, count, planes, error);
    if (status == UR_OK)
        status = ur_mesh_bands(job->mesh, job->direction, planes, count, &banded, error);
    if (status == UR_OK) {
        status = flatten_bands(job, &banded, planes, count, strips, failure, error);
        ur_mesh_free(&banded);
    }
    free(planes);
    return status;
}

/* ---- The search ---------------------------------------------------------- */

/* Cuts the surface into count strips and flattens them (until one is out of the limits). */
static ur_status trial(const strip_job *job, size_t count, ur_strips *strips,
                       strip_failure *failure, ur_error *error)
{
    memset(strips, 0, sizeof *strips);
    memset(failure, 0, sizeof *failure);
    strips->bands = count;
    strips->tried = 1;
    if (job->mesh)
        strips->direction = job->direction;
    ur_status status = job->mesh ? mesh_trial(job, count, strips, failure, error)
                                 : ruled_trial(job, count, strips, failure, error);
    if (status != UR_OK)
        ur_strips_free(strips);
    return status;
}

static ur_status refuse(const ur_strip_limits *limits, const strip_failure *failure,
                        ur_error *error)
{
    size_t n = limits->max_strips;
    char why[160];
    if (failure->flipped)
        c_snprintf(why, sizeof why, "strip %zu comes out with a triangle turned over",
                   failure->band + 1);
    else
        c_snprintf(why, sizeof why, "strip %zu still stretches %.3g %% and compresses %.3g %%",
                   failure->band + 1, 100 * failure->stretch, 100 * failure->compression);
    return ur_error_set(error, UR_ERROR_INPUT,
                        "the surface needs more than %zu strip%s to stay within %g %% stretch "
                        "and %g %% compression: with %zu, %s",
                        n, n == 1 ? "" : "s", 100 * limits->max_stretch,
                        100 * limits->max_compression, n, why);
}

/*
 * Doubles the count until the strips fit, then bisects between the largest
 * count known not to fit and the smallest known to fit; keeps the strips of
 * the smallest.  Assumes that a count that fits has no larger count that
 * does not (the strain falls as strips narrow; see flatten.h).
 */
static ur_status search(const strip_job *job, ur_strips *best, ur_error *error)
{
    const ur_strip_limits *limits = job->limits;
    size_t too_few = 0, count = 1, tried = 0; /* too_few: 0 until a count fails */
    strip_failure failure;
    for (;;) {
        ur_status status = trial(job, count, best, &failure, error);
        if (status != UR_OK)
            return status;
        tried++;
        if (!failure.failed)
            break;
        ur_strips_free(best);
        if (count >= limits->max_strips)
            return refuse(limits, &failure, error);
        too_few = count;
        count = count > limits->max_strips / 2 ? limits->max_strips : 2 * count;
    }
    while (count - too_few > 1) {
        size_t middle = too_few + (count - too_few) / 2;
        ur_strips candidate;
        ur_status status = trial(job, middle, &candidate, &failure, error);
        if (status != UR_OK) {
            ur_strips_free(best);
            return status;
        }
        tried++;
        if (failure.failed) {
            ur_strips_free(&candidate);
            too_few = middle;
        } else {
            ur_strips_free(best);
            *best = candidate;
            count = middle;
        }
    }
    best->tried = tried;
    return UR_OK;
}

static ur_status check_limits(const ur_strip_limits *limits, ur_error *error)
{
    if (!limits)
        return ur_error_set(error, UR_ERROR_INPUT, "no strain limits for the strips");
    if (!(limits->max_stretch >= 0) || !(limits->max_compression >= 0))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "the largest stretch and compression of a strip must be numbers >= "
                            "0, not %g and %g",
                            limits->max_stretch, limits->max_compression);
    if (limits->max_strips == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "at most 0 strips: there must be 1 or more");
    return UR_OK;
}

static ur_status check_count(size_t count, ur_error *error)
{
    return count > 0 ? UR_OK
                     : ur_error_set(error, UR_ERROR_INPUT,
                                    "a surface is cut into 1 strip or more, not 0");
}

/* A mesh job: the unit direction (chosen when NULL) and the mesh's extent along it. */
static ur_status mesh_job(const ur_mesh *mesh, const ur_vec3 *direction, strip_job *job,
                          ur_error *error)
{
    if (mesh->triangle_count == 0)
        return ur_error_set(error, UR_ERROR_INPUT, "the mesh has no triangles");
    ur_vec3 d;
    ur_status status = direction ? UR_OK : ur_mesh_bending_direction(mesh, &d, error);
    if (status != UR_OK)
        return status;
    if (direction) {
        double length = ur_vec3_length(*direction);
        if (!(length > 0) || !isfinite(length))
            return ur_error_set(error, UR_ERROR_INPUT,
                                "the direction across the strips must have a finite, non-zero "
                                "length");
        d = ur_vec3_scale(*direction, 1.0 / length);
    }
    job->mesh = mesh;
    job->direction = d;
    job->low = INFINITY;
    job->high = -INFINITY;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            double s = ur_vec3_dot(mesh->vertices[mesh->triangles[t][k]], d);
            job->low = fmin(job->low, s);
            job->high = fmax(job->high, s);
        }
    return UR_OK;
}

ur_status ur_flatten_strips_ruled(ur_ruled *ruled, const ur_strip_limits *limits,
                                  const ur_flatten_options *options, ur_strips *strips,
                                  ur_error *error)
{
    memset(strips, 0, sizeof *strips);
    ur_status status = check_limits(limits, error);
    if (status != UR_OK)
        return status;
    strip_job job = {.ruled = ruled, .options = options, .limits = limits};
    return search(&job, strips, error);
}

ur_status ur_strips_of_ruled(ur_ruled *ruled, size_t count, const ur_flatten_options *options,
                             ur_strips *strips, ur_error *error)
{
    memset(strips, 0, sizeof *strips);
    ur_status status = check_count(count, error);
    if (status != UR_OK)
        return status;
    strip_job job = {.ruled = ruled, .options = options};
    strip_failure failure;
    return trial(&job, count, strips, &failure, error);
}

ur_status ur_flatten_strips_mesh(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                                 const ur_vec3 *direction, const ur_strip_limits *limits,
                                 const ur_flatten_options *options, ur_strips *strips,
                                 ur_error *error)
{
    memset(strips, 0, sizeof *strips);
    strip_job job = {
        .seams = seams, .seam_count = seam_count, .options = options, .limits = limits};
    ur_status status = check_limits(limits, error);
    if (status == UR_OK)
        status = mesh_job(mesh, direction, &job, error);
    return status == UR_OK ? search(&job, strips, error) : status;
}

ur_status ur_strips_of_mesh(const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                            ur_vec3 direction, size_t count, const ur_flatten_options *options,
                            ur_strips *strips, ur_error *error)
{
    memset(strips, 0, sizeof *strips);
    strip_job job = {.seams = seams, .seam_count = seam_count, .options = options};
    strip_failure failure;
    ur_status status = check_count(count, error);
    if (status == UR_OK)
        status = mesh_job(mesh, &direction, &job, error);
    return status == UR_OK ? trial(&job, count, strips, &failure, error) : status;
}
