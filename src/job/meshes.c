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

/* How far a joint (tab or lap) stands out from the seam it is on, with the stock's thickness. */
static double joint_reach(const ur_material *material)
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
    double joint = joint_reach(material);
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

static void end_progress(const job_run *run)
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
 * A piece of an unfolding as a net: its outline, its folds, no strain.
 * Folds that turn by less than hidden (radians) are left out: a smooth
 * surface's many gentle folds, which paper takes by curling, where
 * scoring each would only weaken it (as Blender's Paper Model hides folds
 * below its "Hidden Edge Angle"); *left_out counts them.
 */
static ur_status net_of_unfolded(const ur_mesh *mesh, const ur_unfolded_piece *piece, size_t index,
                                 double hidden, ur_net *net, size_t *left_out, ur_error *error)
{
    memset(net, 0, sizeof *net);
    c_snprintf(net->name, sizeof net->name, "P%zu", index + 1);
    net->outline_3d = ur_alloc_array(piece->outline_count, sizeof *net->outline_3d, error);
    if (!net->outline_3d)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < piece->outline_count; i++)
        net->outline_3d[i] = mesh->vertices[piece->outline_vertices[i]];
    net->outline = ur_alloc_array(piece->outline_count, sizeof *net->outline, error);
    net->folds = ur_alloc_array(piece->fold_count, sizeof *net->folds, error);
    net->fold_valley = ur_alloc_array(piece->fold_count, sizeof *net->fold_valley, error);
    if (!net->outline || !net->folds || !net->fold_valley)
        return UR_ERROR_MEMORY;
    memcpy(net->outline, piece->outline, piece->outline_count * sizeof *net->outline);
    net->outline_count = piece->outline_count;
    for (size_t k = 0; k < piece->fold_count; k++) {
        if (piece->folds[k].angle < hidden) {
            (*left_out)++;
            continue;
        }
        net->folds[net->fold_count] = (ur_segment){piece->folds[k].start, piece->folds[k].end};
        net->fold_valley[net->fold_count++] = piece->folds[k].valley;
    }
    net->area_3d = piece->area_3d;
    net->flat_area = piece->flat_area;
    net->polygon_count = piece->face_count;
    return ur_net_set_faces(net, mesh, piece->triangles, piece->triangle_count, error);
}

/* The unfolding's progress, as report_flattening's. */
static void report_unfolding(void *context, const char *phase, double fraction)
{
    ur_job_progress progress = {.kind = UR_JOB_UNFOLDING, .phase = phase, .fraction = fraction};
    job_progress(context, &progress);
}

/*
 * The mean length of the mesh's triangle sides (each inner edge twice).
 * The unfolding leaves half a tab's depth between the parts of a piece,
 * so that every seam has room for a tab (a lower one where it must); on a
 * finer mesh, whose faces are shorter than a tab is deep, half a mean
 * edge: a full gap cut Blender's subdivided monkey head (4.6 mm edges,
 * 6 mm tabs) into 219 pieces, no gap left 501 seams without a tab in 22
 * pieces, half an edge gives 127 pieces and 13.  Finer still (edges
 * shorter than half a tab), a tab spans several edges and few seams lack
 * room without a gap: a 99,904-triangle sphere (1.7 mm edges) comes in 5
 * pieces with 4 % of its seam edges untabbed, against 198 pieces with a
 * gap, which took minutes and gigabytes to nest.
 */
static double mean_edge_length(const ur_mesh *mesh)
{
    double sum = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            sum += ur_vec3_distance(mesh->vertices[mesh->triangles[t][k]],
                                    mesh->vertices[mesh->triangles[t][(k + 1) % 3]]);
    return mesh->triangle_count ? sum / (3.0 * (double)mesh->triangle_count) : 0.0;
}

/*
 * The search for fewer pieces takes a number of steps (fewer when it
 * finds the fewest pieces the mesh allows), counted, so that a mesh
 * unfolds the same way every time and on every machine, however loaded:
 * UNFOLD_WORK divided by the triangles (a step's cost grows with them), at
 * most UNFOLD_MOST_STEPS, and UNFOLD_STEPS when that would be less than
 * twice as many; the library keeps the steps after its first 200 only
 * when they give fewer pieces (Blender's monkey head, 968 triangles, 723
 * steps: 17 pieces instead of 31; a 2,208-triangle sphere keeps 200 steps
 * and its time).  A mesh that the first 200 steps leave in many pieces gets
 * UNFOLD_STEPS_PER_PIECE steps for each, up to 1,000: a step costs about a
 * millisecond, a piece the nesting far more (Blender's monkey head
 * subdivided once: 132 pieces and 26 s in all with 200 steps, 106 and
 * 20 s with 1,000; not a mesh whose steps are timed).  Only a mesh of
 * more than UNFOLD_TIMED_ABOVE triangles, whose steps take long, stops
 * early after UNFOLD_SECONDS of wall-clock time, and may then unfold
 * differently from one run to the next.  (A 2,208-triangle sphere takes
 * 200 steps in about 0.25 s of CPU; a wall-clock limit on every mesh made
 * the sample meshes' pieces depend on the machine's load.)
 */
enum {
    UNFOLD_STEPS = 200,
    UNFOLD_MOST_STEPS = 1000,
    UNFOLD_TIMED_ABOVE = 20000,
    UNFOLD_STEPS_PER_PIECE = 8
};
#define UNFOLD_WORK 7e5
#define UNFOLD_SECONDS 5.0

static size_t unfold_steps(const ur_mesh *mesh)
{
    double steps = UNFOLD_WORK / (double)(mesh->triangle_count ? mesh->triangle_count : 1);
    if (steps < 2 * UNFOLD_STEPS) /* too few more to be worth a second search */
        return UNFOLD_STEPS;
    return (size_t)fmin(UNFOLD_MOST_STEPS, steps);
}

/*
 * The unfolding's options for the job: the room on a sheet less a joint
 * on each side, the search's steps, and the gap kept for tabs.
 */
static void unfold_options(const job_run *run, const job_room *room, const ur_material *material,
                           const ur_mesh *mesh, ur_unfold_options *options)
{
    double joint = joint_reach(material);
    ur_unfold_options_default(options);
    if (run->job.develop.split && room->width - 2 * joint > 0) { /* --no-split: refuse instead */
        options->room_length = room->length;
        options->room_width = room->width - 2 * joint;
    }
    options->seed = (uint64_t)run->job.seed;
    if (run->job.fewer_pieces) /* a seam joined by hand costs half a piece */
        options->gap_break_cost = 0.5;
    options->max_steps = unfold_steps(mesh);
    bool timed = mesh->triangle_count > UNFOLD_TIMED_ABOVE;
    options->steps_per_piece = timed ? 0 : UNFOLD_STEPS_PER_PIECE;
    options->time_budget = timed ? UNFOLD_SECONDS : 0.0;
    if (run->job.unfold_steps > 0) { /* the steps asked, all of them, on any machine alike */
        options->max_steps = run->job.unfold_steps;
        options->steps_per_piece = 0;
        options->time_budget = 0.0;
    }
    double tab = material->joint == UR_JOINT_LAP ? material->lap_width : material->tab_depth;
    double edge = mean_edge_length(mesh);
    if (job_makes_joints(run) && edge >= tab / 2) {
        options->min_gap = fmin(tab, edge) / 2;
        options->small_piece_area = tab * tab; /* a scrap smaller than a tab's square */
    }
    if (job_shows_progress(run)) {
        options->progress = report_unfolding;
        options->progress_context = (void *)run;
    }
    options->context = run->job.context;
}

/* One unfolding of the mesh as nets, with what its note says and what the choice weighs. */
typedef struct unfolded_nets {
    ur_net_list nets;
    ur_unfolding summary; /* the unfolding's counts, without its pieces */
    double area;          /* 3D, of all the pieces */
    size_t hidden;        /* folds left out by --hide-folds */
    size_t untabbed;      /* seam stretches whose tab finds no room */
} unfolded_nets;

/* Unfolds the mesh with the options into nets (out->nets, also on failure the caller's to free). */
static ur_status unfold_once(const job_run *run, const ur_mesh *mesh, const ur_seam *seams,
                             size_t seam_count, const ur_unfold_options *options,
                             unfolded_nets *out, ur_error *error)
{
    memset(out, 0, sizeof *out);
    ur_unfolding unfolding;
    ur_status status = ur_unfold_with_options(mesh, seams, seam_count, options, &unfolding, error);
    if (status != UR_OK)
        return status;
    out->nets.nets = ur_alloc_array(unfolding.count, sizeof *out->nets.nets, error);
    if (!out->nets.nets)
        status = UR_ERROR_MEMORY;
    for (size_t k = 0; status == UR_OK && k < unfolding.count; k++) {
        out->nets.count++;
        status = net_of_unfolded(mesh, &unfolding.pieces[k], k, run->job.hide_folds * M_PI / 180,
                                 &out->nets.nets[k], &out->hidden, error);
        out->area += unfolding.pieces[k].area_3d;
    }
    out->summary = unfolding;
    out->summary.pieces = NULL;
    ur_unfolding_free(&unfolding);
    return status;
}

/*
 * Whether unfolding a is better than b: fewer pieces and seam stretches
 * without a tab together, each such stretch weighed as `cost` pieces (the
 * search's own weight for a join without the gap); then fewer stretches.
 */
static bool better_unfolding(const unfolded_nets *a, const unfolded_nets *b, double cost)
{
    double score_a = (double)a->nets.count + cost * (double)a->untabbed;
    double score_b = (double)b->nets.count + cost * (double)b->untabbed;
    if (score_a != score_b)
        return score_a < score_b;
    return a->untabbed < b->untabbed;
}

/*
 * The gap the unfolding keeps for tabs is tried as given and at half, and
 * the unfolding with fewer pieces and tabs that find no room (counted by
 * putting them on) is kept.  Neither gap is best on every mesh: with
 * 6 mm paper tabs on A3 at 1 unit = 60 mm, Blender's UV sphere comes in 6
 * pieces with every tab at the full gap and in 4 at half, a 48 x 24 sphere
 * in 10 pieces with 74 seam edges untabbed and in 8 with none, the torus
 * in 5 and 3 (one untabbed), but the monkey head in 14 pieces (3
 * untabbed) and in 6 (41 untabbed); measured before scraps smaller than
 * a tab were joined (small_piece_area).  The tries run side by side, the
 * second in a thread of its own (one after the other if it cannot
 * start), each reading the mesh and making its own nets; only the first
 * shows its progress.
 */
enum { UNFOLD_GAP_TRIES = 2 };

/* One try of the unfolding: what it needs, and what it gives. */
typedef struct unfold_try {
    const job_run *run;
    const ur_material *material;
    const ur_mesh *mesh;
    const ur_seam *seams;
    size_t seam_count;
    ur_unfold_options options;
    bool count_tabs; /* whether the tabs are counted, for a choice */
    unfolded_nets result;
    ur_status status;
    ur_error error;
} unfold_try;

static int run_try(void *data)
{
    unfold_try *t = data;
    t->status =
        unfold_once(t->run, t->mesh, t->seams, t->seam_count, &t->options, &t->result, &t->error);
    if (t->status == UR_OK && t->count_tabs)
        t->status = job_count_untabbed(t->run, t->material, &t->result.nets, &t->result.untabbed,
                                       &t->error);
    return 0;
}

/* Runs the tries side by side and waits for them all. */
static void run_tries(unfold_try *tries, size_t count)
{
    thrd_t threads[UNFOLD_GAP_TRIES];
    bool started[UNFOLD_GAP_TRIES] = {false};
    for (size_t k = 1; k < count; k++)
        started[k] = thrd_create(&threads[k], run_try, &tries[k]) == thrd_success;
    run_try(&tries[0]);
    for (size_t k = 1; k < count; k++) {
        if (started[k])
            thrd_join(threads[k], NULL);
        else
            run_try(&tries[k]);
    }
}

static void note_unfolding(const job_run *run, const unfolded_nets *chosen)
{
    const ur_unfolding *u = &chosen->summary;
    if (run->job.quiet)
        return;
    job_note(run,
             "%s: unfolded into %zu piece%s (%zu of a single face) in %zu search steps: "
             "%zu folds (%zu valleys), %zu seam edges",
             run->job.command, u->count, u->count == 1 ? "" : "s", u->single_face, u->steps,
             u->folds, u->valleys, u->seams);
    if (run->job.hide_folds > 0)
        job_note_about(run, "hide-folds",
                       "%s: hide-folds leaves out %zu folds that turn by less than %g degrees",
                       run->job.command, chosen->hidden, run->job.hide_folds);
}

/*
 * Unfolds along the edges: every face keeps its exact shape, flat faces
 * are not folded, and every piece fits the room on a sheet (0 x 0, or
 * --no-split: no limit) with a joint (tab or lap) on each side: the room's
 * length leaves one at each end already.  The search for fewer pieces
 * takes the steps unfold_steps gives, with the job's --seed, at each gap
 * tried.
 */
static ur_status unfold_mesh(const job_run *run, const job_room *room, const ur_material *material,
                             const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                             ur_net_list *nets, double *area)
{
    ur_unfold_options options;
    unfold_options(run, room, material, mesh, &options);
    size_t count = options.min_gap > 0 ? UNFOLD_GAP_TRIES : 1;
    unfold_try tries[UNFOLD_GAP_TRIES];
    for (size_t k = 0; k < count; k++) {
        tries[k] = (unfold_try){.run = run,
                                .material = material,
                                .mesh = mesh,
                                .seams = seams,
                                .seam_count = seam_count,
                                .options = options,
                                .count_tabs = count > 1};
        tries[k].options.min_gap = options.min_gap / (double)(1u << k);
        if (k > 0)
            tries[k].options.progress = NULL;
    }
    run_tries(tries, count);
    end_progress(run);
    size_t best = 0, failed = count;
    for (size_t k = 0; k < count; k++) {
        if (tries[k].status != UR_OK)
            failed = failed < count ? failed : k;
        else if (k > 0 &&
                 better_unfolding(&tries[k].result, &tries[best].result, options.gap_break_cost))
            best = k;
    }
    for (size_t k = 0; k < count; k++)
        if (k != best || failed < count)
            ur_net_list_free(&tries[k].result.nets);
    if (failed < count)
        return fail(run, &tries[failed].error);
    note_unfolding(run, &tries[best].result);
    *nets = tries[best].result.nets;
    *area = tries[best].result.area;
    return UR_OK;
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
    end_progress(run);
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
        code = unfold_mesh(run, room, material, mesh, seams, seam_count, nets, area);
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
    end_progress(run);
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
