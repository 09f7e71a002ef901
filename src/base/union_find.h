/*
 * union_find.h (library-internal): disjoint sets of the numbers 0 .. n - 1
 * in an array parent (parent[x] == x at a root), shared by every module
 * that groups things: corners into vertices, triangles into regions,
 * faces into pieces.
 */
#ifndef UNROLL_BASE_UNION_FIND_H
#define UNROLL_BASE_UNION_FIND_H

#include <stdbool.h>
#include <stddef.h>

/* parent[x] = x for every x: n sets of one. */
void union_find_init(size_t *parent, size_t n);

/* The root of x's set, halving the path on the way (each node then points to its grandparent). */
size_t union_find_root(size_t *parent, size_t x);

/*
 * Joins the sets of a and b; the smaller root becomes the root of both, so
 * that numbering the roots in order numbers the sets by their smallest
 * member.  Returns false when they were one set already.
 */
bool union_find_join(size_t *parent, size_t a, size_t b);

#endif
