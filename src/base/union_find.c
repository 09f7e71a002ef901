/*
 * union_find.c: disjoint sets with path halving (union_find.h).  Joining
 * by the smaller root keeps set numbers deterministic; the paths stay
 * short enough in practice without union by rank.
 */
#include "union_find.h"

void union_find_init(size_t *parent, size_t n)
{
    for (size_t x = 0; x < n; x++)
        parent[x] = x;
}

size_t union_find_root(size_t *parent, size_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

bool union_find_join(size_t *parent, size_t a, size_t b)
{
    a = union_find_root(parent, a);
    b = union_find_root(parent, b);
    if (a == b)
        return false;
    if (a < b)
        parent[b] = a;
    else
        parent[a] = b;
    return true;
}
