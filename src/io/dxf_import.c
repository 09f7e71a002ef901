/* placeholder */
#include "parts_internal.h"
ur_status parts_read_dxf(parts_collection *collection, ur_error *error)
{
    return ur_error_set(error, UR_ERROR_INPUT, "%s: todo", collection->path);
}
