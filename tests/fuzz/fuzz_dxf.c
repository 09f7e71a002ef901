/*
 * fuzz_dxf.c: fuzz target for DXF parts (src/io/dxf_import.c and
 * parts_import.c): what `unroll nest` reads from an ASCII DXF file, from
 * group codes through entities, bulges and chained lines to rings with
 * their holes.
 */
#include "parts_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    import_and_check("parts.dxf", data, size);
    return 0;
}
