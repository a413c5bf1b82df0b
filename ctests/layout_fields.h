/* Every field of `struct triangulateio`, in Triangle 1.6's order, as an X-macro: X(name, kind)
 * with kind 'd' for `double *`, 'i' for `int *` and 'n' for `int`. Shared by layout.c (our
 * header) and layout_debian.c (Debian's triangle.h), which cannot share a translation unit
 * because both define the struct. */
#ifndef LAYOUT_FIELDS_H
#define LAYOUT_FIELDS_H

#define TRIANGULATEIO_FIELDS(X)                                                                   \
    X(pointlist, 'd')                                                                             \
    X(pointattributelist, 'd')                                                                    \
    X(pointmarkerlist, 'i')                                                                       \
    X(numberofpoints, 'n')                                                                        \
    X(numberofpointattributes, 'n')                                                               \
    X(trianglelist, 'i')                                                                          \
    X(triangleattributelist, 'd')                                                                 \
    X(trianglearealist, 'd')                                                                      \
    X(neighborlist, 'i')                                                                          \
    X(numberoftriangles, 'n')                                                                     \
    X(numberofcorners, 'n')                                                                       \
    X(numberoftriangleattributes, 'n')                                                            \
    X(segmentlist, 'i')                                                                           \
    X(segmentmarkerlist, 'i')                                                                     \
    X(numberofsegments, 'n')                                                                      \
    X(holelist, 'd')                                                                              \
    X(numberofholes, 'n')                                                                         \
    X(regionlist, 'd')                                                                            \
    X(numberofregions, 'n')                                                                       \
    X(edgelist, 'i')                                                                              \
    X(edgemarkerlist, 'i')                                                                        \
    X(normlist, 'd')                                                                              \
    X(numberofedges, 'n')

#define TRIANGULATEIO_FIELD_COUNT 23

#endif
