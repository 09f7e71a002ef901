/*
 * report.c: the JSON report (jansson): what was unrolled, per piece its 3D
 * and flat area and how faithful the flat edges are, per sheet how well the
 * stock is used, and which files were written.
 *
 * Numbers that cannot be computed (a coverage of a piece without 3D area, a
 * NaN from upstream) are written as null: JSON has no NaN, and a reader is
 * better served by "unknown" than by a made-up 0.
 */
#include "unroll/out.h"

#include <errno.h>
#include <jansson.h>
#include <math.h>
#include <string.h>

#include "json.h"

static json_t *text_or_null(const char *text)
{
    return text ? json_string(text) : json_null();
}

/* A fixed-size name that may fill its array without a terminator. */
static json_t *name_of(const char *name, size_t size)
{
    return json_stringn(name, strnlen(name, size));
}

/* The 1-based sheet a piece is placed on, 0 when it is on none. */
static size_t sheet_of(const ur_layout *layout, size_t piece_index)
{
    for (size_t s = 0; layout && s < layout->sheet_count; s++)
        for (size_t p = 0; p < layout->sheets[s].placement_count; p++)
            if (layout->sheets[s].placements[p].piece_index == piece_index)
                return s + 1;
    return 0;
}

static json_t *box_json(ur_box box)
{
    json_t *object = json_object();
    bool known = box.min.x <= box.max.x && box.min.y <= box.max.y; /* not empty */
    if (!object ||
        json_object_set_new(object, "width_mm",
                            known ? json_number(ur_box_width(box)) : json_null()) != 0 ||
        json_object_set_new(object, "height_mm",
                            known ? json_number(ur_box_height(box)) : json_null()) != 0) {
        json_decref(object);
        return NULL;
    }
    return object;
}

/* A figure of a record, or null where it has none (NAN). */
static json_t *figure_json(double value)
{
    return isnan(value) ? json_null() : json_number(value);
}

static json_t *record_json(const ur_allowance_record *record)
{
    json_t *object = json_object();
    json_t *where = json_pack("[ff]", record->where.x, record->where.y);
    if (!object || !where ||
        json_object_set_new(object, "kind", json_string(ur_allowance_kind_name(record->kind))) !=
            0 ||
        json_object_set_new(object, "count", json_integer((json_int_t)record->count)) != 0 ||
        json_object_set_new(object, "value", figure_json(record->value)) != 0 ||
        json_object_set_new(object, "limit", figure_json(record->limit)) != 0 ||
        json_object_set_new(object, "at_mm", where) != 0 ||
        json_object_set_new(object, "warning", json_boolean(record->warning)) != 0 ||
        (record->kind == UR_ALLOWANCE_BENDING &&
         (json_object_set_new(object, "facet_angle_degrees", json_number(record->facet_angle)) !=
              0 ||
          json_object_set_new(object, "rows", json_integer((json_int_t)record->rows)) != 0)) ||
        json_object_set_new(object, "reason", name_of(record->reason, sizeof record->reason)) !=
            0) {
        if (!object)
            json_decref(where);
        json_decref(object);
        return NULL;
    }
    return object;
}

/* What was added to the piece and why, in the order it was added. */
static json_t *records_json(const ur_piece *piece)
{
    json_t *array = json_array();
    for (size_t i = 0; array && i < piece->record_count; i++)
        if (json_array_append_new(array, record_json(&piece->records[i])) != 0) {
            json_decref(array);
            return NULL;
        }
    return array;
}

/* The names of the pieces left off the sheets (--sheets N). */
static json_t *not_placed_json(const ur_layout *layout, const ur_piece *pieces)
{
    json_t *array = json_array();
    for (size_t k = 0; array && layout && k < layout->not_placed_count; k++) {
        const ur_piece *piece = &pieces[layout->not_placed[k]];
        if (json_array_append_new(array, name_of(piece->name, sizeof piece->name)) != 0) {
            json_decref(array);
            return NULL;
        }
    }
    return array;
}

/* A count, or null when it is 0: not known for this kind of piece. */
static json_t *count_or_null(size_t count)
{
    return count > 0 ? json_integer((json_int_t)count) : json_null();
}

/* json_object_set_new takes value even when it fails, so nothing leaks here. */
static json_t *piece_json(const ur_piece *piece, size_t sheet)
{
    const ur_piece_measures *m = &piece->measures;
    json_t *object = json_object();
    if (!object ||
        json_object_set_new(object, "name", name_of(piece->name, sizeof piece->name)) != 0 ||
        json_object_set_new(object, "area_3d_mm2", json_number(m->area_3d)) != 0 ||
        json_object_set_new(object, "flat_area_mm2", json_number(m->flat_area)) != 0 ||
        json_object_set_new(object, "coverage",
                            m->area_3d > 0 ? json_number(m->flat_area / m->area_3d)
                                           : json_null()) != 0 ||
        json_object_set_new(object, "bounding_box", box_json(piece->box)) != 0 ||
        json_object_set_new(object, "edge_length_error", json_number(m->edge_error)) != 0 ||
        json_object_set_new(object, "max_stretch", json_number(m->max_stretch)) != 0 ||
        json_object_set_new(object, "max_compression", json_number(m->max_compression)) != 0 ||
        json_object_set_new(object, "triangles", count_or_null(m->triangle_count)) != 0 ||
        json_object_set_new(object, "faces", count_or_null(m->polygon_count)) != 0 ||
        json_object_set_new(object, "allowances", records_json(piece)) != 0 ||
        json_object_set_new(object, "sheet",
                            sheet ? json_integer((json_int_t)sheet) : json_null()) != 0) {
        json_decref(object);
        return NULL;
    }
    return object;
}

static json_t *pieces_json(const ur_piece *pieces, size_t piece_count, const ur_layout *layout)
{
    json_t *array = json_array();
    for (size_t i = 0; array && i < piece_count; i++)
        if (json_array_append_new(array, piece_json(&pieces[i], sheet_of(layout, i))) != 0) {
            json_decref(array);
            return NULL;
        }
    return array;
}

/* The file a sheet went to, when the context says what the cut files are called. */
static ur_status sheet_file(const ur_report_context *context, const ur_layout *layout, size_t index,
                            json_t **file, ur_error *error)
{
    *file = NULL;
    if (!context->sheet_path)
        return UR_OK;
    char name[4096];
    ur_status status = ur_sheet_file_name(context->sheet_path, index, layout->sheet_count, name,
                                          sizeof name, error);
    if (status != UR_OK)
        return status;
    *file = json_string(name);
    return *file ? UR_OK : ur_error_set(error, UR_ERROR_INPUT, "'%s' is not UTF-8", name);
}

/* Cut length, travel and time of the sheet cut as the files say (ur_sheet_cut_plan). */
static json_t *cutting_json(const ur_report_context *context, const ur_sheet *sheet,
                            const ur_piece *pieces)
{
    ur_cut_plan plan;
    ur_error error;
    if (ur_sheet_cut_plan(sheet, pieces, ur_operation_order(), !context->drawing_order,
                          context->machine, &plan, &error) != UR_OK)
        return NULL;
    ur_cut_plan_free(&plan);
    return json_pack("{s:o, s:o, s:o}", "cut_length_mm", json_number(plan.cut_length), "travel_mm",
                     json_number(plan.travel_length), "time_s",
                     context->machine ? json_number(plan.seconds) : json_null());
}

/* The offcut the parts leave at the sheet's right end (nesting's last sheet), or null. */
static json_t *offcut_json(const ur_sheet *sheet)
{
    if (!(sheet->offcut_width > 0))
        return json_null();
    return json_pack("{s:o, s:o}", "width_mm", json_number(sheet->offcut_width), "height_mm",
                     json_number(sheet->height));
}

static json_t *sheet_json(const ur_report_context *context, const ur_layout *layout, size_t index,
                          const ur_piece *pieces)
{
    const ur_sheet *sheet = &layout->sheets[index];
    json_t *object = json_object();
    if (!object || json_object_set_new(object, "index", json_integer((json_int_t)index + 1)) != 0 ||
        json_object_set_new(object, "width_mm", json_number(sheet->width)) != 0 ||
        json_object_set_new(object, "height_mm", json_number(sheet->height)) != 0 ||
        json_object_set_new(object, "remnant", json_boolean(sheet->remnant)) != 0 ||
        json_object_set_new(object, "pieces", json_integer((json_int_t)sheet->placement_count)) !=
            0 ||
        json_object_set_new(object, "utilisation",
                            json_number(ur_sheet_utilisation(sheet, pieces))) != 0 ||
        json_object_update_new(object, cutting_json(context, sheet, pieces)) != 0 ||
        json_object_set_new(object, "offcut", offcut_json(sheet)) != 0 ||
        (sheet->material[0] &&
         json_object_set_new(object, "material",
                             name_of(sheet->material, sizeof sheet->material)) != 0)) {
        json_decref(object);
        return NULL;
    }
    return object;
}

static ur_status sheets_json(const ur_report_context *context, const ur_layout *layout,
                             const ur_piece *pieces, json_t **sheets, ur_error *error)
{
    *sheets = json_array();
    if (!*sheets)
        return ur_error_out_of_memory(error);
    for (size_t i = 0; layout && i < layout->sheet_count; i++) {
        json_t *sheet = sheet_json(context, layout, i, pieces);
        json_t *file = NULL;
        ur_status status =
            sheet ? sheet_file(context, layout, i, &file, error) : ur_error_out_of_memory(error);
        if (status == UR_OK && file && json_object_set_new(sheet, "file", file) != 0)
            status = ur_error_out_of_memory(error);
        if (status == UR_OK && json_array_append_new(*sheets, sheet) != 0)
            status = ur_error_out_of_memory(error);
        else if (status != UR_OK)
            json_decref(sheet);
        if (status != UR_OK) {
            json_decref(*sheets);
            *sheets = NULL;
            return status;
        }
    }
    return UR_OK;
}

static json_t *outputs_json(const char *const *outputs)
{
    json_t *array = json_array();
    for (size_t i = 0; array && outputs && outputs[i]; i++)
        if (json_array_append_new(array, json_string(outputs[i])) != 0) {
            json_decref(array);
            return NULL;
        }
    return array;
}

static json_t *layer_json(const ur_report_layer *layer)
{
    json_t *object = json_object();
    if (!object || json_object_set_new(object, "surface", text_or_null(layer->surface)) != 0 ||
        json_object_set_new(object, "developed", text_or_null(layer->developed)) != 0 ||
        json_object_set_new(object, "offset_mm", json_number(layer->offset)) != 0 ||
        json_object_set_new(object, "k_factor", json_number(layer->k_factor)) != 0 ||
        json_object_set_new(object, "thickness_mm", json_number(layer->thickness)) != 0) {
        json_decref(object);
        return NULL;
    }
    return object;
}

/* "rail_repair": how far the rails moved, where most, and the files of the moved rails. */
static json_t *repair_json(const ur_report_repair *repair)
{
    json_t *object = json_object(), *where = json_object();
    if (!object || !where ||
        json_object_set_new(where, "rail", json_integer(repair->largest_rail)) != 0 ||
        json_object_set_new(where, "point", json_integer((json_int_t)repair->largest_point + 1)) !=
            0 ||
        json_object_set_new(where, "position", json_point(repair->largest_position)) != 0 ||
        json_object_set_new(where, "along_mm", json_number(repair->largest_along)) != 0 ||
        json_object_set_new(object, "rails", text_or_null(repair->rails)) != 0 ||
        json_object_set_new(object, "largest_displacement_mm", json_number(repair->largest)) != 0 ||
        json_object_set_new(object, "mean_displacement_mm", json_number(repair->mean)) != 0 ||
        json_object_set(object, "largest_at", where) != 0 ||
        json_object_set_new(object, "adjusted_rail", text_or_null(repair->adjusted_rail)) != 0 ||
        json_object_set_new(object, "adjusted_rail1", text_or_null(repair->adjusted_rail1)) != 0) {
        json_decref(where);
        json_decref(object);
        return NULL;
    }
    json_decref(where); /* set without _new: object holds its own reference */
    return object;
}

/* The top-level object; on failure *root is NULL and error says why. */
static ur_status report_json(const ur_report_context *context, const ur_piece *pieces,
                             size_t piece_count, const ur_layout *layout, json_t **root,
                             ur_error *error)
{
    const ur_machine *machine = context->machine;
    const ur_material *material = context->material;
    json_t *sheets = NULL;
    ur_status status = sheets_json(context, layout, pieces, &sheets, error);
    if (status != UR_OK) {
        *root = NULL;
        return status;
    }
    *root = json_object();
    if (!*root || json_object_set_new(*root, "unroll", json_string(UR_VERSION)) != 0 ||
        json_object_set_new(*root, "surface", text_or_null(context->surface)) != 0 ||
        json_object_set_new(*root, "method", text_or_null(context->method)) != 0 ||
        json_object_set_new(*root, "machine",
                            machine ? name_of(machine->name, sizeof machine->name) : json_null()) !=
            0 ||
        json_object_set_new(*root, "material",
                            material ? name_of(material->name, sizeof material->name)
                                     : json_null()) != 0 ||
        json_object_set_new(*root, "surface_area_mm2", json_number(context->surface_area)) != 0 ||
        json_object_set_new(*root, "pieces", pieces_json(pieces, piece_count, layout)) != 0 ||
        json_object_set(*root, "sheets", sheets) != 0 ||
        json_object_set_new(*root, "outputs", outputs_json(context->outputs)) != 0 ||
        json_object_set_new(*root, "not_placed", not_placed_json(layout, pieces)) != 0 ||
        json_object_set_new(*root, "domain_gaps",
                            json_intervals(context->gaps, context->gap_count)) != 0) {
        json_decref(sheets);
        json_decref(*root);
        *root = NULL;
        /* jansson refuses strings that are not UTF-8 the same way as no memory. */
        return ur_error_set(error, UR_ERROR_INTERNAL,
                            "cannot build the report: out of memory or a name not in UTF-8");
    }
    json_decref(sheets); /* set without _new: root holds its own reference */
    if (context->sheets_lower_bound > 0 &&
        json_object_set_new(*root, "sheets_lower_bound",
                            json_integer((json_int_t)context->sheets_lower_bound)) != 0) {
        json_decref(*root);
        *root = NULL;
        return ur_error_out_of_memory(error);
    }
    if (context->layer && json_object_set_new(*root, "layer", layer_json(context->layer)) != 0) {
        json_decref(*root);
        *root = NULL;
        return ur_error_out_of_memory(error);
    }
    if (context->repair &&
        json_object_set_new(*root, "rail_repair", repair_json(context->repair)) != 0) {
        json_decref(*root);
        *root = NULL;
        return ur_error_out_of_memory(error);
    }
    return UR_OK;
}

/* Placements must name pieces that exist: the report reads each of them. */
static ur_status check_layout(const ur_layout *layout, size_t piece_count, ur_error *error)
{
    for (size_t s = 0; layout && s < layout->sheet_count; s++)
        for (size_t p = 0; p < layout->sheets[s].placement_count; p++)
            if (layout->sheets[s].placements[p].piece_index >= piece_count)
                return ur_error_set(error, UR_ERROR_INTERNAL,
                                    "sheet %zu places piece %zu of only %zu", s + 1,
                                    layout->sheets[s].placements[p].piece_index + 1, piece_count);
    return UR_OK;
}

/* To path, or to stream when path is NULL. */
static ur_status write_report(const char *path, FILE *stream, const ur_report_context *context,
                              const ur_piece *pieces, size_t piece_count, const ur_layout *layout,
                              ur_context *run, ur_error *error)
{
    if ((!path && !stream) || !context || (!pieces && piece_count > 0))
        return ur_error_set(error, UR_ERROR_INTERNAL, "report writer called without %s",
                            !path && !stream ? "a path"
                            : !context       ? "a context"
                                             : "pieces");
    ur_status status = check_layout(layout, piece_count, error);
    json_t *root = NULL;
    if (status == UR_OK)
        status = report_json(context, pieces, piece_count, layout, &root, error);
    if (status == UR_OK)
        status = path ? json_write(path, root, run, error) : json_write_stream(stream, root, error);
    json_decref(root);
    return status;
}

ur_status ur_report_write(const char *path, const ur_report_context *context,
                          const ur_piece *pieces, size_t piece_count, const ur_layout *layout,
                          ur_context *run, ur_error *error)
{
    if (!path)
        return ur_error_set(error, UR_ERROR_INTERNAL, "report writer called without a path");
    return write_report(path, NULL, context, pieces, piece_count, layout, run, error);
}

ur_status ur_report_write_stream(FILE *stream, const ur_report_context *context,
                                 const ur_piece *pieces, size_t piece_count,
                                 const ur_layout *layout, ur_error *error)
{
    return write_report(NULL, stream, context, pieces, piece_count, layout, NULL, error);
}
