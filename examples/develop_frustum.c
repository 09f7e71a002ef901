/*
 * develop_frustum.c: a program of its own built on libunroll alone.  It
 * develops a frustum of a right circular cone (base radius 40 mm, top
 * radius 20 mm, 40 mm high) exactly, makes each net a piece with its
 * rulings scored, places the pieces on the bed of the co2-60w machine and
 * writes them as SVG.
 *
 *   cc develop_frustum.c $(pkg-config --cflags --libs unroll) -o develop_frustum
 *   ./develop_frustum frustum.svg "$(pkg-config --variable=profiledir unroll)"
 *
 * The last argument is where the machine profiles are (the installed ones).
 *
 * The frustum's lateral area is pi (R + r) s with slant s = sqrt((R - r)^2 + h^2):
 * the program fails unless the flat pieces cover exactly that much.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <unroll/unroll.h>

#define BASE_RADIUS 40.0
#define TOP_RADIUS 20.0
#define HEIGHT 40.0
#define PI 3.14159265358979323846

typedef struct frustum_run {
    ur_ruled ruled;
    bool have_ruled;
    ur_net_list nets;
    ur_piece *pieces;
    size_t piece_count;
    ur_layout layout;
    ur_machine machine;
} frustum_run;

/* The apex of the whole cone, and the fraction of each ruling kept below it. */
static ur_status make_frustum(frustum_run *run, ur_error *error)
{
    ur_curve *base = NULL;
    ur_status status = ur_curve_new_circle(BASE_RADIUS, &base, error);
    if (status != UR_OK)
        return status;
    double apex_height = HEIGHT * BASE_RADIUS / (BASE_RADIUS - TOP_RADIUS);
    double cut = 1.0 - TOP_RADIUS / BASE_RADIUS;
    status = ur_ruled_cone(base, ur_vec3_make(0, 0, apex_height), cut, &run->ruled, error);
    run->have_ruled = status == UR_OK;
    return status;
}

static ur_status make_pieces(frustum_run *run, ur_error *error)
{
    run->pieces = ur_alloc_array(run->nets.count, sizeof *run->pieces, error);
    if (!run->pieces)
        return error->status;
    ur_allowance_options options = {.draw_rulings = true};
    for (size_t k = 0; k < run->nets.count; k++) {
        ur_status status = ur_piece_from_net(&run->nets.nets[k], &options, &run->pieces[k], error);
        if (status != UR_OK)
            return status;
        run->piece_count++;
    }
    return UR_OK;
}

static ur_status check_area(const frustum_run *run, ur_error *error)
{
    double slant = hypot(BASE_RADIUS - TOP_RADIUS, HEIGHT);
    double expected = PI * (BASE_RADIUS + TOP_RADIUS) * slant;
    double flat = 0;
    for (size_t k = 0; k < run->nets.count; k++)
        flat += run->nets.nets[k].flat_area;
    printf("frustum: %zu piece(s), flat area %.2f mm2, lateral area %.2f mm2\n", run->nets.count,
           flat, expected);
    if (fabs(flat - expected) > 1e-3 * expected)
        return ur_error_set(error, UR_ERROR_INTERNAL, "the net's area is %.2f mm2, not %.2f", flat,
                            expected);
    return UR_OK;
}

static ur_status run_frustum(frustum_run *run, const char *output, const char *profiles,
                             ur_error *error)
{
    ur_status status = make_frustum(run, error);
    ur_develop_options develop;
    ur_develop_options_default(&develop);
    if (status == UR_OK)
        status = ur_develop(&run->ruled, &develop, &run->nets, error);
    if (status == UR_OK)
        status = check_area(run, error);
    if (status == UR_OK)
        status = make_pieces(run, error);
    if (status == UR_OK)
        status =
            ur_machine_load((const char *const[]){profiles, NULL}, "co2-60w", &run->machine, error);
    if (status == UR_OK) {
        ur_layout_options layout = {.sheet_width = run->machine.bed_width,
                                    .sheet_height = run->machine.bed_height,
                                    .margin = run->machine.margin,
                                    .spacing = run->machine.spacing};
        status = ur_layout_rows(run->pieces, run->piece_count, &layout, &run->layout, error);
    }
    if (status == UR_OK) {
        ur_output_options options = {.title = "a frustum developed by libunroll"};
        status = ur_write_svg(output, &run->layout, run->pieces, &run->machine, &options, error);
    }
    return status;
}

static void free_run(frustum_run *run)
{
    ur_layout_free(&run->layout);
    for (size_t k = 0; k < run->piece_count; k++)
        ur_piece_free(&run->pieces[k]);
    free(run->pieces);
    ur_net_list_free(&run->nets);
    if (run->have_ruled)
        ur_ruled_free(&run->ruled);
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: develop_frustum OUTPUT.svg PROFILE_DIRECTORY\n");
        return 2;
    }
    frustum_run run = {0};
    ur_error error;
    ur_status status = run_frustum(&run, argv[1], argv[2], &error);
    free_run(&run);
    if (status != UR_OK) {
        /* error.setting names the settings the message is about, if any. */
        fprintf(stderr, "develop_frustum: %s%s%s%s\n", error.message,
                error.setting[0] ? " (settings: " : "", error.setting, error.setting[0] ? ")" : "");
        return 1;
    }
    printf("frustum: wrote %s\n", argv[1]);
    return 0;
}
