/*
 * embree_bench: traces a mesh and ray sets written by renderlab-trace's `embree` example with
 * Embree 3, on one thread, in every query mode Embree offers, and writes the single-ray hits
 * back so that the example can compare them with renderlab-trace's. Run by hand, not by CI;
 * nothing in the Cargo workspace links Embree.
 *
 * Build and run (Debian: `apt-get install libembree-dev`):
 *
 *     cc -O2 -o out/embree_bench scripts/embree_bench/embree_bench.c -lembree3 -lm
 *     cargo run --release -p renderlab-trace --example embree -- out/embree_bench [REPS] [ROUNDS] [MESHES]
 *
 * The example writes out/embree/MESH.bin for each mesh, runs `embree_bench out/embree/MESH.bin
 * out/embree/MESH.hits REPS` and parses the `rate` and `build` lines it prints. By hand:
 *
 *     out/embree_bench out/embree/terrain.bin out/embree/terrain.hits 5
 *
 * Input (little-endian): "RLTRACE1" or "RLTRACE2"; u32 vertices, u32 triangles; f32 x,y,z per
 * vertex; u32 i,j,k per triangle; with "RLTRACE2" then u32 instances and per instance twelve f32,
 * its object-to-world transform as a column-major 3×4 matrix (the scene is then those instances
 * of the mesh, built as Embree instances over one mesh scene); u32 sets; per set: 16 bytes of name (NUL-padded), u32 flags (bit 0: an
 * occlusion query, bit 1: coherent rays), u32 rays, then per ray eight f32: origin x,y,z,
 * t_min, direction x,y,z, t_max.
 *
 * Output: per set, per ray, the result of rtcIntersect1 (u32 primitive, 0xffffffff for a miss,
 * and f32 t; in an instanced scene the primitive is instance · triangles + triangle) or of rtcOccluded1 (u8, 1 when occluded). Printed: the build times and, per scene
 * flag (default, robust), set and mode, one line
 *
 *     rate SCENE SET MODE MRAYS_PER_CPU_SECOND MRAYS_PER_WALL_SECOND SAME_AS_SINGLE
 *
 * with the median over REPS passes over the set, timed by this thread's CPU time (other
 * processes sharing the cores do not count), and how many rays got the same result as the
 * default scene's single-ray query (the same primitive and t within 1e-4, relative and at least
 * absolute, or the same occlusion). Modes: "1" (rtcIntersect1/rtcOccluded1
 * per ray), "8" and "16" (packets of consecutive rays, rtcIntersect8/16), "1M" (streams of 256
 * consecutive rays, rtcIntersect1M/rtcOccluded1M). Packets and streams use the coherent
 * context flag when the set says its rays are coherent (except occlusion in an instanced
 * scene). Builds use Embree's default quality (medium) and all cores; with
 * EMBREE_BENCH_QUALITY=high they use RTC_BUILD_QUALITY_HIGH (for triangle meshes Embree's
 * builder with spatial splits).
 *
 * Serving passes (for scripts/paired_passes.py, which alternates it pass by pass with our
 * `profile_set … serve`): `embree_bench SCENE.bin - serve` with EMBREE_BENCH_ONLY=SET:MODE
 * builds the default scene once, runs one warm-up pass, prints "ready", then runs one pass per
 * line read on its input and prints that pass's seconds (wall clock), until its input ends.
 *
 * For profiling one workload (under valgrind's cachegrind, say), two environment variables:
 * EMBREE_BENCH_ONLY=SET:MODE traces only that set in that mode on the default scene (the robust
 * scene is still built) and writes no hits file, and EMBREE_BENCH_CONFIG is passed to rtcNewDevice ("verbose=3" prints
 * Embree's statistics of each hierarchy: node and leaf counts and their SAH costs).
 */

#define _POSIX_C_SOURCE 199309L
#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define STREAM 256
#define MAX_SETS 16
#define MAX_REPS 64

typedef struct {
    float org[3], tmin, dir[3], tmax;
} Ray;

typedef struct {
    char name[17];
    uint32_t flags;
    uint32_t n;
    Ray *rays;
    uint32_t *prim; /* single-ray results: primitive (closest) */
    float *t;       /* and distance */
    uint8_t *occ;   /* or occlusion */
} Set;

static double now(clockid_t clock) {
    struct timespec ts;
    clock_gettime(clock, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void die(const char *what) {
    fprintf(stderr, "embree_bench: %s\n", what);
    exit(1);
}

static void read_exact(FILE *f, void *dst, size_t bytes) {
    if (fread(dst, 1, bytes, f) != bytes) die("input file truncated");
}

static void *alloc(size_t bytes) {
    void *p = aligned_alloc(64, (bytes + 63) / 64 * 64);
    if (!p) die("out of memory");
    return p;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n) {
    qsort(v, n, sizeof(double), cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

static void init_rayhit(struct RTCRayHit *rh, const Ray *r) {
    rh->ray.org_x = r->org[0];
    rh->ray.org_y = r->org[1];
    rh->ray.org_z = r->org[2];
    rh->ray.tnear = r->tmin;
    rh->ray.dir_x = r->dir[0];
    rh->ray.dir_y = r->dir[1];
    rh->ray.dir_z = r->dir[2];
    rh->ray.time = 0.0f;
    rh->ray.tfar = r->tmax;
    rh->ray.mask = 0xffffffffu;
    rh->ray.id = 0;
    rh->ray.flags = 0;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

/* The triangles of the mesh, to number a hit in an instance as instance · triangles + triangle. */
static uint32_t mesh_triangles;

static uint32_t hit_prim(unsigned geom, unsigned inst, unsigned prim) {
    if (geom == RTC_INVALID_GEOMETRY_ID) return 0xffffffffu;
    return inst == RTC_INVALID_GEOMETRY_ID ? prim : inst * mesh_triangles + prim;
}

/* One pass of `mode` over the set: results into prim/t or occ. */
typedef void (*Pass)(RTCScene, const Set *, uint32_t *, float *, uint8_t *);

/* Whether the scene is instanced: there occlusion queries go without the coherent flag (with
 * it, Embree 3.13.5's rtcOccluded16 through instances did not finish in minutes, and its
 * rtcOccluded8 ran at two thirds of the incoherent rate). */
static int instanced;

static void context(struct RTCIntersectContext *ctx, const Set *s) {
    rtcInitIntersectContext(ctx);
    int coherent = (s->flags & 2) && !(instanced && (s->flags & 1));
    ctx->flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
}

static void pass1(RTCScene scene, const Set *s, uint32_t *prim, float *t, uint8_t *occ) {
    struct RTCIntersectContext ctx;
    context(&ctx, s);
    for (uint32_t i = 0; i < s->n; i++) {
        struct RTCRayHit rh;
        init_rayhit(&rh, &s->rays[i]);
        if (s->flags & 1) {
            rtcOccluded1(scene, &ctx, &rh.ray);
            occ[i] = rh.ray.tfar == -INFINITY;
        } else {
            rtcIntersect1(scene, &ctx, &rh);
            prim[i] = hit_prim(rh.hit.geomID, rh.hit.instID[0], rh.hit.primID);
            t[i] = rh.ray.tfar;
        }
    }
}

static void pass1m(RTCScene scene, const Set *s, uint32_t *prim, float *t, uint8_t *occ) {
    struct RTCIntersectContext ctx;
    context(&ctx, s);
    static struct RTCRayHit rh[STREAM];
    static struct RTCRay r[STREAM];
    for (uint32_t base = 0; base < s->n; base += STREAM) {
        uint32_t m = s->n - base < STREAM ? s->n - base : STREAM;
        for (uint32_t j = 0; j < m; j++) init_rayhit(&rh[j], &s->rays[base + j]);
        if (s->flags & 1) {
            for (uint32_t j = 0; j < m; j++) r[j] = rh[j].ray;
            rtcOccluded1M(scene, &ctx, r, m, sizeof(struct RTCRay));
            for (uint32_t j = 0; j < m; j++) occ[base + j] = r[j].tfar == -INFINITY;
        } else {
            rtcIntersect1M(scene, &ctx, rh, m, sizeof(struct RTCRayHit));
            for (uint32_t j = 0; j < m; j++) {
                prim[base + j] = hit_prim(rh[j].hit.geomID, rh[j].hit.instID[0], rh[j].hit.primID);
                t[base + j] = rh[j].ray.tfar;
            }
        }
    }
}

/* Packets of W consecutive rays; a short last packet has invalid lanes. */
#define PACKET_PASS(W)                                                                          \
    static void pass##W(RTCScene scene, const Set *s, uint32_t *prim, float *t, uint8_t *occ) { \
        struct RTCIntersectContext ctx;                                                         \
        context(&ctx, s);                                                                       \
        static struct RTCRayHit##W rh;                                                          \
        static int valid[W];                                                                    \
        for (uint32_t base = 0; base < s->n; base += W) {                                       \
            for (int j = 0; j < W; j++) {                                                       \
                uint32_t i = base + j;                                                          \
                const Ray *r = &s->rays[i < s->n ? i : base];                                   \
                valid[j] = i < s->n ? -1 : 0;                                                   \
                rh.ray.org_x[j] = r->org[0];                                                    \
                rh.ray.org_y[j] = r->org[1];                                                    \
                rh.ray.org_z[j] = r->org[2];                                                    \
                rh.ray.tnear[j] = r->tmin;                                                      \
                rh.ray.dir_x[j] = r->dir[0];                                                    \
                rh.ray.dir_y[j] = r->dir[1];                                                    \
                rh.ray.dir_z[j] = r->dir[2];                                                    \
                rh.ray.time[j] = 0.0f;                                                          \
                rh.ray.tfar[j] = r->tmax;                                                       \
                rh.ray.mask[j] = 0xffffffffu;                                                   \
                rh.ray.id[j] = j;                                                               \
                rh.ray.flags[j] = 0;                                                            \
                rh.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;                                     \
                rh.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;                                  \
            }                                                                                   \
            if (s->flags & 1) {                                                                 \
                rtcOccluded##W(valid, scene, &ctx, &rh.ray);                                    \
                for (int j = 0; j < W && base + j < s->n; j++)                                  \
                    occ[base + j] = rh.ray.tfar[j] == -INFINITY;                                \
            } else {                                                                            \
                rtcIntersect##W(valid, scene, &ctx, &rh);                                       \
                for (int j = 0; j < W && base + j < s->n; j++) {                                \
                    prim[base + j] = hit_prim(rh.hit.geomID[j], rh.hit.instID[0][j], rh.hit.primID[j]); \
                    t[base + j] = rh.ray.tfar[j];                                               \
                }                                                                               \
            }                                                                                   \
        }                                                                                       \
    }
PACKET_PASS(8)
PACKET_PASS(16)

/* The scene of the mesh, or of `ninst` instances of it (transforms `xfm`, 12 floats each);
 * `ms` is the time of the commits. */
/* The build quality of every scene (EMBREE_BENCH_QUALITY). */
static enum RTCBuildQuality quality = RTC_BUILD_QUALITY_MEDIUM;

static RTCScene build(RTCDevice device, uint32_t nv, const float *pos, uint32_t nt, const uint32_t *idx,
                      uint32_t ninst, const float *xfm, enum RTCSceneFlags flags, double *ms) {
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneFlags(scene, flags);
    rtcSetSceneBuildQuality(scene, quality);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, nv);
    memcpy(v, pos, (size_t)nv * 12);
    uint32_t *ix = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, nt);
    memcpy(ix, idx, (size_t)nt * 12);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    double t0 = now(CLOCK_MONOTONIC);
    rtcCommitScene(scene);
    if (ninst > 0) {
        RTCScene top = rtcNewScene(device);
        rtcSetSceneFlags(top, flags);
        rtcSetSceneBuildQuality(top, quality);
        for (uint32_t i = 0; i < ninst; i++) {
            RTCGeometry inst = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
            rtcSetGeometryInstancedScene(inst, scene);
            rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm + 12 * (size_t)i);
            rtcCommitGeometry(inst);
            rtcAttachGeometryByID(top, inst, i);
            rtcReleaseGeometry(inst);
        }
        rtcCommitScene(top);
        rtcReleaseScene(scene); /* the instances hold it */
        scene = top;
    }
    *ms = (now(CLOCK_MONOTONIC) - t0) * 1e3;
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) die("Embree could not build the scene");
    return scene;
}

int main(int argc, char **argv) {
    if (argc < 3) die("usage: embree_bench SCENE.bin HITS.bin [REPS|serve]");
    int serve = argc > 3 && !strcmp(argv[3], "serve");
    int reps = serve ? 1 : argc > 3 ? atoi(argv[3]) : 5;
    if (reps < 1 || reps > MAX_REPS) die("REPS must be 1..64");
    FILE *f = fopen(argv[1], "rb");
    if (!f) die("cannot open the scene file");
    char magic[8];
    read_exact(f, magic, 8);
    instanced = !memcmp(magic, "RLTRACE2", 8);
    if (!instanced && memcmp(magic, "RLTRACE1", 8)) die("not a scene file (magic)");
    uint32_t nv, nt, nsets;
    read_exact(f, &nv, 4);
    read_exact(f, &nt, 4);
    if (nv > (1u << 28) || nt > (1u << 28)) die("mesh too large");
    float *pos = alloc((size_t)nv * 12 + 16);
    uint32_t *idx = alloc((size_t)nt * 12);
    read_exact(f, pos, (size_t)nv * 12);
    read_exact(f, idx, (size_t)nt * 12);
    for (size_t i = 0; i < (size_t)nt * 3; i++)
        if (idx[i] >= nv) die("index out of range");
    mesh_triangles = nt;
    uint32_t ninst = 0;
    float *xfm = NULL;
    if (instanced) {
        read_exact(f, &ninst, 4);
        if (ninst < 1 || ninst > (1u << 16)) die("instance count out of range");
        xfm = alloc((size_t)ninst * 48);
        read_exact(f, xfm, (size_t)ninst * 48);
    }
    read_exact(f, &nsets, 4);
    if (nsets > MAX_SETS) die("too many ray sets");
    Set sets[MAX_SETS];
    for (uint32_t s = 0; s < nsets; s++) {
        memset(sets[s].name, 0, sizeof sets[s].name);
        read_exact(f, sets[s].name, 16);
        read_exact(f, &sets[s].flags, 4);
        read_exact(f, &sets[s].n, 4);
        if (sets[s].n > (1u << 26)) die("ray set too large");
        sets[s].rays = alloc((size_t)sets[s].n * sizeof(Ray));
        read_exact(f, sets[s].rays, (size_t)sets[s].n * sizeof(Ray));
        sets[s].prim = alloc((size_t)sets[s].n * 4);
        sets[s].t = alloc((size_t)sets[s].n * 4);
        sets[s].occ = alloc(sets[s].n);
    }
    fclose(f);

    /* EMBREE_BENCH_ONLY=SET:MODE: one set in one mode on the default scene. */
    const char *only = getenv("EMBREE_BENCH_ONLY");
    char only_set[32] = "", only_mode[8] = "";
    if (only) {
        const char *colon = strchr(only, ':');
        if (!colon || colon == only || (size_t)(colon - only) >= sizeof only_set || strlen(colon + 1) == 0 ||
            strlen(colon + 1) >= sizeof only_mode)
            die("EMBREE_BENCH_ONLY must be SET:MODE (MODE one of 1, 8, 16, 1M)");
        memcpy(only_set, only, (size_t)(colon - only));
        strcpy(only_mode, colon + 1);
    }
    if (serve && !only) die("serve needs EMBREE_BENCH_ONLY=SET:MODE");
    const char *q = getenv("EMBREE_BENCH_QUALITY");
    if (q && strcmp(q, "high") == 0) quality = RTC_BUILD_QUALITY_HIGH;
    else if (q && strcmp(q, "medium") != 0) die("EMBREE_BENCH_QUALITY must be medium or high");
    RTCDevice device = rtcNewDevice(getenv("EMBREE_BENCH_CONFIG"));
    if (!device) die("Embree found no device");
    printf("embree %d.%d.%d, %u triangles, %u instances, %d passes per mode, %s quality\n", RTC_VERSION_MAJOR,
           RTC_VERSION_MINOR, RTC_VERSION_PATCH, nt, ninst, reps, quality == RTC_BUILD_QUALITY_HIGH ? "high" : "medium");

    const char *scene_names[2] = {"default", "robust"};
    enum RTCSceneFlags scene_flags[2] = {RTC_SCENE_FLAG_NONE, RTC_SCENE_FLAG_ROBUST};
    const char *mode_names[4] = {"1", "8", "16", "1M"};
    Pass passes[4] = {pass1, pass8, pass16, pass1m};
    for (int sc = 0; sc < (serve ? 1 : 2); sc++) {
        double ms[3];
        RTCScene scene = NULL;
        for (int b = 0; b < (serve ? 1 : 3); b++) {
            if (scene) rtcReleaseScene(scene);
            scene = build(device, nv, pos, nt, idx, ninst, xfm, scene_flags[sc], &ms[b]);
        }
        printf("build %s %.1f ms (median of %d, wall clock)\n", scene_names[sc], median(ms, serve ? 1 : 3), serve ? 1 : 3);
        for (uint32_t s = 0; s < nsets; s++) {
            Set *set = &sets[s];
            uint32_t *prim = alloc((size_t)set->n * 4);
            float *t = alloc((size_t)set->n * 4);
            uint8_t *occ = alloc(set->n);
            for (int m = 0; m < 4; m++) {
                if (only && (sc != 0 || strcmp(only_set, set->name) || strcmp(only_mode, mode_names[m]))) continue;
                double cpu[MAX_REPS], wall[MAX_REPS];
                passes[m](scene, set, prim, t, occ); /* warm-up */
                if (serve) {
                    char line[64];
                    printf("ready\n");
                    fflush(stdout);
                    while (fgets(line, sizeof line, stdin)) {
                        double w0 = now(CLOCK_MONOTONIC);
                        passes[m](scene, set, prim, t, occ);
                        printf("%.9f\n", now(CLOCK_MONOTONIC) - w0);
                        fflush(stdout);
                    }
                    return 0;
                }
                for (int r = 0; r < reps; r++) {
                    double c0 = now(CLOCK_THREAD_CPUTIME_ID), w0 = now(CLOCK_MONOTONIC);
                    passes[m](scene, set, prim, t, occ);
                    cpu[r] = set->n / (now(CLOCK_THREAD_CPUTIME_ID) - c0) / 1e6;
                    wall[r] = set->n / (now(CLOCK_MONOTONIC) - w0) / 1e6;
                }
                if (m == 0 && sc == 0) {
                    memcpy(set->prim, prim, (size_t)set->n * 4);
                    memcpy(set->t, t, (size_t)set->n * 4);
                    memcpy(set->occ, occ, set->n);
                }
                uint32_t same = 0;
                for (uint32_t i = 0; i < set->n; i++)
                    same += (set->flags & 1) ? occ[i] == set->occ[i]
                                             : prim[i] == set->prim[i] &&
                                                   (prim[i] == 0xffffffffu ||
                                                    fabsf(t[i] - set->t[i]) <= 1e-4f * fmaxf(t[i], 1.0f));
                printf("rate %s %s %s %.3f %.3f %u\n", scene_names[sc], set->name, mode_names[m],
                       median(cpu, reps), median(wall, reps), same);
                fflush(stdout);
            }
            free(prim);
            free(t);
            free(occ);
        }
        rtcReleaseScene(scene);
    }
    rtcReleaseDevice(device);

    if (only) return 0; /* a partial run writes no hits */
    FILE *o = fopen(argv[2], "wb");
    if (!o) die("cannot write the hits file");
    for (uint32_t s = 0; s < nsets; s++) {
        for (uint32_t i = 0; i < sets[s].n; i++) {
            if (sets[s].flags & 1) {
                fwrite(&sets[s].occ[i], 1, 1, o);
            } else {
                fwrite(&sets[s].prim[i], 4, 1, o);
                fwrite(&sets[s].t[i], 4, 1, o);
            }
        }
    }
    if (fclose(o)) die("cannot write the hits file");
    return 0;
}
