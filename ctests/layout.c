/* `struct triangulateio` of include/triangle_rs.h has Triangle 1.6's layout: 168 bytes, the
 * documented LP64 offsets, the right field types, and (when built with -DHAVE_DEBIAN_TRIANGLE_H
 * and linked with layout_debian.c) the same size, alignment, offsets and field sizes as Debian's
 * triangle.h. Prints one line per mismatch and exits 1; prints nothing and exits 0 when all
 * match. */
#include <stddef.h>
#include <stdio.h>

#include "layout_fields.h"
#include "triangle_rs.h"

#define FIELD_NAME(name, kind) #name,
#define OFFSET_OF(name, kind) offsetof(struct triangulateio, name),
#define SIZE_OF(name, kind) sizeof(((struct triangulateio *)0)->name),
#define KIND_OF(name, kind) kind,

static const char *const field_names[] = {TRIANGULATEIO_FIELDS(FIELD_NAME)};
static const size_t offsets[] = {TRIANGULATEIO_FIELDS(OFFSET_OF)};
static const size_t field_sizes[] = {TRIANGULATEIO_FIELDS(SIZE_OF)};
static const char kinds[] = {TRIANGULATEIO_FIELDS(KIND_OF)};

/* Triangle 1.6 on LP64 and LLP64 (8-byte pointers, 4-byte int). */
static const size_t lp64_offsets[TRIANGULATEIO_FIELD_COUNT] = {
    0, 8, 16, 24, 28, 32, 40, 48, 56, 64, 68, 72, 80, 88, 96, 104, 112, 120, 128, 136, 144, 152, 160};

#ifdef HAVE_DEBIAN_TRIANGLE_H
extern const size_t debian_triangulateio_offsets[];
extern const size_t debian_triangulateio_field_sizes[];
extern const size_t debian_triangulateio_size;
extern const size_t debian_triangulateio_align;
#endif

/* Compile-time type checks: assigning a field's address to a pointer of the expected type is a
 * constraint violation (an error with -Werror=incompatible-pointer-types) if the type differs. */
static void check_types(struct triangulateio *io) {
    double **d;
    int **i;
    int *n;
    d = &io->pointlist;
    d = &io->pointattributelist;
    i = &io->pointmarkerlist;
    n = &io->numberofpoints;
    n = &io->numberofpointattributes;
    i = &io->trianglelist;
    d = &io->triangleattributelist;
    d = &io->trianglearealist;
    i = &io->neighborlist;
    n = &io->numberoftriangles;
    n = &io->numberofcorners;
    n = &io->numberoftriangleattributes;
    i = &io->segmentlist;
    i = &io->segmentmarkerlist;
    n = &io->numberofsegments;
    d = &io->holelist;
    n = &io->numberofholes;
    d = &io->regionlist;
    n = &io->numberofregions;
    i = &io->edgelist;
    i = &io->edgemarkerlist;
    d = &io->normlist;
    n = &io->numberofedges;
    (void)d;
    (void)i;
    (void)n;
}

int main(void) {
    int failures = 0;
    size_t k;
    struct triangulateio io = {0};
    check_types(&io);

    if (sizeof(struct triangulateio) != 168) {
        printf("sizeof(struct triangulateio) = %zu, expected 168\n", sizeof(struct triangulateio));
        failures++;
    }
    for (k = 0; k < TRIANGULATEIO_FIELD_COUNT; k++) {
        size_t expected_size = kinds[k] == 'n' ? sizeof(int) : sizeof(void *);
        if (field_sizes[k] != expected_size) {
            printf("sizeof(%s) = %zu, expected %zu\n", field_names[k], field_sizes[k], expected_size);
            failures++;
        }
        if (sizeof(void *) == 8 && sizeof(int) == 4 && offsets[k] != lp64_offsets[k]) {
            printf("offsetof(%s) = %zu, expected %zu\n", field_names[k], offsets[k], lp64_offsets[k]);
            failures++;
        }
    }
#ifdef HAVE_DEBIAN_TRIANGLE_H
    if (sizeof(struct triangulateio) != debian_triangulateio_size) {
        printf("sizeof = %zu, Debian's %zu\n", sizeof(struct triangulateio), debian_triangulateio_size);
        failures++;
    }
    if (_Alignof(struct triangulateio) != debian_triangulateio_align) {
        printf("alignment = %zu, Debian's %zu\n", (size_t)_Alignof(struct triangulateio),
               debian_triangulateio_align);
        failures++;
    }
    for (k = 0; k < TRIANGULATEIO_FIELD_COUNT; k++) {
        if (offsets[k] != debian_triangulateio_offsets[k]) {
            printf("offsetof(%s) = %zu, Debian's %zu\n", field_names[k], offsets[k],
                   debian_triangulateio_offsets[k]);
            failures++;
        }
        if (field_sizes[k] != debian_triangulateio_field_sizes[k]) {
            printf("sizeof(%s) = %zu, Debian's %zu\n", field_names[k], field_sizes[k],
                   debian_triangulateio_field_sizes[k]);
            failures++;
        }
    }
#endif
    return failures == 0 ? 0 : 1;
}
