/*
 * unfolding.c: a mesh unfolded along its edges ('unroll mesh --flatten
 * unfold'): the unfolding's options for the job (the room on a sheet, the
 * search's steps, the gap kept for tabs), its tries at two gaps side by
 * side and the choice between them, and its pieces as nets.
 */
#include "stages.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <threads.h>

#include "unroll/flatten.h"

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
    double joint = job_joint_reach(material);
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
 * start), each reading the mesh and making its own nets.
 *
 * A try whose first run (before the search) costs at least twice what
 * the other's does, and TRY_FAR_BEHIND pieces more, is dropped there, and
 * the other has the machine to itself: its search with the room turned
 * runs beside the level one (ur_unfold_options.threads), and its tabs
 * need no counting.  No search has brought such a try level: the bench's
 * 48 x 24 sphere starts at 86 against 26 and ends in 8 pieces with 71
 * seam edges untabbed against 6 with none.  Blender's primitives and the
 * samples start closer (within a third, but the subdivided monkey, 221
 * against 121, which the half gap wins too, and the cylinder, 3 against 1,
 * both one piece in the end).  Which try is kept depends on the two first
 * runs alone, whether the tries ran side by side or one after the other
 * (when no thread can start: then the first runs before it can know that
 * it will be alone, with one thread, which may round a piece's size
 * otherwise, see ur_unfold).  Only the try that leads shows its progress:
 * the first, or the other once the first is dropped.
 */
enum { UNFOLD_GAP_TRIES = 2 };
#define TRY_FAR_BEHIND 10.0

/* Whether a first run of this cost is far behind one of that cost (false if either is NAN). */
static bool far_behind(double cost, double other)
{
    return cost >= 2 * other && cost >= other + TRY_FAR_BEHIND;
}

/* What the tries tell each other, under its lock. */
typedef struct try_race {
    mtx_t lock;
    cnd_t told;
    bool side_by_side;              /* each try waits for the other's first run */
    bool known[UNFOLD_GAP_TRIES];   /* its first run is made, or it ended before one */
    double first[UNFOLD_GAP_TRIES]; /* that run's cost; NAN when it ended before */
    size_t leader;                  /* the try that shows its progress */
} try_race;

/* One try of the unfolding: what it needs, and what it gives. */
typedef struct unfold_try {
    const job_run *run;
    const ur_material *material;
    const ur_mesh *mesh;
    const ur_seam *seams;
    size_t seam_count;
    ur_unfold_options options;
    size_t index;
    try_race *race;  /* NULL for a try alone */
    bool count_tabs; /* whether the tabs are counted, for a choice */
    bool dropped;    /* stopped after its first run, far behind the other */
    unfolded_nets result;
    ur_status status;
    ur_error error;
} unfold_try;

/* The threads a try's search takes when it has the machine to itself. */
enum { TRY_ALONE_THREADS = 2 };

/* ur_unfold_options.started: tells the other try, and drops or frees this one. */
static bool try_started(void *context, double cost, size_t *threads)
{
    unfold_try *t = context;
    try_race *r = t->race;
    size_t other = 1 - t->index;
    mtx_lock(&r->lock);
    r->first[t->index] = cost;
    r->known[t->index] = true;
    cnd_broadcast(&r->told);
    while (r->side_by_side && !r->known[other])
        cnd_wait(&r->told, &r->lock);
    if (r->known[other] && far_behind(cost, r->first[other])) {
        t->dropped = true;
    } else if (r->known[other] && far_behind(r->first[other], cost)) {
        *threads = TRY_ALONE_THREADS;
        t->count_tabs = false;
        r->leader = t->index;
    }
    mtx_unlock(&r->lock);
    return !t->dropped;
}

/* A try that ended before its first run says so, lest the other wait for it. */
static void try_ended(unfold_try *t)
{
    try_race *r = t->race;
    if (!r)
        return;
    mtx_lock(&r->lock);
    if (!r->known[t->index]) {
        r->first[t->index] = NAN;
        r->known[t->index] = true;
        cnd_broadcast(&r->told);
    }
    mtx_unlock(&r->lock);
}

/* The unfolding's progress, from the try that leads. */
static void report_if_leading(void *context, const char *phase, double fraction)
{
    unfold_try *t = context;
    mtx_lock(&t->race->lock);
    if (t->race->leader == t->index)
        report_unfolding((void *)t->run, phase, fraction);
    mtx_unlock(&t->race->lock);
}

static int run_try(void *data)
{
    unfold_try *t = data;
    t->status =
        unfold_once(t->run, t->mesh, t->seams, t->seam_count, &t->options, &t->result, &t->error);
    try_ended(t);
    if (t->status == UR_OK && t->count_tabs)
        t->status = job_count_untabbed(t->run, t->material, &t->result.nets, &t->result.untabbed,
                                       &t->error);
    return 0;
}

/* Runs the tries side by side and waits for them all. */
static void run_tries(unfold_try *tries, size_t count, try_race *race)
{
    thrd_t threads[UNFOLD_GAP_TRIES];
    bool started[UNFOLD_GAP_TRIES] = {false};
    race->side_by_side = count > 1; /* before the second starts: it may wait for the first */
    for (size_t k = 1; k < count; k++)
        started[k] = thrd_create(&threads[k], run_try, &tries[k]) == thrd_success;
    if (count > 1 && !started[1]) /* nothing runs beside the first: it must not wait */
        race->side_by_side = false;
    run_try(&tries[0]);
    for (size_t k = 1; k < count; k++) {
        if (started[k])
            thrd_join(threads[k], NULL);
        else
            run_try(&tries[k]);
    }
}

/*
 * The try kept: the one the other is far behind, else the better; ties to
 * the first.  UNFOLD_GAP_TRIES if one failed (*failed, the first to fail).
 */
static size_t chosen_try(const unfold_try *tries, size_t count, const try_race *race,
                         double gap_break_cost, size_t *failed)
{
    *failed = count;
    for (size_t k = 0; k < count && *failed == count; k++)
        if (!tries[k].dropped && tries[k].status != UR_OK)
            *failed = k;
    if (*failed < count)
        return UNFOLD_GAP_TRIES;
    if (count == 1)
        return 0;
    if (far_behind(race->first[0], race->first[1]))
        return 1;
    if (far_behind(race->first[1], race->first[0]))
        return 0;
    return better_unfolding(&tries[1].result, &tries[0].result, gap_break_cost) ? 1 : 0;
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

/* The tries' options: the gap halved for the second; the race's callbacks when there are two. */
static void set_up_tries(const job_run *run, const ur_material *material, const ur_mesh *mesh,
                         const ur_seam *seams, size_t seam_count, const ur_unfold_options *options,
                         unfold_try *tries, size_t count, try_race *race)
{
    for (size_t k = 0; k < count; k++) {
        unfold_try *t = &tries[k];
        *t = (unfold_try){.run = run,
                          .material = material,
                          .mesh = mesh,
                          .seams = seams,
                          .seam_count = seam_count,
                          .options = *options,
                          .index = k,
                          .race = count > 1 ? race : NULL,
                          .count_tabs = count > 1};
        t->options.min_gap = options->min_gap / (double)(1u << k);
        if (count == 1) {
            t->options.threads = TRY_ALONE_THREADS;
            continue;
        }
        t->options.started = try_started;
        t->options.started_context = t;
        if (options->progress) {
            t->options.progress = report_if_leading;
            t->options.progress_context = t;
        }
    }
}

/*
 * Unfolds along the edges: every face keeps its exact shape, flat faces
 * are not folded, and every piece fits the room on a sheet (0 x 0, or
 * --no-split: no limit) with a joint (tab or lap) on each side: the room's
 * length leaves one at each end already.  The search for fewer pieces
 * takes the steps unfold_steps gives, with the job's --seed, at each gap
 * tried.
 */
ur_status job_unfold_mesh(const job_run *run, const job_room *room, const ur_material *material,
                          const ur_mesh *mesh, const ur_seam *seams, size_t seam_count,
                          ur_net_list *nets, double *area)
{
    ur_unfold_options options;
    unfold_options(run, room, material, mesh, &options);
    size_t count = options.min_gap > 0 ? UNFOLD_GAP_TRIES : 1;
    try_race race = {.leader = 0};
    if (mtx_init(&race.lock, mtx_plain) != thrd_success)
        return job_fail(run, UR_ERROR_INTERNAL, "%s: a lock could not be made", run->job.command);
    if (cnd_init(&race.told) != thrd_success) {
        mtx_destroy(&race.lock);
        return job_fail(run, UR_ERROR_INTERNAL, "%s: a lock could not be made", run->job.command);
    }
    unfold_try tries[UNFOLD_GAP_TRIES];
    set_up_tries(run, material, mesh, seams, seam_count, &options, tries, count, &race);
    run_tries(tries, count, &race);
    job_end_flattening(run);
    size_t failed, best = chosen_try(tries, count, &race, options.gap_break_cost, &failed);
    cnd_destroy(&race.told);
    mtx_destroy(&race.lock);
    for (size_t k = 0; k < count; k++)
        if (k != best)
            ur_net_list_free(&tries[k].result.nets);
    if (failed < count)
        return job_fail_from(run, &tries[failed].error);
    note_unfolding(run, &tries[best].result);
    *nets = tries[best].result.nets;
    *area = tries[best].result.area;
    return UR_OK;
}
