/* A C program written the way Triangle's users write them: zeroed structs, a full call on a small
 * point set, checks of every output array, `trifree` of each, caller-provided output buffers,
 * `triangulate_catch_exit`, and the error paths (non-zero return, a message from
 * `triangulate_last_error`, nothing written, nothing printed).
 *
 * Every call passes `Q`, so on success this program prints nothing at all (tests/ctests.rs checks
 * that stdout and stderr stay empty; under valgrind it also checks for leaks).
 * `basic loud` makes one failing call without `Q` instead: Triangle reports errors even then, and
 * the test checks that something was printed.
 *
 * Exit codes: 0 all checks passed, 1 a check failed (described on stdout). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "triangle_rs.h"

static int failures = 0;

#define CHECK(cond, ...)                                                                          \
    do {                                                                                          \
        if (!(cond)) {                                                                            \
            printf("%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);                       \
            printf(__VA_ARGS__);                                                                  \
            printf("\n");                                                                         \
            failures++;                                                                           \
        }                                                                                         \
    } while (0)

/* Eight points: a 4 x 3 rectangle and four interior points in general position. The Delaunay
 * triangulation of n points with h on the hull (none collinear) has 2n - 2 - h triangles and
 * 3n - 3 - h edges. */
#define NPOINTS 8
#define NHULL 4
#define NTRIANGLES (2 * NPOINTS - 2 - NHULL)
#define NEDGES (3 * NPOINTS - 3 - NHULL)
static double points[2 * NPOINTS] = {0, 0, 4, 0, 4, 3, 0, 3, 1, 1, 3, 1.2, 2.2, 2.1, 1.3, 2.4};
static double attributes[NPOINTS] = {10, 11, 12, 13, 14, 15, 16, 17};
/* Point 5 (an interior point) carries marker 7, corner 2 carries marker 5; the rest 0. */
static int markers[NPOINTS] = {0, 0, 5, 0, 0, 7, 0, 0};
static const int is_hull[NPOINTS] = {1, 1, 1, 1, 0, 0, 0, 0};

static void make_input(struct triangulateio *in) {
    memset(in, 0, sizeof *in);
    in->pointlist = points;
    in->numberofpoints = NPOINTS;
    in->pointattributelist = attributes;
    in->numberofpointattributes = 1;
    in->pointmarkerlist = markers;
}

static int all_pointers_null(const struct triangulateio *io) {
    return io->pointlist == NULL && io->pointattributelist == NULL && io->pointmarkerlist == NULL &&
           io->trianglelist == NULL && io->triangleattributelist == NULL &&
           io->trianglearealist == NULL && io->neighborlist == NULL && io->segmentlist == NULL &&
           io->segmentmarkerlist == NULL && io->holelist == NULL && io->regionlist == NULL &&
           io->edgelist == NULL && io->edgemarkerlist == NULL && io->normlist == NULL;
}

static void free_all(struct triangulateio *io) {
    /* holelist/regionlist alias the input's arrays (Triangle's rule): never freed here. */
    trifree(io->pointlist);
    trifree(io->pointattributelist);
    trifree(io->pointmarkerlist);
    trifree(io->trianglelist);
    trifree(io->triangleattributelist);
    trifree(io->neighborlist);
    trifree(io->segmentlist);
    trifree(io->segmentmarkerlist);
    trifree(io->edgelist);
    trifree(io->edgemarkerlist);
    trifree(io->normlist);
    memset(io, 0, sizeof *io);
}

static double cross(const double *a, const double *b, const double *c) {
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static int is_hull_edge(int a, int b) {
    /* The hull is the rectangle 0-1-2-3. */
    int lo = a < b ? a : b, hi = a < b ? b : a;
    return lo >= 0 && hi <= 3 && (hi - lo == 1 || (lo == 0 && hi == 3));
}

/* Does triangle t (0-based corners) contain the directed or undirected edge a-b? */
static int triangle_has_edge(const int *t, int a, int b) {
    int k;
    for (k = 0; k < 3; k++) {
        int u = t[k], v = t[(k + 1) % 3];
        if ((u == a && v == b) || (u == b && v == a)) return 1;
    }
    return 0;
}

/* Checks the full output of `zcenvQ` (base 0) or `cenvQ` (base 1). */
static void check_full_output(const struct triangulateio *out, const struct triangulateio *vor,
                              int base) {
    int i, k, hull_segments = 0, hull_edges = 0, rays = 0;
    double area = 0;
    int tri[NTRIANGLES * 3];

    CHECK(out->numberofpoints == NPOINTS, "%d", out->numberofpoints);
    CHECK(out->numberofpointattributes == 1, "%d", out->numberofpointattributes);
    CHECK(out->pointlist != NULL && out->pointlist != points, "pointlist is a new array");
    CHECK(out->pointattributelist != NULL, "pointattributelist written");
    CHECK(out->pointmarkerlist != NULL, "pointmarkerlist written");
    if (out->pointlist && out->pointattributelist && out->pointmarkerlist) {
        for (i = 0; i < NPOINTS; i++) {
            int expected = markers[i] != 0 ? markers[i] : is_hull[i];
            CHECK(out->pointlist[2 * i] == points[2 * i] &&
                      out->pointlist[2 * i + 1] == points[2 * i + 1],
                  "point %d moved", i);
            CHECK(out->pointattributelist[i] == attributes[i], "attribute of point %d", i);
            CHECK(out->pointmarkerlist[i] == expected, "marker of point %d = %d, expected %d", i,
                  out->pointmarkerlist[i], expected);
        }
    }

    CHECK(out->numberoftriangles == NTRIANGLES, "%d triangles", out->numberoftriangles);
    CHECK(out->numberofcorners == 3, "%d corners", out->numberofcorners);
    CHECK(out->numberoftriangleattributes == 0, "%d", out->numberoftriangleattributes);
    CHECK(out->triangleattributelist == NULL, "no triangle attributes");
    CHECK(out->trianglearealist == NULL, "trianglearealist is never written");
    if (out->trianglelist == NULL || out->numberoftriangles != NTRIANGLES) {
        CHECK(0, "no usable trianglelist");
        return;
    }
    for (i = 0; i < 3 * NTRIANGLES; i++) tri[i] = out->trianglelist[i] - base;
    for (i = 0; i < NTRIANGLES; i++) {
        const int *t = tri + 3 * i;
        int valid = 1;
        for (k = 0; k < 3; k++) valid &= t[k] >= 0 && t[k] < NPOINTS;
        CHECK(valid, "triangle %d has an index out of range", i);
        if (!valid) return;
        CHECK(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "triangle %d repeats a vertex", i);
        {
            double c = cross(points + 2 * t[0], points + 2 * t[1], points + 2 * t[2]);
            CHECK(c > 0, "triangle %d is not counter-clockwise (cross %g)", i, c);
            area += c / 2;
        }
    }
    CHECK(fabs(area - 12.0) < 1e-12, "triangle areas sum to %.17g, not the hull area 12", area);

    /* Neighbours: neighbour k is opposite corner k and shares the edge of the other two corners;
     * -1 exactly on the hull. */
    CHECK(out->neighborlist != NULL, "neighborlist written");
    if (out->neighborlist) {
        for (i = 0; i < NTRIANGLES; i++) {
            const int *t = tri + 3 * i;
            for (k = 0; k < 3; k++) {
                int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
                int nb = out->neighborlist[3 * i + k];
                if (is_hull_edge(a, b)) {
                    CHECK(nb == -1, "triangle %d, hull edge %d-%d has neighbour %d", i, a, b, nb);
                } else {
                    int j = nb - base;
                    CHECK(nb != -1 && j >= 0 && j < NTRIANGLES && j != i &&
                              triangle_has_edge(tri + 3 * j, a, b),
                          "triangle %d: neighbour %d across %d-%d does not share that edge", i, nb,
                          a, b);
                }
            }
        }
    }

    /* c: the hull as segments with marker 1. */
    CHECK(out->numberofsegments == NHULL, "%d segments", out->numberofsegments);
    CHECK(out->segmentlist != NULL && out->segmentmarkerlist != NULL, "segments written");
    if (out->segmentlist && out->segmentmarkerlist) {
        for (i = 0; i < out->numberofsegments && i < 64; i++) {
            int a = out->segmentlist[2 * i] - base, b = out->segmentlist[2 * i + 1] - base;
            hull_segments += is_hull_edge(a, b);
            CHECK(out->segmentmarkerlist[i] == 1, "segment %d marker %d", i,
                  out->segmentmarkerlist[i]);
        }
        CHECK(hull_segments == NHULL, "%d segments lie on the hull", hull_segments);
    }
    CHECK(out->holelist == NULL && out->regionlist == NULL, "no holes/regions without p");
    CHECK(out->numberofholes == 0 && out->numberofregions == 0, "hole/region counts");

    /* e: every triangulation edge once, marker 1 on the hull, else 0. */
    CHECK(out->numberofedges == NEDGES, "%d edges", out->numberofedges);
    CHECK(out->edgelist != NULL && out->edgemarkerlist != NULL, "edges written");
    CHECK(out->normlist == NULL, "out.normlist is for Voronoi only");
    if (out->edgelist && out->edgemarkerlist && out->numberofedges == NEDGES) {
        for (i = 0; i < NEDGES; i++) {
            int a = out->edgelist[2 * i] - base, b = out->edgelist[2 * i + 1] - base;
            int found = 0;
            for (k = 0; k < NTRIANGLES; k++) found += triangle_has_edge(tri + 3 * k, a, b);
            CHECK(found == (is_hull_edge(a, b) ? 1 : 2), "edge %d-%d lies in %d triangles", a, b,
                  found);
            CHECK(out->edgemarkerlist[i] == is_hull_edge(a, b), "edge %d-%d marker %d", a, b,
                  out->edgemarkerlist[i]);
            hull_edges += is_hull_edge(a, b);
            for (k = 0; k < i; k++) {
                int c = out->edgelist[2 * k] - base, d = out->edgelist[2 * k + 1] - base;
                CHECK(!((a == c && b == d) || (a == d && b == c)), "edge %d-%d listed twice", a, b);
            }
        }
        CHECK(hull_edges == NHULL, "%d hull edges", hull_edges);
    }

    /* v: one vertex per triangle (its circumcentre), one edge per triangulation edge, rays on the
     * hull with second index -1 and a non-zero direction. */
    CHECK(vor->numberofpoints == NTRIANGLES, "%d Voronoi points", vor->numberofpoints);
    CHECK(vor->numberofpointattributes == 1, "%d", vor->numberofpointattributes);
    CHECK(vor->numberofedges == NEDGES, "%d Voronoi edges", vor->numberofedges);
    CHECK(vor->pointlist && vor->pointattributelist && vor->edgelist && vor->normlist,
          "Voronoi arrays written");
    CHECK(vor->pointmarkerlist == NULL && vor->edgemarkerlist == NULL, "Voronoi has no markers");
    if (vor->pointlist && vor->edgelist && vor->normlist && vor->numberofpoints == NTRIANGLES &&
        vor->numberofedges == NEDGES) {
        for (i = 0; i < NTRIANGLES; i++) {
            const double *c = vor->pointlist + 2 * i;
            double r[3];
            for (k = 0; k < 3; k++) {
                const double *p = points + 2 * tri[3 * i + k];
                r[k] = hypot(p[0] - c[0], p[1] - c[1]);
            }
            CHECK(fabs(r[0] - r[1]) < 1e-9 && fabs(r[0] - r[2]) < 1e-9,
                  "Voronoi point %d is not the circumcentre of triangle %d", i, i);
        }
        for (i = 0; i < NEDGES; i++) {
            int a = vor->edgelist[2 * i] - base, b = vor->edgelist[2 * i + 1];
            const double *norm = vor->normlist + 2 * i;
            CHECK(a >= 0 && a < NTRIANGLES, "Voronoi edge %d starts at %d", i, a);
            if (b == -1) {
                rays++;
                CHECK(norm[0] != 0 || norm[1] != 0, "ray %d has no direction", i);
            } else {
                b -= base;
                CHECK(b >= 0 && b < NTRIANGLES && b != a, "Voronoi edge %d ends at %d", i, b);
                CHECK(norm[0] == 0 && norm[1] == 0, "finite Voronoi edge %d has a direction", i);
            }
        }
        CHECK(rays == NHULL, "%d rays", rays);
    }
}

/* A full call with every output. */
static void full_call(const char *switches, int base) {
    struct triangulateio in, out, vor;
    int rc;
    make_input(&in);
    memset(&out, 0, sizeof out);
    memset(&vor, 0, sizeof vor);
    rc = triangulate(switches, &in, &out, &vor);
    CHECK(rc == 0, "triangulate(\"%s\") returned %d: %s", switches, rc, triangulate_last_error());
    CHECK(strcmp(triangulate_last_error(), "") == 0, "last error after a success: %s",
          triangulate_last_error());
    if (rc == 0) check_full_output(&out, &vor, base);
    /* The input is read only. */
    CHECK(in.pointlist == points && points[2] == 4 && markers[5] == 7, "input changed");
    free_all(&out);
    free_all(&vor);
    return 1;
}

/* Triangle's "Fortran" convention: non-NULL output pointers are the caller's buffers and are
 * written into, never replaced; `out.pointlist = in.pointlist` is allowed. */
static void caller_buffers(void) {
    struct triangulateio in, out, vor;
    double point_buffer[2 * NPOINTS];
    int marker_buffer[NPOINTS];
    int triangle_buffer[3 * NTRIANGLES + 1];
    int edge_buffer[2 * NEDGES];
    double points_copy[2 * NPOINTS];
    int i, rc;

    make_input(&in);
    memset(&out, 0, sizeof out);
    memset(&vor, 0, sizeof vor);
    for (i = 0; i < 2 * NPOINTS; i++) point_buffer[i] = -999;
    for (i = 0; i < 3 * NTRIANGLES + 1; i++) triangle_buffer[i] = -999;
    out.pointlist = point_buffer;
    out.pointmarkerlist = marker_buffer;
    out.trianglelist = triangle_buffer;
    out.edgelist = edge_buffer;
    rc = triangulate("zeQ", &in, &out, &vor);
    CHECK(rc == 0, "caller buffers: %s", triangulate_last_error());
    CHECK(out.pointlist == point_buffer && out.pointmarkerlist == marker_buffer &&
              out.trianglelist == triangle_buffer && out.edgelist == edge_buffer,
          "a caller buffer was replaced");
    for (i = 0; i < 2 * NPOINTS; i++) CHECK(point_buffer[i] == points[i], "point %d", i / 2);
    for (i = 0; i < 3 * NTRIANGLES; i++)
        CHECK(triangle_buffer[i] >= 0 && triangle_buffer[i] < NPOINTS, "corner %d", i);
    CHECK(triangle_buffer[3 * NTRIANGLES] == -999, "written past the triangles");
    for (i = 0; i < NPOINTS; i++)
        CHECK(marker_buffer[i] == (markers[i] ? markers[i] : is_hull[i]), "marker %d", i);
    /* The arrays this call allocated (it had no buffer for them). */
    trifree(out.pointattributelist);
    trifree(out.edgemarkerlist);
    CHECK(out.neighborlist == NULL && out.segmentlist == NULL, "not asked for");

    /* out.pointlist = in.pointlist: the output overwrites the input with the same points. */
    memcpy(points_copy, points, sizeof points);
    make_input(&in);
    in.pointlist = points_copy;
    memset(&out, 0, sizeof out);
    out.pointlist = in.pointlist;
    rc = triangulate("zQ", &in, &out, NULL);
    CHECK(rc == 0, "aliased pointlist: %s", triangulate_last_error());
    CHECK(out.pointlist == points_copy, "aliased pointlist replaced");
    CHECK(memcmp(points_copy, points, sizeof points) == 0, "aliased pointlist changed");
    out.pointlist = NULL; /* the caller's, not ours to free */
    free_all(&out);
}

static void catch_exit(void) {
    struct triangulateio in, out;
    int rc;
    make_input(&in);
    memset(&out, 0, sizeof out);
    rc = triangulate_catch_exit("zQ", &in, &out, NULL);
    CHECK(rc == 0, "triangulate_catch_exit success returned %d", rc);
    free_all(&out);
    in.numberofpoints = 2;
    rc = triangulate_catch_exit("zQ", &in, &out, NULL);
    CHECK(rc == 1, "triangulate_catch_exit error returned %d", rc);
    CHECK(all_pointers_null(&out), "output written on error");
}

/* One failing call: non-zero, a message containing `keyword` (case-insensitive), nothing
 * written to out or vorout. */
static void expect_error(const char *what, const char *switches, struct triangulateio *in,
                         int give_out, int give_vorout, const char *keyword, int check_keyword) {
    struct triangulateio out, vor;
    const char *message;
    int rc;
    memset(&out, 0, sizeof out);
    memset(&vor, 0, sizeof vor);
    rc = triangulate(switches, in, give_out ? &out : NULL, give_vorout ? &vor : NULL);
    message = triangulate_last_error();
    CHECK(rc != 0, "%s: succeeded", what);
    CHECK(message != NULL && message[0] != '\0', "%s: no message", what);
    if (check_keyword && message != NULL) {
        char lower[512];
        size_t k;
        for (k = 0; message[k] && k + 1 < sizeof lower; k++)
            lower[k] = (char)(message[k] >= 'A' && message[k] <= 'Z' ? message[k] + 32 : message[k]);
        lower[k] = '\0';
        CHECK(strstr(lower, keyword) != NULL, "%s: message \"%s\" lacks \"%s\"", what, message,
              keyword);
    }
    CHECK(all_pointers_null(&out) && all_pointers_null(&vor), "%s: output written on error",
          what);
    free_all(&out);
    free_all(&vor);
}

static void error_paths(void) {
    struct triangulateio in;
    double bad[2 * NPOINTS];
    int i;

    make_input(&in);
    expect_error("NULL in", "zQ", NULL, 1, 1, "null", 1);
    expect_error("NULL out", "zQ", &in, 0, 1, "null", 1);
    expect_error("NULL switches", NULL, &in, 1, 1, "null", 1);
    expect_error("v with NULL vorout", "zvQ", &in, 1, 0, "vorout", 1);

    make_input(&in);
    in.numberofpoints = -1;
    expect_error("negative numberofpoints", "zQ", &in, 1, 1, "numberofpoints", 1);
    make_input(&in);
    in.numberofpointattributes = -3;
    expect_error("negative numberofpointattributes", "zQ", &in, 1, 1, "numberofpointattributes",
                 1);
    make_input(&in);
    in.pointlist = NULL;
    expect_error("NULL pointlist", "zQ", &in, 1, 1, "pointlist", 1);
    make_input(&in);
    in.pointattributelist = NULL;
    expect_error("NULL pointattributelist", "zQ", &in, 1, 1, "pointattributelist", 1);

    for (i = 0; i < 2 * NPOINTS; i++) bad[i] = points[i];
    bad[7] = NAN;
    make_input(&in);
    in.pointlist = bad;
    expect_error("NaN coordinate", "zQ", &in, 1, 1, "finite", 1);
    bad[7] = points[7];
    bad[10] = -INFINITY;
    expect_error("infinite coordinate", "zQ", &in, 1, 1, "finite", 1);
    make_input(&in);
    in.numberofpoints = 2;
    expect_error("two points", "zQ", &in, 1, 1, "three", 1);
    in.numberofpoints = 0;
    expect_error("no points", "zQ", &in, 1, 1, "three", 1);
    make_input(&in);
    expect_error("a0", "za0Q", &in, 1, 1, "area", 1);
    expect_error("a0.0", "za0.0Q", &in, 1, 1, "area", 1);

    /* A success after failures clears the message. */
    {
        struct triangulateio out;
        memset(&out, 0, sizeof out);
        make_input(&in);
        CHECK(triangulate("zQ", &in, &out, NULL) == 0, "%s", triangulate_last_error());
        CHECK(triangulate_last_error()[0] == '\0', "message kept after success");
        free_all(&out);
    }
}

/* Warnings are kept for the caller with or without Q (triangulate_last_warning): a duplicate
 * vertex, and a quality mesh that the coordinates' precision keeps below the angle (300 points
 * in a square 800 units in the last place wide at 10^15); a clean call clears them. */
static void warnings(void) {
    struct triangulateio in, out;
    double doubled[2 * (NPOINTS + 1)];
    make_input(&in);
    memcpy(doubled, points, sizeof points);
    doubled[2 * NPOINTS] = points[4];
    doubled[2 * NPOINTS + 1] = points[5];
    in.pointlist = doubled;
    in.numberofpoints = NPOINTS + 1;
    in.pointattributelist = NULL;
    in.numberofpointattributes = 0;
    in.pointmarkerlist = NULL;
    memset(&out, 0, sizeof out);
    CHECK(triangulate("zQ", &in, &out, NULL) == 0, "%s", triangulate_last_error());
    CHECK(strstr(triangulate_last_warning(), "duplicate") != NULL, "duplicate warning: '%s'",
          triangulate_last_warning());
    free_all(&out);

    enum { FAR = 300 };
    static double far[2 * FAR];
    unsigned long long state = 12345;
    for (int i = 0; i < 2 * FAR; i++) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        far[i] = 1e15 + (double)(state >> 11) / 9007199254740992.0 * 100.0;
    }
    memset(&in, 0, sizeof in);
    in.pointlist = far;
    in.numberofpoints = FAR;
    memset(&out, 0, sizeof out);
    CHECK(triangulate("zq30Q", &in, &out, NULL) == 0, "%s", triangulate_last_error());
    CHECK(strstr(triangulate_last_warning(), "precision") != NULL, "precision warning: '%s'",
          triangulate_last_warning());
    free_all(&out);

    make_input(&in);
    memset(&out, 0, sizeof out);
    CHECK(triangulate("zQ", &in, &out, NULL) == 0, "%s", triangulate_last_error());
    CHECK(triangulate_last_warning()[0] == '\0', "warning kept: '%s'", triangulate_last_warning());
    free_all(&out);
}

int main(int argc, char **argv) {
    if (argc > 1 && strcmp(argv[1], "loud") == 0) {
        struct triangulateio in;
        make_input(&in);
        in.numberofpoints = 2;
        /* Without Q the error must be reported on stdout or stderr. */
        return triangulate("z", &in, NULL, NULL) != 0 ? 0 : 1;
    }
    full_call("zcenvQ", 0);
    full_call("cenvQ", 1);
    caller_buffers();
    catch_exit();
    error_paths();
    warnings();
    if (failures) {
        printf("%d check(s) failed\n", failures);
        return 1;
    }
    return 0;
}
