/*
 * llvmpipe_bench: draws the relief benchmark's frame (written by renderlab-relief's `llvmpipe`
 * example) with hand-written GLSL on whatever OpenGL driver EGL's surfaceless platform gives
 * (Mesa's llvmpipe on a machine without a GPU), one draw per frame into an sRGB framebuffer
 * object, and answers timing and read-back commands on stdin, so that the example can
 * interleave its own frames with these. Run by hand, not by CI; nothing in the Cargo
 * workspace links OpenGL.
 *
 * Build and run (Debian: libegl-dev, libgl-dev; Mesa's libegl-mesa0 and libgl1-mesa-dri):
 *
 *     cc -O2 -o out/llvmpipe_bench scripts/llvmpipe_bench/llvmpipe_bench.c -lEGL -lOpenGL
 *     LP_NUM_THREADS=2 cargo run --release -p renderlab-relief --example llvmpipe -- out/llvmpipe_bench
 *
 * Input (argv[1], little-endian): "RLLPIPE3"; u32 width, height; f32 background r,g,b
 * (linear); f32 to_light x,y,z (unit, world); f32 ambient, specular exponent, specular
 * strength, height scale (UV per unit depth); u32 vertices, then 12 f32 per vertex
 * (position 3, normal 3, uv 2, tangent 4 with handedness in w); u32 indices, then u32 each;
 * u32 views, then per view 16 f32 (world → clip, column-major, depth in [0, 1]) and the eye
 * x,y,z; two textures (albedo: sRGB-encoded, normal: unorm-encoded), each u32 levels, then
 * per level u32 width, height and width·height u32 RGBA8 texels (red in the low byte, row 0
 * at v = 0); the depth map: u32 width, height, width·height u16 (depth · 65535); the
 * complexity map: u32 width, height (powers of two), width·height f32; the packed map on its
 * padded grid: u32 width + 1, height + 1, then u32 texels (16-bit depth code high, cone ratio
 * code low); f32 constants: depth step, ratio step, cone-newton's least step, least slope,
 * largest tolerance and Newton reach, and the relaxed cone march's fallback sample count.
 *
 * Commands on stdin, one a line; each answered with one line on stdout:
 *
 *     time TECH VIEW N     → "ms T1 T2 … TN": N frames, each clear + draw + glFinish, wall ms
 *     dump TECH VIEW PATH  → "ok": one frame's RGBA8 pixels, row 0 at the top, to PATH
 *     quit
 *
 * TECH is 0 basic (albedo only), 1 normal (lit by the normal map), 2 parallax (one offset
 * step from the depth at the entry point), 3 POM-32 (32 layers, the last two interpolated),
 * 4 steep parallax (32 layers, the first layer below the surface), 5 relief mapping (16
 * layers, then 6 bisection steps between the last layer above and the first below), 6 the
 * thesis's adaptive POM (layers from the view angle and the complexity map, 4 to 32, then
 * POM's march and interpolation), 7 cone-newton (at most 64 relaxed cone steps and 3 Illinois
 * steps, stopping within 0.25 texels by Newton's estimate: the WGSL twin's operations), 8
 * relaxed cone stepping (at most 16 cone steps on the packed map's per-cell ratios, a short
 * march to the bottom when they run out, then 5 bisection steps: the operations of the CPU's
 * packed-map kernel, the depth filtered by the sampler as for the other techniques).
 * The maths is the fused CPU frame's: the exact UV Jacobian from the perspective-correct
 * interpolants, the level of detail ½·log2(max(|J_x|², |J_y|²)) in texels clamped to the
 * levels, trilinear filtering by the sampler (the texture's own mip chain, repeat wrap), sRGB
 * albedo decoded per texel, the normal filtered as stored, the ambient + Lambert +
 * Blinn–Phong light in tangent space, and sRGB encoding by the framebuffer.
 */
#define GL_GLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/glext.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define TECHS 9

static void die(const char *msg) {
    fprintf(stderr, "llvmpipe_bench: %s\n", msg);
    exit(1);
}

/* A cursor over the input file. */
typedef struct {
    const uint8_t *p, *end;
} Reader;

static void take(Reader *r, void *dst, size_t n) {
    if ((size_t)(r->end - r->p) < n) die("input truncated");
    memcpy(dst, r->p, n);
    r->p += n;
}
static uint32_t u32(Reader *r) {
    uint32_t v;
    take(r, &v, 4);
    return v;
}
static float f32(Reader *r) {
    float v;
    take(r, &v, 4);
    return v;
}

typedef struct {
    float view_proj[16];
    float eye[3];
} View;

/* Uploads a one-channel map (u32 width, height, then its texels of `bytes` each) to texture
 * unit `unit` with `filter` and repeat wrap. */
static void read_map(Reader *r, GLenum unit, GLenum internal, GLenum type, size_t bytes, GLint filter,
                     const char *what) {
    uint32_t w = u32(r), h = u32(r);
    glActiveTexture(unit);
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    glTexStorage2D(GL_TEXTURE_2D, 1, internal, (GLsizei)w, (GLsizei)h);
    if ((size_t)(r->end - r->p) / bytes < (size_t)w * h) {
        fprintf(stderr, "llvmpipe_bench: %s truncated\n", what);
        exit(1);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, (GLint)bytes);
    GLenum format = internal == GL_R32UI ? GL_RED_INTEGER : GL_RED;
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, (GLsizei)w, (GLsizei)h, format, type, r->p);
    r->p += (size_t)w * h * bytes;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

/* Uploads a texture with its levels as given; returns its name. */
static GLuint read_texture(Reader *r, GLenum internal, int *levels_out, int *w0, int *h0) {
    uint32_t levels = u32(r);
    if (levels == 0 || levels > 16) die("bad level count");
    GLuint tex;
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_2D, tex);
    for (uint32_t k = 0; k < levels; k++) {
        uint32_t w = u32(r), h = u32(r);
        if (k == 0) {
            *w0 = (int)w;
            *h0 = (int)h;
            glTexStorage2D(GL_TEXTURE_2D, (GLsizei)levels, internal, (GLsizei)w, (GLsizei)h);
        }
        size_t n = (size_t)w * h * 4;
        if ((size_t)(r->end - r->p) < n) die("texture truncated");
        glTexSubImage2D(GL_TEXTURE_2D, (GLint)k, 0, 0, (GLsizei)w, (GLsizei)h, GL_RGBA, GL_UNSIGNED_BYTE, r->p);
        r->p += n;
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, (GLint)levels - 1);
    *levels_out = (int)levels;
    return tex;
}

static const char *VERTEX =
    "layout(location = 0) in vec3 position;\n"
    "layout(location = 1) in vec3 normal;\n"
    "layout(location = 2) in vec2 uv;\n"
    "layout(location = 3) in vec4 tangent;\n"
    "uniform mat4 view_proj;\n"
    "out vec2 v_uv;\n"
    "out vec3 v_world;\n"
    "out vec3 v_t;\n"
    "out vec3 v_b;\n"
    "out vec3 v_n;\n"
    "void main() {\n"
    "    gl_Position = view_proj * vec4(position, 1.0);\n"
    "    v_uv = uv;\n"
    "    v_world = position;\n"
    /* The tangent frame as the CPU builds it: N, T by Gram-Schmidt, B = N x T . sign. */
    "    vec3 n = normalize(normal);\n"
    "    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);\n"
    "    t = dot(t, t) > 0.0 ? normalize(t) : vec3(1.0, 0.0, 0.0);\n"
    "    v_t = t;\n"
    "    v_b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);\n"
    "    v_n = n;\n"
    "}\n";

static const char *FRAGMENT =
    "in vec2 v_uv;\n"
    "in vec3 v_world;\n"
    "in vec3 v_t;\n"
    "in vec3 v_b;\n"
    "in vec3 v_n;\n"
    "uniform vec3 eye;\n"
    "uniform vec3 to_light;\n"
    "layout(binding = 0) uniform sampler2D albedo_map;\n"
    "layout(binding = 1) uniform sampler2D normal_map;\n"
    "layout(binding = 2) uniform sampler2D depth_map;\n"
    "layout(binding = 3) uniform sampler2D complexity_map;\n"
    "layout(binding = 4) uniform usampler2D packed_map;\n"
    "out vec4 color;\n"
    "float lod(vec2 dx, vec2 dy) {\n"
    "    vec2 a = dx * TEX_SIZE, b = dy * TEX_SIZE;\n"
    "    float r = max(max(dot(a, a), dot(b, b)), 1e-30);\n"
    "    return clamp(0.5 * log2(r), 0.0, TEX_LEVELS - 1.0);\n"
    "}\n"
    "vec2 uv_per_depth(vec3 v) { return -v.xy / max(v.z, 1e-3) * HEIGHT_SCALE; }\n"
    "float depth_at(vec2 uv) { return textureLod(depth_map, uv, 0.0).r; }\n"
    "#if TECH == 7 || TECH == 8\n"
    /* The packed map's bilinear depth, cone ratio and depth gradient at texel coordinates
     * (x, y), as the CPU's packed fetch (power-of-two sides: wrap by masking). */
    "struct Packed { float depth; float ratio; float ddx; float ddy; };\n"
    "Packed packed_at(float x, float y) {\n"
    "    float x0 = floor(x), y0 = floor(y);\n"
    "    float fx = x - x0, fy = y - y0;\n"
    "    ivec2 n = textureSize(packed_map, 0) - ivec2(1);\n"
    "    int xw = int(x0) & (n.x - 1), yw = int(y0) & (n.y - 1);\n"
    "    uint t00 = texelFetch(packed_map, ivec2(xw, yw), 0).r;\n"
    "    uint t10 = texelFetch(packed_map, ivec2(xw + 1, yw), 0).r;\n"
    "    uint t01 = texelFetch(packed_map, ivec2(xw, yw + 1), 0).r;\n"
    "    uint t11 = texelFetch(packed_map, ivec2(xw + 1, yw + 1), 0).r;\n"
    "    float d00 = float(t00 >> 16u), d10 = float(t10 >> 16u);\n"
    "    float d01 = float(t01 >> 16u), d11 = float(t11 >> 16u);\n"
    "    float dx0 = d10 - d00, dx1 = d11 - d01;\n"
    "    float top = d00 + dx0 * fx, bottom = d01 + dx1 * fx;\n"
    "    float dy = bottom - top;\n"
    "    return Packed((top + dy * fy) * DEPTH_STEP, float(t00 & 0xffffu) * RATIO_STEP,\n"
    "                  (dx0 + (dx1 - dx0) * fy) * DEPTH_STEP, dy * DEPTH_STEP);\n"
    "}\n"
    "float cn_min(float a, float b) { return a < b ? a : b; }\n"
    "float cn_max(float a, float b) { return a > b ? a : b; }\n"
    "#endif\n"
    "#if TECH == 8\n"
    /* Relaxed cone stepping on the packed map: the depth along the ray where it meets the
     * surface (phases: 0 cone steps, 1 the tail toward the bottom, 2 bisection). */
    "float cone_step(vec2 uv0, vec3 v) {\n"
    "    const int steps = 16, refine = 5;\n"
    "    vec2 dp = uv_per_depth(v);\n"
    "    vec2 size = vec2(textureSize(packed_map, 0) - ivec2(1));\n"
    "    float s = sqrt(dot(dp, dp));\n"
    "    float px = uv0.x * size.x - 0.5, py = uv0.y * size.y - 0.5;\n"
    "    float tu = dp.x * size.x, tv = dp.y * size.y;\n"
    "    ivec2 wrap = ivec2(size) - ivec2(1);\n"
    "    float t = 0.0, a = 0.0, b = 1.0;\n"
    "    int k = 0, phase = 0;\n"
    "    for (int iter = 0; iter <= steps + CONE_TAIL + refine + 2; iter++) {\n"
    "        float c = phase == 0 ? t : phase == 1 ? t + (1.0 - t) * float(k) / float(CONE_TAIL) : 0.5 * (a + b);\n"
    /* The depth filtered by the sampler, as the other techniques read it; the cone ratio of the
     * bilinear cell's first texel, as the CPU's packed fetch takes it. */
    "        float depth = depth_at(uv0 + dp * c);\n"
    "        ivec2 cell = ivec2(floor(vec2(px + tu * c, py + tv * c))) & wrap;\n"
    "        float ratio = float(texelFetch(packed_map, cell, 0).r & 0xffffu) * RATIO_STEP;\n"
    "        float f = c - depth;\n"
    "        bool found = false;\n"
    "        if (phase == 0) {\n"
    "            if (f >= 0.0) { b = c; found = true; }\n"
    "            else {\n"
    "                float gap = depth - c;\n"
    "                a = c;\n"
    "                float r = ratio;\n"
    "                float step = s > 0.0 ? r * gap / (s + r) : gap;\n"
    "                t = cn_min(c + cn_max(step, CN_MIN_STEP), 1.0);\n"
    "                k += 1;\n"
    "                if (k >= steps) { phase = 1; k = 0; }\n"
    "            }\n"
    "        } else if (phase == 1) {\n"
    "            if (f >= 0.0 || k + 1 > CONE_TAIL) { b = c; found = true; }\n"
    "            else { a = c; k += 1; }\n"
    "        } else {\n"
    "            if (f >= 0.0) b = c; else a = c;\n"
    "            k += 1;\n"
    "            if (k >= refine) return 0.5 * (a + b);\n"
    "        }\n"
    "        if (found) {\n"
    "            if (b <= 0.0) return 0.0;\n"
    "            phase = 2; k = 0;\n"
    "        }\n"
    "    }\n"
    "    return 0.5 * (a + b);\n"
    "}\n"
    "#endif\n"
    "#if TECH == 7\n"
    "float cn_interp(float a, float fa, float b, float fb) {\n"
    "    float den = fb - fa;\n"
    "    return den > 1e-12 ? cn_min(cn_max((a * fb - b * fa) / den, a), b) : 0.5 * (a + b);\n"
    "}\n"
    /* The depth along the ray (0 at the entry, 1 at the bottom) where it meets the surface. */
    "float cone_newton(vec2 uv0, vec3 v) {\n"
    "    const int steps = 64, secant = 3;\n"
    "    const float tol = 0.25;\n"
    "    vec2 dp = uv_per_depth(v);\n"
    "    vec2 size = vec2(textureSize(packed_map, 0) - ivec2(1));\n"
    "    float s = sqrt(dot(dp, dp));\n"
    "    float eps = clamp(tol / max(s * max(size.x, size.y), 1e-3), 1e-6, CN_MAX_EPS);\n"
    "    float px = uv0.x * size.x - 0.5, py = uv0.y * size.y - 0.5;\n"
    "    float tu = dp.x * size.x, tv = dp.y * size.y;\n"
    "    float t = 0.0, a = 0.0, fa = -1.0, b = 1.0, fb = 0.0;\n"
    "    int k = 0, phase = 0;\n"
    "    for (int iter = 0; iter <= steps + secant + 1; iter++) {\n"
    "        float c = phase != 0 ? cn_interp(a, fa, b, fb) : t;\n"
    "        Packed smp = packed_at(px + tu * c, py + tv * c);\n"
    "        float f = c - smp.depth;\n"
    "        float fp = 1.0 - (smp.ddx * tu + smp.ddy * tv);\n"
    "        float gap = -f;\n"
    "        float rcp = 1.0 / fp;\n"
    "        if (phase == 0) {\n"
    "            if (f >= 0.0) {\n"
    "                if (c <= 0.0) return 0.0;\n"
    "                if (f <= eps * cn_max(fp, CN_MIN_SLOPE))\n"
    "                    return fp >= CN_MIN_SLOPE ? cn_min(cn_max(c - f * rcp, a), c) : c;\n"
    "                b = c; fb = f; k = 0; phase = 1;\n"
    "            } else if (fp >= CN_MIN_SLOPE && gap <= eps * fp) {\n"
    "                return cn_min(c + gap * rcp, 1.0);\n"
    "            } else if (k + 1 >= steps) {\n"
    "                return cn_min(c + gap * (fp > 1.0 ? rcp : 1.0), 1.0);\n"
    "            } else {\n"
    "                a = c; fa = f;\n"
    "                float cone = s > 0.0 ? smp.ratio * gap / (s + smp.ratio) : gap;\n"
    "                float step = cone;\n"
    "                if (fp >= CN_MIN_SLOPE && gap <= eps * fp * CN_JUMP) step = cn_max(cone, gap * rcp);\n"
    "                t = cn_min(c + cn_max(step, CN_MIN_STEP), 1.0);\n"
    "                k += 1;\n"
    "            }\n"
    "        } else {\n"
    "            if (abs(f) <= eps * cn_max(fp, CN_MIN_SLOPE))\n"
    "                return fp >= CN_MIN_SLOPE ? cn_min(cn_max(c - f * rcp, a), b) : c;\n"
    "            if (f >= 0.0) { b = c; fb = f; if (phase == 3) fa *= 0.5; phase = 3; }\n"
    "            else { a = c; fa = f; if (phase == 2) fb *= 0.5; phase = 2; }\n"
    "            k += 1;\n"
    "            if (k >= secant) return cn_interp(a, fa, b, fb);\n"
    "        }\n"
    "    }\n"
    "    return 1.0;\n"
    "}\n"
    "#endif\n"
    "void main() {\n"
    /* The exact UV Jacobian: uv.q is affine in screen space (q = 1/w). */
    "    float q = gl_FragCoord.w;\n"
    "    vec2 h = v_uv * q;\n"
    "    vec2 dx = (dFdxFine(h) - v_uv * dFdxFine(q)) / q;\n"
    "    vec2 dy = (dFdyFine(h) - v_uv * dFdyFine(q)) / q;\n"
    "    float l = lod(dx, dy);\n"
    "    vec2 uv = v_uv;\n"
    "#if TECH >= 1\n"
    "    vec3 view = normalize(eye - v_world);\n"
    "    vec3 vts = vec3(dot(v_t, view), dot(v_b, view), dot(v_n, view));\n"
    "    vec3 lts = vec3(dot(v_t, to_light), dot(v_b, to_light), dot(v_n, to_light));\n"
    "#endif\n"
    "#if TECH == 2\n"
    "    uv += uv_per_depth(vts) * depth_at(uv);\n"
    "#elif TECH == 7\n"
    "    uv += uv_per_depth(vts) * cone_newton(uv, vts);\n"
    "#elif TECH == 8\n"
    "    uv += uv_per_depth(vts) * cone_step(uv, vts);\n"
    "#elif TECH >= 3\n"
    "#if TECH == 6\n"
    /* The thesis's layer count: the complexity texel at the entry (nearest, wrapped), the view
     * angle's factor (1 - |v.z|)^0.8, int(mix(mix(MIN, MAX/2, f), mix(MIN, MAX, f), c)). */
    "    vec2 cs = vec2(textureSize(complexity_map, 0));\n"
    "    float c = clamp(textureLod(complexity_map, (floor(uv * cs) + 0.5) / cs, 0.0).r, 0.0, 1.0);\n"
    "    float f = pow(max(1.0 - abs(normalize(vts).z), 0.0), 0.8);\n"
    "    float lo = 4.0 + (16.0 - 4.0) * f, hi = 4.0 + (32.0 - 4.0) * f;\n"
    "    float layers = float(max(int(lo + (hi - lo) * c), 1));\n"
    "#else\n"
    "    float layers = LAYERS;\n"
    "#endif\n"
    "    vec2 step = uv_per_depth(vts) * (1.0 / layers);\n"
    "    vec2 uv0 = uv;\n"
    "    float map = depth_at(uv);\n"
    "    vec2 prev_uv = uv;\n"
    "    float prev_map = map;\n"
    "    int i = 0;\n"
    "    while (float(i) * (1.0 / layers) < map && i < int(layers)) {\n"
    "        prev_uv = uv;\n"
    "        prev_map = map;\n"
    "        i += 1;\n"
    "        uv = uv0 + step * float(i);\n"
    "        map = depth_at(uv);\n"
    "    }\n"
    "    float layer = float(i) * (1.0 / layers);\n"
    "    float prev_layer = i == 0 ? 0.0 : layer - 1.0 / layers;\n"
    "#if TECH == 3 || TECH == 6\n"
    "    float after = map - layer, before = prev_map - prev_layer, denom = after - before;\n"
    "    float w = abs(denom) > 1e-12 ? clamp(after / denom, 0.0, 1.0) : 0.0;\n"
    "    uv = prev_uv * w + uv * (1.0 - w);\n"
    "#elif TECH == 5\n"
    /* Bisection between the layers, along the whole ray (no search when layer 0 is below). */
    "    if (i > 0) {\n"
    "        vec2 dp = uv_per_depth(vts);\n"
    "        float a = prev_layer, b = layer;\n"
    "        for (int k = 0; k < BINARY; k++) {\n"
    "            float mid = 0.5 * (a + b);\n"
    "            if (mid >= depth_at(uv0 + dp * mid)) b = mid; else a = mid;\n"
    "        }\n"
    "        uv = uv0 + dp * (0.5 * (a + b));\n"
    "    }\n"
    "#endif\n"
    "#endif\n"
    "    vec3 albedo = textureLod(albedo_map, uv, l).rgb;\n"
    "#if TECH == 0\n"
    "    color = vec4(albedo, 1.0);\n"
    "#else\n"
    "    vec3 raw = textureLod(normal_map, uv, l).xyz * 2.0 - 1.0;\n"
    "    vec3 n = dot(raw, raw) > 1e-30 ? normalize(raw) : vec3(0.0, 0.0, 1.0);\n"
    "    float diff = max(dot(n, lts), 0.0);\n"
    "    vec3 hv = lts + vts;\n"
    "    vec3 hh = dot(hv, hv) > 0.0 ? normalize(hv) : vec3(0.0);\n"
    "    float nh = max(dot(n, hh), 0.0);\n"
    /* x^EXPONENT by squaring, as the CPU raises a whole exponent. */
    "    float acc = 1.0, base = nh;\n"
    "    for (int e = EXPONENT; e > 0; e >>= 1) {\n"
    "        if ((e & 1) == 1) acc *= base;\n"
    "        base *= base;\n"
    "    }\n"
    "    float facing = lts.z > 0.0 ? 1.0 : 0.0;\n"
    "    color = vec4(albedo * AMBIENT + (albedo * diff + vec3(acc * STRENGTH)) * facing, 1.0);\n"
    "#endif\n"
    "}\n";

static GLuint compile(GLenum kind, const char *prelude, const char *src) {
    GLuint s = glCreateShader(kind);
    const char *parts[2] = {prelude, src};
    glShaderSource(s, 2, parts, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        fprintf(stderr, "%s\n", log);
        die("shader did not compile");
    }
    return s;
}

static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

int main(int argc, char **argv) {
    if (argc != 2) die("usage: llvmpipe_bench INPUT < commands");
    FILE *f = fopen(argv[1], "rb");
    if (!f) die("cannot open the input");
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    uint8_t *data = malloc((size_t)size);
    if (!data || fread(data, 1, (size_t)size, f) != (size_t)size) die("cannot read the input");
    fclose(f);
    Reader r = {data, data + size};
    char magic[8];
    take(&r, magic, 8);
    if (memcmp(magic, "RLLPIPE3", 8) != 0) die("not an RLLPIPE3 file");
    uint32_t width = u32(&r), height = u32(&r);
    float bg[3], to_light[3], ambient, exponent, strength, height_scale;
    for (int i = 0; i < 3; i++) bg[i] = f32(&r);
    for (int i = 0; i < 3; i++) to_light[i] = f32(&r);
    ambient = f32(&r);
    exponent = f32(&r);
    strength = f32(&r);
    height_scale = f32(&r);
    uint32_t nv = u32(&r);
    float *vertices = malloc(nv * 12 * sizeof(float));
    take(&r, vertices, nv * 12 * sizeof(float));
    uint32_t ni = u32(&r);
    uint32_t *indices = malloc(ni * sizeof(uint32_t));
    take(&r, indices, ni * sizeof(uint32_t));
    uint32_t nviews = u32(&r);
    View *views = malloc(nviews * sizeof(View));
    for (uint32_t i = 0; i < nviews; i++) {
        for (int k = 0; k < 16; k++) views[i].view_proj[k] = f32(&r);
        for (int k = 0; k < 3; k++) views[i].eye[k] = f32(&r);
    }

    /* EGL on the surfaceless platform, a desktop OpenGL 4.5 core context, no window. */
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    if (!get_display) die("no eglGetPlatformDisplayEXT");
    EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    EGLint major, minor;
    if (!eglInitialize(dpy, &major, &minor)) die("eglInitialize failed");
    if (!eglBindAPI(EGL_OPENGL_API)) die("no desktop OpenGL");
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx == EGL_NO_CONTEXT) die("no OpenGL 4.5 core context");
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) die("eglMakeCurrent failed");
    fprintf(stderr, "llvmpipe_bench: %s; %s\n", (const char *)glGetString(GL_RENDERER),
            (const char *)glGetString(GL_VERSION));

    int albedo_levels, normal_levels, aw, ah, nw, nh;
    glActiveTexture(GL_TEXTURE0);
    read_texture(&r, GL_SRGB8_ALPHA8, &albedo_levels, &aw, &ah);
    glActiveTexture(GL_TEXTURE1);
    read_texture(&r, GL_RGBA8, &normal_levels, &nw, &nh);
    if (albedo_levels != normal_levels || aw != nw || ah != nh) die("albedo and normal of different shapes");
    read_map(&r, GL_TEXTURE2, GL_R16, GL_UNSIGNED_SHORT, 2, GL_LINEAR, "depth map");
    read_map(&r, GL_TEXTURE3, GL_R32F, GL_FLOAT, 4, GL_NEAREST, "complexity map");
    read_map(&r, GL_TEXTURE4, GL_R32UI, GL_UNSIGNED_INT, 4, GL_NEAREST, "packed map");
    float consts[7];
    for (int i = 0; i < 7; i++) consts[i] = f32(&r);

    /* The mesh. */
    GLuint vao, vbo, ibo;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, nv * 12 * sizeof(float), vertices, GL_STATIC_DRAW);
    glGenBuffers(1, &ibo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, ni * sizeof(uint32_t), indices, GL_STATIC_DRAW);
    const int offsets[4] = {0, 3, 6, 8}, sizes[4] = {3, 3, 2, 4};
    for (int a = 0; a < 4; a++) {
        glEnableVertexAttribArray((GLuint)a);
        glVertexAttribPointer((GLuint)a, sizes[a], GL_FLOAT, GL_FALSE, 12 * sizeof(float),
                              (const void *)(offsets[a] * sizeof(float)));
    }

    /* One program per technique, its constants compiled in. */
    GLuint programs[TECHS];
    for (int t = 0; t < TECHS; t++) {
        char prelude[1024];
        snprintf(prelude, sizeof prelude,
                 "#version 450 core\n#define TECH %d\n#define TEX_SIZE vec2(%d.0, %d.0)\n"
                 "#define TEX_LEVELS %d.0\n#define HEIGHT_SCALE %.9g\n#define LAYERS %d.0\n"
                 "#define BINARY 6\n#define EXPONENT %d\n#define AMBIENT %.9g\n#define STRENGTH %.9g\n"
                 "#define DEPTH_STEP float(%.9g)\n#define RATIO_STEP float(%.9g)\n"
                 "#define CN_MIN_STEP float(%.9g)\n#define CN_MIN_SLOPE float(%.9g)\n"
                 "#define CN_MAX_EPS float(%.9g)\n#define CN_JUMP float(%.9g)\n#define CONE_TAIL %d\n",
                 t, aw, ah, albedo_levels, height_scale, t == 5 ? 16 : 32, (int)exponent, ambient,
                 strength, consts[0], consts[1], consts[2], consts[3], consts[4], consts[5],
                 (int)consts[6]);
        GLuint p = glCreateProgram();
        glAttachShader(p, compile(GL_VERTEX_SHADER, prelude, VERTEX));
        glAttachShader(p, compile(GL_FRAGMENT_SHADER, prelude, FRAGMENT));
        glLinkProgram(p);
        GLint ok = 0;
        glGetProgramiv(p, GL_LINK_STATUS, &ok);
        if (!ok) die("program did not link");
        programs[t] = p;
    }
    if ((float)(int)exponent != exponent) die("the specular exponent must be a whole number");

    /* The sRGB render target (linear shader output, encoded on write). */
    GLuint fbo, rb;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_SRGB8_ALPHA8, (GLsizei)width, (GLsizei)height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) die("incomplete framebuffer");
    glEnable(GL_FRAMEBUFFER_SRGB);
    glViewport(0, 0, (GLsizei)width, (GLsizei)height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glClearColor(bg[0], bg[1], bg[2], 1.0f);
    /* Our frame puts row 0 at the top; GL's window y points up: `dump` writes the rows read
       back from the last to the first. */

    uint8_t *pixels = malloc((size_t)width * height * 4);
    char line[1024];
    while (fgets(line, sizeof line, stdin)) {
        char cmd[16], path[900];
        int tech = 0, view = 0, n = 0;
        if (sscanf(line, "%15s", cmd) != 1) continue;
        if (strcmp(cmd, "quit") == 0) break;
        int is_time = strcmp(cmd, "time") == 0;
        if (is_time ? sscanf(line, "%*s %d %d %d", &tech, &view, &n) != 3
                    : sscanf(line, "%*s %d %d %899s", &tech, &view, path) != 3)
            die("bad command");
        if (tech < 0 || tech >= TECHS || view < 0 || (uint32_t)view >= nviews) die("bad technique or view");
        GLuint p = programs[tech];
        glUseProgram(p);
        glUniformMatrix4fv(glGetUniformLocation(p, "view_proj"), 1, GL_FALSE, views[view].view_proj);
        glUniform3fv(glGetUniformLocation(p, "eye"), 1, views[view].eye);
        glUniform3fv(glGetUniformLocation(p, "to_light"), 1, to_light);
        if (is_time) {
            printf("ms");
            for (int i = 0; i < n; i++) {
                double t0 = now_ms();
                glClear(GL_COLOR_BUFFER_BIT);
                glDrawElements(GL_TRIANGLES, (GLsizei)ni, GL_UNSIGNED_INT, 0);
                glFinish();
                printf(" %.4f", now_ms() - t0);
            }
            printf("\n");
        } else {
            glClear(GL_COLOR_BUFFER_BIT);
            glDrawElements(GL_TRIANGLES, (GLsizei)ni, GL_UNSIGNED_INT, 0);
            glFinish();
            glPixelStorei(GL_PACK_ALIGNMENT, 4);
            glReadPixels(0, 0, (GLsizei)width, (GLsizei)height, GL_RGBA, GL_UNSIGNED_BYTE, pixels);
            FILE *o = fopen(path, "wb");
            if (!o) die("cannot write the dump");
            for (uint32_t y = 0; y < height; y++)
                fwrite(pixels + (size_t)(height - 1 - y) * width * 4, 1, (size_t)width * 4, o);
            fclose(o);
            printf("ok\n");
        }
        fflush(stdout);
    }
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    return 0;
}
