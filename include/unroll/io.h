/*
 * unroll/io.h: reading what the user gives: curves as CSV and the machine and
 * material profiles (XML validated against RelaxNG schemas).
 *
 * Every error message names the file and, where there is one, the line:
 * "FILE:LINE: message".
 */
#ifndef UNROLL_IO_H
#define UNROLL_IO_H

#include <stdbool.h>
#include <stddef.h>

#include "unroll/base.h"
#include "unroll/geom.h"

/* ---- Curves ------------------------------------------------------------ */

/*
 * Reads "x,y,z" per line; '#' starts a comment, blank lines are skipped.  A
 * last point equal to the first marks a closed curve: it is dropped and
 * *closed set.  Refuses fewer than 4 points, non-numeric, NaN or infinite
 * coordinates and a point equal to the one before it.  The caller frees
 * *points with free().
 */
ur_status ur_curve_csv_read(const char *path, ur_vec3 **points, size_t *count, bool *closed,
                            ur_error *error);

/* Writes points as CSV, atomically (temporary file, then rename). */
ur_status ur_curve_csv_write(const char *path, const ur_vec3 *points, size_t count,
                             ur_error *error);

/* ---- Profiles ---------------------------------------------------------- */

typedef struct ur_op_style {
    char layer[64];    /* layer name shown in the cutter software */
    char colour[8];    /* "#RRGGBB" */
    double line_width; /* stroke width in mm */
} ur_op_style;

typedef enum ur_machine_kind { UR_MACHINE_LASER, UR_MACHINE_ROUTER } ur_machine_kind;

typedef struct ur_machine {
    char name[64]; /* the file name without .xml */
    char description[256];
    char source[1024]; /* the file it was read from */
    ur_machine_kind kind;
    double bed_width, bed_height; /* mm */
    double kerf;                  /* mm: beam width or bit diameter */
    double margin;                /* mm kept free along sheet edges */
    double spacing;               /* mm kept free between parts */
    double cut_speed;             /* mm/s */
    double travel_speed;          /* mm/s */
    ur_op_style styles[UR_OP_COUNT];
} ur_machine;

typedef struct ur_sheet_size {
    double width, height; /* mm */
} ur_sheet_size;

typedef enum ur_grain_rule {
    UR_GRAIN_NONE,   /* no grain: any rotation */
    UR_GRAIN_ALONG,  /* rulings (bending axes) along the grain */
    UR_GRAIN_ACROSS, /* rulings across the grain */
} ur_grain_rule;

#define UR_MAX_STOCK_SIZES 8

typedef struct ur_material {
    char name[64];
    char description[256];
    char source[1024];
    double thickness;                        /* mm */
    ur_sheet_size stock[UR_MAX_STOCK_SIZES]; /* first is the default */
    int stock_count;
    double kerf_laser;               /* mm, overrides the machine's; 0 when not given */
    double kerf_router;              /* likewise */
    double bend_radius_with_grain;   /* mm: smallest radius without cracking */
    double bend_radius_across_grain; /* mm */
    double max_stretch;              /* allowed strain, e.g. 0.01 for 1 % */
    double max_compression;          /* allowed strain */
    double k_factor;                 /* neutral layer position, 0..1 of thickness */
    double tab_depth;                /* glue tab depth, mm */
    double tab_angle;                /* taper of the tab sides, degrees */
    ur_grain_rule grain;
    double grain_tolerance;  /* degrees */
    double hinge_cut_length; /* living hinge: slit length, mm */
    double hinge_connection; /* uncut bridge between slits, mm */
    double hinge_distance;   /* distance between slit rows, mm */
} ur_material;

/* "machines" or "materials": the sub-folder of a profile root. */
typedef enum ur_profile_kind { UR_PROFILE_MACHINE, UR_PROFILE_MATERIAL } ur_profile_kind;

/*
 * Profile roots, searched in order: ./profiles, then $UNROLL_PROFILES, then
 * the installed share directory (UR_PROFILE_DIR at build time).  A profile
 * NAME is the file ROOT/machines/NAME.xml or ROOT/materials/NAME.xml; the
 * schemas are ROOT/schema/machine.rng and ROOT/schema/material.rng, taken
 * from the first root that has them.
 */
ur_status ur_profile_find(ur_profile_kind kind, const char *name, char *path, size_t path_size,
                          ur_error *error);

/* Reads and validates one profile file. */
ur_status ur_machine_read(const char *path, ur_machine *machine, ur_error *error);
ur_status ur_material_read(const char *path, ur_material *material, ur_error *error);

/* Finds NAME on the search path, then reads it. */
ur_status ur_machine_load(const char *name, ur_machine *machine, ur_error *error);
ur_status ur_material_load(const char *name, ur_material *material, ur_error *error);

/* One entry of a listing of every profile on the search path. */
typedef struct ur_profile_entry {
    ur_profile_kind kind;
    char name[64];
    char description[256];
    char source[1024];
} ur_profile_entry;

/*
 * Lists every profile found (a name found in an earlier root hides the same
 * name in later ones), sorted by kind then name.  The caller frees *entries.
 */
ur_status ur_profile_list(ur_profile_entry **entries, size_t *count, ur_error *error);

/* The kerf a machine cuts in a material: the material's figure if it has one. */
double ur_effective_kerf(const ur_machine *machine, const ur_material *material);

#endif
