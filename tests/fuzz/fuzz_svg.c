/*
 * fuzz_svg.c: fuzz target for SVG parts (src/io/svg_import.c and
 * parts_import.c): what `unroll nest` reads from an SVG file, from the XML
 * through paths, shapes, transforms and units to rings with their holes.
 */
#include "parts_check.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    import_and_check("parts.svg", data, size);
    return 0;
}
