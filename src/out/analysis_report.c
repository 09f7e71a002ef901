/*
 * analysis_report.c: the JSON report of 'unroll analyze': the verdict, the
 * curvature figures, the domain of existence and every ruling analysed.
 */
#include "unroll/out.h"

#include "json.h"

static json_t *ruling_json(const ur_ruling_analysis *ruling)
{
    json_t *item = json_object();
    if (!item || json_object_set_new(item, "u", json_number(ruling->u)) != 0 ||
        json_object_set_new(item, "arc_mm", json_number(ruling->arc)) != 0 ||
        json_object_set_new(item, "near", json_point(ruling->near)) != 0 ||
        json_object_set_new(item, "far", json_point(ruling->far)) != 0 ||
        json_object_set_new(item, "in_gap", json_boolean(ruling->in_gap)) != 0 ||
        json_object_set_new(item, "residual_rad", json_number(ruling->residual)) != 0 ||
        json_object_set_new(item, "gaussian_min", json_number(ruling->gaussian_min)) != 0 ||
        json_object_set_new(item, "gaussian_max", json_number(ruling->gaussian_max)) != 0 ||
        json_object_set_new(item, "bend_radius_mm", json_number(ruling->bend_radius)) != 0 ||
        json_object_set_new(item, "regression_v", json_number(ruling->striction_v)) != 0) {
        json_decref(item);
        return NULL;
    }
    return item;
}

static json_t *rulings_json(const ur_analysis *analysis)
{
    json_t *array = json_array();
    for (size_t k = 0; array && k < analysis->ruling_count; k++)
        if (json_array_append_new(array, ruling_json(&analysis->rulings[k])) != 0) {
            json_decref(array);
            return NULL;
        }
    return array;
}

ur_status ur_analysis_report_write(const char *path, const char *surface, ur_ruled *ruled,
                                   const ur_analysis *analysis, ur_context *context,
                                   ur_error *error)
{
    const ur_interval *gaps;
    size_t gap_count = ur_ruled_gaps(ruled, &gaps);
    json_t *gaussian = json_pack(
        "{s:o, s:o, s:o, s:o, s:o}", "min", json_number(analysis->gaussian_min), "min_at",
        json_point(analysis->gaussian_min_at), "max", json_number(analysis->gaussian_max), "max_at",
        json_point(analysis->gaussian_max_at), "mean", json_number(analysis->gaussian_mean));
    json_t *root = json_object();
    if (!gaussian || !root || json_object_set_new(root, "unroll", json_string(UR_VERSION)) != 0 ||
        json_object_set_new(root, "surface", json_string(surface)) != 0 ||
        json_object_set_new(root, "developable", json_boolean(analysis->developable)) != 0 ||
        json_object_set_new(root, "max_residual_rad", json_number(analysis->max_residual)) != 0 ||
        json_object_set_new(root, "area_mm2", json_number(analysis->area_3d)) != 0 ||
        json_object_set(root, "gaussian_curvature", gaussian) != 0 ||
        json_object_set_new(root, "min_bend_radius_mm", json_number(analysis->min_bend_radius)) !=
            0 ||
        json_object_set_new(root, "min_bend_at", json_point(analysis->min_bend_at)) != 0 ||
        json_object_set_new(root, "domain_gaps", json_intervals(gaps, gap_count)) != 0 ||
        json_object_set_new(root, "rulings", rulings_json(analysis)) != 0) {
        json_decref(gaussian);
        json_decref(root);
        return ur_error_out_of_memory(error);
    }
    json_decref(gaussian);
    ur_status status = json_write(path, root, context, error);
    json_decref(root);
    return status;
}
