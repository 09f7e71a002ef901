/*
 * png.h: a cairo image as a PNG document for atomic_write (private to
 * src/out), shared by the plots that write PNG.
 */
#ifndef UNROLL_OUT_PNG_H
#define UNROLL_OUT_PNG_H

#include <cairo.h>
#include <stdbool.h>
#include <stdio.h>

static inline cairo_status_t png_write_bytes(void *stream, const unsigned char *data,
                                             unsigned int length)
{
    return fwrite(data, 1, length, stream) == length ? CAIRO_STATUS_SUCCESS
                                                     : CAIRO_STATUS_WRITE_ERROR;
}

/* An atomic_emitter: data is the cairo_surface_t to write. */
static inline bool png_emit(FILE *stream, const void *surface)
{
    return cairo_surface_write_to_png_stream((cairo_surface_t *)surface, png_write_bytes, stream) ==
           CAIRO_STATUS_SUCCESS;
}

#endif
