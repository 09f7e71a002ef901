/*
 * frames.c: each triangle laid in its own plane, the Jacobian of the map
 * from there to a flat layout, its closest rotation and its singular values
 * (all closed forms for 2 x 2), and the ARAP energy built on them.
 */
#include "flatten_internal.h"

#include <math.h>
#include <stdlib.h>

/*
 * A triangle of less area than this times the square of the piece's size
 * has none: the bound ur_mesh_clean drops triangles by, so that a cleaned
 * mesh is never refused here.
 */

static ur_status check_triangles(const ur_mesh *mesh, ur_error *error)
{
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            if (mesh->triangles[t][k] >= mesh->vertex_count)
                return ur_error_set(error, UR_ERROR_INPUT,
                                    "triangle %zu uses vertex %zu, but the piece has %zu "
                                    "vertices",
                                    t + 1, mesh->triangles[t][k] + 1, mesh->vertex_count);
    return UR_OK;
}

static ur_status check_mesh(const ur_mesh *mesh, ur_error *error)
{
    if (!mesh)
        return ur_error_set(error, UR_ERROR_INPUT, "no piece to flatten");
    if (mesh->triangle_count == 0 || !mesh->triangles)
        return ur_error_set(error, UR_ERROR_INPUT, "the piece has no triangles");
    if (mesh->vertex_count == 0 || !mesh->vertices)
        return ur_error_set(error, UR_ERROR_INPUT, "the piece has no vertices");
    ur_status status = ur_mesh_check_vertices(mesh->vertices, mesh->vertex_count, error);
    return status ? status : check_triangles(mesh, error);
}

/* The cotangent of the angle at corner k: dot over cross of the two sides leaving it. */
static double corner_cotangent(const ur_vec2 corner[3], int k)
{
    ur_vec2 a = ur_vec2_sub(corner[(k + 1) % 3], corner[k]);
    ur_vec2 b = ur_vec2_sub(corner[(k + 2) % 3], corner[k]);
    return ur_vec2_dot(a, b) / ur_vec2_cross(a, b);
}

/* Lays p0 p1 p2 in its plane; false when it has no area to speak of. */
static bool make_frame(ur_vec3 p0, ur_vec3 p1, ur_vec3 p2, double smallest, flat_frame *frame)
{
    ur_vec3 e1 = ur_vec3_sub(p1, p0), e2 = ur_vec3_sub(p2, p0);
    double length = ur_vec3_length(e1);
    double twice_area = ur_vec3_length(ur_vec3_cross(e1, e2));
    if (!(0.5 * twice_area > smallest) || !(length > 0))
        return false;
    frame->corner[0] = ur_vec2_make(0, 0);
    frame->corner[1] = ur_vec2_make(length, 0);
    frame->corner[2] = ur_vec2_make(ur_vec3_dot(e1, e2) / length, twice_area / length);
    frame->area = 0.5 * twice_area;
    for (int k = 0; k < 3; k++)
        frame->cot[k] = corner_cotangent(frame->corner, k);
    /* [x1 x2x; 0 x2y] is upper triangular: its inverse is written out. */
    double x1 = frame->corner[1].x, x2 = frame->corner[2].x, y2 = frame->corner[2].y;
    frame->inverse[0][0] = 1 / x1;
    frame->inverse[0][1] = -x2 / (x1 * y2);
    frame->inverse[1][0] = 0;
    frame->inverse[1][1] = 1 / y2;
    return true;
}

ur_status flat_frames(const ur_mesh *mesh, flat_frame **frames, ur_error *error)
{
    *frames = NULL;
    ur_status status = check_mesh(mesh, error);
    if (status)
        return status;
    flat_frame *made = ur_alloc_array(mesh->triangle_count, sizeof *made, error);
    if (!made)
        return UR_ERROR_MEMORY;
    double size = ur_mesh_size(mesh);
    double smallest = UR_MESH_ZERO_AREA * size * size;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        const size_t *c = mesh->triangles[t];
        if (!make_frame(mesh->vertices[c[0]], mesh->vertices[c[1]], mesh->vertices[c[2]], smallest,
                        &made[t])) {
            free(made);
            return ur_error_set(error, UR_ERROR_INPUT,
                                "triangle %zu (vertices %zu, %zu, %zu) has no area: clean the "
                                "mesh first",
                                t + 1, c[0] + 1, c[1] + 1, c[2] + 1);
        }
    }
    *frames = made;
    return UR_OK;
}

flat_matrix flat_jacobian(const flat_frame *frame, ur_vec2 u0, ur_vec2 u1, ur_vec2 u2)
{
    /* J = [u1 - u0, u2 - u0] [x1 - x0, x2 - x0]^-1 */
    ur_vec2 d1 = ur_vec2_sub(u1, u0), d2 = ur_vec2_sub(u2, u0);
    const double(*m)[2] = frame->inverse;
    flat_matrix j = {d1.x * m[0][0] + d2.x * m[1][0], d1.x * m[0][1] + d2.x * m[1][1],
                     d1.y * m[0][0] + d2.y * m[1][0], d1.y * m[0][1] + d2.y * m[1][1]};
    return j;
}

flat_matrix flat_triangle_jacobian(const ur_mesh *mesh, const flat_frame *frames,
                                   const ur_vec2 *layout, size_t t)
{
    const size_t *c = mesh->triangles[t];
    return flat_jacobian(&frames[t], layout[c[0]], layout[c[1]], layout[c[2]]);
}

double flat_rotation(flat_matrix j, double *cosine, double *sine)
{
    double p = j.a + j.d, q = j.c - j.b;
    double norm = sqrt(p * p + q * q);
    /* J = [a b; b -a] (a reflection times a scale) is as close to every rotation: keep none. */
    *cosine = norm > 0 ? p / norm : 1;
    *sine = norm > 0 ? q / norm : 0;
    /*
     * Entry by entry rather than as |J|^2 - 2 norm + 2, which cancels to
     * rounding (1e-16) when J is nearly a rotation and would hide the
     * convergence of an isometry.
     */
    double da = j.a - *cosine, db = j.b + *sine, dc = j.c - *sine, dd = j.d - *cosine;
    return da * da + db * db + dc * dc + dd * dd;
}

/*
 * J = [a b; c d] is the sum of a similarity [e -h; h e] and an
 * anti-similarity [f g; g -f] (e = (a + d)/2, f = (a - d)/2, g = (c + b)/2,
 * h = (c - b)/2); the singular values are the sum and the difference of
 * their scales.  The direction of sigma1 in the flat plane is the leading
 * eigenvector of J J^T.
 */
ur_strain flat_strain(flat_matrix j)
{
    double e = 0.5 * (j.a + j.d), f = 0.5 * (j.a - j.d);
    double g = 0.5 * (j.c + j.b), h = 0.5 * (j.c - j.b);
    double similar = hypot(e, h), anti = hypot(f, g);
    double p = j.a * j.a + j.b * j.b, q = j.c * j.c + j.d * j.d, r = j.a * j.c + j.b * j.d;
    double angle = 0.5 * atan2(2 * r, p - q);
    ur_strain strain = {similar + anti, fabs(similar - anti), {cos(angle), sin(angle)}};
    return strain;
}

double flat_energy(const ur_mesh *mesh, const flat_frame *frames, const ur_vec2 *layout)
{
    double energy = 0, area = 0;
    for (size_t t = 0; t < mesh->triangle_count; t++) {
        double cosine, sine;
        flat_matrix j = flat_triangle_jacobian(mesh, frames, layout, t);
        energy += frames[t].area * flat_rotation(j, &cosine, &sine);
        area += frames[t].area;
    }
    return energy / area;
}
