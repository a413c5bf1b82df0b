/* The layout of `struct triangulateio` as Debian's /usr/include/triangle.h (Triangle 1.6)
 * declares it, exported as tables for layout.c to compare with ours. */
#include <stddef.h>
#include <triangle.h>

#include "layout_fields.h"

#define OFFSET_OF(name, kind) offsetof(struct triangulateio, name),
#define SIZE_OF(name, kind) sizeof(((struct triangulateio *)0)->name),

const size_t debian_triangulateio_offsets[] = {TRIANGULATEIO_FIELDS(OFFSET_OF)};
const size_t debian_triangulateio_field_sizes[] = {TRIANGULATEIO_FIELDS(SIZE_OF)};
const size_t debian_triangulateio_size = sizeof(struct triangulateio);
const size_t debian_triangulateio_align = _Alignof(struct triangulateio);
