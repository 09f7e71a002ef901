/*
 * net.c: flat nets (core.h) freed.  Making them is src/develop's
 * (developments) and src/flatten's (flattened and unfolded meshes).
 */
#include "unroll/core.h"

#include <stdlib.h>
#include <string.h>

void ur_net_free(ur_net *net)
{
    free(net->outline);
    free(net->rulings);
    free(net->ruling_parameters);
    free(net->seam_sides);
    free(net->outline_3d);
    free(net->folds);
    free(net->fold_valley);
    free(net->shading.triangles);
    free(net->shading.strain);
    free(net->shading.direction);
    free(net->faces_3d);
    memset(net, 0, sizeof *net);
}

void ur_net_list_free(ur_net_list *nets)
{
    for (size_t k = 0; k < nets->count; k++)
        ur_net_free(&nets->nets[k]);
    free(nets->nets);
    nets->nets = NULL;
    nets->count = 0;
}
