/*
 * analyze.c: 'unroll analyze SURFACE ...' (is it developable, its Gaussian
 * curvature, bend radii, domain of existence and edge of regression) and
 * 'unroll compare SURFACE ...' (the discrete methods of the seed paper,
 * [Seed2018] in docs/bibliography.md, against the exact net as n grows).
 * Both print their findings on standard output.
 */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "unroll/analyze.h"
#include "unroll/develop.h"
#include "unroll/out.h"

static bool to_stdout(const char *path)
{
    return path && strcmp(path, "-") == 0;
}

/* Where the findings go: standard output, unless a file written there takes it. */
static FILE *findings(const ur_job *job)
{
    bool taken = to_stdout(job->report_path) || to_stdout(job->png_path) ||
                 to_stdout(job->csv_path) || to_stdout(job->regression_path) ||
                 to_stdout(job->adjusted_rail_path) || to_stdout(job->adjusted_rail1_path);
    return taken ? stderr : stdout;
}

/* -0 prints as 0: a developable's K is zero, not negative. */
static double shown(double value)
{
    return value == 0 ? 0.0 : value;
}

static bool outputs_possible(const ur_job *job)
{
    const char *options[] = {"--png",        "--csv",           "--report",
                             "--regression", "--adjusted-rail", "--adjusted-rail1"};
    const char *paths[] = {job->png_path,        job->csv_path,           job->report_path,
                           job->regression_path, job->adjusted_rail_path, job->adjusted_rail1_path};
    for (int k = 0; k < 6; k++)
        if (paths[k] && strcmp(paths[k], "-") != 0 && !cli_directory_exists(options[k], paths[k]))
            return false;
    return true;
}

static void print_point(FILE *out, ur_vec3 p)
{
    fprintf(out, "(%.4g, %.4g, %.4g)", p.x, p.y, p.z);
}

static void print_gaps(FILE *out, ur_ruled *ruled)
{
    const ur_interval *gaps;
    size_t count = ur_ruled_gaps(ruled, &gaps);
    if (ruled->kind != UR_RULED_STRIP)
        return;
    if (count == 0) {
        fprintf(out, "  domain of existence: the whole of rail 1\n");
        return;
    }
    fprintf(out, "  domain of existence: %zu gap%s along rail 1\n", count, count == 1 ? "" : "s");
    for (size_t k = 0; k < count; k++)
        fprintf(out, "    %.6g to %.6g mm along rail 1 (u %.6g to %.6g): %s\n", gaps[k].arc_start,
                gaps[k].arc_end, gaps[k].u_start, gaps[k].u_end,
                gaps[k].reason == UR_GAP_NO_RULING ? "no ruling" : "rulings cross");
}

/* Where the edge of regression lies relative to the surface. */
static void print_regression(FILE *out, const ur_analysis *analysis)
{
    size_t inside = 0, known = 0;
    for (size_t k = 0; k < analysis->ruling_count; k++) {
        const ur_ruling_analysis *ruling = &analysis->rulings[k];
        if (ruling->in_gap || isnan(ruling->striction_v))
            continue;
        known++;
        /* Strictly between the rails: on a rail (a tangent developable's edge) is not inside. */
        inside += ruling->striction_v > 1e-9 && ruling->striction_v < 1 - 1e-9;
    }
    if (!analysis->developable)
        fprintf(out,
                "  line of striction (where neighbouring rulings come closest): inside the "
                "surface on %zu of %zu rulings\n",
                inside, known);
    else if (known == 0)
        fprintf(out, "  edge of regression: at infinity (parallel rulings)\n");
    else
        fprintf(out,
                "  edge of regression: %s (%zu of %zu rulings meet their neighbours "
                "between the rails)\n",
                inside ? "passes through the surface" : "outside the surface", inside, known);
}

static void print_analysis(const ur_job *job, ur_ruled *ruled, const ur_analysis *analysis)
{
    FILE *out = findings(job);
    const ur_ruling_analysis *worst = &analysis->rulings[analysis->worst_ruling];
    if (analysis->developable)
        fprintf(out,
                "%s: developable (the tangent plane turns by at most %.3g degrees along a "
                "ruling)\n",
                job->surface, analysis->max_residual * 180 / M_PI);
    else
        fprintf(out,
                "%s: not developable: the tangent plane turns by up to %.4g degrees along "
                "the ruling at %.6g mm along rail 1\n",
                job->surface, analysis->max_residual * 180 / M_PI, worst->arc);
    fprintf(out, "  area %.6g mm2\n", analysis->area_3d);
    fprintf(out, "  Gaussian curvature K (1/mm2): min %.4g at ", shown(analysis->gaussian_min));
    print_point(out, analysis->gaussian_min_at);
    fprintf(out, ", max %.4g at ", shown(analysis->gaussian_max));
    print_point(out, analysis->gaussian_max_at);
    fprintf(out, ", mean %.4g\n", shown(analysis->gaussian_mean));
    if (isfinite(analysis->min_bend_radius)) {
        fprintf(out, "  smallest bend radius %.4g mm at ", analysis->min_bend_radius);
        print_point(out, analysis->min_bend_at);
        fputc('\n', out);
    } else {
        fprintf(out, "  flat: no bending anywhere\n");
    }
    print_gaps(out, ruled);
    print_regression(out, analysis);
}

static int analysis_outputs(const ur_job *job, ur_ruled *ruled, const ur_analysis *analysis)
{
    ur_error error;
    char title[256];
    snprintf(title, sizeof title, "unroll analyze %s: Gaussian curvature", job->surface);
    if (job->png_path && ur_analysis_png_write(job->png_path, ruled, analysis, title, cli_context(),
                                               &error) != UR_OK) {
        cli_message("analyze: --png %s: %s", job->png_path, error.message);
        return cli_exit_status(&error);
    }
    if (job->report_path && ur_analysis_report_write(job->report_path, job->surface, ruled,
                                                     analysis, cli_context(), &error) != UR_OK) {
        cli_message("analyze: --report %s: %s", job->report_path, error.message);
        return cli_exit_status(&error);
    }
    return 0;
}

int cli_analyze(const ur_job *job)
{
    if (!outputs_possible(job))
        return EXIT_IO;
    ur_ruled ruled;
    ur_job_callbacks callbacks = cli_callbacks(job);
    ur_error error;
    if (ur_job_surface_with_curves(job, &callbacks, &ruled, &error) != UR_OK) {
        cli_error(NULL, &error);
        return cli_exit_status(&error);
    }
    int code = 0;
    ur_analysis analysis;
    memset(&analysis, 0, sizeof analysis);
    if (!code && ur_analyze(&ruled, NULL, &analysis, &error) != UR_OK) {
        cli_error("analyze", &error);
        code = cli_exit_status(&error);
    }
    if (!code) {
        print_analysis(job, &ruled, &analysis);
        code = analysis_outputs(job, &ruled, &analysis);
    }
    ur_analysis_free(&analysis);
    ur_ruled_free(&ruled);
    return code;
}

/* ---- compare ------------------------------------------------------------ */

enum { COMPARE_FIRST = 8, COMPARE_LAST = 4096 };

static void print_table(const ur_job *job, const ur_compare_table *table)
{
    FILE *out = findings(job);
    fprintf(out,
            "%s: surface %.8g mm2; relative area error (net - surface) / surface, largest "
            "relative rail length error, largest distance to the exact net (mm)\n",
            job->surface, table->area_3d);
    fprintf(out, "%6s %12s %12s %12s %11s %11s %11s %11s %11s\n", "n", "triangle", "quad", "exact",
            "tri edge", "quad edge", "exact edge", "tri dist", "quad dist");
    for (size_t k = 0; k < table->count; k++) {
        const ur_compare_row *row = &table->rows[k];
        fprintf(out, "%6zu %12.4e %12.4e %12.4e %11.3e %11.3e %11.3e %11.3e %11.3e\n", row->n,
                row->area_error[UR_COMPARE_TRIANGLE], row->area_error[UR_COMPARE_QUAD],
                row->area_error[UR_COMPARE_EXACT], row->edge_error[UR_COMPARE_TRIANGLE],
                row->edge_error[UR_COMPARE_QUAD], row->edge_error[UR_COMPARE_EXACT],
                row->distance[UR_COMPARE_TRIANGLE], row->distance[UR_COMPARE_QUAD]);
    }
}

int cli_compare(const ur_job *job)
{
    if (!outputs_possible(job))
        return EXIT_IO;
    ur_ruled ruled;
    ur_job_callbacks callbacks = cli_callbacks(job);
    ur_error error;
    if (ur_job_surface(job, &callbacks, &ruled, &error) != UR_OK) {
        cli_error(NULL, &error);
        return cli_exit_status(&error);
    }
    int code = 0;
    ur_compare_table table = {NULL, 0, 0.0};
    ur_status status = ur_ruled_check(&ruled, &error);
    if (status == UR_OK)
        status = ur_compare(&ruled, COMPARE_FIRST, COMPARE_LAST, &table, &error);
    char title[256];
    snprintf(title, sizeof title, "unroll compare %s: discrete nets against the exact net",
             job->surface);
    if (status == UR_OK) {
        print_table(job, &table);
        if (job->csv_path)
            status = ur_compare_csv_write(job->csv_path, &table, cli_context(), &error);
    }
    if (status == UR_OK && job->png_path)
        status = ur_compare_plot_png(job->png_path, &table, title, cli_context(), &error);
    if (status != UR_OK) {
        cli_error("compare", &error);
        code = cli_exit_status(&error);
    }
    ur_compare_table_free(&table);
    ur_ruled_free(&ruled);
    return code;
}
