/*
 * orient.c: turning triangles over so that each connected part of a mesh
 * runs one way: every edge two triangles share is run in opposite
 * directions by them, as flattening and the boundary loops need.
 *
 * A breadth-first walk over each part fixes every triangle's direction
 * relative to the first one; meeting a triangle already fixed the other way
 * means the part is one-sided (a Mobius strip) and cannot be oriented.
 * Which of the two directions the part then takes: outward for a closed
 * part (positive signed volume), else the one most of its triangles already
 * had, so that a few flipped triangles are what gets repaired.
 */
#include "mesh_internal.h"

#include <stdlib.h>

enum { KEEP = 0, TURN = 1, UNSEEN = 2 };

typedef struct walk {
    const size_t (*triangles)[3];
    const size_t *twins;
    unsigned char *turn; /* per triangle: KEEP, TURN or UNSEEN */
    size_t *queue;       /* triangles in the order reached; parts one after the other */
    size_t tail;
} walk;

/* Reaches the part of seed; false, with *conflict, when it is one-sided. */
static bool walk_part(walk *w, size_t seed, mesh_conflict *conflict)
{
    size_t head = w->tail;
    w->turn[seed] = KEEP;
    w->queue[w->tail++] = seed;
    while (head < w->tail) {
        size_t t = w->queue[head++];
        for (size_t h = 3 * t; h < 3 * t + 3; h++) {
            size_t g = w->twins[h];
            if (g == UR_NO_EDGE)
                continue;
            /* Two triangles running their edge the same way disagree. */
            bool same = mesh_from(w->triangles, h) == mesh_from(w->triangles, g);
            unsigned char want = (unsigned char)(w->turn[t] ^ same);
            size_t s = g / 3;
            if (w->turn[s] == UNSEEN) {
                w->turn[s] = want;
                w->queue[w->tail++] = s;
            } else if (w->turn[s] != want) {
                conflict->first = t;
                conflict->second = s;
                conflict->a = mesh_from(w->triangles, h);
                conflict->b = mesh_to(w->triangles, h);
                return false;
            }
        }
    }
    return true;
}

/* Six times the signed volume the part encloses, as it will be oriented. */
static double part_volume(const walk *w, const size_t *part, size_t count, const ur_vec3 *vertices)
{
    ur_vec3 origin = vertices[w->triangles[part[0]][0]];
    double volume = 0;
    for (size_t i = 0; i < count; i++) {
        const size_t *c = w->triangles[part[i]];
        ur_vec3 a = ur_vec3_sub(vertices[c[0]], origin);
        ur_vec3 b = ur_vec3_sub(vertices[c[1]], origin);
        ur_vec3 d = ur_vec3_sub(vertices[c[2]], origin);
        double det = ur_vec3_det(a, b, d);
        volume += w->turn[part[i]] == TURN ? -det : det;
    }
    return volume;
}

static bool part_is_closed(const walk *w, const size_t *part, size_t count)
{
    for (size_t i = 0; i < count; i++)
        for (size_t h = 3 * part[i]; h < 3 * part[i] + 3; h++)
            if (w->twins[h] == UR_NO_EDGE)
                return false;
    return true;
}

/* Chooses the part's direction: outward when closed, else the majority's. */
static void settle_part(walk *w, const size_t *part, size_t count, const ur_vec3 *vertices)
{
    bool invert;
    double volume = part_is_closed(w, part, count) ? part_volume(w, part, count, vertices) : 0;
    if (volume != 0) {
        invert = volume < 0;
    } else {
        size_t turned = 0;
        for (size_t i = 0; i < count; i++)
            turned += w->turn[part[i]] == TURN;
        invert = 2 * turned > count;
    }
    if (invert)
        for (size_t i = 0; i < count; i++)
            w->turn[part[i]] ^= 1;
}

ur_status mesh_orient(size_t (*triangles)[3], size_t triangle_count, const size_t *twins,
                      const ur_vec3 *vertices, bool *flipped, mesh_conflict *conflict,
                      ur_error *error)
{
    walk w = {(const size_t(*)[3])triangles, twins, NULL, NULL, 0};
    w.turn = ur_alloc_array(triangle_count, sizeof *w.turn, error);
    w.queue = ur_alloc_array(triangle_count, sizeof *w.queue, error);
    ur_status status = w.turn && w.queue ? UR_OK : UR_ERROR_MEMORY;
    for (size_t t = 0; t < triangle_count && status == UR_OK; t++)
        w.turn[t] = UNSEEN;
    for (size_t seed = 0; seed < triangle_count && status == UR_OK; seed++) {
        if (w.turn[seed] != UNSEEN)
            continue;
        size_t start = w.tail;
        if (!walk_part(&w, seed, conflict))
            status = UR_ERROR_INPUT;
        else
            settle_part(&w, w.queue + start, w.tail - start, vertices);
    }
    for (size_t t = 0; t < triangle_count && status == UR_OK; t++) {
        flipped[t] = w.turn[t] == TURN;
        if (flipped[t]) {
            size_t corner = triangles[t][1];
            triangles[t][1] = triangles[t][2];
            triangles[t][2] = corner;
        }
    }
    free(w.turn);
    free(w.queue);
    return status;
}
