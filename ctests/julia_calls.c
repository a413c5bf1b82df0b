/*
 * The library calls of the Julia package TriangleRS (julia/src) and of Triangulate.jl run on
 * triangle-rs, made from C, so that they are tested on machines without Julia
 * (tests/julia_abi.rs compiles and runs this file in `cargo test`).
 *
 * Everything here mirrors the Julia code: the same symbols and argument types as its `ccall`s,
 * the same struct (CTriangulateIO), input arrays built as Julia builds them (column-major, one
 * column per item, 1-based indices), the same ownership (every output array is owned and freed
 * with libc `free`, as `unsafe_wrap(...; own=true)` lets Julia's GC do, except `holelist` and
 * `regionlist`, which alias the input), the same callback (seven doubles plus `user_data`
 * through a trampoline; the global `triunsuitable_callback` for Triangulate.jl).
 *
 * The cases are those of Triangulate.jl's test suite. Their expectations are facts about the
 * mesh, not Triangle's element order: exact counts where the mesh is unique, counts within a
 * band around Triangle 1.6's where refinement makes them depend on the order of insertion.
 *
 * Output: one line per case, `PASS <case>` or `FAIL <case>: ...`. Exit status 0 if nothing
 * failed.
 */
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---------------------------------------------------------------------------------------- */
/* The C side of Julia's `mutable struct CTriangulateIO` (julia/src/ctriangulateio.jl):       */
/* Ptr{Cdouble} = double *, Ptr{Cint} = int *, Cint = int, in the same order.                */

struct CTriangulateIO {
    double *pointlist;
    double *pointattributelist;
    int *pointmarkerlist;
    int numberofpoints;
    int numberofpointattributes;

    int *trianglelist;
    double *triangleattributelist;
    double *trianglearealist;
    int *neighborlist;
    int numberoftriangles;
    int numberofcorners;
    int numberoftriangleattributes;

    int *segmentlist;
    int *segmentmarkerlist;
    int numberofsegments;

    double *holelist;
    int numberofholes;

    double *regionlist;
    int numberofregions;

    int *edgelist;
    int *edgemarkerlist;
    double *normlist;
    int numberofedges;
};

_Static_assert(sizeof(struct CTriangulateIO) == 168 || sizeof(void *) != 8,
               "CTriangulateIO must be Triangle's 168-byte struct on 64-bit systems");

/* Where Triangle's own header is installed, check the mirror against it field by field. */
#if defined(__has_include)
#if __has_include(<triangle.h>)
#include <triangle.h>
#define SAME_OFFSET(field)                                                                   \
    _Static_assert(offsetof(struct CTriangulateIO, field) == offsetof(struct triangulateio, field), \
                   "offset of " #field)
SAME_OFFSET(pointlist);
SAME_OFFSET(pointattributelist);
SAME_OFFSET(pointmarkerlist);
SAME_OFFSET(numberofpoints);
SAME_OFFSET(numberofpointattributes);
SAME_OFFSET(trianglelist);
SAME_OFFSET(triangleattributelist);
SAME_OFFSET(trianglearealist);
SAME_OFFSET(neighborlist);
SAME_OFFSET(numberoftriangles);
SAME_OFFSET(numberofcorners);
SAME_OFFSET(numberoftriangleattributes);
SAME_OFFSET(segmentlist);
SAME_OFFSET(segmentmarkerlist);
SAME_OFFSET(numberofsegments);
SAME_OFFSET(holelist);
SAME_OFFSET(numberofholes);
SAME_OFFSET(regionlist);
SAME_OFFSET(numberofregions);
SAME_OFFSET(edgelist);
SAME_OFFSET(edgemarkerlist);
SAME_OFFSET(normlist);
SAME_OFFSET(numberofedges);
_Static_assert(sizeof(struct CTriangulateIO) == sizeof(struct triangulateio), "size");
#endif
#endif

/* The library's entry points, declared as the Julia `ccall`s type them. */

/* TriangleRS: ccall(lib.triangulate_reentrant, Cint, (Cstring, Ref{CTriangulateIO} x3,
   Ptr{Cvoid}, Ptr{Cvoid}, Ref{Cint}), ...). The callback is the @cfunction of
   `unsuitable_trampoline`: Cint (Cdouble x7, Ptr{Cvoid}). */
typedef int (*ReentrantUnsuitable)(double, double, double, double, double, double, double, void *);
int triangulate_reentrant(const char *switches, struct CTriangulateIO *in, struct CTriangulateIO *out,
                          struct CTriangulateIO *vorout, ReentrantUnsuitable unsuitable, void *user_data,
                          const int *cancel);
/* TriangleRS: ccall(lib.triangulate_last_error, Ptr{UInt8}, ()). */
const char *triangulate_last_error(void);
/* TriangleRS: ccall(lib.trifree, Cvoid, (Ptr{Cvoid},), p). */
void trifree(void *memptr);

/* Triangulate.jl (Triangle_jll's names): ccall((:triangulate_catch_exit, libtriangle), Cint,
   (Cstring, Ref{CTriangulateIO} x3), ...) and ccall((:triunsuitable_callback, libtriangle),
   Cvoid, (Ptr{Cvoid},), @cfunction(jl_wrap_triunsuitable, Cint, (Cdouble x7))). */
typedef int (*GlobalUnsuitable)(double, double, double, double, double, double, double);
int triangulate_catch_exit(char *switches, struct CTriangulateIO *in, struct CTriangulateIO *out,
                           struct CTriangulateIO *vorout);
void triunsuitable_callback(GlobalUnsuitable unsuitable);

/* ---------------------------------------------------------------------------------------- */
/* Reporting.                                                                                */

static int failures = 0;
static const char *current_case = "";
static bool case_failed = false;

#define CHECK(cond, ...)                                                                     \
    do {                                                                                     \
        if (!(cond)) {                                                                       \
            printf("FAIL %s: line %d: %s: ", current_case, __LINE__, #cond);                 \
            printf(__VA_ARGS__);                                                             \
            printf("\n");                                                                    \
            case_failed = true;                                                              \
        }                                                                                    \
    } while (0)

static void begin_case(const char *name) {
    current_case = name;
    case_failed = false;
}

static void end_case(void) {
    if (case_failed) {
        failures++;
    } else {
        printf("PASS %s\n", current_case);
    }
    fflush(stdout);
}

/* ---------------------------------------------------------------------------------------- */
/* Julia arrays as TriangleRS holds them: column-major, dims[0] rows (an item's width) by     */
/* dims[1] columns (the items); a Vector has ndims 1. `owned` is an array that Julia took with */
/* unsafe_wrap(...; own=true): its GC frees it with libc `free`.                              */

typedef struct {
    void *data;
    int ndims;
    int dims[2];
    bool owned;
} JArray;

static JArray jl_empty(int ndims) {
    JArray a = {NULL, ndims, {0, 0}, false};
    return a;
}

static size_t jl_length(JArray a) { return a.ndims == 1 ? (size_t)a.dims[0] : (size_t)a.dims[0] * a.dims[1]; }
static bool jl_isempty(JArray a) { return jl_length(a) == 0; }
static int jl_items(JArray a) { return a.dims[a.ndims - 1]; } /* size(a, ndims(a)) */
static int jl_rows(JArray a) { return a.dims[0]; }             /* size(a, 1) */

/* 1-based element access, as in Julia. */
#define JF(a, i, j) (((double *)(a).data)[((i) - 1) + (size_t)((j) - 1) * (a).dims[0]])
#define JI(a, i, j) (((int *)(a).data)[((i) - 1) + (size_t)((j) - 1) * (a).dims[0]])
#define JIV(a, i) (((int *)(a).data)[(i) - 1])

/* Julia arrays that Julia code allocated itself (input arrays) are kept in this pool: the GC
   frees them, never the library. */
static void *julia_heap[256];
static int julia_heap_used = 0;

static void *julia_alloc(size_t bytes) {
    void *p = calloc(1, bytes ? bytes : 1);
    if (p == NULL || julia_heap_used == (int)(sizeof julia_heap / sizeof julia_heap[0])) {
        fprintf(stderr, "out of test memory\n");
        exit(2);
    }
    julia_heap[julia_heap_used++] = p;
    return p;
}

/* The Julia literal `T[a b c; d e f]` (rows x cols, written row by row) as a Julia matrix. */
static JArray jl_matrix(size_t elsize, int rows, int cols, const void *row_major) {
    JArray a = {julia_alloc(elsize * rows * cols), 2, {rows, cols}, false};
    for (int i = 0; i < rows; i++)
        for (int j = 0; j < cols; j++)
            memcpy((char *)a.data + elsize * (i + (size_t)j * rows), (const char *)row_major + elsize * (i * cols + j),
                   elsize);
    return a;
}

static JArray jl_f64(int rows, int cols, const double *row_major) { return jl_matrix(sizeof(double), rows, cols, row_major); }
static JArray jl_int(int rows, int cols, const int *row_major) { return jl_matrix(sizeof(int), rows, cols, row_major); }

/* `Matrix(a')`: the transposed copy, as `Matrix{Float64}([...]')` materialises it. */
static JArray jl_adjoint(size_t elsize, JArray a) {
    JArray t = {julia_alloc(elsize * jl_length(a)), 2, {a.dims[1], a.dims[0]}, false};
    for (int i = 0; i < a.dims[0]; i++)
        for (int j = 0; j < a.dims[1]; j++)
            memcpy((char *)t.data + elsize * (j + (size_t)i * t.dims[0]), (char *)a.data + elsize * (i + (size_t)j * a.dims[0]),
                   elsize);
    return t;
}

/* `T[a, b, c]`. */
static JArray jl_vector(size_t elsize, int n, const void *values) {
    JArray v = {julia_alloc(elsize * n), 1, {n, 0}, false};
    memcpy(v.data, values, elsize * n);
    return v;
}

/* Julia's `mutable struct TriangulateIO` (julia/src/triangulateio.jl), field for field. */
typedef struct {
    JArray pointlist;             /* Matrix{Cdouble} 2 x n */
    JArray pointattributelist;    /* Matrix{Cdouble} k x n */
    JArray pointmarkerlist;       /* Vector{Cint} n */
    JArray trianglelist;          /* Matrix{Cint} 3|6 x m */
    JArray triangleattributelist; /* Matrix{Cdouble} k x m */
    JArray trianglearealist;      /* Vector{Cdouble} m */
    JArray neighborlist;          /* Matrix{Cint} 3 x m */
    JArray segmentlist;           /* Matrix{Cint} 2 x s */
    JArray segmentmarkerlist;     /* Vector{Cint} s */
    JArray holelist;              /* Matrix{Cdouble} 2 x h */
    JArray regionlist;            /* Matrix{Cdouble} 4 x r */
    JArray edgelist;              /* Matrix{Cint} 2 x e */
    JArray edgemarkerlist;        /* Vector{Cint} e */
    JArray normlist;              /* Matrix{Cdouble} 2 x e */
} JTriangulateIO;

/* The keyword constructor with no arguments: every field empty. */
static JTriangulateIO jl_triangulateio(void) {
    JTriangulateIO t = {
        jl_empty(2), jl_empty(2), jl_empty(1), jl_empty(2), jl_empty(2), jl_empty(1), jl_empty(2),
        jl_empty(2), jl_empty(1), jl_empty(2), jl_empty(2), jl_empty(2), jl_empty(1), jl_empty(2),
    };
    return t;
}

/* What Julia's GC does once a TriangulateIO is unreachable: free the arrays it owns. */
static void jl_gc_collect(JTriangulateIO *t) {
    JArray *fields[] = {&t->pointlist, &t->pointattributelist, &t->pointmarkerlist, &t->trianglelist,
                        &t->triangleattributelist, &t->trianglearealist, &t->neighborlist, &t->segmentlist,
                        &t->segmentmarkerlist, &t->holelist, &t->regionlist, &t->edgelist, &t->edgemarkerlist,
                        &t->normlist};
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++) {
        if (fields[i]->owned) free(fields[i]->data);
        *fields[i] = jl_empty(fields[i]->ndims);
    }
}

/* ---------------------------------------------------------------------------------------- */
/* CTriangulateIO(tio::TriangulateIO): pointers into the Julia arrays, no copies.             */

static void *array_pointer(JArray a) { return jl_isempty(a) ? NULL : a.data; }

/* Returns false (Julia: ArgumentError) when sizes do not match. */
static bool ctio_from_tio(const JTriangulateIO *t, struct CTriangulateIO *c) {
    memset(c, 0, sizeof *c);
    int npoints = t->pointlist.dims[1];
    if (npoints > 0 && jl_rows(t->pointlist) != 2) return false;
    c->numberofpoints = npoints;
    c->pointlist = array_pointer(t->pointlist);
    int nattributes = jl_rows(t->pointattributelist);
    if (nattributes > 0) {
        if (jl_items(t->pointattributelist) != npoints) return false;
        c->numberofpointattributes = nattributes;
        c->pointattributelist = array_pointer(t->pointattributelist);
    }
    if (!jl_isempty(t->pointmarkerlist)) {
        if (jl_items(t->pointmarkerlist) != npoints) return false;
        c->pointmarkerlist = array_pointer(t->pointmarkerlist);
    }
    int ntriangles = t->trianglelist.dims[1];
    if (ntriangles > 0) {
        c->numberoftriangles = ntriangles;
        c->numberofcorners = jl_rows(t->trianglelist);
        c->trianglelist = array_pointer(t->trianglelist);
        int ntriangleattributes = jl_rows(t->triangleattributelist);
        if (ntriangleattributes > 0) {
            if (jl_items(t->triangleattributelist) != ntriangles) return false;
            c->numberoftriangleattributes = ntriangleattributes;
            c->triangleattributelist = array_pointer(t->triangleattributelist);
        }
        if (!jl_isempty(t->trianglearealist)) {
            if (jl_items(t->trianglearealist) != ntriangles) return false;
            c->trianglearealist = array_pointer(t->trianglearealist);
        }
    }
    int nsegments = t->segmentlist.dims[1];
    if (nsegments > 0 && jl_rows(t->segmentlist) != 2) return false;
    c->numberofsegments = nsegments;
    c->segmentlist = array_pointer(t->segmentlist);
    if (nsegments > 0 && !jl_isempty(t->segmentmarkerlist)) {
        if (jl_items(t->segmentmarkerlist) != nsegments) return false;
        c->segmentmarkerlist = array_pointer(t->segmentmarkerlist);
    }
    int nholes = t->holelist.dims[1];
    if (nholes > 0 && jl_rows(t->holelist) != 2) return false;
    c->numberofholes = nholes;
    c->holelist = array_pointer(t->holelist);
    int nregions = t->regionlist.dims[1];
    if (nregions > 0 && jl_rows(t->regionlist) != 4) return false;
    c->numberofregions = nregions;
    c->regionlist = array_pointer(t->regionlist);
    return true;
}

/* ---------------------------------------------------------------------------------------- */
/* TriangulateIO(ctio; input): take ownership of the library's arrays.                       */

/* take_array: NULL -> empty; zero-sized -> freed now with trifree; else owned (own=true). */
static JArray take_array(void *p, int ndims, int rows, int cols) {
    if (p == NULL) return jl_empty(ndims);
    if (rows == 0 || (ndims == 2 && cols == 0)) {
        trifree(p);
        return jl_empty(ndims);
    }
    JArray a = {p, ndims, {rows, ndims == 2 ? cols : 0}, true};
    return a;
}

/* aliased_array: holelist/regionlist are the input's arrays; never owned. */
static JArray aliased_array(double *p, int rows, int items, const JArray *input) {
    if (p == NULL || items == 0) return jl_empty(2);
    if (input != NULL && !jl_isempty(*input) && p == (double *)input->data) return *input; /* shared */
    JArray a = {p, 2, {rows, items}, false};                                                  /* own=false */
    return a;
}

/* ALLOCATED_FIELDS in ctriangulateio.jl: every array the library may allocate in out/vorout
   (not holelist/regionlist, which it copies from the input). */
#define FOR_ALLOCATED_FIELDS(X)                                                                \
    X(pointlist) X(pointattributelist) X(pointmarkerlist) X(trianglelist) X(triangleattributelist) \
    X(trianglearealist) X(neighborlist) X(segmentlist) X(segmentmarkerlist) X(edgelist)        \
    X(edgemarkerlist) X(normlist)

static void tio_from_ctio(struct CTriangulateIO *c, const JTriangulateIO *input, JTriangulateIO *t) {
    int np = c->numberofpoints, nt = c->numberoftriangles, ns = c->numberofsegments, ne = c->numberofedges;
    *t = jl_triangulateio();
    t->pointlist = take_array(c->pointlist, 2, 2, np);
    t->pointattributelist = take_array(c->pointattributelist, 2, c->numberofpointattributes, np);
    t->pointmarkerlist = take_array(c->pointmarkerlist, 1, np, 0);
    t->trianglelist = take_array(c->trianglelist, 2, c->numberofcorners, nt);
    t->triangleattributelist = take_array(c->triangleattributelist, 2, c->numberoftriangleattributes, nt);
    t->trianglearealist = take_array(c->trianglearealist, 1, nt, 0);
    t->neighborlist = take_array(c->neighborlist, 2, 3, nt);
    t->segmentlist = take_array(c->segmentlist, 2, 2, ns);
    t->segmentmarkerlist = take_array(c->segmentmarkerlist, 1, ns, 0);
    t->holelist = aliased_array(c->holelist, 2, c->numberofholes, input ? &input->holelist : NULL);
    t->regionlist = aliased_array(c->regionlist, 4, c->numberofregions, input ? &input->regionlist : NULL);
    t->edgelist = take_array(c->edgelist, 2, 2, ne);
    t->edgemarkerlist = take_array(c->edgemarkerlist, 1, ne, 0);
    t->normlist = take_array(c->normlist, 2, 2, ne);
    /* Everything allocated now belongs to `t`: clear the pointers so nothing frees twice. */
#define CLEAR_FIELD(field) c->field = NULL;
    FOR_ALLOCATED_FIELDS(CLEAR_FIELD)
#undef CLEAR_FIELD
}

/* free_allocated!: after an error, free whatever the library left (never hole/region lists). */
static void free_allocated(struct CTriangulateIO *c) {
#define FREE_FIELD(field)                                                                    \
    if (c->field != NULL) {                                                                  \
        trifree(c->field);                                                                   \
        c->field = NULL;                                                                     \
    }
    FOR_ALLOCATED_FIELDS(FREE_FIELD)
#undef FREE_FIELD
}

/* ---------------------------------------------------------------------------------------- */
/* The `u` test: UnsuitableCall and unsuitable_trampoline (julia/src/unsuitable.jl).          */

/* A Julia function f(x1, y1, x2, y2, x3, y3, area) with its captured state; returns 1 (true),
   0 (false) or -1, which stands for "throws". */
typedef int (*JuliaTest)(void *closure, double, double, double, double, double, double, double);

typedef struct {
    JuliaTest test; /* NULL: `nothing` */
    void *closure;
    int cancel;  /* call.cancel[], passed as Ref{Cint} */
    bool failed; /* call.failure !== nothing */
    int calls_after_failure;
} UnsuitableCall;

static int unsuitable_trampoline(double org_x, double org_y, double dest_x, double dest_y, double apex_x,
                                 double apex_y, double area, void *user_data) {
    UnsuitableCall *call = user_data;
    if (call->failed) {
        call->calls_after_failure++;
        return 0;
    }
    int verdict = call->test(call->closure, org_x, org_y, dest_x, dest_y, apex_x, apex_y, area);
    if (verdict < 0) { /* catch err: remember it, cancel the call */
        call->failed = true;
        call->cancel = 1;
        return 0;
    }
    /* Julia: `convert(Cint, verdict) != 0`, so `true`, `1` and `1.0` all split; a result that
       does not convert (0.5, "yes") throws inside the try, like the negative verdict here. */
    return verdict ? 1 : 0;
}

/* ---------------------------------------------------------------------------------------- */
/* triangulate(switches, triin; unsuitable) -> (triout, vorout)                              */

enum { JL_OK = 0, JL_TRIANGULATE_ERROR = 1, JL_TEST_THREW = 2, JL_ARGUMENT_ERROR = 3 };

typedef struct {
    int outcome;
    char message[512]; /* TriangulateError(msg) */
} JlResult;

static JlResult jl_triangulate(const char *switches, const JTriangulateIO *triin, JTriangulateIO *triout,
                               JTriangulateIO *vorout, JuliaTest test, void *closure) {
    JlResult result = {JL_OK, ""};
    *triout = jl_triangulateio();
    *vorout = jl_triangulateio();
    /* replace(switches, "z" => ""): Julia's indices stay 1-based whatever the switches say. */
    char without_z[256];
    size_t kept = 0;
    for (const char *c = switches; *c != '\0' && kept + 1 < sizeof without_z; c++) {
        if (*c != 'z') without_z[kept++] = *c;
    }
    without_z[kept] = '\0';
    switches = without_z;
    const JTriangulateIO input = *triin; /* shallow_copy: the same arrays */
    struct CTriangulateIO ctio_in, ctio_out, vor_out;
    memset(&ctio_out, 0, sizeof ctio_out); /* CTriangulateIO(): NULL and 0 everywhere */
    memset(&vor_out, 0, sizeof vor_out);
    UnsuitableCall call = {test, closure, 0, false, 0};
    if (!ctio_from_tio(&input, &ctio_in)) {
        result.outcome = JL_ARGUMENT_ERROR;
        return result;
    }
    ReentrantUnsuitable callback = test == NULL ? NULL : unsuitable_trampoline;
    void *user_data = test == NULL ? NULL : &call;
    int rc = triangulate_reentrant(switches, &ctio_in, &ctio_out, &vor_out, callback, user_data, &call.cancel);
    if (rc != 0) {
        const char *message = triangulate_last_error();
        snprintf(result.message, sizeof result.message, "%s", message ? message : "");
        free_allocated(&ctio_out);
        free_allocated(&vor_out);
        result.outcome = call.failed ? JL_TEST_THREW : JL_TRIANGULATE_ERROR;
        return result;
    }
    tio_from_ctio(&ctio_out, &input, triout);
    tio_from_ctio(&vor_out, &input, vorout);
    if (call.failed) result.outcome = JL_TEST_THREW;
    return result;
}

/* ---------------------------------------------------------------------------------------- */
/* Triangulate.jl's raw call, unchanged: the global callback, then triangulate_catch_exit.    */

static JuliaTest triunsuitable_func = NULL; /* Triangulate.jl's module global */
static void *triunsuitable_closure = NULL;

static int jl_wrap_triunsuitable(double org_x, double org_y, double dest_x, double dest_y, double apex_x,
                                 double apex_y, double area) {
    if (triunsuitable_func == NULL) return 0;
    return triunsuitable_func(triunsuitable_closure, org_x, org_y, dest_x, dest_y, apex_x, apex_y, area) > 0;
}

static int triangulatejl_raw(const char *switches, struct CTriangulateIO *in, struct CTriangulateIO *out,
                             struct CTriangulateIO *vorout) {
    if (strchr(switches, 'u') != NULL) triunsuitable_callback(jl_wrap_triunsuitable);
    char buffer[256];
    snprintf(buffer, sizeof buffer, "%s", switches); /* Cstring: a NUL-terminated copy */
    return triangulate_catch_exit(buffer, in, out, vorout);
}

/* ---------------------------------------------------------------------------------------- */
/* Mesh checks (1-based, as the Julia tests).                                                */

/* a + b = *sum + *error exactly (Knuth's two-sum). */
static void two_sum(double a, double b, double *sum, double *error) {
    *sum = a + b;
    double b_virtual = *sum - a, a_virtual = *sum - b_virtual;
    *error = (a - a_virtual) + (b - b_virtual);
}

/* The exact sign of a sum of doubles: the terms are accumulated into a nonoverlapping expansion
   (components of increasing magnitude, zeros dropped), whose last component has the sign. */
static int exact_sign_of_sum(const double *terms, int count) {
    double expansion[64];
    int length = 0;
    for (int i = 0; i < count; i++) {
        double carry = terms[i];
        int kept = 0;
        for (int j = 0; j < length; j++) {
            double sum, error;
            two_sum(carry, expansion[j], &sum, &error);
            carry = sum;
            if (error != 0) expansion[kept++] = error;
        }
        if (carry != 0) expansion[kept++] = carry;
        length = kept;
    }
    return length == 0 ? 0 : expansion[length - 1] > 0 ? 1 : -1;
}

/* The exact sign of the orientation of (a, b, c): +1 counterclockwise. The determinant is
   ax*by - ax*cy - ay*bx + ay*cx + bx*cy - by*cx; each product is split exactly with fma.
   Rounded arithmetic is not enough: the ten attribute points hold a triangle whose doubled
   area is 2^-53. */
static int exact_orientation(JArray p, int a, int b, int c) {
    const double factors[6][3] = {
        {JF(p, 1, a), JF(p, 2, b), 1},  {JF(p, 1, a), JF(p, 2, c), -1}, {JF(p, 2, a), JF(p, 1, b), -1},
        {JF(p, 2, a), JF(p, 1, c), 1},  {JF(p, 1, b), JF(p, 2, c), 1},  {JF(p, 2, b), JF(p, 1, c), -1},
    };
    double terms[12];
    for (int i = 0; i < 6; i++) {
        double product = factors[i][0] * factors[i][1];
        terms[2 * i] = factors[i][2] * product;
        terms[2 * i + 1] = factors[i][2] * fma(factors[i][0], factors[i][1], -product);
    }
    return exact_sign_of_sum(terms, 12);
}

static double twice_area(JArray p, int a, int b, int c) {
    return (JF(p, 1, b) - JF(p, 1, a)) * (JF(p, 2, c) - JF(p, 2, a)) -
           (JF(p, 2, b) - JF(p, 2, a)) * (JF(p, 1, c) - JF(p, 1, a));
}

static double triangle_area(const JTriangulateIO *t, int k) {
    return twice_area(t->pointlist, JI(t->trianglelist, 1, k), JI(t->trianglelist, 2, k), JI(t->trianglelist, 3, k)) / 2;
}

static double max_triangle_area(const JTriangulateIO *t) {
    double m = 0;
    for (int k = 1; k <= jl_items(t->trianglelist); k++) m = fmax(m, triangle_area(t, k));
    return m;
}

static double angle_at(JArray p, int a, int b, int c) {
    double ux = JF(p, 1, b) - JF(p, 1, a), uy = JF(p, 2, b) - JF(p, 2, a);
    double vx = JF(p, 1, c) - JF(p, 1, a), vy = JF(p, 2, c) - JF(p, 2, a);
    return atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / M_PI;
}

static double min_angle(const JTriangulateIO *t) {
    double m = 180;
    for (int k = 1; k <= jl_items(t->trianglelist); k++) {
        int a = JI(t->trianglelist, 1, k), b = JI(t->trianglelist, 2, k), c = JI(t->trianglelist, 3, k);
        m = fmin(m, fmin(angle_at(t->pointlist, a, b, c), fmin(angle_at(t->pointlist, b, c, a), angle_at(t->pointlist, c, a, b))));
    }
    return m;
}

/* The triangle holding the directed edge (u, v), or -1. */
static int triangle_with_edge(const JTriangulateIO *t, int u, int v) {
    for (int k = 1; k <= jl_items(t->trianglelist); k++)
        for (int i = 1; i <= 3; i++)
            if (JI(t->trianglelist, i, k) == u && JI(t->trianglelist, i % 3 + 1, k) == v) return k;
    return -1;
}

/* Valid mesh: indices 1..n, CCW (or flat, if allowed), each directed edge once, total area
   (if area > 0), segments are mesh edges, neighbours consistent (neighbour i across the edge
   opposite corner i). */
static void check_mesh_allowing(const JTriangulateIO *t, double area, bool allow_flat) {
    int n = jl_items(t->pointlist), m = jl_items(t->trianglelist);
    CHECK(t->pointlist.ndims == 2 && jl_rows(t->pointlist) == 2, "pointlist has %d rows", jl_rows(t->pointlist));
    CHECK(m > 0, "no triangles");
    CHECK(jl_rows(t->trianglelist) == 3 || jl_rows(t->trianglelist) == 6, "%d corners", jl_rows(t->trianglelist));
    for (int k = 1; k <= m; k++)
        for (int i = 1; i <= jl_rows(t->trianglelist); i++)
            CHECK(JI(t->trianglelist, i, k) >= 1 && JI(t->trianglelist, i, k) <= n, "triangle %d corner %d = %d of %d points", k,
                  i, JI(t->trianglelist, i, k), n);
    if (case_failed) return;
    double total = 0;
    for (int k = 1; k <= m; k++) {
        int orientation = exact_orientation(t->pointlist, JI(t->trianglelist, 1, k), JI(t->trianglelist, 2, k),
                                            JI(t->trianglelist, 3, k));
        CHECK(orientation > 0 || (allow_flat && orientation == 0), "triangle %d is not counterclockwise (area %g)", k,
              triangle_area(t, k));
        total += triangle_area(t, k);
        for (int i = 1; i <= 3; i++) {
            int u = JI(t->trianglelist, i, k), v = JI(t->trianglelist, i % 3 + 1, k);
            CHECK(triangle_with_edge(t, u, v) == k, "directed edge %d-%d is in two triangles", u, v);
        }
    }
    if (area > 0) CHECK(fabs(total - area) <= 1e-12 * area, "total area %.17g, expected %.17g", total, area);
    for (int s = 1; s <= jl_items(t->segmentlist); s++) {
        int u = JI(t->segmentlist, 1, s), v = JI(t->segmentlist, 2, s);
        CHECK(triangle_with_edge(t, u, v) > 0 || triangle_with_edge(t, v, u) > 0, "segment %d (%d-%d) is not a mesh edge", s, u,
              v);
    }
    if (!jl_isempty(t->neighborlist)) {
        CHECK(jl_rows(t->neighborlist) == 3 && jl_items(t->neighborlist) == m, "neighborlist is %dx%d", jl_rows(t->neighborlist),
              jl_items(t->neighborlist));
        for (int k = 1; k <= m && !case_failed; k++)
            for (int i = 1; i <= 3; i++) {
                int a = JI(t->trianglelist, i % 3 + 1, k), b = JI(t->trianglelist, (i + 1) % 3 + 1, k);
                CHECK(JI(t->neighborlist, i, k) == triangle_with_edge(t, b, a), "neighbour %d of triangle %d is %d, expected %d", i,
                      k, JI(t->neighborlist, i, k), triangle_with_edge(t, b, a));
            }
    }
}

static void check_mesh(const JTriangulateIO *t, double area) { check_mesh_allowing(t, area, false); }

static double total_area(const JTriangulateIO *t) {
    double total = 0;
    for (int k = 1; k <= jl_items(t->trianglelist); k++) total += triangle_area(t, k);
    return total;
}

/* Triangle (a, b, c) rotated to start at its smallest index. */
static void canonical(int *a, int *b, int *c) {
    while (*a > *b || *a > *c) {
        int t = *a;
        *a = *b;
        *b = *c;
        *c = t;
    }
}

/* Does the mesh hold exactly the triangles `expected` (3 x count, any order and rotation)? */
static bool same_triangles(const JTriangulateIO *t, const int (*expected)[3], int count) {
    if (jl_items(t->trianglelist) != count) return false;
    for (int e = 0; e < count; e++) {
        int a = expected[e][0], b = expected[e][1], c = expected[e][2];
        canonical(&a, &b, &c);
        bool found = false;
        for (int k = 1; k <= count && !found; k++) {
            int x = JI(t->trianglelist, 1, k), y = JI(t->trianglelist, 2, k), z = JI(t->trianglelist, 3, k);
            canonical(&x, &y, &z);
            found = x == a && y == b && z == c;
        }
        if (!found) return false;
    }
    return true;
}

/* The marker of segment {u, v} (either direction), or -999 if absent. */
static int segment_marker(const JTriangulateIO *t, int u, int v) {
    for (int s = 1; s <= jl_items(t->segmentlist); s++) {
        int a = JI(t->segmentlist, 1, s), b = JI(t->segmentlist, 2, s);
        if ((a == u && b == v) || (a == v && b == u)) return jl_isempty(t->segmentmarkerlist) ? 0 : JIV(t->segmentmarkerlist, s);
    }
    return -999;
}

static bool same_points(JArray a, JArray b, int count) {
    for (int j = 1; j <= count; j++)
        if (JF(a, 1, j) != JF(b, 1, j) || JF(a, 2, j) != JF(b, 2, j)) return false;
    return true;
}

/* Runs jl_triangulate; true if it succeeded (a failure is reported). */
static bool run(const char *switches, const JTriangulateIO *triin, JTriangulateIO *triout, JTriangulateIO *vorout,
                JuliaTest test, void *closure) {
    JlResult r = jl_triangulate(switches, triin, triout, vorout, test, closure);
    CHECK(r.outcome == JL_OK, "triangulate(\"%s\") gave outcome %d: %s", switches, r.outcome, r.message);
    return r.outcome == JL_OK;
}

/* The counts of the diamond meshed with paAqQ. Triangle 1.6 gives 177 points, 319 triangles and
   33 segments (Triangulate.jl's test_triangulate); a quality mesh is not unique, so triangle-rs
   must land in a band around those: refinement that stops too early or runs away fails. The
   counts must also fit together: the diamond is a disc, so Euler's formula holds with every
   boundary edge a segment, and each of the 4 input segments is split into pieces. */
static void check_refined_diamond_counts(int points, int triangles, int segments) {
    CHECK(points >= 106 && points <= 266, "%d points (Triangle 1.6: 177)", points);
    CHECK(triangles >= 191 && triangles <= 479, "%d triangles (Triangle 1.6: 319)", triangles);
    CHECK(segments >= 20 && segments <= 50, "%d segments (Triangle 1.6: 33)", segments);
    /* V - E + F = 1 for a triangulated disc, with 2E = 3F + (boundary edges = segments). */
    CHECK((3 * triangles + segments) % 2 == 0 && points - (3 * triangles + segments) / 2 + triangles == 1,
          "Euler: %d points, %d triangles, %d boundary segments do not make a disc", points, triangles, segments);
}

/* ---------------------------------------------------------------------------------------- */
/* The inputs of Triangulate.jl's tests, written as the Julia code writes them.              */

static JTriangulateIO diamond_with_region(void) {
    /* triin.pointlist = Matrix{Float64}([1.0 0.0; 0.0 1.0; -1.0 0.0; 0.0 -1.0]') etc. */
    static const double points[] = {1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, -1.0};
    static const int segments[] = {1, 2, 2, 3, 3, 4, 4, 1};
    static const int markers[] = {1, 2, 3, 4};
    static const double region[] = {0.5, 0.5, 1, 0.01};
    JTriangulateIO t = jl_triangulateio();
    t.pointlist = jl_adjoint(sizeof(double), jl_f64(4, 2, points));
    t.segmentlist = jl_adjoint(sizeof(int), jl_int(4, 2, segments));
    t.segmentmarkerlist = jl_vector(sizeof(int), 4, markers);
    t.regionlist = jl_adjoint(sizeof(double), jl_f64(1, 4, region));
    return t;
}

static JTriangulateIO unit_square(void) {
    static const double points[] = {0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0};
    static const int segments[] = {1, 2, 2, 3, 3, 4, 4, 1};
    static const int markers[] = {1, 2, 3, 4};
    JTriangulateIO t = jl_triangulateio();
    t.pointlist = jl_adjoint(sizeof(double), jl_f64(4, 2, points));
    t.segmentlist = jl_adjoint(sizeof(int), jl_int(4, 2, segments));
    t.segmentmarkerlist = jl_vector(sizeof(int), 4, markers);
    return t;
}

static const double attr_x[] = {1.9, 1.2, 1.5, 1.6, 1.3, 1.9, 1.2, 1.4, 1.1, 1.0};
static const double attr_y[] = {1.5, 1.4, 1.7, 1.2, 1.3, 1.9, 2.0, 1.9, 1.5, 1.0};
static const double attr_z[] = {1.7, 1.0, 1.1, 1.6, 2.0, 1.8, 1.7, 1.8, 1.7, 1.5};

/* TriangulateIO(; pointlist = [x; y]) with pointattributelist = z (1 x 10). */
static JTriangulateIO attribute_points(bool with_attributes) {
    double xy[20];
    memcpy(xy, attr_x, sizeof attr_x);
    memcpy(xy + 10, attr_y, sizeof attr_y);
    JTriangulateIO t = jl_triangulateio();
    t.pointlist = jl_f64(2, 10, xy);
    if (with_attributes) t.pointattributelist = jl_f64(1, 10, attr_z);
    return t;
}

/* ---------------------------------------------------------------------------------------- */
/* Cases.                                                                                    */

static void case_diamond_paAqQ(void) {
    begin_case("diamond paAqQ (test_triangulate)");
    JTriangulateIO triin = diamond_with_region(), triout, vorout;
    if (run("paAqQ", &triin, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 2.0);
        int n = jl_items(triout.pointlist), m = jl_items(triout.trianglelist);
        check_refined_diamond_counts(n, m, jl_items(triout.segmentlist));
        CHECK(jl_items(triout.segmentmarkerlist) == jl_items(triout.segmentlist), "one marker per segment");
        CHECK(same_points(triout.pointlist, triin.pointlist, 4), "input points moved");
        CHECK(max_triangle_area(&triout) <= 0.01 * (1 + 1e-12), "largest area %g", max_triangle_area(&triout));
        CHECK(min_angle(&triout) >= 20 - 1e-9, "smallest angle %g", min_angle(&triout));
        CHECK(jl_rows(triout.triangleattributelist) == 1 && jl_items(triout.triangleattributelist) == m,
              "triangleattributelist is %dx%d", jl_rows(triout.triangleattributelist), jl_items(triout.triangleattributelist));
        for (int k = 1; k <= m && !case_failed; k++) CHECK(JF(triout.triangleattributelist, 1, k) == 1.0, "attribute of %d", k);
        for (int s = 1; s <= jl_items(triout.segmentmarkerlist); s++)
            CHECK(JIV(triout.segmentmarkerlist, s) >= 1 && JIV(triout.segmentmarkerlist, s) <= 4, "segment marker %d",
                  JIV(triout.segmentmarkerlist, s));
        CHECK(triout.regionlist.data == triin.regionlist.data && !triout.regionlist.owned, "regionlist must alias the input");
        CHECK(jl_isempty(vorout.pointlist), "Voronoi output without v");
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

/* test_ctriangulate, through Triangulate.jl's own raw call (catch_exit, global callback). */
static void case_raw_diamond_paAqQ(void) {
    begin_case("raw CTriangulateIO paAqQ via triangulate_catch_exit (test_ctriangulate)");
    JTriangulateIO jl = diamond_with_region();
    JArray faceregions = jl_int(4, 1, (const int[]){1, 2, 3, 4}); /* Matrix{Cint}([1 2 3 4]') */
    struct CTriangulateIO triin, triout, vorout;
    memset(&triin, 0, sizeof triin);
    memset(&triout, 0, sizeof triout);
    memset(&vorout, 0, sizeof vorout);
    triin.numberofpoints = jl_items(jl.pointlist);
    triin.pointlist = jl.pointlist.data;
    triin.numberofsegments = jl_items(jl.segmentlist);
    triin.segmentlist = jl.segmentlist.data;
    triin.segmentmarkerlist = faceregions.data;
    triin.numberofregions = jl_items(jl.regionlist);
    triin.regionlist = jl.regionlist.data;
    int rc = triangulatejl_raw("paAqQ", &triin, &triout, &vorout);
    const char *message = rc ? triangulate_last_error() : "";
    CHECK(rc == 0, "rc %d: %s", rc, message);
    check_refined_diamond_counts(triout.numberofpoints, triout.numberoftriangles, triout.numberofsegments);
    CHECK(triout.regionlist == triin.regionlist, "regionlist must be the input's pointer");
    CHECK(triout.holelist == NULL, "holelist");
    JTriangulateIO owned;
    tio_from_ctio(&triout, NULL, &owned);
    if (!case_failed) check_mesh(&owned, 2.0);
    jl_gc_collect(&owned);
    free_allocated(&triout);
    free_allocated(&vorout);
    end_case();
}

static void case_t_shape_pcDQ(void) {
    begin_case("T-shaped PSLG pcDQ, no segment markers (test_triangulate2)");
    static const double points[] = {0.0, 1.0, 2.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    static const int segments[] = {1, 2, 2, 2, 3, 4};
    JTriangulateIO triin = jl_triangulateio(), triout, vorout;
    triin.pointlist = jl_f64(2, 4, points);
    triin.segmentlist = jl_int(2, 3, segments);
    if (run("pcDQ", &triin, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 1.0);
        static const int expected[][3] = {{1, 2, 4}, {2, 3, 4}};
        CHECK(jl_items(triout.pointlist) == 4, "%d points", jl_items(triout.pointlist));
        CHECK(same_triangles(&triout, expected, 2), "triangles differ from (1,2,4), (2,3,4)");
        CHECK(jl_items(triout.segmentlist) == 5, "%d segments", jl_items(triout.segmentlist));
        /* Input segments keep marker 0 unless on the boundary, where they get 1; hull segments 1. */
        CHECK(segment_marker(&triout, 1, 2) == 1 && segment_marker(&triout, 2, 3) == 1 && segment_marker(&triout, 2, 4) == 0 &&
                  segment_marker(&triout, 3, 4) == 1 && segment_marker(&triout, 1, 4) == 1,
              "segment markers");
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

static void case_two_points(void) {
    begin_case("two points Q -> TriangulateError (test_triangulate_catch_exit)");
    JTriangulateIO triin = jl_triangulateio(), triout, vorout;
    triin.pointlist = jl_f64(2, 2, (const double[]){1.0, 0.0, 0.0, 1.0});
    JlResult r = jl_triangulate("Q", &triin, &triout, &vorout, NULL, NULL);
    CHECK(r.outcome == JL_TRIANGULATE_ERROR, "outcome %d", r.outcome);
    CHECK(strstr(r.message, "at least three") != NULL, "message: %s", r.message);
    CHECK(jl_isempty(triout.pointlist) && jl_isempty(triout.trianglelist), "output after an error");
    end_case();

    begin_case("two points, raw call returns 1 (test_ctriangulate_catch_exit)");
    struct CTriangulateIO in, out, vor;
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    memset(&vor, 0, sizeof vor);
    JArray nodes = jl_f64(2, 2, (const double[]){1.0, 0.0, 0.0, 1.0});
    in.numberofpoints = 2;
    in.pointlist = nodes.data;
    int rc = triangulatejl_raw("", &in, &out, &vor);
    CHECK(rc == 1, "rc %d", rc);
    CHECK(out.pointlist == NULL && out.trianglelist == NULL, "arrays allocated on error");
    free_allocated(&out);
    free_allocated(&vor);
    /* And the reentrant entry reports the same error with its message on this thread. */
    memset(&out, 0, sizeof out);
    int zero = 0;
    rc = triangulate_reentrant("Q", &in, &out, &vor, NULL, NULL, &zero);
    CHECK(rc != 0, "rc %d", rc);
    CHECK(triangulate_last_error() != NULL && triangulate_last_error()[0] != '\0', "no message");
    end_case();
}

/* Issue 12: an index out of range is a TriangulateError, never a silently emptied mesh; `rp`
   gives back the holes like `p`. */
static void case_bad_indices_and_rp_holes(void) {
    begin_case("0-based segments -> TriangulateError naming the segment and the range");
    JTriangulateIO triin = unit_square(), triout, vorout;
    triin.segmentlist = jl_adjoint(sizeof(int), jl_int(4, 2, (const int[]){0, 1, 1, 2, 2, 3, 3, 0}));
    JlResult r = jl_triangulate("pQ", &triin, &triout, &vorout, NULL, NULL);
    CHECK(r.outcome == JL_TRIANGULATE_ERROR, "outcome %d", r.outcome);
    CHECK(strstr(r.message, "Segment 1 has endpoint 0") != NULL && strstr(r.message, "numbered 1 to 4") != NULL,
          "message: %s", r.message);
    CHECK(jl_isempty(triout.trianglelist), "output after an error");
    end_case();

    begin_case("rpq keeps the holes of the input (refining a mesh of a square with a hole)");
    static const double points[] = {0, 0, 4, 0, 4, 4, 0, 4, 1, 1, 3, 1, 3, 3, 1, 3};
    static const int segments[] = {1, 2, 2, 3, 3, 4, 4, 1, 5, 6, 6, 7, 7, 8, 8, 5};
    JTriangulateIO square = jl_triangulateio(), mesh, refined, vor2;
    square.pointlist = jl_adjoint(sizeof(double), jl_f64(8, 2, points));
    square.segmentlist = jl_adjoint(sizeof(int), jl_int(8, 2, segments));
    square.holelist = jl_f64(2, 1, (const double[]){2, 2});
    if (run("pQ", &square, &mesh, &vorout, NULL, NULL)) {
        CHECK(jl_items(mesh.trianglelist) == 8, "%d triangles", jl_items(mesh.trianglelist));
        JTriangulateIO again = mesh; /* the output as the next input, with the holes */
        if (run("rpq30Q", &again, &refined, &vor2, NULL, NULL)) {
            check_mesh(&refined, 12.0); /* the square less its hole, which the mesh does not cover */
            CHECK(jl_items(refined.holelist) == 1 && refined.holelist.data == again.holelist.data,
                  "holelist: %d items", jl_items(refined.holelist));
        }
        jl_gc_collect(&refined);
        jl_gc_collect(&vor2);
    }
    jl_gc_collect(&mesh);
    jl_gc_collect(&vorout);
    end_case();
}

static void case_square_neighbors(void) {
    begin_case("unit square pqQn (test_neighbors)");
    JTriangulateIO triin = unit_square(), triout, vorout;
    if (run("pqQn", &triin, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 1.0);
        CHECK(jl_items(triout.pointlist) == 4 && same_points(triout.pointlist, triin.pointlist, 4), "points changed");
        CHECK(jl_items(triout.trianglelist) == 2, "%d triangles", jl_items(triout.trianglelist));
        CHECK(jl_rows(triout.neighborlist) == 3 && jl_items(triout.neighborlist) == 2, "neighborlist size");
        int missing = 0;
        for (int k = 1; k <= jl_items(triout.neighborlist); k++)
            for (int i = 1; i <= 3; i++) missing += JI(triout.neighborlist, i, k) == -1;
        CHECK(missing == 4, "%d boundary neighbours", missing);
        CHECK(segment_marker(&triout, 1, 2) == 1 && segment_marker(&triout, 2, 3) == 2 && segment_marker(&triout, 3, 4) == 3 &&
                  segment_marker(&triout, 4, 1) == 4 && jl_items(triout.segmentlist) == 4,
              "segments");
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

static void case_square_o2(void) {
    begin_case("unit square pqQ (test_o2)");
    JTriangulateIO triin = unit_square(), triout, vorout;
    if (run("pqQ", &triin, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 1.0);
        CHECK(jl_items(triout.pointlist) == 4 && same_points(triout.pointlist, triin.pointlist, 4), "points changed");
        CHECK(jl_rows(triout.trianglelist) == 3 && jl_items(triout.trianglelist) == 2, "trianglelist size");
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();

    begin_case("unit square pqo2Q (test_o2)");
    if (run("pqo2Q", &triin, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 1.0);
        CHECK(jl_rows(triout.trianglelist) == 6 && jl_items(triout.trianglelist) == 2, "trianglelist is %dx%d",
              jl_rows(triout.trianglelist), jl_items(triout.trianglelist));
        CHECK(jl_items(triout.pointlist) == 9, "%d points", jl_items(triout.pointlist));
        CHECK(same_points(triout.pointlist, triin.pointlist, 4), "input points moved");
        if (!case_failed) {
            bool used[10] = {false};
            for (int k = 1; k <= 2; k++)
                for (int i = 1; i <= 3; i++) {
                    /* Node 3+i is the midpoint of the edge opposite corner i. */
                    int mid = JI(triout.trianglelist, 3 + i, k);
                    int a = JI(triout.trianglelist, i % 3 + 1, k), b = JI(triout.trianglelist, (i + 1) % 3 + 1, k);
                    CHECK(mid >= 5 && mid <= 9, "mid node %d", mid);
                    if (mid < 5 || mid > 9) continue;
                    used[mid] = true;
                    CHECK(JF(triout.pointlist, 1, mid) == (JF(triout.pointlist, 1, a) + JF(triout.pointlist, 1, b)) / 2 &&
                              JF(triout.pointlist, 2, mid) == (JF(triout.pointlist, 2, a) + JF(triout.pointlist, 2, b)) / 2,
                          "node %d is not the midpoint of %d-%d", mid, a, b);
                }
            CHECK(used[5] && used[6] && used[7] && used[8] && used[9], "mid nodes 5..9 not all used");
        }
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

/* Triangle 1.6's triangulation of the ten attribute points (test_pointattributelist's
   trianglelist, one row per triangle). No four points are cocircular: it is the unique
   Delaunay triangulation, so the set is exact whatever the order. */
static const int attribute_delaunay[13][3] = {
    {10, 5, 2}, {5, 10, 4}, {7, 9, 8}, {2, 9, 10}, {2, 3, 9}, {9, 7, 10}, {2, 5, 3},
    {4, 1, 3},  {8, 3, 6},  {8, 9, 3}, {6, 3, 1},  {8, 6, 7},  {3, 5, 4},
};

static void case_point_attributes(void) {
    begin_case("point attributes Q (test_pointattributelist)");
    JTriangulateIO pointset = attribute_points(true), triout, vorout;
    double hull_area = 0;
    if (run("Q", &pointset, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 0);
        hull_area = total_area(&triout);
        CHECK(jl_items(triout.pointlist) == 10 && same_points(triout.pointlist, pointset.pointlist, 10), "points changed");
        CHECK(jl_rows(triout.pointattributelist) == 1 && jl_items(triout.pointattributelist) == 10, "attributes are %dx%d",
              jl_rows(triout.pointattributelist), jl_items(triout.pointattributelist));
        for (int j = 1; j <= 10 && !case_failed; j++)
            CHECK(JF(triout.pointattributelist, 1, j) == attr_z[j - 1], "attribute %d", j);
        CHECK(same_triangles(&triout, attribute_delaunay, 13), "not the Delaunay triangulation (%d triangles)",
              jl_items(triout.trianglelist));
        CHECK(jl_isempty(vorout.pointlist) && jl_isempty(vorout.edgelist), "Voronoi output without v");
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();

    begin_case("point attributes Qa0.05 (test_pointattributelist)");
    if (run("Qa0.05", &pointset, &triout, &vorout, NULL, NULL)) {
        /* Triangle 1.6 splits the hull edge 10-7 at its midpoint, which is point 9's position
           (up to 2^-53), leaving two flat triangles: tolerated, as they are Triangle's own. */
        check_mesh_allowing(&triout, hull_area, true);
        int n = jl_items(triout.pointlist);
        CHECK(n > 10, "%d points (Triangle 1.6: 16)", n);
        CHECK(same_points(triout.pointlist, pointset.pointlist, 10), "input points moved");
        CHECK(jl_rows(triout.pointattributelist) == 1 && jl_items(triout.pointattributelist) == n, "attributes size");
        for (int j = 1; j <= n && !case_failed; j++) {
            CHECK(isfinite(JF(triout.pointattributelist, 1, j)), "attribute %d", j);
            if (j <= 10) CHECK(JF(triout.pointattributelist, 1, j) == attr_z[j - 1], "attribute %d changed", j);
        }
        CHECK(max_triangle_area(&triout) <= 0.05 * (1 + 1e-12), "largest area %g", max_triangle_area(&triout));
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

static void case_voronoi_and_hull(void) {
    begin_case("Voronoi diagram vQ (example_pointsets)");
    JTriangulateIO points = attribute_points(false), triout, vorout;
    int nrays = -1;
    if (run("vQ", &points, &triout, &vorout, NULL, NULL)) {
        int m = jl_items(triout.trianglelist);
        int nedges = jl_items(triout.pointlist) + m - 1; /* Euler, every point used */
        nrays = 2 * nedges - 3 * m;                      /* one per convex hull edge */
        CHECK(jl_rows(vorout.pointlist) == 2 && jl_items(vorout.pointlist) == m, "Voronoi points %dx%d", jl_rows(vorout.pointlist),
              jl_items(vorout.pointlist));
        CHECK(jl_rows(vorout.edgelist) == 2 && jl_items(vorout.edgelist) == nedges, "Voronoi edges %d, expected %d",
              jl_items(vorout.edgelist), nedges);
        CHECK(jl_rows(vorout.normlist) == 2 && jl_items(vorout.normlist) == nedges, "normlist size");
        CHECK(jl_isempty(vorout.pointattributelist), "no attributes: the (empty) array is freed, not kept");
        if (!case_failed) {
            int rays = 0;
            for (int e = 1; e <= nedges; e++) {
                int a = JI(vorout.edgelist, 1, e), b = JI(vorout.edgelist, 2, e);
                bool zero_norm = JF(vorout.normlist, 1, e) == 0 && JF(vorout.normlist, 2, e) == 0;
                CHECK(a >= 1 && a <= m, "edge %d starts at %d", e, a);
                CHECK(b == -1 ? !zero_norm : (b >= 1 && b <= m && zero_norm), "edge %d: end %d", e, b);
                rays += b == -1;
            }
            CHECK(rays == nrays, "%d rays, expected %d", rays, nrays);
            for (int k = 1; k <= m; k++) { /* Voronoi vertex k is the circumcentre of triangle k */
                double d[3];
                for (int i = 1; i <= 3; i++) {
                    int c = JI(triout.trianglelist, i, k);
                    d[i - 1] = hypot(JF(vorout.pointlist, 1, k) - JF(triout.pointlist, 1, c),
                                     JF(vorout.pointlist, 2, k) - JF(triout.pointlist, 2, c));
                }
                CHECK(fabs(d[0] - d[1]) <= 1e-9 * d[0] && fabs(d[0] - d[2]) <= 1e-9 * d[0], "vertex %d is not a circumcentre", k);
            }
        }
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();

    begin_case("convex hull segments cQ (example_pointsets)");
    if (run("cQ", &points, &triout, &vorout, NULL, NULL)) {
        check_mesh(&triout, 0);
        int nseg = jl_items(triout.segmentlist);
        if (nrays >= 0) CHECK(nseg == nrays, "%d hull segments, expected %d", nseg, nrays);
        for (int s = 1; s <= nseg; s++) {
            int u = JI(triout.segmentlist, 1, s), v = JI(triout.segmentlist, 2, s);
            CHECK((triangle_with_edge(&triout, u, v) > 0) != (triangle_with_edge(&triout, v, u) > 0), "segment %d-%d not on the hull",
                  u, v);
            CHECK(JIV(triout.segmentmarkerlist, s) == 1, "hull segment marker %d", JIV(triout.segmentmarkerlist, s));
        }
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

/* ---------------------------------------------------------------------------------------- */
/* The `u` test.                                                                             */

typedef struct {
    double limit;      /* unsuitable if area > limit */
    int calls;
    bool consistent;   /* every call had area > 0 equal to the corners' area */
    bool throws;       /* "throw" on the first call */
} AreaTest;

static int area_test(void *closure, double x1, double y1, double x2, double y2, double x3, double y3, double area) {
    AreaTest *t = closure;
    t->calls++;
    double twice = (x2 - x1) * (y3 - y1) - (y2 - y1) * (x3 - x1);
    double longest = fmax(hypot(x2 - x1, y2 - y1), fmax(hypot(x3 - x2, y3 - y2), hypot(x1 - x3, y1 - y3)));
    if (!(area > 0 && fabs(area - twice / 2) <= 1e-12 * longest * longest)) t->consistent = false;
    if (t->throws) return -1;
    return area > t->limit;
}

static JTriangulateIO diamond(void) {
    JTriangulateIO t = jl_triangulateio();
    t.pointlist = jl_f64(2, 4, (const double[]){1, 0, -1, 0, 0, 1, 0, -1});
    t.segmentlist = jl_int(2, 4, (const int[]){1, 2, 3, 4, 2, 3, 4, 1});
    return t;
}

static void case_triunsuitable_setter(void) {
    begin_case("triunsuitable! is callable; without u the test is never called");
    AreaTest global_test = {0.01, 0, true, false};
    triunsuitable_func = area_test; /* Triangulate.jl: triunsuitable!(f) sets the global */
    triunsuitable_closure = &global_test;
    triunsuitable_callback(jl_wrap_triunsuitable);
    JTriangulateIO jl = diamond();
    struct CTriangulateIO in, out, vor;
    CHECK(ctio_from_tio(&jl, &in), "sizes");
    memset(&out, 0, sizeof out);
    memset(&vor, 0, sizeof vor);
    int rc = triangulatejl_raw("Q", &in, &out, &vor);
    CHECK(rc == 0, "rc %d: %s", rc, rc ? triangulate_last_error() : "");
    CHECK(global_test.calls == 0, "called %d times without u", global_test.calls);
    JTriangulateIO owned, owned_vor;
    tio_from_ctio(&out, &jl, &owned);
    tio_from_ctio(&vor, &jl, &owned_vor);
    if (rc == 0) check_mesh(&owned, 2.0);
    jl_gc_collect(&owned);
    jl_gc_collect(&owned_vor);
    triunsuitable_callback(NULL);
    triunsuitable_func = NULL;

    AreaTest own_test = {0.01, 0, true, false};
    JTriangulateIO triout, vorout;
    if (run("Q", &jl, &triout, &vorout, area_test, &own_test)) check_mesh(&triout, 2.0);
    CHECK(own_test.calls == 0, "called %d times without u", own_test.calls);
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

static void case_u_per_call(void) {
    begin_case("u with a per-call test (triangulate(...; unsuitable))");
    JTriangulateIO triin = diamond(), triout, vorout;
    AreaTest test = {0.01, 0, true, false};
    if (run("quQ", &triin, &triout, &vorout, area_test, &test)) {
        check_mesh(&triout, 2.0);
        CHECK(test.calls > 0, "the test was never called");
        CHECK(test.consistent, "the seven doubles are not org, dest, apex (CCW) and their area");
        CHECK(max_triangle_area(&triout) <= 0.01 * (1 + 1e-12), "largest area %g", max_triangle_area(&triout));
    }
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

static void case_u_global(void) {
    begin_case("u with the global triunsuitable_callback (Triangulate.jl unchanged)");
    AreaTest test = {0.01, 0, true, false};
    triunsuitable_func = area_test;
    triunsuitable_closure = &test;
    JTriangulateIO jl = diamond();
    struct CTriangulateIO in, out, vor;
    CHECK(ctio_from_tio(&jl, &in), "sizes");
    memset(&out, 0, sizeof out);
    memset(&vor, 0, sizeof vor);
    int rc = triangulatejl_raw("quQ", &in, &out, &vor);
    const char *message = rc ? triangulate_last_error() : "";
    CHECK(rc == 0, "rc %d: %s", rc, message);
    JTriangulateIO owned;
    tio_from_ctio(&out, &jl, &owned);
    if (rc == 0) {
        check_mesh(&owned, 2.0);
        CHECK(test.calls > 0, "the global test was never called");
        CHECK(test.consistent, "the seven doubles are not org, dest, apex (CCW) and their area");
        CHECK(max_triangle_area(&owned) <= 0.01 * (1 + 1e-12), "largest area %g", max_triangle_area(&owned));
    }
    jl_gc_collect(&owned);
    free_allocated(&out);
    free_allocated(&vor);
    triunsuitable_callback(NULL);
    triunsuitable_func = NULL;
    end_case();
}

/* Two threads mesh at once with different tests (TriangleRS: two tasks, each with its own
   triunsuitable!): each call must see only its own test through its user_data. */
typedef struct {
    JTriangulateIO triin, triout, vorout;
    AreaTest test;
    JlResult result;
} ThreadJob;

static void *thread_job(void *arg) {
    ThreadJob *job = arg;
    job->result = jl_triangulate("quQ", &job->triin, &job->triout, &job->vorout, area_test, &job->test);
    return NULL;
}

static void case_u_two_threads(void) {
    begin_case("u from two threads at once, each with its own test");
    ThreadJob coarse = {diamond(), jl_triangulateio(), jl_triangulateio(), {0.1, 0, true, false}, {0, ""}};
    ThreadJob fine = {diamond(), jl_triangulateio(), jl_triangulateio(), {0.005, 0, true, false}, {0, ""}};
    pthread_t a, b;
    CHECK(pthread_create(&a, NULL, thread_job, &coarse) == 0, "thread");
    CHECK(pthread_create(&b, NULL, thread_job, &fine) == 0, "thread");
    pthread_join(a, NULL);
    pthread_join(b, NULL);
    CHECK(coarse.result.outcome == JL_OK && fine.result.outcome == JL_OK, "outcomes %d %d: %s %s", coarse.result.outcome,
          fine.result.outcome, coarse.result.message, fine.result.message);
    if (!case_failed) {
        check_mesh(&coarse.triout, 2.0);
        check_mesh(&fine.triout, 2.0);
        CHECK(max_triangle_area(&coarse.triout) <= 0.1 * (1 + 1e-12), "coarse: largest area %g", max_triangle_area(&coarse.triout));
        CHECK(max_triangle_area(&fine.triout) <= 0.005 * (1 + 1e-12), "fine: largest area %g", max_triangle_area(&fine.triout));
        CHECK(jl_items(fine.triout.trianglelist) > jl_items(coarse.triout.trianglelist), "fine mesh not finer");
        CHECK(coarse.test.calls > 0 && fine.test.calls > 0 && coarse.test.consistent && fine.test.consistent, "calls");
    }
    jl_gc_collect(&coarse.triout);
    jl_gc_collect(&coarse.vorout);
    jl_gc_collect(&fine.triout);
    jl_gc_collect(&fine.vorout);
    end_case();
}

static void case_z_is_dropped(void) {
    begin_case("z is accepted and dropped: pzQ is pQ, indices stay 1-based");
    JTriangulateIO triin = diamond(), zmesh, zvor, plain, plain_vor;
    bool z_ok = run("pzQ", &triin, &zmesh, &zvor, NULL, NULL);
    bool plain_ok = run("pQ", &triin, &plain, &plain_vor, NULL, NULL);
    if (z_ok && plain_ok) {
        check_mesh(&zmesh, 2.0);
        int n = jl_items(zmesh.pointlist), count = jl_items(plain.trianglelist);
        int low = n + 1, high = 0;
        for (int k = 1; k <= jl_items(zmesh.trianglelist); k++) {
            for (int i = 1; i <= 3; i++) {
                int corner = JI(zmesh.trianglelist, i, k);
                low = corner < low ? corner : low;
                high = corner > high ? corner : high;
            }
        }
        CHECK(low == 1 && high == n, "corner indices span %d..%d with %d points", low, high, n);
        CHECK(count == 2, "pQ of the diamond has %d triangles", count);
        int expected[2][3];
        for (int k = 1; k <= count && k <= 2; k++) {
            for (int i = 1; i <= 3; i++) expected[k - 1][i - 1] = JI(plain.trianglelist, i, k);
        }
        CHECK(same_triangles(&zmesh, (const int (*)[3])expected, count), "pzQ and pQ differ");
        for (int s = 1; s <= jl_items(zmesh.segmentlist); s++) {
            for (int i = 1; i <= 2; i++) {
                int end = JI(zmesh.segmentlist, i, s);
                CHECK(end >= 1 && end <= n, "segment end %d with %d points", end, n);
            }
        }
    }
    jl_gc_collect(&zmesh);
    jl_gc_collect(&zvor);
    jl_gc_collect(&plain);
    jl_gc_collect(&plain_vor);
    end_case();
}

static void case_u_throws(void) {
    begin_case("an exception in the test cancels the call and is rethrown");
    JTriangulateIO triin = diamond(), triout, vorout;
    AreaTest test = {0.01, 0, true, true};
    JlResult r = jl_triangulate("quQ", &triin, &triout, &vorout, area_test, &test);
    CHECK(r.outcome == JL_TEST_THREW, "outcome %d: %s", r.outcome, r.message);
    CHECK(test.calls == 1, "the test ran %d times", test.calls);
    jl_gc_collect(&triout);
    jl_gc_collect(&vorout);
    end_case();
}

int main(void) {
    case_diamond_paAqQ();
    case_raw_diamond_paAqQ();
    case_t_shape_pcDQ();
    case_two_points();
    case_bad_indices_and_rp_holes();
    case_square_neighbors();
    case_square_o2();
    case_point_attributes();
    case_voronoi_and_hull();
    case_triunsuitable_setter();
    case_u_per_call();
    case_u_global();
    case_u_two_threads();
    case_u_throws();
    case_z_is_dropped();
    for (int i = 0; i < julia_heap_used; i++) free(julia_heap[i]);
    printf("%d failed\n", failures);
    return failures == 0 ? 0 : 1;
}
