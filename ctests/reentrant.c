/* triangle-rs is reentrant: concurrent calls from two threads give the same results as serial
 * calls, and `triangulate_reentrant` hands each call its own callback and user_data (no global
 * state), on the calling thread. Also checks Triangulate.jl's global `triunsuitable_callback`
 * and the cancel flag.
 *
 * Exit codes: 0 passed, 1 a check failed. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "triangle_rs.h"

static int failures = 0;
static pthread_mutex_t failures_lock = PTHREAD_MUTEX_INITIALIZER;

#define CHECK(cond, ...)                                                                          \
    do {                                                                                          \
        if (!(cond)) {                                                                            \
            pthread_mutex_lock(&failures_lock);                                                   \
            printf("%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);                       \
            printf(__VA_ARGS__);                                                                  \
            printf("\n");                                                                         \
            failures++;                                                                           \
            pthread_mutex_unlock(&failures_lock);                                                 \
        }                                                                                         \
    } while (0)

static void free_all(struct triangulateio *io) {
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

/* splitmix64: the same small seeded generator as the Rust tests. */
static unsigned long long splitmix64(unsigned long long *state) {
    unsigned long long z = (*state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

static double *random_points(int n, unsigned long long seed) {
    double *p = malloc(2 * (size_t)n * sizeof *p);
    int i;
    for (i = 0; i < 2 * n; i++) p[i] = (double)(splitmix64(&seed) >> 11) * 0x1.0p-53;
    return p;
}

static int compare_triples(const void *a, const void *b) {
    const int *x = a, *y = b;
    int k;
    for (k = 0; k < 3; k++)
        if (x[k] != y[k]) return x[k] < y[k] ? -1 : 1;
    return 0;
}

/* Rotates each triangle so that its smallest index comes first (keeping the orientation) and
 * sorts the triangles: a canonical form that does not depend on output order. */
static void canonicalize(int *triangles, int count) {
    int i;
    for (i = 0; i < count; i++) {
        int *t = triangles + 3 * i;
        while (t[0] > t[1] || t[0] > t[2]) {
            int first = t[0];
            t[0] = t[1];
            t[1] = t[2];
            t[2] = first;
        }
    }
    qsort(triangles, (size_t)count, 3 * sizeof(int), compare_triples);
}

/* ---- Part 1: concurrent plain triangulations equal serial ones. ---- */

struct plain_job {
    int npoints;
    double *points;
    int *expected; /* canonical triangles of the serial call */
    int expected_count;
    int repetitions;
    char error[256];
};

static int triangulate_canonical(const struct plain_job *job, int **triangles, int *count,
                                 char *error) {
    struct triangulateio in, out;
    int rc;
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    in.pointlist = job->points;
    in.numberofpoints = job->npoints;
    rc = triangulate_reentrant("zQ", &in, &out, NULL, NULL, NULL, NULL);
    if (rc != 0) {
        snprintf(error, 256, "%s", triangulate_last_error());
        free_all(&out);
        return rc;
    }
    canonicalize(out.trianglelist, out.numberoftriangles);
    *triangles = out.trianglelist;
    *count = out.numberoftriangles;
    out.trianglelist = NULL;
    free_all(&out);
    return 0;
}

static void *plain_thread(void *arg) {
    struct plain_job *job = arg;
    int r;
    for (r = 0; r < job->repetitions; r++) {
        int *triangles = NULL, count = 0;
        int rc = triangulate_canonical(job, &triangles, &count, job->error);
        CHECK(rc == 0, "concurrent call failed: %s", job->error);
        if (rc != 0) break;
        CHECK(count == job->expected_count &&
                  memcmp(triangles, job->expected, 3 * (size_t)count * sizeof(int)) == 0,
              "a concurrent call (%d points) differs from the serial one", job->npoints);
        trifree(triangles);
    }
    return NULL;
}

static void concurrent_plain(void) {
    struct plain_job jobs[2] = {{1500, NULL, NULL, 0, 8, ""}, {2500, NULL, NULL, 0, 5, ""}};
    pthread_t threads[2];
    int j;
    for (j = 0; j < 2; j++) {
        jobs[j].points = random_points(jobs[j].npoints, 1000 + (unsigned long long)j);
        if (triangulate_canonical(&jobs[j], &jobs[j].expected, &jobs[j].expected_count,
                                  jobs[j].error) != 0) {
            CHECK(0, "serial call failed: %s", jobs[j].error);
            free(jobs[0].points);
            free(jobs[1].points);
            trifree(jobs[0].expected);
            return;
        }
    }
    for (j = 0; j < 2; j++) pthread_create(&threads[j], NULL, plain_thread, &jobs[j]);
    for (j = 0; j < 2; j++) pthread_join(threads[j], NULL);
    for (j = 0; j < 2; j++) {
        free(jobs[j].points);
        trifree(jobs[j].expected);
    }
}

/* ---- Part 2: per-call callbacks and user_data (`u`). ---- */

struct refine_job {
    const char *name;
    double max_area;
    pthread_t thread; /* set by the job's own thread before its first call */
    pthread_t handle; /* for pthread_join */
    long calls;
    long foreign_calls; /* calls with another job's user_data or from another thread */
    int rc;
    int triangles;
    double largest_area;
    char error[256];
};

static struct refine_job job_a = {"A", 0.01, 0, 0, 0, 0, 0, 0, 0, ""};
static struct refine_job job_b = {"B", 0.002, 0, 0, 0, 0, 0, 0, 0, ""};

static int area_test(struct refine_job *expected, double area, void *user_data) {
    struct refine_job *job = user_data;
    if (job != expected || !pthread_equal(pthread_self(), expected->thread)) {
        expected->foreign_calls++;
        return 0;
    }
    job->calls++;
    return area > job->max_area;
}

static int unsuitable_a(double ox, double oy, double dx, double dy, double ax, double ay,
                        double area, void *user_data) {
    (void)ox, (void)oy, (void)dx, (void)dy, (void)ax, (void)ay;
    return area_test(&job_a, area, user_data);
}

static int unsuitable_b(double ox, double oy, double dx, double dy, double ax, double ay,
                        double area, void *user_data) {
    (void)ox, (void)oy, (void)dx, (void)dy, (void)ax, (void)ay;
    return area_test(&job_b, area, user_data);
}

static double square[] = {0, 0, 1, 0, 1, 1, 0, 1, 0.31, 0.42, 0.73, 0.28};

static double largest_triangle_area(const struct triangulateio *out) {
    double largest = 0;
    int i;
    for (i = 0; i < out->numberoftriangles; i++) {
        const int *t = out->trianglelist + 3 * i;
        const double *a = out->pointlist + 2 * t[0], *b = out->pointlist + 2 * t[1],
                     *c = out->pointlist + 2 * t[2];
        double area = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        if (area > largest) largest = area;
    }
    return largest;
}

static void *refine_thread(void *arg) {
    struct refine_job *job = arg;
    triunsuitable_user_fn callback = job == &job_a ? unsuitable_a : unsuitable_b;
    int r;
    job->thread = pthread_self();
    for (r = 0; r < 5; r++) {
        struct triangulateio in, out;
        memset(&in, 0, sizeof in);
        memset(&out, 0, sizeof out);
        in.pointlist = square;
        in.numberofpoints = 6;
        job->rc = triangulate_reentrant("zQu", &in, &out, NULL, callback, job, NULL);
        if (job->rc != 0) {
            snprintf(job->error, sizeof job->error, "%s", triangulate_last_error());
            free_all(&out);
            break;
        }
        job->triangles = out.numberoftriangles;
        job->largest_area = largest_triangle_area(&out);
        free_all(&out);
    }
    return NULL;
}

static void concurrent_callbacks(void) {
    pthread_create(&job_a.handle, NULL, refine_thread, &job_a);
    pthread_create(&job_b.handle, NULL, refine_thread, &job_b);
    pthread_join(job_a.handle, NULL);
    pthread_join(job_b.handle, NULL);
    CHECK(job_a.rc == 0 && job_b.rc == 0, "u failed: %s / %s", job_a.error, job_b.error);
    CHECK(job_a.foreign_calls == 0 && job_b.foreign_calls == 0,
          "a callback got another call's user_data or ran on another thread (%ld, %ld)",
          job_a.foreign_calls, job_b.foreign_calls);
    CHECK(job_a.calls > 0 && job_b.calls > 0, "callbacks not called (%ld, %ld)", job_a.calls,
          job_b.calls);
    CHECK(job_a.largest_area <= job_a.max_area * (1 + 1e-12), "A: a triangle of area %g left",
          job_a.largest_area);
    CHECK(job_b.largest_area <= job_b.max_area * (1 + 1e-12), "B: a triangle of area %g left",
          job_b.largest_area);
    /* Each bound forces at least 1/max_area triangles: the two calls really differ. */
    CHECK(job_a.triangles >= 100 && job_b.triangles >= 500 && job_b.triangles > job_a.triangles,
          "triangle counts %d and %d", job_a.triangles, job_b.triangles);
}

/* ---- Part 3: Triangulate.jl's global callback. ---- */

static long global_calls = 0;

static int global_unsuitable(double ox, double oy, double dx, double dy, double ax, double ay,
                             double area) {
    (void)ox, (void)oy, (void)dx, (void)dy, (void)ax, (void)ay;
    global_calls++;
    return area > 0.02;
}

static void global_callback(void) {
    struct triangulateio in, out;
    int rc;
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    in.pointlist = square;
    in.numberofpoints = 6;
    triunsuitable_callback(global_unsuitable);
    rc = triangulate("zQu", &in, &out, NULL);
    triunsuitable_callback(NULL);
    CHECK(rc == 0, "global callback: %s", triangulate_last_error());
    CHECK(global_calls > 0, "the global callback was not called");
    if (rc == 0) {
        double largest = largest_triangle_area(&out);
        CHECK(largest <= 0.02 * (1 + 1e-12), "a triangle of area %g left", largest);
        CHECK(out.numberoftriangles >= 50, "%d triangles", out.numberoftriangles);
    }
    free_all(&out);
}

/* ---- Part 4: a cancelled refinement ends early: either a valid mesh or a "cancel" error. ---- */

#define CANCEL_CALL_LIMIT 100000

static int always_unsuitable(double ox, double oy, double dx, double dy, double ax, double ay,
                             double area, void *user_data) {
    (void)ox, (void)oy, (void)dx, (void)dy, (void)ax, (void)ay, (void)area;
    /* Unsuitable until the limit, so that an ignored cancel flag fails the check below instead
     * of refining forever. */
    return ++*(long *)user_data < CANCEL_CALL_LIMIT;
}

static void cancelled(void) {
    struct triangulateio in, out;
    int cancel = 1;
    long calls = 0;
    int rc;
    memset(&in, 0, sizeof in);
    memset(&out, 0, sizeof out);
    in.pointlist = square;
    in.numberofpoints = 6;
    rc = triangulate_reentrant("zQu", &in, &out, NULL, always_unsuitable, &calls, &cancel);
    CHECK(calls < CANCEL_CALL_LIMIT, "the cancel flag was ignored (%ld callback calls)", calls);
    if (rc == 0) {
        CHECK(out.numberoftriangles > 0 && out.trianglelist != NULL, "cancelled: no mesh");
    } else {
        CHECK(strstr(triangulate_last_error(), "ancel") != NULL, "cancelled: %s",
              triangulate_last_error());
    }
    free_all(&out);
}

int main(void) {
    concurrent_plain();
    concurrent_callbacks();
    global_callback();
    cancelled();
    if (failures) {
        printf("%d check(s) failed\n", failures);
        return 1;
    }
    return 0;
}
