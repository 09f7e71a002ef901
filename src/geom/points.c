/*
 * points.c: numbering the points of a list so that the same point has the
 * same number (points.h).
 */
#include "points.h"

#include <stdlib.h>

/* A point and where it stands in the list, to sort by point. */
typedef struct placed_point {
    ur_vec3 point;
    size_t index;
} placed_point;

static int compare_placed(const void *a, const void *b)
{
    return ur_vec3_order(((const placed_point *)a)->point, ((const placed_point *)b)->point);
}

ur_status geom_number_points(const ur_vec3 *points, size_t count, size_t *numbers, ur_error *error)
{
    placed_point *sorted = ur_alloc_array(count, sizeof *sorted, error);
    if (!sorted)
        return UR_ERROR_MEMORY;
    for (size_t i = 0; i < count; i++)
        sorted[i] = (placed_point){points[i], i};
    qsort(sorted, count, sizeof *sorted, compare_placed);
    size_t number = 0;
    for (size_t k = 0; k < count; k++) {
        if (k > 0 && ur_vec3_order(sorted[k].point, sorted[k - 1].point) != 0)
            number++;
        numbers[sorted[k].index] = number;
    }
    free(sorted);
    return UR_OK;
}
