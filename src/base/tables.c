/*
 * tables.c: large zeroed tables whose pages are mapped at once (tables.h).
 */
#include "tables.h"

/* Smaller than any page size in use, so that every page gets a write. */
#define PAGE_STRIDE 4096

void *table_alloc(size_t count, size_t size, ur_error *error)
{
    unsigned char *memory = ur_alloc_array(count, size, error);
    if (!memory)
        return NULL;
    size_t bytes = (count ? count : 1) * size; /* ur_alloc_array checked the product */
    volatile unsigned char *page = memory;     /* volatile: the writes are not left out */
    for (size_t at = 0; at < bytes; at += PAGE_STRIDE)
        page[at] = 0;
    return memory;
}
