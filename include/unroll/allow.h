/*
 * unroll/allow.h: pieces, i.e. what will be cut, and the fabrication
 * allowances that turn a flat net into them.
 *
 * A piece is a set of paths in its own plane coordinates (millimetres, y up),
 * each tagged with the operation the cutter performs on it: the net's
 * outline (CUT), its rulings and folds (SCORE), and what the material needs
 * to take the 3D shape again (docs/design.md, section 5): joints and labels
 * on seams, kerfing cuts, overlap allowances, bending kerfs, kerf compensation
 * and holding bridges.  Each allowance added is recorded on the piece with
 * the reason for it, for the report.
 *
 * The order the pipeline applies them: kerfing, overlaps and bending
 * inside the net's own outline; labels, then joints (which grow the
 * outline); then kerf compensation (which moves it); then, once the piece
 * is placed, bridges (which open it).
 */
#ifndef UNROLL_ALLOW_H
#define UNROLL_ALLOW_H

#include "unroll/core.h"
#include "unroll/develop.h"
#include "unroll/geom.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ur_allowance_options {
    bool draw_rulings; /* rulings as SCORE lines */
} ur_allowance_options;

/*
 * The angle the polyline turns through about centre from its first point
 * to its last, radians (> 0 counter-clockwise), each step taken the short
 * way: the sweep of an arc whose points these are.
 */
UR_API double ur_arc_sweep(ur_vec2 centre, const ur_vec2 *points, size_t count);

/*
 * Builds the piece for a net, its shading copied; the caller frees it with
 * ur_piece_free.
 */
UR_API ur_status ur_piece_from_net(const ur_net *net, const ur_allowance_options *options,
                                   ur_piece *piece, ur_error *error);

/* ---- Labels: single-stroke engraved text (label.c) -------------------- */

/*
 * A Hershey single-stroke font (libhersheyfont), loaded once and passed to
 * the functions that engrave text.  ur_font_open loads "rowmans" (Roman
 * simplex) from the system's hershey-fonts data; NULL name means that one.
 * A name that is not a font there (letters, digits, '_' and '-' only) is
 * UR_ERROR_INPUT, the message naming it and the package hershey-fonts-data.
 * The font's cap height is measured on its 'H'.
 */
typedef struct ur_font ur_font;
UR_API ur_status ur_font_open(const char *name, ur_font **font, ur_error *error);
UR_API void ur_font_close(ur_font *font);

/*
 * The strokes of text as open ENGRAVE polylines, cap height `height` mm,
 * baseline from (0, 0) towards +x, y up (descenders go below 0); *width is
 * the advance of the whole text.  Only printable ASCII the font has is
 * accepted (UR_ERROR_INPUT says which character is not).  The caller frees
 * the paths' points and the array with ur_paths_free, even when *count is 0.
 */
UR_API ur_status ur_text_strokes(const ur_font *font, const char *text, double height,
                                 ur_path **paths, size_t *count, double *width, ur_error *error);

/*
 * Engraves text on the piece as ENGRAVE paths: inside the piece (outline
 * paths[0], a closed ring: labels go on before bridges), as near `near` as
 * it can be put, its baseline along `direction` (turned half round when its
 * x, or for x = 0 its y, is negative, so it never reads upside down), at
 * most `height` mm high and no smaller than `min_height`, and clear of
 * every path of the piece by `clearance` mm (checked with GEOS), outside
 * every closed CUT or KERF path but the outline (a hole).  The text's box is
 * what must fit.  Heights are tried from `height` down in steps of 0.8 to
 * `min_height`, each first within about the text's own length of `near`;
 * only when none fits there is the rest of the piece searched, largest
 * height first.  On success it records a UR_ALLOWANCE_LABEL entry (value:
 * the height used, where: the text's centre).  *placed says whether it
 * found room; when it did not (or the text is only spaces), the piece is
 * unchanged and the caller records a warning.  UR_ERROR_INPUT for a NULL or
 * empty text, heights not 0 < min_height <= height, a negative clearance,
 * a non-finite `near` or a zero or non-finite direction.
 */
UR_API ur_status ur_piece_add_label(ur_piece *piece, const ur_font *font, const char *text,
                                    ur_vec2 near, ur_vec2 direction, double height,
                                    double min_height, double clearance, bool *placed,
                                    ur_error *error);

/* ---- Joints on seams (joints.c) --------------------------------------- */

/* ---- Splice pieces (splice.c) ------------------------------------------- */

/*
 * A splice piece joins a seam from behind where no tab or lap fits on
 * either side: a strip `width` mm on each side of the seam (seam, count
 * points in the coordinates of piece_a's outline, which it follows
 * counter-clockwise, so piece_a lies on its left), its outline the seam
 * buffered by the width with flat ends, the seam a MARK line along its
 * middle, and with a font each half engraved with the name of the piece
 * that goes on it and the seam's label ("P1 A1" on the left, "P2 A1" on
 * the right).  strap says it is wood's butt strap (for the record's
 * words).  Records a UR_ALLOWANCE_JOINT entry; the caller frees the piece
 * with ur_piece_free.  UR_ERROR_INPUT for fewer than 2 points, a seam of
 * no length or sizes that are not positive.
 */
typedef struct ur_splice_request {
    const ur_vec2 *seam;
    size_t count;
    double width;      /* mm on each side of the seam */
    const char *name;  /* of the new piece */
    const char *label; /* the seam's, "A1" */
    const char *piece_a, *piece_b;
    bool strap;
    const ur_font *font; /* NULL: no labels */
    double label_height;
} ur_splice_request;

/* Pieces made by the joints, owned: free with ur_splice_list_free. */
typedef struct ur_splice_list {
    ur_piece *pieces;
    size_t count;
} ur_splice_list;

UR_API ur_status ur_splice_piece(const ur_splice_request *request, ur_piece *piece,
                                 ur_error *error);
UR_API ur_status ur_splice_list_add(ur_splice_list *list, const ur_splice_request *request,
                                    ur_error *error);
UR_API void ur_splice_list_free(ur_splice_list *list);

typedef struct ur_joint_options {
    bool lap;            /* lap joints (wood) instead of glue tabs */
    double tab_depth;    /* mm */
    double tab_angle;    /* degrees between a tab's base and its sides; 90 for none */
    double lap_width;    /* mm */
    double thickness;    /* of the material, mm: see ur_pieces_add_joints */
    const ur_font *font; /* NULL: no labels */
    double label_height; /* mm */
    bool name_pieces;    /* engrave each piece's name too */
    /*
     * Where no joint fits either side of a stretch of a seam: NULL, a
     * warning ("join it by hand"); else a splice piece (ur_splice_piece,
     * as wide on each side as a tab is deep or a lap wide) is added here.
     */
    ur_splice_list *splices;
    /*
     * A lap lies on the other piece's lapped zone and must bend with it:
     * with lap_kerfs, the KERF lines of that zone (bending grooves, hinge
     * slits) are carried onto the lap, kept lap_kerf_margin mm inside its
     * edges (a hinge's solid margin; 0 for grooves, which run out).
     */
    bool lap_kerfs;
    double lap_kerf_margin;
    const ur_context *context; /* stops with UR_ERROR_CANCELLED once it is cancelled; NULL: never */
    /*
     * Called now and then with the phase ("labels", then "tabs" or "laps") and how
     * far it is, from 0 to 1 (each phase ends with 1); NULL for none.
     */
    void (*progress)(void *context, const char *phase, double fraction);
    void *progress_context;
} ur_joint_options;

/* The label of seam number seam (from 1): "A1" ... "A99", "B1" ... "Z99", then "AA1" ... */
UR_API void ur_seam_label(int seam, char *label, size_t size);

/*
 * Puts a joint on every seam of the nets (pieces[k] was made from
 * nets->nets[k] and its outline is still the net's: joints go on once).
 *
 * Tabs: one tapered glue tab per straight stretch of each seam (on a
 * folded mesh, per edge), a SCORE fold at its base, the outline grown
 * around it; tabs on neighbouring edges leave a notch down to the seam's
 * corner so that each folds on its own.  Sides may be closed loops (the
 * rim of a hole).  The side is the one more full tabs fit on, balancing the
 * tabs between the pieces when both are alike.  A tab that would overlap
 * its piece, another tab or a label (or come nearer than a small gap to
 * anything but its neighbours at the corners) goes full size on the other
 * side, then is made lower, then shorter along its edge, on either side;
 * failing that a warning for that edge says what is in the way on each
 * side.  Clashes are tested against the net's outline in a GEOS STRtree
 * and the tabs already placed in a grid, so each test is local; the
 * outline is grown by all of a piece's tabs at once.  On stock 1 mm thick
 * or more the first `thickness` mm of a tab is a band with a second fold,
 * so that it wraps the edge of the other piece.  One UR_ALLOWANCE_JOINT
 * record per seam side with tabs (count: how many), one warning per edge
 * without.
 *
 * Laps: one piece extends under the other by lap_width (the outline grown
 * by a band along the whole seam, or each half of a closed loop); the
 * lapped zone is drawn as a closed MARK path on both pieces.
 *
 * With a font, both sides of every seam get its label (ur_seam_label)
 * engraved inside the piece near the seam's middle, along the seam's edge
 * there, and pieces their names when name_pieces.  Records a UR_ALLOWANCE_JOINT or
 * UR_ALLOWANCE_LABEL entry for each (warnings for what found no room).
 */
UR_API ur_status ur_pieces_add_joints(ur_piece *pieces, const ur_net_list *nets,
                                      const ur_joint_options *options, ur_error *error);

/*
 * Once the piece is placed turned by `angle` (radians, counter-clockwise),
 * turns every label that would then read upside down by half a turn about
 * its centre, so that all read upright on the sheet.
 */
UR_API void ur_piece_turn_labels(ur_piece *piece, double angle);

/*
 * Hinges and joints agree (joint_kerfs.c): once the joints are on (their
 * folds and marks are paths[first ..]), every KERF line of the piece is cut
 * back to keep `clearance` mm from each MARK and SCORE line among them (a
 * lap zone's mark line, a tab's folds); what is left of a line shorter
 * than `shortest` is dropped.  *trimmed: how many lines were cut.  Label
 * records keep pointing at their strokes.  UR_ERROR_INPUT for a clearance
 * not above 0 or a negative shortest.
 */
UR_API ur_status ur_piece_keep_kerfs_off_joints(ur_piece *piece, size_t first, double clearance,
                                                double shortest, size_t *trimmed, ur_error *error);

/* ---- Kerf compensation and bridges (kerf.c, bridges.c) ---------------- */

/*
 * Offsets the outer outline (paths[0]) outward by kerf / 2 and every other
 * closed CUT path (a hole) inward by kerf / 2, with mitred joins so that
 * corners stay sharp (GEOS buffer, mitre limit 10: corners down to about
 * 11 degrees keep their point); other paths are untouched.  The outline
 * stays counter-clockwise, each hole keeps its direction, the box is
 * recomputed.  Refuses with UR_ERROR_INPUT naming the piece, leaving it
 * unchanged, for a kerf that is negative or not finite, or an outline
 * already opened by bridges.  A hole with a part narrower than the kerf,
 * which moved in would vanish or split, is left as drawn with a warning
 * record (cut so, it comes out half a kerf wider all round).  A slot of
 * the outline whose mouth is narrower than the kerf closes into a hole as
 * the outline moves out: the room behind the mouth is added as a closed
 * CUT path (a hole, clockwise), so that the slot's sides are still cut,
 * with a warning record that the mouth holds them together; a room of
 * less than a kerf square is filled, with a warning record.  Material the
 * beam would burn away gets a warning record too, found by the opening
 * of the outline as drawn by the kerf: a piece narrower than the kerf
 * everywhere, one a narrow neck would leave in parts, or a narrow part of
 * more than 50 kerf squares where the narrow material is more than a
 * hundredth of the piece (the tip a sharp corner loses is less).
 * A kerf of 0 does nothing.  A path that is exactly a circle (its
 * circle set) stays exactly one, radius kerf / 2 more (outline) or less
 * (hole), its points moved along their radii onto it, without GEOS; a
 * hole whose radius would not stay above 0 is left as drawn, as above.
 * Records a UR_ALLOWANCE_KERF_COMPENSATION entry (value: the kerf) and
 * adds the kerf to piece->kerf_compensated.
 */
UR_API ur_status ur_piece_compensate_kerf(ur_piece *piece, double kerf, ur_error *error);

/*
 * Opens `count` uncut gaps of `width` mm in the outer outline, evenly
 * spaced along it by arc length; count 0 means automatic: one per 300 mm
 * of outline (rounded), at least 3 for a router, at least 2 for a laser
 * (router true or false).  Each gap keeps at least its own width of cut
 * (along the outline) from every corner and from the next gap.  A corner is
 * any stretch of outline no longer than three gap widths over which the
 * direction turns by more than 30 degrees in all (and would not without
 * its first or last vertex): a sharp vertex, or a curve tighter than a
 * radius of about 5.7 widths (bridges.c says more).  The even spread is
 * placed to miss corners where it can; a gap that would still touch one
 * moves to the nearest place allowed.  The closed outline becomes open CUT
 * paths, gap to gap (the first stays paths[0], the others are appended) and
 * piece->bridged is set; an outline that was exactly a circle becomes arcs
 * of it (each path's circle and sweep set, its ends moved onto the circle).  Apply after placement:
 * nothing after this may treat paths[0] as a closed ring.  Records a UR_ALLOWANCE_BRIDGES entry
 * (count: the gaps made, value: the width), a warning when fewer fit than
 * asked; when none fits the outline stays closed and unbridged.  Refuses
 * (UR_ERROR_INPUT naming the piece) a width not above 0 or not finite and a
 * piece already bridged.
 */
UR_API ur_status ur_piece_add_bridges(ur_piece *piece, size_t count, double width, bool router,
                                      ur_error *error);

/* ---- Kerfing cuts and overlap allowances (relief.c) ------------------- */

/*
 * Where the net must stretch more than the material allows (under-covers),
 * KERF slits across the direction of needed stretch; where it must shrink
 * more than allowed (over-covers), slits or darts from the boundary with
 * MARK overlap zones.  Driven by the net's shading (per-triangle strain and
 * direction) for a flattening, and by coverage (flat / 3D area) and the
 * rulings for the discrete triangle and quad methods.  Sizes from the
 * material: kerfing_opening, kerfing_margin, overlap style.  Records each
 * region's entry with the strain that triggered it and the limit.
 */
typedef struct ur_relief_limits {
    double max_stretch, max_compression; /* allowed strain, fractions */
    double opening;                      /* widest a kerfing slit opens, mm */
    double margin;                       /* slits stop this far from the outline, mm */
    bool darts;                          /* overlap darts instead of slits */
    bool kerfing, overlaps;              /* which of the two to add */
} ur_relief_limits;

UR_API ur_status ur_piece_add_relief(ur_piece *piece, const ur_net *net,
                                     const ur_relief_limits *limits, ur_error *error);

/* ---- Bending kerfs (bending.c) ---------------------------------------- */

/*
 * KERF lines parallel to the rulings where the surface bends tighter than
 * min_radius.  The radius R at a ruling is ur_analyze_bend_radius at its
 * parameter (ur_net.ruling_parameters, so `ruled` must be the surface the
 * net was developed from); spacings are measured across the rulings along
 * the net, between the rulings' midpoints.  A region is a run of the net
 * where R < min_radius.
 *
 * Rows (grooves or hinge rows) are spaced so that each turns the sheet by
 * at most facet_angle degrees (the angle between the tangent planes of
 * consecutive rows), and never farther apart than the widest spacing:
 * w R / d for router grooves (at which a groove closes completely), the
 * hinge's row distance for a laser; ceil(integral of the row density) of
 * them, at least 1, centred in the region.  Rows are never closer than
 * their width (w, or the laser's kerf) plus min_web: where the facet angle
 * would need them closer, they stay at that spacing and a warning says by
 * how much each turns.  Router grooves that could not close even then
 * (w R / d below that spacing) are placed every w, touching, with a
 * warning.  With thickness given, a router warns where the uncut skin
 * (thickness - d) is too thick to bend to R (its outer-fibre strain over
 * that of the whole sheet at min_radius): the groove would need to be
 * deeper than the profile allows.
 *
 * router: each groove is a line along its ruling from outline to outline
 * (it does not cut through).  laser: the material's living hinge: each row
 * of slits hinge_cut_length long with hinge_connection bridges, alternate
 * rows half a period along, clipped to stay hinge_connection from the
 * outline (shorter remnants dropped).  One UR_ALLOWANCE_BENDING record per
 * region: count the lines, rows the grooves or rows, facet_angle the
 * largest turn per row, value the smallest R, limit min_radius, the
 * reason the radius, spacing and depth (or the hinge); warnings as above.
 * A net without ruling_parameters (a flattened mesh) is left alone; fewer
 * than 2 drawn rulings give a warning where a bend is too tight.
 * UR_ERROR_INPUT for sizes that are not positive, a facet angle outside
 * [0, 90] or a negative minimum web, kerf or thickness.  See bending.c.
 */
typedef struct ur_bending_options {
    double min_radius;   /* the material's smallest bend radius, mm */
    bool router;         /* grooves (router) or through-cut hinge (laser) */
    double groove_width; /* w: the bit diameter, mm */
    double groove_depth; /* d: thickness minus skin, mm */
    double hinge_cut_length, hinge_connection, hinge_distance; /* laser pattern, mm */
    double facet_angle; /* degrees each row may turn the sheet by; 0: UR_DEFAULT_FACET_ANGLE */
    double min_web;     /* thinnest material left between grooves or slits, mm; 0: none */
    double kerf;        /* laser: the width a slit cuts, mm (0: a line) */
    double thickness;   /* of the material, mm; 0: the skin is not checked */
} ur_bending_options;

UR_API ur_status ur_piece_add_bending_kerfs(ur_piece *piece, const ur_net *net, ur_ruled *ruled,
                                            const ur_bending_options *options, ur_error *error);

#ifdef __cplusplus
}
#endif

#endif
