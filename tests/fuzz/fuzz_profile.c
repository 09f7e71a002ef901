/*
 * fuzz_profile.c: fuzz target for machine and material profiles
 * (src/io/profile.c): libxml2 parses the file, the RelaxNG schema from
 * profiles/schema/ validates it and the reader turns it into a ur_machine
 * or ur_material.  The same bytes are read as both.
 *
 * The schemas are read from ./profiles/schema: run the target from the top
 * of the source tree (make fuzz does).
 */
#include "fuzz_support.h"

#include <math.h>

#include "unroll/io.h"

/* A name and strings that end inside their arrays. */
#define FUZZ_TERMINATED(array) FUZZ_CHECK(memchr((array), '\0', sizeof(array)) != NULL)

static void check_machine(const ur_machine *machine)
{
    FUZZ_CHECK(strcmp(machine->name, "profile") == 0);
    FUZZ_TERMINATED(machine->description);
    FUZZ_CHECK(isfinite(machine->bed_width) && machine->bed_width > 0);
    FUZZ_CHECK(isfinite(machine->bed_height) && machine->bed_height > 0);
    FUZZ_CHECK(isfinite(machine->kerf) && machine->kerf >= 0);
    FUZZ_CHECK(isfinite(machine->margin) && isfinite(machine->spacing));
    FUZZ_CHECK(isfinite(machine->bridge_width));
    for (int op = 0; op < UR_OP_COUNT; op++) {
        FUZZ_TERMINATED(machine->styles[op].layer);
        FUZZ_TERMINATED(machine->styles[op].colour);
        FUZZ_TERMINATED(machine->styles[op].dash);
        FUZZ_CHECK(isfinite(machine->styles[op].line_width));
    }
}

static void check_material(const ur_material *material)
{
    FUZZ_CHECK(strcmp(material->name, "profile") == 0);
    FUZZ_TERMINATED(material->description);
    FUZZ_CHECK(isfinite(material->thickness) && material->thickness > 0);
    FUZZ_CHECK(material->stock_count >= 0 && material->stock_count <= UR_MAX_STOCK_SIZES);
    for (int i = 0; i < material->stock_count; i++)
        FUZZ_CHECK(isfinite(material->stock[i].width) && isfinite(material->stock[i].height));
    FUZZ_CHECK(isfinite(material->k_factor) && isfinite(material->tab_depth));
    FUZZ_CHECK(isfinite(material->max_stretch) && isfinite(material->max_compression));
    FUZZ_CHECK(isfinite(material->label_height) && isfinite(material->groove_skin));
}

static const char *const roots[] = {"./profiles", NULL};

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ur_error error;
    ur_machine machine;
    if (ur_machine_read_buffer(roots, "profile.xml", data, size, &machine, &error) == UR_OK)
        check_machine(&machine);
    else
        FUZZ_CHECK(strstr(error.message, "profile.xml") != NULL);
    ur_material material;
    if (ur_material_read_buffer(roots, "profile.xml", data, size, &material, &error) == UR_OK)
        check_material(&material);
    else
        FUZZ_CHECK(strstr(error.message, "profile.xml") != NULL);
    return 0;
}
