/*
 * discrete.c: the two discrete unrollings of the seed paper ([Seed2018] in
 * docs/bibliography.md; docs/algorithms.md, section 5) of a ruled surface
 * cut into n parts along its rulings, P_i on rail a and A_i on rail b (for a
 * tangent developable P_i on the edge of regression and A_i = P_i + L t_i).
 *
 * Triangle method: keep triangle A_i A_i+1 P_i+1 and neglect the sliver
 * P_i P_i+1 A_i, which is thin because the tangent at P_i passes close to
 * P_i+1.  Each triangle is laid down with its vertex A_i on the previous one
 * and its side A_i P_i+1 along the previous ruling A_i P_i ([Seed2018]'s
 * "points 1, 2, B aligned").  The net is smaller than the surface.
 *
 * Quad method: flatten each twisted quadrilateral P_i P_i+1 A_i+1 A_i keeping
 * its four sides and its longer diagonal, i.e. hinge its two triangles on
 * that diagonal; consecutive quads share the ruling P_i+1 A_i+1.  The net is
 * larger than the surface.
 */
#include "develop_internal.h"

#include <stdlib.h>

/*
 * Which side of a hinge p -> q a new vertex goes.  Every triangle is laid
 * with the orientation it has in its cell of the 3D strip, so the side
 * follows from the strip's orientation and never from where earlier points
 * lie: a degenerate cell (a cone's apex, where A_i = A_i+1) puts such points
 * on the hinge itself, and their side of it is rounding noise.
 */
enum side { LEFT = 1, RIGHT = -1 };

static void order_pair(double *larger, double *smaller)
{
    if (*larger < *smaller) {
        double swap = *larger;
        *larger = *smaller;
        *smaller = swap;
    }
}

/*
 * The area of a triangle from its sides by Kahan's formula, which stays
 * accurate for needle-like triangles; 0 when rounding has broken the
 * triangle inequality (a side of length 0).
 */
static double triangle_area(double a, double b, double c)
{
    order_pair(&a, &b);
    order_pair(&b, &c);
    order_pair(&a, &b);
    double product = (a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c));
    return product > 0 ? 0.25 * sqrt(product) : 0.0;
}

/*
 * The point x with |x - p| = to_p and |x - q| = to_q on the given side of
 * line pq.  Its height above pq comes from the area: the textbook
 * sqrt(to_p^2 - a^2) loses half the digits when x is close to p or q, and
 * would move a cone's apex by 1e-8 of the slant height at every cell.
 */
static ur_vec2 third_vertex(ur_vec2 p, ur_vec2 q, double to_p, double to_q, enum side side)
{
    ur_vec2 axis = ur_vec2_sub(q, p);
    double base = ur_vec2_length(axis);
    /* A hinge of length 0 has no direction; a quad hinges on its longer diagonal, so never. */
    if (!(base > 0))
        return p;
    ur_vec2 along = ur_vec2_scale(axis, 1.0 / base);
    ur_vec2 left = {-along.y, along.x};
    double a = (to_p * to_p - to_q * to_q + base * base) / (2 * base);
    double h = side * 2 * triangle_area(base, to_p, to_q) / base;
    return ur_vec2_add_scaled(ur_vec2_add_scaled(p, along, a), left, h);
}

static ur_vec2 along_ray(ur_vec2 from, ur_vec2 toward, double distance)
{
    ur_vec2 d = ur_vec2_sub(toward, from);
    return ur_vec2_add_scaled(from, d, distance / ur_vec2_length(d));
}

/*
 * The first triangle is laid to the left of its ruling A_0 P_0 and every
 * later one with the same orientation, so A_i+1 is always to the left of
 * A_i P_i+1.
 */
static void unroll_triangles(const ur_vec3 *p, const ur_vec3 *a, strip *s)
{
    size_t n = s->count - 1;
    s->skip_first_near = true;
    s->far[0] = ur_vec2_make(0, 0);
    /* P_0 is no vertex of the net; it only gives the first ruling's direction. */
    s->near[0] = ur_vec2_make(0, -ur_vec3_distance(a[0], p[0]));
    for (size_t i = 0; i < n; i++) {
        s->near[i + 1] = along_ray(s->far[i], s->near[i], ur_vec3_distance(a[i], p[i + 1]));
        s->far[i + 1] = third_vertex(s->far[i], s->near[i + 1], ur_vec3_distance(a[i], a[i + 1]),
                                     ur_vec3_distance(p[i + 1], a[i + 1]), LEFT);
    }
}

/*
 * The first quad is laid to the left of its ruling P_0 A_0, which makes
 * every cell P_i P_i+1 A_i+1 A_i clockwise in the net; both triangles of a
 * cell keep that orientation, which fixes the side of each hinge their new
 * vertex goes on, whatever the cell's shape (a cone's apex cells have
 * A_i = A_i+1 and a first triangle of area 0).
 */
static void unroll_quads(const ur_vec3 *p, const ur_vec3 *a, strip *s)
{
    size_t n = s->count - 1;
    s->near[0] = ur_vec2_make(0, 0);
    s->far[0] = ur_vec2_make(0, ur_vec3_distance(a[0], p[0]));
    for (size_t i = 0; i < n; i++) {
        if (ur_vec3_distance(p[i], a[i + 1]) >= ur_vec3_distance(p[i + 1], a[i])) {
            /* diagonal P_i A_i+1: triangles (P_i, A_i+1, A_i) then (P_i, P_i+1, A_i+1) */
            s->far[i + 1] = third_vertex(s->near[i], s->far[i], ur_vec3_distance(p[i], a[i + 1]),
                                         ur_vec3_distance(a[i], a[i + 1]), LEFT);
            s->near[i + 1] =
                third_vertex(s->near[i], s->far[i + 1], ur_vec3_distance(p[i], p[i + 1]),
                             ur_vec3_distance(a[i + 1], p[i + 1]), LEFT);
        } else {
            /* diagonal P_i+1 A_i: triangles (P_i, P_i+1, A_i) then (A_i, P_i+1, A_i+1) */
            s->near[i + 1] = third_vertex(s->near[i], s->far[i], ur_vec3_distance(p[i], p[i + 1]),
                                          ur_vec3_distance(a[i], p[i + 1]), LEFT);
            s->far[i + 1] =
                third_vertex(s->far[i], s->near[i + 1], ur_vec3_distance(a[i], a[i + 1]),
                             ur_vec3_distance(p[i + 1], a[i + 1]), RIGHT);
        }
    }
}

ur_status develop_discrete(ur_ruled *ruled, const ur_develop_options *options, strip *s,
                           ur_error *error)
{
    if (options->method == UR_METHOD_TRIANGLE && ruled->kind != UR_RULED_TANGENT) {
        ur_error_set(error, UR_ERROR_INPUT,
                     "method triangle: the paper's triangle construction relies on consecutive "
                     "tangents nearly meeting, so it applies only to tangent developables "
                     "(helicoid, tangent); use method quad or exact");
        return ur_error_set_setting(error, "method method");
    }
    size_t n = options->rulings;
    if (n < 1) {
        ur_error_set(error, UR_ERROR_INPUT, "rulings must be at least 1");
        return ur_error_set_setting(error, "rulings");
    }
    ur_status status = strip_alloc(s, n + 1, error);
    if (status != UR_OK)
        return status;
    ur_vec3 *p = ur_alloc_array(n + 1, sizeof *p, error);
    ur_vec3 *a = ur_alloc_array(n + 1, sizeof *a, error);
    if (!p || !a) {
        free(p);
        free(a);
        strip_free(s);
        return UR_ERROR_MEMORY;
    }
    double u0 = ur_ruled_start(ruled), u1 = ur_ruled_end(ruled);
    for (size_t i = 0; i <= n; i++) {
        ur_vec3 rails[4];
        s->u[i] = u0 + (u1 - u0) * i / n;
        s->drawn[i] = true;
        ur_ruled_rails(ruled, s->u[i], rails);
        p[i] = rails[0];
        a[i] = rails[2];
    }
    if (options->method == UR_METHOD_TRIANGLE)
        unroll_triangles(p, a, s);
    else
        unroll_quads(p, a, s);
    free(p);
    free(a);
    return UR_OK;
}
