/*
 * tables.h (library-internal, used by the unfolding's caches): large
 * zeroed tables whose pages are mapped at once.
 *
 * A table from calloc that is read before it is written (a hash table
 * asked whether it holds a key before the key is stored) has each page
 * mapped first to the system's shared page of zeros, then copied at its
 * first write.  The copy is a second fault, and while another thread of
 * the process runs it makes the kernel flush the address caches of every
 * core: a tenth of the unfolding's time on a 2,000-triangle sphere went
 * there.  Writing a zero into each page at once maps it for writing from
 * the start.
 */
#ifndef UNROLL_BASE_TABLES_H
#define UNROLL_BASE_TABLES_H

#include "unroll/base.h"

#include <stddef.h>

/* As ur_alloc_array, with every page of the table written once. */
void *table_alloc(size_t count, size_t size, ur_error *error);

#endif
