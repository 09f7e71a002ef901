/*
 * surface_options.c: the settings of a surface job: the surface's
 * parameters (each for the surfaces it applies to), how a mesh is read,
 * how the surface becomes pieces (method, rulings, flattening, strain)
 * and what goes on them (allowances, bridges), the pictures beside the cut
 * files, and the analyses' files.  Each value is checked here, with a
 * message that says what is wrong with it (the caller names the setting).
 */
#include "options.h"

#include "unroll/flatten.h"

#include "../base/c_locale.h"

#include <math.h>
#include <stddef.h>
#include <string.h>
#include <strings.h>

/* A number setting is the ur_job field at its offset. */
static ur_status set_number_at(ur_job *job, size_t offset, const char *value, ur_error *error)
{
    return job_number(value, (double *)((char *)job + offset), error);
}

#define NUMBER_SETTER(function, field)                                                             \
    static ur_status function(ur_job *job, const char *value, ur_error *error)                     \
    {                                                                                              \
        return set_number_at(job, offsetof(ur_job, field), value, error);                          \
    }

NUMBER_SETTER(set_radius, radius)
NUMBER_SETTER(set_height, height)
NUMBER_SETTER(set_top_radius, top_radius)
NUMBER_SETTER(set_cut, cut)
NUMBER_SETTER(set_pitch, pitch)
NUMBER_SETTER(set_turns, turns)
NUMBER_SETTER(set_width, width)
NUMBER_SETTER(set_offset, offset)
NUMBER_SETTER(set_scale, scale)

/* A path setting is the ur_job field at its offset. */
#define PATH_SETTER(function, field)                                                               \
    static ur_status function(ur_job *job, const char *value, ur_error *error)                     \
    {                                                                                              \
        (void)error;                                                                               \
        job->field = value;                                                                        \
        return UR_OK;                                                                              \
    }

PATH_SETTER(set_curve, curve_path)
PATH_SETTER(set_rail1, rail_paths[0])
PATH_SETTER(set_rail2, rail_paths[1])
PATH_SETTER(set_regression, regression_path)
PATH_SETTER(set_adjusted_rail, adjusted_rail_path)
PATH_SETTER(set_adjusted_rail1, adjusted_rail1_path)
PATH_SETTER(set_strain_png, strain_png_path)
PATH_SETTER(set_png, png_path)
PATH_SETTER(set_csv, csv_path)

static ur_status set_vector(const char *value, ur_vec3 *vector, bool *given, ur_error *error)
{
    if (!job_scan_vector(value, '\0', vector))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not three numbers X,Y,Z (each at most %g)", value,
                            UR_LENGTH_MAX);
    *given = true;
    return UR_OK;
}

static ur_status set_direction(ur_job *job, const char *value, ur_error *error)
{
    return set_vector(value, &job->direction, &job->has_direction, error);
}

static ur_status set_apex(ur_job *job, const char *value, ur_error *error)
{
    return set_vector(value, &job->apex, &job->has_apex, error);
}

/* A direction the rails move along, or a normal of the planes they move in: not zero. */
static ur_status set_nonzero_vector(const char *value, ur_vec3 *vector, bool *given,
                                    ur_error *error)
{
    ur_status status = set_vector(value, vector, given, error);
    if (status == UR_OK && !(ur_vec3_length(*vector) > 0)) {
        *given = false;
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' must not be zero", value);
    }
    return status;
}

static ur_status set_adjust_direction(ur_job *job, const char *value, ur_error *error)
{
    return set_nonzero_vector(value, &job->adjust_direction, &job->has_adjust_direction, error);
}

static ur_status set_adjust_plane(ur_job *job, const char *value, ur_error *error)
{
    return set_nonzero_vector(value, &job->adjust_plane, &job->has_adjust_plane, error);
}

static ur_status set_corners(ur_job *job, const char *value, ur_error *error)
{
    const char *rest = value;
    for (int k = 0; k < 4 && rest; k++)
        rest = job_scan_vector(rest, k < 3 ? ':' : '\0', &job->corners[k]);
    if (!rest)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not four corners X,Y,Z:X,Y,Z:X,Y,Z:X,Y,Z (each number at "
                            "most %g)",
                            value, UR_LENGTH_MAX);
    job->has_corners = true;
    return UR_OK;
}

static ur_status set_pairing(ur_job *job, const char *value, ur_error *error)
{
    if (strcmp(value, "natural") != 0 && strcmp(value, "developable") != 0)
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not one of natural, developable",
                            value);
    job->natural_pairing = strcmp(value, "natural") == 0;
    return UR_OK;
}

static ur_status set_strict(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->strict = true;
    return UR_OK;
}

static ur_status set_fewer_pieces(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->fewer_pieces = true;
    return UR_OK;
}

/* The angle in degrees, 0 or more and less than 180, below which folds are not drawn. */
static ur_status set_hide_folds(ur_job *job, const char *value, ur_error *error)
{
    double degrees;
    ur_status status = job_number(value, &degrees, error);
    if (status != UR_OK)
        return status;
    if (!(degrees >= 0 && degrees < 180))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not an angle in degrees, 0 or more and less than 180", value);
    job->hide_folds = degrees;
    return UR_OK;
}

/* The unfolding search's steps, from 1 to 1,000,000. */
static ur_status set_unfold_steps(ur_job *job, const char *value, ur_error *error)
{
    return job_count(value, 1000000, &job->unfold_steps, error);
}

/* rail1, rail2 or both: the rails a strip reshapes. */
static ur_status set_adjust(ur_job *job, const char *value, ur_error *error)
{
    const char *names[] = {"rail1", "rail2", "both"};
    for (unsigned k = 0; k < 3; k++)
        if (strcmp(value, names[k]) == 0) {
            job->adjust_rails = k + 1;
            return UR_OK;
        }
    return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not one of rail1, rail2, both", value);
}

/* As it was before adjust: rail 2 moves, its ends too when they must. */
static ur_status set_adjust_rail2(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->adjust_rails = UR_REPAIR_RAIL2;
    job->adjust_ends = true;
    return UR_OK;
}

static ur_status set_adjust_ends(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->adjust_ends = true;
    return UR_OK;
}

static ur_status set_adjust_max(ur_job *job, const char *value, ur_error *error)
{
    double largest;
    ur_status status = job_number(value, &largest, error);
    if (status != UR_OK)
        return status;
    if (!(largest > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a positive number of mm", value);
    job->adjust_max = largest;
    return UR_OK;
}

/* Which layer of the material the 3D surface is. */
static ur_status set_surface_layer(ur_job *job, const char *value, ur_error *error)
{
    int layer = ur_surface_layer_from_name(value);
    if (layer < 0)
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not one of outer, inner, mid, neutral",
                            value);
    job->surface_layer = layer;
    return UR_OK;
}

static ur_status set_units(ur_job *job, const char *value, ur_error *error)
{
    if (ur_length_unit_from_name(value) < 0)
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not one of mm, cm, m, in", value);
    job->unit_name = value;
    return UR_OK;
}

/* One more seam file (the setting repeats). */
static ur_status set_seams(ur_job *job, const char *value, ur_error *error)
{
    size_t most = sizeof job->seam_paths / sizeof job->seam_paths[0];
    if (job->seam_count == most)
        return ur_error_set(error, UR_ERROR_INPUT, "at most %zu seam files", most);
    job->seam_paths[job->seam_count++] = value;
    return UR_OK;
}

/* charts (a mesh's default: flatten -1, as when none is given), arap, lscm, strips, unfold. */
static ur_status set_flatten(ur_job *job, const char *value, ur_error *error)
{
    bool charts = strcmp(value, "charts") == 0, unfold = strcmp(value, "unfold") == 0;
    bool strips = strcmp(value, "strips") == 0;
    int method = unfold || strips || charts ? -1 : ur_flatten_method_from_name(value);
    if (method < 0 && !unfold && !strips && !charts)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not one of charts, arap, lscm, strips, unfold", value);
    if ((unfold || charts) && !(job->surface && strcmp(job->surface, "mesh") == 0))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is for meshes (it cuts a mesh along its edges)", value);
    job->unfold = unfold;
    job->strips = strips;
    job->flatten = method;
    return UR_OK;
}

static ur_status set_iterations(ur_job *job, const char *value, ur_error *error)
{
    return job_count(value, 100000, &job->iterations, error);
}

static ur_status set_max_strain(ur_job *job, const char *value, ur_error *error)
{
    double strain;
    ur_status status = job_number(value, &strain, error);
    if (status != UR_OK)
        return status;
    if (!(strain > 0 && strain < 1))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not a fraction between 0 and 1 (0.01 is 1 %%)", value);
    job->max_strain = strain;
    return UR_OK;
}

/* The assembly guide's file: its extension says the format, and only two are drawn. */
static ur_status set_assembly(ur_job *job, const char *value, ur_error *error)
{
    size_t length = strlen(value);
    const char *extension = length > 4 ? value + length - 4 : "";
    if (strcasecmp(extension, ".png") != 0 && strcasecmp(extension, ".pdf") != 0)
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not a .png or .pdf file name (the assembly guide is a "
                            "picture or a PDF)",
                            value);
    job->assembly_path = value;
    return UR_OK;
}

static ur_status set_assembly_up(ur_job *job, const char *value, ur_error *error)
{
    if (strcmp(value, "auto") == 0)
        job->assembly_up = UR_UP_AUTO;
    else if (strcmp(value, "y") == 0)
        job->assembly_up = UR_UP_Y;
    else if (strcmp(value, "z") == 0)
        job->assembly_up = UR_UP_Z;
    else
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not auto, y or z (the axis that points up)", value);
    return UR_OK;
}

static ur_status set_method(ur_job *job, const char *value, ur_error *error)
{
    int method = ur_method_from_name(value);
    if (method < 0)
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not one of exact, triangle, quad",
                            value);
    job->develop.method = (ur_method)method;
    return UR_OK;
}

/* How many rulings (and so strips or triangles) the development has. */
static ur_status set_parts(ur_job *job, const char *value, ur_error *error)
{
    return job_count(value, 10000000, &job->develop.rulings, error);
}

static ur_status set_rulings(ur_job *job, const char *value, ur_error *error)
{
    (void)value;
    (void)error;
    job->draw_rulings = true;
    return UR_OK;
}

static ur_status set_tolerance(ur_job *job, const char *value, ur_error *error)
{
    double tolerance;
    ur_status status = job_number(value, &tolerance, error);
    if (status != UR_OK)
        return status;
    if (!(tolerance > 0))
        return ur_error_set(error, UR_ERROR_INPUT, "'%s' is not a positive number", value);
    job->develop.tolerance = tolerance;
    return UR_OK;
}

static const struct {
    const char *name;
    unsigned bit;
} allowance_names[] = {
    {"tabs", UR_ALLOW_TABS},       {"kerfing", UR_ALLOW_KERFING}, {"overlaps", UR_ALLOW_OVERLAPS},
    {"bending", UR_ALLOW_BENDING}, {"bridges", UR_ALLOW_BRIDGES},
};

/* One name of a list, length bytes long, into *bits. */
static ur_status add_allowance(const char *name, size_t length, unsigned *bits, ur_error *error)
{
    for (size_t k = 0; k < sizeof allowance_names / sizeof allowance_names[0]; k++)
        if (strlen(allowance_names[k].name) == length &&
            strncmp(allowance_names[k].name, name, length) == 0) {
            *bits |= allowance_names[k].bit;
            return UR_OK;
        }
    return ur_error_set(error, UR_ERROR_INPUT,
                        "'%.*s' is not one of tabs, kerfing, overlaps, bending, bridges (or give "
                        "auto or none)",
                        (int)length, name);
}

/* auto, none, or a comma-separated list of allowances. */
static ur_status set_allowances(ur_job *job, const char *value, ur_error *error)
{
    unsigned bits = 0;
    bool automatic = strcmp(value, "auto") == 0;
    if (!automatic && strcmp(value, "none") != 0)
        for (const char *start = value;;) {
            const char *comma = strchr(start, ',');
            size_t length = comma ? (size_t)(comma - start) : strlen(start);
            ur_status status = add_allowance(start, length, &bits, error);
            if (status != UR_OK)
                return status;
            if (!comma)
                break;
            start = comma + 1;
        }
    job->allowances = bits;
    job->allowances_auto = automatic;
    return UR_OK;
}

static ur_status set_bridges(ur_job *job, const char *value, ur_error *error)
{
    long count;
    if (strcmp(value, "auto") == 0)
        count = -1;
    else if (strcmp(value, "none") == 0)
        count = 0;
    else if (!job_whole_number(value, 1, 1000, &count))
        return ur_error_set(error, UR_ERROR_INPUT,
                            "'%s' is not auto, none or a count from 1 to 1000", value);
    job->bridges = count;
    return UR_OK;
}

/* The surfaces each surface setting applies to. */
#define CYLINDER_CONE " cylinder cone "
#define STRIP " strip "
#define FLATTENED " strip ruled hypar mesh "
#define DEVELOPED " cylinder cone helicoid tangent strip ruled hypar "

/* Every setting of the surface and of how it becomes pieces, described once. */
const job_setting job_surface_settings[] = {
    {"radius", true, UR_JOB_OPTION_SURFACE, " cylinder cone helicoid ", set_radius},
    {"height", true, UR_JOB_OPTION_SURFACE, CYLINDER_CONE, set_height},
    {"top-radius", true, UR_JOB_OPTION_SURFACE, " cone ", set_top_radius},
    {"curve", true, UR_JOB_OPTION_SURFACE, " cylinder cone tangent ", set_curve},
    {"direction", true, UR_JOB_OPTION_SURFACE, " cylinder ", set_direction},
    {"apex", true, UR_JOB_OPTION_SURFACE, " cone ", set_apex},
    {"cut", true, UR_JOB_OPTION_SURFACE, " cone ", set_cut},
    {"pitch", true, UR_JOB_OPTION_SURFACE, " helicoid ", set_pitch},
    {"turns", true, UR_JOB_OPTION_SURFACE, " helicoid ", set_turns},
    {"width", true, UR_JOB_OPTION_SURFACE, " helicoid tangent ", set_width},
    {"offset", true, UR_JOB_OPTION_SURFACE, " helicoid tangent ", set_offset},
    {"rail1", true, UR_JOB_OPTION_SURFACE, " strip ruled ", set_rail1},
    {"rail2", true, UR_JOB_OPTION_SURFACE, " strip ruled ", set_rail2},
    {"pairing", true, UR_JOB_OPTION_SURFACE, STRIP, set_pairing},
    {"strict", false, UR_JOB_OPTION_SURFACE, STRIP, set_strict},
    {"regression", true, UR_JOB_OPTION_SURFACE, STRIP, set_regression},
    {"adjust", true, UR_JOB_OPTION_SURFACE, STRIP, set_adjust},
    {"adjust-rail2", false, UR_JOB_OPTION_SURFACE, STRIP, set_adjust_rail2},
    {"adjust-direction", true, UR_JOB_OPTION_SURFACE, STRIP, set_adjust_direction},
    {"adjust-plane", true, UR_JOB_OPTION_SURFACE, STRIP, set_adjust_plane},
    {"adjust-ends", false, UR_JOB_OPTION_SURFACE, STRIP, set_adjust_ends},
    {"adjust-max", true, UR_JOB_OPTION_SURFACE, STRIP, set_adjust_max},
    {"adjusted-rail", true, UR_JOB_OPTION_SURFACE, STRIP, set_adjusted_rail},
    {"adjusted-rail1", true, UR_JOB_OPTION_SURFACE, STRIP, set_adjusted_rail1},
    {"corners", true, UR_JOB_OPTION_SURFACE, " hypar ", set_corners},
    {"surface", true, UR_JOB_OPTION_SURFACE, DEVELOPED, set_surface_layer},
    {"units", true, UR_JOB_OPTION_SURFACE, " mesh ", set_units},
    {"scale", true, UR_JOB_OPTION_SURFACE, " mesh ", set_scale},
    {"seams", true, UR_JOB_OPTION_SURFACE, " mesh ", set_seams},
    {"flatten", true, UR_JOB_OPTION_SURFACE, FLATTENED, set_flatten},
    {"iterations", true, UR_JOB_OPTION_SURFACE, FLATTENED, set_iterations},
    {"max-strain", true, UR_JOB_OPTION_SURFACE, FLATTENED, set_max_strain},
    {"fewer-pieces", false, UR_JOB_OPTION_SURFACE, " mesh ", set_fewer_pieces},
    {"hide-folds", true, UR_JOB_OPTION_SURFACE, " mesh ", set_hide_folds},
    {"unfold-steps", true, UR_JOB_OPTION_SURFACE, " mesh ", set_unfold_steps},
    {"method", true, UR_JOB_OPTION_SURFACE, NULL, set_method},
    {"parts", true, UR_JOB_OPTION_SURFACE, NULL, set_parts},
    {"rulings", false, UR_JOB_OPTION_SURFACE, NULL, set_rulings},
    {"tolerance", true, UR_JOB_OPTION_SURFACE, NULL, set_tolerance},
    {"allowances", true, UR_JOB_OPTION_SURFACE, NULL, set_allowances},
    {"bridges", true, UR_JOB_OPTION_SURFACE, NULL, set_bridges},
    {"strain-png", true, UR_JOB_OPTION_SURFACE, NULL, set_strain_png},
    {"assembly", true, UR_JOB_OPTION_SURFACE, NULL, set_assembly},
    {"assembly-up", true, UR_JOB_OPTION_SURFACE, NULL, set_assembly_up},
    {"png", true, UR_JOB_OPTION_ANALYSIS, NULL, set_png},
    {"csv", true, UR_JOB_OPTION_ANALYSIS, NULL, set_csv},
};

const size_t job_surface_setting_count =
    sizeof job_surface_settings / sizeof job_surface_settings[0];
