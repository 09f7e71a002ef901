/*
 * pair_table.c: what the nester keeps per pair of shapes at their turns
 * (their convex sums, their no-fit polygon, when the pair was first met),
 * in a hash table of the pairs met.  A table with a slot for every pair
 * grew with the square of the parts: 1,188 nets of an unfolded mesh at 4
 * turns, 540 MB of slots of which a few per cent were ever used.
 */
#include "nest_internal.h"

#include <stdint.h>
#include <stdlib.h>

/* A key no pair has: pair keys are indices well below SIZE_MAX. */
#define EMPTY_KEY SIZE_MAX
enum { FIRST_CAPACITY = 1024 };

/* The slot to look in first for key: Fibonacci hashing into capacity, a power of two. */
static size_t home_of(size_t key, size_t capacity)
{
    uint64_t mixed = (uint64_t)key * UINT64_C(0x9E3779B97F4A7C15);
    return (size_t)(mixed >> 32) & (capacity - 1);
}

/* The slot holding key, or the empty one where it would go (linear probing). */
static pair_entry *slot_of(pair_entry *slots, size_t capacity, size_t key)
{
    size_t s = home_of(key, capacity);
    while (slots[s].key != EMPTY_KEY && slots[s].key != key)
        s = (s + 1) & (capacity - 1);
    return &slots[s];
}

static pair_entry *make_slots(size_t capacity)
{
    pair_entry *slots = malloc(capacity * sizeof *slots);
    for (size_t s = 0; slots && s < capacity; s++)
        slots[s] = (pair_entry){EMPTY_KEY, NULL, NULL, 0};
    return slots;
}

/* Doubles the table (or makes its first slots); false when memory runs out. */
static bool grow(pair_table *table)
{
    size_t capacity = table->capacity ? 2 * table->capacity : FIRST_CAPACITY;
    pair_entry *slots = make_slots(capacity);
    if (!slots)
        return false;
    for (size_t s = 0; s < table->capacity; s++)
        if (table->slots[s].key != EMPTY_KEY)
            *slot_of(slots, capacity, table->slots[s].key) = table->slots[s];
    free(table->slots);
    table->slots = slots;
    table->capacity = capacity;
    return true;
}

pair_entry *pair_table_find(const pair_table *table, size_t key)
{
    if (!table->capacity)
        return NULL;
    pair_entry *entry = slot_of(table->slots, table->capacity, key);
    return entry->key == key ? entry : NULL;
}

pair_entry *pair_table_add(pair_table *table, size_t key)
{
    pair_entry *entry = pair_table_find(table, key);
    if (entry)
        return entry;
    /* At most half full: probes stay short. */
    if (2 * (table->count + 1) > table->capacity && !grow(table))
        return NULL;
    entry = slot_of(table->slots, table->capacity, key);
    *entry = (pair_entry){key, NULL, NULL, 0};
    table->count++;
    return entry;
}

void pair_table_free(GEOSContextHandle_t geos, pair_table *table)
{
    for (size_t s = 0; s < table->capacity; s++) {
        nest_sum_list_free(table->slots[s].sums);
        if (table->slots[s].nfp)
            GEOSGeom_destroy_r(geos, table->slots[s].nfp);
    }
    free(table->slots);
    *table = (pair_table){NULL, 0, 0};
}
