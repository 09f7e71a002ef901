/*
 * meshes.c: surfaces that are flattened rather than developed: a mesh from
 * a file ('unroll mesh FILE'), and a ruled surface that is not developable
 * (hypar, ruled, a naturally paired strip), triangulated first.  Each piece
 * (a topological disk) is laid flat with LSCM and ARAP and becomes a net
 * that carries its strain; a mesh from a file is by default first cut into
 * charts that each lie flat within the material's strain (ur_flatten_charts).
 */
#include "stages.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>
#include <unistd.h>

#include "unroll/flatten.h"
#include "unroll/io.h"
#include "unroll/nest.h"

/* Triangulation of a ruled surface for flattening: rulings along, parts across. */
enum { RULED_ALONG = 96, RULED_ACROSS = 24 };

static ur_status fail(const job_run *run, const ur_error *error)
{
    return job_fail_from(run, error);
}

double job_joint_reach(const ur_material *material)
{
    return (material->joint == UR_JOINT_LAP ? material->lap_width : material->tab_depth) +
           material->thickness;
}

/*
 * The room a flattened piece may take on a sheet: its joints stand out all
 * round it, so its width keeps a joint's reach on each side, as its length
 * does already (job_fit_room).  Without it a piece cut to fit came out too
 * wide once its tabs were on (Blender's torus in 3 mm plywood at 10 x:
 * a 611 x 442 mm net, 620 x 451 mm with tabs, for a 600 x 400 mm sheet).
 */
static job_room room_for_joints(const job_run *run, const job_room *room,
                                const ur_material *material)
{
    job_room inner = *room;
    double joint = job_joint_reach(material);
    if (job_makes_joints(run) && inner.width - 2 * joint > 0)
        inner.width -= 2 * joint;
    return inner;
}

/* Long flattening reports its progress, and its end, to the progress callback. */
static void report_flattening(void *context, size_t iteration, double energy)
{
    ur_job_progress progress = {
        .kind = UR_JOB_FLATTENING, .iteration = iteration, .energy = energy};
    job_progress(context, &progress);
}

void job_end_flattening(const job_run *run)
{
    ur_job_progress done = {.kind = UR_JOB_FLATTENING_DONE};
    job_progress(run, &done);
}

static void flatten_options(const job_run *run, ur_flatten_options *options)
{
    ur_flatten_options_default(options);
    options->context = run->job.context;
    if (job_shows_progress(run)) {
        options->progress = report_flattening;
        options->progress_context = (void *)run;
    }
    if (run->job.flatten >= 0)
        options->method = (ur_flatten_method)run->job.flatten;
    if (run->job.iterations > 0)
        options->iterations = run->job.iterations;
}

/* Appends a net to the list (taking its arrays). */
static ur_status append_net(const job_run *run, ur_net_list *nets, ur_net *net)
{
    ur_error error;
    ur_net *grown = realloc(nets->nets, (nets->count + 1) * sizeof *grown);
    if (!grown) {
        ur_net_free(net);
        ur_error_out_of_memory(&error);
        return fail(run, &error);
    }
    nets->nets = grown;
    nets->nets[nets->count++] = *net;
    return UR_OK;
}

/*
 * Cuts of a piece whose flat outline crosses itself or is too long, one
 * inside another.  Each cut halves or better, and a piece much larger than
 * the sheet takes many: samples/head.obj at 10 x (a metre across) as one
 * chart on A3 needed 7 deep, 101 pieces; at 6 it stopped with a piece
 * that fitted no sheet.
 */
enum { MOST_SPLITS = 12 };

/*
 * How pieces are flattened: the job, the flattening's options, the room on
 * a sheet, and the strain every layout is scaled into where it can be.
 */
typedef struct flattening {
    const job_run *run;
    ur_flatten_options options;
    job_room room;                 /* 0 x 0: pieces are not cut to fit */
    const ur_strip_limits *limits; /* NULL: layouts are kept at the 3D area */
} flattening;

static ur_status flatten_piece(const flattening *f, const ur_mesh *piece, size_t depth,
                               ur_net_list *nets, double *area);

/*
 * A piece cut into parts along its length, each flattened: a flat outline
 * that crosses itself cannot be cut (2 parts), nor can one longer than any
 * sheet.  With a field (a value at each vertex), straight across its
 * levels (ur_mesh_split_by); without, across the distance along the
 * surface from one end (ur_mesh_split_along), which halves a ribbon that
 * winds round.
 */
static ur_status split_piece(const flattening *f, const ur_mesh *piece, const double *field,
                             size_t parts, size_t depth, ur_net_list *nets, double *area)
{
    ur_error error;
    ur_mesh split;
    ur_mesh_piece *pieces = NULL;
    size_t piece_count = 0;
    ur_status cut = field ? ur_mesh_split_by(piece, field, parts, &split, &error)
                          : ur_mesh_split_along(piece, parts, &split, &error);
    if (cut != UR_OK)
        return fail(f->run, &error);
    ur_status code = ur_mesh_pieces(&split, NULL, 0, &pieces, &piece_count, &error) == UR_OK
                         ? 0
                         : fail(f->run, &error);
    for (size_t k = 0; !code && k < piece_count; k++)
        code = flatten_piece(f, &pieces[k].mesh, depth + 1, nets, area);
    ur_mesh_pieces_free(pieces, piece_count);
    ur_mesh_free(&split);
    return code;
}

/* The net's level size, and whether it fits the room, level or turned as nesting turns it. */
static bool fits_room(const flattening *f, const ur_net *net, double *length, double *width)
{
    ur_error error;
    if (ur_outline_level_size(net->outline, net->outline_count, length, width, &error) != UR_OK)
        return true; /* nesting will say */
    if (*length <= f->room.length && *width <= f->room.width)
        return true;
    bool fits;
    double angle;
    if (ur_outline_fit_turn(net->outline, net->outline_count, f->room.length, f->room.width, &fits,
                            &angle, &error) != UR_OK)
        return true;
    return fits;
}

/*
 * Each vertex's position along the longer side of the net's smallest
 * enclosing rectangle: cut at its levels, a flat piece too long for the
 * sheet comes apart straight across (a flat square in rectangles, where
 * the distance along the surface from a corner cut it on the diagonal).
 */
static ur_status lengthwise_field(const job_run *run, const ur_flat_piece *flat, const ur_net *net,
                                  double **field)
{
    ur_error error;
    *field = ur_alloc_array(flat->vertex_count ? flat->vertex_count : 1, sizeof **field, &error);
    if (!*field)
        return fail(run, &error);
    double angle = ur_outline_level_angle(net->outline, net->outline_count);
    ur_transform2 turn = ur_transform2_make(angle, ur_vec2_make(0, 0));
    ur_box box = ur_box_empty();
    for (size_t k = 0; k < net->outline_count; k++)
        ur_box_add(&box, ur_transform2_apply(turn, net->outline[k]));
    bool along_x = ur_box_width(box) >= ur_box_height(box);
    for (size_t v = 0; v < flat->vertex_count; v++) {
        ur_vec2 p = ur_transform2_apply(turn, flat->flat[v]);
        (*field)[v] = along_x ? p.x : p.y;
    }
    return UR_OK;
}

/*
 * One way of cutting a piece into parts: into trial, with the area of
 * the parts' smallest enclosing rectangles (what nesting has to place),
 * and whether every part fits the room; parts that fall apart into more
 * pieces than asked (a C-shaped piece cut straight across) do not.
 */
typedef struct split_trial {
    ur_net_list nets;
    double area, box_area;
    bool fits;
} split_trial;

static ur_status try_split(const flattening *f, const ur_mesh *piece, const double *field,
                           size_t parts, size_t depth, split_trial *trial)
{
    flattening no_fit = *f; /* the trials halve only outlines that cross themselves */
    no_fit.room = (job_room){0, 0};
    *trial = (split_trial){{NULL, 0}, 0, 0, false};
    ur_status code = split_piece(&no_fit, piece, field, parts, depth, &trial->nets, &trial->area);
    trial->fits = !code && (!field || trial->nets.count == parts);
    for (size_t k = 0; trial->fits && k < trial->nets.count; k++) {
        double length, width;
        trial->fits = fits_room(f, &trial->nets.nets[k], &length, &width);
        trial->box_area += length * width;
    }
    return code;
}

/* Moves the trial's nets to the list. */
static ur_status take_trial(const job_run *run, split_trial *trial, ur_net_list *nets, double *area)
{
    ur_status code = 0;
    for (size_t k = 0; !code && k < trial->nets.count; k++) {
        code = append_net(run, nets, &trial->nets.nets[k]);
        trial->nets.nets[k] = (ur_net){0};
    }
    *area += trial->area;
    return code;
}

/*
 * A flat piece longer than the room, cut into the fewest parts along its
 * length that each fit: first as many as its length asks, then one more
 * at a time (the cut follows the mesh's edges, so parts come out a little
 * longer than an even share); then halving (along the surface) whatever
 * still does not fit.  Each count is cut both straight across (field) and
 * along the surface, and the parts whose enclosing rectangles take less
 * area are kept: a flat piece comes out in rectangles (Blender's grid at
 * 500 x 500 mm in two, on 2 sheets of 600 x 400 mm, where the distance
 * from a corner cut it on the diagonal into 4, on 4 sheets).
 */
static ur_status split_to_fit(const flattening *f, const ur_mesh *piece, const double *field,
                              double length, double width, size_t depth, ur_net_list *nets,
                              double *area)
{
    size_t first = (size_t)fmax(2, ceil(length / f->room.length));
    for (size_t parts = first; parts < first + 3; parts++) {
        split_trial across, along;
        ur_status code = try_split(f, piece, field, parts, depth, &across);
        if (code == UR_ERROR_INPUT) /* a part the straight cut left unflattenable */
            code = 0;
        if (!code)
            code = try_split(f, piece, NULL, parts, depth, &along);
        else
            along = (split_trial){{NULL, 0}, 0, 0, false};
        split_trial *best = across.fits ? &across : NULL;
        if (along.fits && (!best || along.box_area < best->box_area))
            best = &along;
        if (!code && best)
            code = take_trial(f->run, best, nets, area);
        ur_net_list_free(&across.nets);
        ur_net_list_free(&along.nets);
        if (code)
            return code;
        if (!best)
            continue;
        if (!f->run->job.quiet)
            job_note_about(f->run, "no-split",
                           "%s: a piece %.0f x %.0f mm does not fit the %.0f x %.0f mm a "
                           "sheet leaves it: cut into %zu along its length (no-split "
                           "refuses instead)",
                           f->run->job.command, length, width, f->room.length, f->room.width,
                           parts);
        return UR_OK;
    }
    return split_piece(f, piece, NULL, 2, depth, nets, area);
}

/*
 * A piece laid flat as a net, or when its outline crosses itself (or a
 * triangle is turned over, which only a piece with holes can keep) or it
 * does not fit the room, cut into parts that are each flattened again.
 */
static ur_status place_flat(const flattening *f, const ur_mesh *piece, const ur_flat_piece *flat,
                            size_t depth, ur_net_list *nets, double *area)
{
    ur_net net;
    ur_error error;
    if (ur_net_from_flat(piece, flat, "", &net, &error) != UR_OK)
        return fail(f->run, &error);
    if ((flat->flipped || !ur_outline_is_simple(net.outline, net.outline_count)) &&
        depth < MOST_SPLITS) {
        ur_net_free(&net);
        return split_piece(f, piece, NULL, 2, depth, nets, area);
    }
    double length, width;
    if (f->run->job.develop.split && f->room.length > 0 && depth < MOST_SPLITS &&
        !fits_room(f, &net, &length, &width)) {
        double *field = NULL;
        ur_status code = lengthwise_field(f->run, flat, &net, &field);
        ur_net_free(&net);
        if (!code)
            code = split_to_fit(f, piece, field, length, width, depth, nets, area);
        free(field);
        return code;
    }
    *area += net.area_3d;
    return append_net(f->run, nets, &net);
}

static ur_status flatten_piece(const flattening *f, const ur_mesh *piece, size_t depth,
                               ur_net_list *nets, double *area)
{
    ur_flat_piece flat;
    ur_error error;
    if (ur_flatten(piece, &f->options, &flat, &error) != UR_OK)
        return fail(f->run, &error);
    if (f->limits)
        ur_flat_piece_fit_limits(&flat, f->limits);
    ur_status code = place_flat(f, piece, &flat, depth, nets, area);
    ur_flat_piece_free(&flat);
    return code;
}

/* Names the nets P1, P2, ... */
static void name_nets(ur_net_list *nets)
{
    for (size_t k = 0; k < nets->count; k++)
        c_snprintf(nets->nets[k].name, sizeof nets->nets[k].name, "P%zu", k + 1);
}

/* Flattens every piece (halving any whose outline crosses itself); nets P1, P2, ... */
static ur_status flatten_pieces(const job_run *run, const job_room *room,
                                const ur_mesh_piece *pieces, size_t count, ur_net_list *nets,
                                double *area)
{
    flattening f = {.run = run, .room = *room};
    flatten_options(run, &f.options);
    *area = 0.0;
    ur_status code = 0;
    for (size_t k = 0; !code && k < count; k++)
        code = flatten_piece(&f, &pieces[k].mesh, 0, nets, area);
    name_nets(nets);
    return code;
}

/* A seam file: a path of mesh vertices, one x,y,z per line. */
static ur_status read_seam(const job_run *run, const char *path, const ur_mesh *mesh,
                           double tolerance, ur_seam **seams, size_t *seam_count)
{
    ur_vec3 *points = NULL;
    size_t count = 0;
    bool closed = false;
    ur_error error;
    if (ur_points_csv_read(path, 2, &points, &count, &closed, &error) != UR_OK)
        return fail(run, &error);
    size_t *vertices = ur_alloc_array(count, sizeof *vertices, &error);
    ur_seam *grown = realloc(*seams, (*seam_count + count) * sizeof *grown);
    ur_status code = vertices && grown ? UR_OK : fail(run, &error);
    if (grown)
        *seams = grown;
    for (size_t i = 0; !code && i < count; i++) {
        size_t best = 0;
        for (size_t v = 1; v < mesh->vertex_count; v++)
            if (ur_vec3_distance(mesh->vertices[v], points[i]) <
                ur_vec3_distance(mesh->vertices[best], points[i]))
                best = v;
        if (!(ur_vec3_distance(mesh->vertices[best], points[i]) <= tolerance)) {
            code = job_fail_about(run, UR_ERROR_INPUT, "seams",
                                  "%s: seams %s: point %zu (%g, %g, %g) is no vertex of the mesh",
                                  run->job.command, path, i + 1, points[i].x, points[i].y,
                                  points[i].z);
        }
        vertices[i] = best;
    }
    for (size_t i = 0; !code && i + 1 < count + (closed ? 1 : 0); i++)
        (*seams)[(*seam_count)++] = (ur_seam){vertices[i], vertices[(i + 1) % count]};
    free(vertices);
    free(points);
    return code;
}

static ur_status read_seams(const job_run *run, const ur_mesh *mesh, double tolerance,
                            ur_seam **seams, size_t *count)
{
    *seams = NULL;
    *count = 0;
    ur_status code = 0;
    for (size_t k = 0; !code && k < run->job.seam_count; k++)
        code = read_seam(run, run->job.seam_paths[k], mesh, tolerance, seams, count);
    return code;
}

static void say_repairs(const job_run *run, const ur_mesh_repairs *repairs)
{
    if (run->job.quiet)
        return;
    if (repairs->welded || repairs->degenerate || repairs->isolated || repairs->flipped)
        job_note(run,
                 "%s: repaired: %zu vertices welded, %zu zero-area triangles and %zu unused "
                 "vertices dropped, %zu triangles turned to agree with their neighbours",
                 run->job.command, repairs->welded, repairs->degenerate, repairs->isolated,
                 repairs->flipped);
    if (repairs->flaps)
        job_note(run,
                 "%s: repaired: %zu flap%s of no thickness dropped (two triangles back to back on "
                 "the same corners, standing on the surface)",
                 run->job.command, repairs->flaps, repairs->flaps == 1 ? "" : "s");
    if (repairs->duplicates)
        job_note(run,
                 "%s: repaired: %zu triangle%s dropped that repeated another's corners (a face "
                 "given twice)",
                 run->job.command, repairs->duplicates, repairs->duplicates == 1 ? "" : "s");
    if (repairs->kept_apart)
        job_note(run,
                 "%s: repaired: %zu vertices left unwelded where welding would join three or more "
                 "faces at an edge: the surfaces there stay apart, not joined by a seam",
                 run->job.command, repairs->kept_apart);
    if (repairs->split)
        job_note(run,
                 "%s: repaired: surfaces that touched along an edge taken apart (%zu vertices "
                 "copied)",
                 run->job.command, repairs->split);
}

/*
 * The strain --flatten strips keeps within: the material's, or --max-strain
 * for both.  The limits bound the flattening's map from 3D to flat; where
 * it stretches (sigma1 > 1) the flat piece is longer than the surface and
 * the material must be compressed to take the shape again, and where it
 * compresses the material must stretch: so the material's compression
 * bounds the map's stretch, and its stretch the map's compression.
 */
static ur_strip_limits strip_limits(const job_run *run, const ur_material *material)
{
    ur_strip_limits limits = {material->max_compression, material->max_stretch, 64};
    if (!isnan(run->job.max_strain))
        limits.max_stretch = limits.max_compression = run->job.max_strain;
    return limits;
}

/*
 * Pieces that bend tighter than the material can: bending kerfs follow a
 * developed surface's rulings (bending.c), and a flattened mesh piece has
 * none, so it would crack (Blender's cylinder, radius 60 mm, in 3 mm
 * plywood, whose smallest bend radius is 150 mm).  The material's smaller
 * radius (with or across its grain) is the limit, so that a warning is
 * sure.  A tally of the pieces looked at, those too tight and the
 * tightest.
 */
typedef struct bend_tally {
    double limit;
    size_t pieces, tight;
    double least;
} bend_tally;

static bend_tally bend_tally_start(const ur_material *material)
{
    return (bend_tally){
        .limit = fmin(material->bend_radius_with_grain, material->bend_radius_across_grain),
        .least = INFINITY};
}

static void bend_tally_add(bend_tally *tally, const ur_mesh *piece)
{
    double radius;
    ur_vec3 at;
    ur_error error;
    tally->pieces++;
    if (tally->limit > 0 && ur_mesh_tightest_bend(piece, &radius, &at, &error) == UR_OK &&
        radius < tally->limit) {
        tally->tight++;
        tally->least = fmin(tally->least, radius);
    }
}

/* what: the kind of piece, singular ("chart"). */
static void warn_tight_bends(const job_run *run, const ur_material *material,
                             const bend_tally *tally, const char *what)
{
    if (tally->tight == 0)
        return;
    char which[64];
    if (tally->pieces == 1) /* one piece, chart or strip is the whole mesh */
        c_snprintf(which, sizeof which, "the mesh bends");
    else
        c_snprintf(which, sizeof which, "%zu of the %zu %ss bend%s", tally->tight, tally->pieces,
                   what, tally->tight == 1 ? "s" : "");
    job_warn(run,
             "%s: warning: %s tighter than %s takes (a radius of %g mm), down to %.1f mm, and a "
             "flattened piece gets no bending kerfs: use a thinner material, or develop a "
             "cylinder or cone as a surface of its own",
             run->job.command, which, material->name, tally->limit, tally->least);
}

/*
 * Names the nets from first on, all of strip band (counted from 0): S3,
 * or S3.1, S3.2, ... when the strip is in parts (a band of a mesh that
 * falls apart, or a strip cut to fit).
 */
static void name_strip_parts(ur_net_list *nets, size_t first, size_t band)
{
    size_t parts = nets->count - first;
    for (size_t k = first; k < nets->count; k++) {
        char *name = nets->nets[k].name;
        if (parts == 1)
            c_snprintf(name, sizeof nets->nets[k].name, "S%zu", band + 1);
        else
            c_snprintf(name, sizeof nets->nets[k].name, "S%zu.%zu", band + 1, k - first + 1);
    }
}

/*
 * The strips' pieces as nets S1, S2, ... in order across the surface,
 * each cut along its length where it does not fit the room (a flat grid
 * is one strip as large as the grid) or its outline crosses itself.  The
 * pieces come band by band, and a band's parts are numbered together (the
 * sample lampshade's one strip comes in two pieces: S1.1 and S1.2, not
 * two S1).
 */
static ur_status nets_of_strips(const job_run *run, const job_room *room, const ur_strips *strips,
                                const ur_strip_limits *limits, ur_net_list *nets, double *area)
{
    flattening f = {.run = run, .room = *room, .limits = limits};
    flatten_options(run, &f.options);
    f.options.progress = NULL; /* the strips' progress has ended */
    *area = 0.0;
    ur_status code = 0;
    size_t first = 0; /* the first net of the band */
    for (size_t k = 0; !code && k < strips->count; k++) {
        const ur_strip *strip = &strips->strips[k];
        if (k == 0 || strip->band != strips->strips[k - 1].band)
            first = nets->count;
        code = place_flat(&f, &strip->piece.mesh, &strip->flat, 0, nets, area);
        if (!code)
            name_strip_parts(nets, first, strip->band);
    }
    if (!code && !run->job.quiet)
        job_note(run,
                 "%s: %zu strip%s keep the strain within %.3g %% stretch and %.3g %% "
                 "compression (at most %.3g %% and %.3g %%)",
                 run->job.command, strips->bands, strips->bands == 1 ? "" : "s",
                 100 * limits->max_stretch, 100 * limits->max_compression,
                 100 * strips->max_stretch, 100 * strips->max_compression);
    return code;
}

/* --flatten strips on a mesh or a ruled surface (mesh NULL), with the material's limits. */
/* seams: the user's (--seams), on the mesh; none for a ruled surface. */
static ur_status flatten_in_strips(const job_run *run, const job_room *room,
                                   const ur_material *material, ur_mesh *mesh, const ur_seam *seams,
                                   size_t seam_count, ur_ruled *ruled, ur_net_list *nets,
                                   double *area)
{
    ur_strip_limits limits = strip_limits(run, material);
    ur_flatten_options options;
    flatten_options(run, &options);
    ur_strips strips;
    ur_error error;
    ur_status status = mesh ? ur_flatten_strips_mesh(mesh, seams, seam_count, NULL, &limits,
                                                     &options, &strips, &error)
                            : ur_flatten_strips_ruled(ruled, &limits, &options, &strips, &error);
    job_end_flattening(run);
    if (status != UR_OK) {
        return job_fail_about(run, error.status, "max-strain",
                              "%s: %s (max-strain sets another limit)", run->job.command,
                              error.message);
    }
    ur_status code = nets_of_strips(run, room, &strips, &limits, nets, area);
    bend_tally tally = bend_tally_start(material);
    for (size_t k = 0; !code && k < strips.count; k++)
        bend_tally_add(&tally, &strips.strips[k].piece.mesh);
    if (!code)
        warn_tight_bends(run, material, &tally, "strip");
    ur_strips_free(&strips);
    return code;
}

/*
 * A mesh whose faces meet at sharp edges comes out in charts of a face or
 * two (Blender's monkey head in 2 mm cardboard: 197 charts, 106 of them so),
 * which --flatten unfold holds together by folds, every face exact (17
 * pieces).  Said when at least a quarter of the charts, and 10 or more, are
 * of two triangles or fewer (a finely meshed model's charts are larger).
 */
static void suggest_unfolding(const job_run *run, const ur_charts *charts)
{
    size_t small = 0;
    for (size_t k = 0; k < charts->count; k++)
        small += charts->charts[k].piece.mesh.triangle_count <= 2;
    if (small >= 10 && 4 * small >= charts->count && !run->job.quiet)
        job_note_about(run, "flatten",
                       "%s: note: %zu of the %zu charts are a face or two of the mesh, cut apart "
                       "at sharp edges; flatten unfold joins such faces along folds instead, "
                       "every face exact",
                       run->job.command, small, charts->count);
}

/*
 * The default for a mesh: charts within the material's strain (or
 * --max-strain), each placed as a net (cut again where its outline
 * crosses itself or it does not fit the room).
 */
static ur_status flatten_charts(const job_run *run, const job_room *room,
                                const ur_material *material, const ur_mesh *mesh,
                                const ur_seam *seams, size_t seam_count, ur_net_list *nets,
                                double *area)
{
    ur_strip_limits limits = strip_limits(run, material);
    flattening f = {.run = run, .room = *room, .limits = &limits};
    flatten_options(run, &f.options);
    f.options.method = UR_FLATTEN_ARAP;
    f.options.progress = NULL; /* one line per layout would only flicker */
    ur_charts charts;
    ur_error error;
    if (ur_flatten_charts(mesh, seams, seam_count, &limits, &f.options, &charts, &error) != UR_OK)
        return fail(run, &error);
    *area = 0.0;
    ur_status code = 0;
    for (size_t k = 0; !code && k < charts.count; k++)
        code = place_flat(&f, &charts.charts[k].piece.mesh, &charts.charts[k].flat, 0, nets, area);
    name_nets(nets);
    if (!code && !run->job.quiet)
        job_note(run,
                 "%s: %zu chart%s (cut at %zu sharp edges, then where over the strain) keep "
                 "within %.3g %% stretch and %.3g %% compression (at most %.3g %% and %.3g %%)",
                 run->job.command, charts.count, charts.count == 1 ? "" : "s", charts.sharp_edges,
                 100 * limits.max_stretch, 100 * limits.max_compression, 100 * charts.max_stretch,
                 100 * charts.max_compression);
    if (!code) {
        suggest_unfolding(run, &charts);
        bend_tally tally = bend_tally_start(material);
        for (size_t k = 0; k < charts.count; k++)
            bend_tally_add(&tally, &charts.charts[k].piece.mesh);
        warn_tight_bends(run, material, &tally, "chart");
    }
    ur_charts_free(&charts);
    return code;
}

/* Triangle t laid flat: its corners in its own plane, the first at the origin. */
static void flat_triangle(const ur_mesh *mesh, size_t t, ur_vec2 corners[3])
{
    const size_t *v = mesh->triangles[t];
    ur_vec3 ab = ur_vec3_sub(mesh->vertices[v[1]], mesh->vertices[v[0]]);
    ur_vec3 ac = ur_vec3_sub(mesh->vertices[v[2]], mesh->vertices[v[0]]);
    double length = ur_vec3_length(ab);
    double along = length > 0 ? ur_vec3_dot(ac, ab) / length : 0.0;
    double across = length > 0 ? ur_vec3_length(ur_vec3_cross(ab, ac)) / length : 0.0;
    corners[0] = ur_vec2_make(0, 0);
    corners[1] = ur_vec2_make(length, 0);
    corners[2] = ur_vec2_make(along, across);
}

/*
 * A triangle that fits no sheet at any turn: cutting along the mesh's
 * edges, as flattening does to fit pieces to sheets, can never make it
 * fit, so the mesh is refused up front, naming the triangle (as unfolding
 * names a flat face), instead of after every cut has been tried.
 */
static ur_status check_triangles_fit(const job_run *run, const job_room *room, const ur_mesh *mesh)
{
    if (!run->job.develop.split || !(room->length > 0 && room->width > 0))
        return 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        ur_vec2 corners[3];
        flat_triangle(mesh, t, corners);
        bool fits = true;
        double angle, length = 0, width = 0;
        ur_error error;
        if (ur_outline_fit_turn(corners, 3, room->length, room->width, &fits, &angle, &error) !=
                UR_OK ||
            fits)
            continue; /* out of memory here: nesting will say */
        if (ur_outline_level_size(corners, 3, &length, &width, &error) != UR_OK)
            continue;
        return job_fail_about(run, UR_ERROR_INPUT, "sheet scale",
                              "%s: triangle %zu is %.1f x %.1f mm and is never cut, but a piece "
                              "may take only %.1f x %.1f mm: give a larger sheet or a smaller "
                              "scale",
                              run->job.command, t + 1, length, width,
                              fmax(room->length, room->width), fmin(room->length, room->width));
    }
    return 0;
}

/* Cleans, cuts into disks and flattens; repairs are news only for a mesh from a file. */
static ur_status nets_of_mesh(const job_run *run, const job_room *room, const ur_material *material,
                              ur_mesh *mesh, bool tell_repairs, ur_net_list *nets, double *area)
{
    ur_error error;
    ur_mesh_repairs repairs;
    double size = mesh->vertex_count ? ur_mesh_size(mesh) : 0.0;
    double weld = 1e-6 * size; /* well below any modelling detail, above float rounding */
    if (ur_mesh_clean(mesh, weld, &repairs, &error) != UR_OK) {
        if (tell_repairs && run->job.mesh_path) /* the library does not know the file's name */
            ur_error_prefix(&error, "%s: ", run->job.mesh_path);
        return fail(run, &error);
    }
    if (tell_repairs)
        say_repairs(run, &repairs);
    char what[64];
    c_snprintf(what, sizeof what, "flattening %zu triangles", mesh->triangle_count);
    ur_status code = job_check_memory(run, what, ur_flatten_memory_estimate(mesh->triangle_count));
    if (code)
        return code;
    job_room flat_room = room_for_joints(run, room, material);
    if (!run->job.unfold) /* unfolding names the flat face that does not fit */
        code = check_triangles_fit(run, &flat_room, mesh);
    if (code)
        return code;
    ur_seam *seams = NULL;
    size_t seam_count = 0;
    code = read_seams(run, mesh, 1e-4 * size, &seams, &seam_count);
    if (!code && run->job.strips) {
        code =
            flatten_in_strips(run, &flat_room, material, mesh, seams, seam_count, NULL, nets, area);
        free(seams);
        return code;
    }
    if (!code && run->job.unfold) {
        code = job_unfold_mesh(run, room, material, mesh, seams, seam_count, nets, area);
        free(seams);
        return code;
    }
    if (!code && run->job.flatten < 0 && strcmp(run->job.surface, "mesh") == 0) {
        code = flatten_charts(run, &flat_room, material, mesh, seams, seam_count, nets, area);
        free(seams);
        return code;
    }
    ur_mesh_piece *pieces = NULL;
    size_t piece_count = 0;
    if (!code && ur_mesh_pieces(mesh, seams, seam_count, &pieces, &piece_count, &error) != UR_OK)
        code = fail(run, &error);
    if (!code)
        code = flatten_pieces(run, &flat_room, pieces, piece_count, nets, area);
    bend_tally tally = bend_tally_start(material);
    for (size_t k = 0; !code && k < piece_count; k++)
        bend_tally_add(&tally, &pieces[k].mesh);
    if (!code)
        warn_tight_bends(run, material, &tally, "piece");
    job_end_flattening(run);
    ur_mesh_pieces_free(pieces, piece_count);
    free(seams);
    return code;
}

/*
 * A model this small (mm) was most likely drawn in metres, as Blender's
 * are, or in inches: mesh files carry no unit, and read as millimetres a
 * chair becomes a crumb.
 */
#define TINY_MODEL 10.0

/* The largest side of the mesh's box (mm); 0 for no vertices. */
static double model_size(const ur_mesh *mesh)
{
    if (mesh->vertex_count == 0)
        return 0;
    ur_vec3 low = mesh->vertices[0], high = mesh->vertices[0];
    for (size_t v = 1; v < mesh->vertex_count; v++) {
        ur_vec3 p = mesh->vertices[v];
        low = ur_vec3_make(fmin(low.x, p.x), fmin(low.y, p.y), fmin(low.z, p.z));
        high = ur_vec3_make(fmax(high.x, p.x), fmax(high.y, p.y), fmax(high.z, p.z));
    }
    return fmax(high.x - low.x, fmax(high.y - low.y, high.z - low.z));
}

/* Without units or a scale, a mesh smaller than TINY_MODEL gets a warning naming both. */
static void warn_if_tiny(const job_run *run, const ur_mesh *mesh)
{
    if (run->job.quiet)
        return;
    double size = model_size(mesh);
    if (!(size < TINY_MODEL) || !(size > 0))
        return;
    job_warn_about(run, "units units scale",
                   "%s: warning: %s is only %.3g mm across, read in millimetres; if it was "
                   "modelled in metres (as Blender's are) give units m (%.4g mm), in inches "
                   "units in (%.4g mm), or scale S",
                   run->job.command, run->job.mesh_path, size, size * 1000, size * 25.4);
}

/*
 * A model smaller than this (mm) whose edges are mostly shorter than a
 * glue tab is deep gets a note suggesting a scale: read at 1:1, a 30 mm
 * recycling symbol from PrusaSlicer unfolded with tabs full of "no room",
 * and at 5 times its size well.  A larger model with short edges is a
 * fine mesh, which a scale would not help.
 */
#define SMALL_FOR_TABS 100.0
/* The size the note's scale brings the model to, at least (mm). */
#define TABS_SIZE 150.0

static int shorter_first(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median length of the triangles' edges; 0 when there are none or memory runs out. */
static double median_edge(const ur_mesh *mesh)
{
    size_t count = 3 * mesh->triangle_count;
    double *lengths = count ? malloc(count * sizeof *lengths) : NULL;
    if (!lengths)
        return 0;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            lengths[3 * t + (size_t)k] =
                ur_vec3_distance(mesh->vertices[mesh->triangles[t][k]],
                                 mesh->vertices[mesh->triangles[t][(k + 1) % 3]]);
        }
    qsort(lengths, count, sizeof *lengths, shorter_first);
    double median = lengths[count / 2];
    free(lengths);
    return median;
}

/* Without units or a scale, a small papercraft model of short edges gets a note with a scale. */
static void note_if_small_for_tabs(const job_run *run, const ur_material *material,
                                   const ur_mesh *mesh)
{
    if (run->job.quiet || !run->job.unfold || !job_makes_joints(run) ||
        material->joint != UR_JOINT_TAB || !(material->tab_depth > 0))
        return;
    double size = model_size(mesh);
    if (!(size >= TINY_MODEL && size < SMALL_FOR_TABS))
        return; /* a tiny model has its warning already; a large one is fine */
    double median = median_edge(mesh);
    if (!(median > 0 && median < material->tab_depth))
        return;
    double scale = ceil(TABS_SIZE / size);
    job_note_about(run, "scale",
                   "%s: note: %s is %.0f mm across and half its edges are under %.1f mm, shorter "
                   "than a glue tab is deep (%g mm): many seams will have no tab; scale %g makes "
                   "it %.0f mm across",
                   run->job.command, run->job.mesh_path, size, median, material->tab_depth, scale,
                   size * scale);
}

/*
 * Says which unit a file that declares one (Collada, 3MF) was read in,
 * unless it is the millimetre the file says and nothing needs saying.
 */
static void note_declared_unit(const job_run *run, double declared_mm, const char *declared)
{
    if (declared_mm == 0)
        return;
    const char *given = run->job.unit_name;
    if (!given) {
        if (declared_mm != 1.0)
            job_note(run, "%s: %s: its unit is %s (%g mm), as the file says", run->job.command,
                     run->job.mesh_path, declared, declared_mm);
        return;
    }
    double given_mm = ur_length_unit_mm((ur_length_unit)ur_length_unit_from_name(given));
    if (given_mm != declared_mm)
        job_note_about(
            run, "units",
            "%s: %s: its unit is %s (%g mm) as the file says, but read in %s, as units says",
            run->job.command, run->job.mesh_path, declared, declared_mm, given);
}

ur_status job_mesh_nets(const job_run *run, const job_room *room, const ur_material *material,
                        ur_net_list *nets, double *area)
{
    if (!run->job.mesh_path) {
        return job_fail(run, UR_ERROR_INPUT, "mesh: give the mesh file to read");
    }
    ur_mesh_import_options options;
    ur_mesh_import_options_default(&options);
    if (run->job.unit_name)
        options.unit = (ur_length_unit)ur_length_unit_from_name(run->job.unit_name);
    if (!isnan(run->job.scale))
        options.scale = run->job.scale;
    char what[64 + 1024];
    c_snprintf(what, sizeof what, "reading %s", run->job.mesh_path);
    ur_status code =
        job_check_memory(run, what, ur_mesh_import_memory_estimate(run->job.mesh_path));
    if (code)
        return code;
    ur_mesh mesh;
    ur_error error;
    if (ur_mesh_import(run->job.mesh_path, &options, &mesh, NULL, &error) != UR_OK)
        return fail(run, &error);
    double declared_mm = 0;
    char declared[32];
    if (ur_mesh_declared_unit(run->job.mesh_path, &declared_mm, declared, &error) != UR_OK) {
        ur_mesh_free(&mesh);
        return fail(run, &error);
    }
    note_declared_unit(run, declared_mm, declared);
    if (!run->job.unit_name && isnan(run->job.scale)) {
        if (declared_mm == 0) /* a unit the file gives is no guess to warn about */
            warn_if_tiny(run, &mesh);
        note_if_small_for_tabs(run, material, &mesh);
    }
    code = nets_of_mesh(run, room, material, &mesh, true, nets, area);
    ur_mesh_free(&mesh);
    return code;
}

ur_status job_flatten_ruled(const job_run *run, const job_room *room, const ur_material *material,
                            ur_ruled *ruled, ur_net_list *nets, double *area)
{
    if (run->job.strips) {
        job_room flat_room = room_for_joints(run, room, material);
        return flatten_in_strips(run, &flat_room, material, NULL, NULL, 0, ruled, nets, area);
    }
    ur_mesh mesh;
    ur_error error;
    if (ur_mesh_from_ruled(ruled, RULED_ALONG, RULED_ACROSS, &mesh, &error) != UR_OK)
        return fail(run, &error);
    ur_status code = nets_of_mesh(run, room, material, &mesh, false, nets, area);
    ur_mesh_free(&mesh);
    return code;
}
