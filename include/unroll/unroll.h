/*
 * unroll/unroll.h: every public header of libunroll at once, for programs
 * that use more than one module.  Link with `pkg-config --libs unroll`.
 */
#ifndef UNROLL_UNROLL_H
#define UNROLL_UNROLL_H

#include "unroll/base.h"
#include "unroll/geom.h"
#include "unroll/core.h"
#include "unroll/surface.h"
#include "unroll/develop.h"
#include "unroll/analyze.h"
#include "unroll/mesh.h"
#include "unroll/flatten.h"
#include "unroll/allow.h"
#include "unroll/nest.h"
#include "unroll/io.h"
#include "unroll/out.h"
#include "unroll/job.h"

#endif
