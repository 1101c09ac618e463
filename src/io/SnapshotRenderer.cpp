// The snapshot rasteriser (declared in SnapshotScene.h). Spheres are discs in an orthographic
// view, each pixel shaded from the sphere's normal there and kept if it is the nearest surface so
// far (a z-buffer); triangles likewise with interpolated depth. Rows are split into bands that the
// threads draw independently, so no two threads ever write the same pixel.
#include <algorithm>
#include <cmath>
#include <limits>

#include <deme/Error.h>

#include "io/SnapshotOverlay.h"
#include "io/SnapshotScene.h"

namespace deme {

namespace {

float3 normalized(const float3& v) { return v * (1.f / length(v)); }

bool hasBox(const SnapshotOptions& o) {
    return o.boxMax.x > o.boxMin.x && o.boxMax.y > o.boxMin.y && o.boxMax.z > o.boxMin.z;
}

// The camera: an orthonormal frame, the box centre as origin, and the pixel scale.
struct View {
    float3 right, up, dir, centre;
    float uc = 0.f, vc = 0.f, scale = 1.f;
    int width = 0, height = 0, sceneWidth = 0;
    bool clip = false;
    float3 bmin, bmax;

    float3 local(const float3& p) const {
        const float3 q = p - centre;
        return make_float3(dot(q, right), dot(q, up), dot(q, dir));
    }
    float px(float u) const { return (u - uc) * scale + 0.5f * (float)sceneWidth; }
    float py(float v) const { return 0.5f * (float)height - (v - vc) * scale; }
    bool inside(const float3& p) const {
        return p.x >= bmin.x && p.y >= bmin.y && p.z >= bmin.z && p.x <= bmax.x && p.y <= bmax.y && p.z <= bmax.z;
    }
    // The world point seen at pixel centre (x, y) at depth d.
    float3 world(float x, float y, float d) const {
        const float u = (x - 0.5f * (float)sceneWidth) / scale + uc, v = (0.5f * (float)height - y) / scale + vc;
        return centre + right * u + up * v + dir * d;
    }
};

View makeView(const SnapshotScene& s, const SnapshotOptions& o) {
    View v;
    v.width = o.width;
    v.height = o.height;
    v.sceneWidth = o.colorBar && o.colorBy != "none" ? std::max(1, o.width - overlayWidth(o.height)) : o.width;
    v.dir = normalized(o.direction);
    float3 up = o.up;
    if (length(cross(v.dir, normalized(up))) < 1e-3f) up = make_float3(0.f, 1.f, 0.f);
    if (length(cross(v.dir, up)) < 1e-3f) up = make_float3(1.f, 0.f, 0.f);
    v.right = normalized(cross(v.dir, up));
    v.up = cross(v.right, v.dir);
    v.clip = hasBox(o);
    float3 lo = o.boxMin, hi = o.boxMax;
    if (!v.clip) {
        const float inf = std::numeric_limits<float>::infinity();
        lo = make_float3(inf, inf, inf), hi = make_float3(-inf, -inf, -inf);
        auto grow = [&](const float3& p, float r) {
            lo = make_float3(std::min(lo.x, p.x - r), std::min(lo.y, p.y - r), std::min(lo.z, p.z - r));
            hi = make_float3(std::max(hi.x, p.x + r), std::max(hi.y, p.y + r), std::max(hi.z, p.z + r));
        };
        float lx = inf, ly = inf, lz = inf, hx = -inf, hy = -inf, hz = -inf;
        const long n = (long)s.spherePos.size();
#pragma omp parallel for reduction(min : lx, ly, lz) reduction(max : hx, hy, hz) if (n > 4096)
        for (long i = 0; i < n; i++) {
            const float3 p = s.spherePos[i];
            const float r = s.sphereRadius[i];
            if (!std::isfinite(p.x + p.y + p.z)) continue;
            lx = std::min(lx, p.x - r), ly = std::min(ly, p.y - r), lz = std::min(lz, p.z - r);
            hx = std::max(hx, p.x + r), hy = std::max(hy, p.y + r), hz = std::max(hz, p.z + r);
        }
        if (n) grow(make_float3(lx, ly, lz), 0.f), grow(make_float3(hx, hy, hz), 0.f);
        for (const float3& p : s.triVert) grow(p, 0.f);
        if (!(hi.x >= lo.x)) lo = make_float3(-1.f, -1.f, -1.f), hi = make_float3(1.f, 1.f, 1.f);  // nothing to draw
    }
    v.bmin = lo, v.bmax = hi;
    v.centre = (lo + hi) * 0.5f;
    float umin = 1e30f, umax = -1e30f, vmin = 1e30f, vmax = -1e30f;
    for (int k = 0; k < 8; k++) {
        const float3 c = make_float3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        const float3 q = v.local(c);
        umin = std::min(umin, q.x), umax = std::max(umax, q.x), vmin = std::min(vmin, q.y), vmax = std::max(vmax, q.y);
    }
    const float margin = v.clip ? 1.f : 1.04f;  // a fitted scene keeps a little air around it
    const float du = std::max((umax - umin) * margin, 1e-30f), dv = std::max((vmax - vmin) * margin, 1e-30f);
    v.scale = std::min((float)v.sceneWidth / du, (float)v.height / dv);
    v.uc = 0.5f * (umin + umax), v.vc = 0.5f * (vmin + vmax);
    return v;
}

// Lit from the upper left, in front; camera space: x right, y up, z towards the viewer.
const float3 LIGHT = make_float3(-0.42f, 0.56f, 0.71f);
const float3 HALF = make_float3(-0.42f * 0.54f, 0.56f * 0.54f, (0.71f + 1.f) * 0.54f);

Rgb shade(const Rgb& base, const float3& n, float ambient) {
    const float diffuse = std::max(0.f, dot(n, LIGHT));
    const float h = std::max(0.f, dot(n, HALF));
    const float h2 = h * h, h4 = h2 * h2, h8 = h4 * h4, spec = 0.3f * h8 * h8 * h8;  // h^24
    Rgb c;
    for (int k = 0; k < 3; k++)
        c[k] = (uint8_t)std::min(255.f, (float)base[k] * (ambient + (1.f - ambient) * diffuse) + 255.f * spec);
    return c;
}

struct Disc {
    float x, y, R, depth, r;  // pixel centre and radius, depth of the centre, world radius
    Rgb color;
};

struct Target {
    RgbImage& img;
    std::vector<float>& z;
    void plot(int x, int y, float depth, const Rgb& c) {
        const size_t i = (size_t)y * img.width + x;
        if (depth >= z[i]) return;
        z[i] = depth;
        std::copy(c.begin(), c.end(), &img.rgb[3 * i]);
    }
};

void drawDisc(Target& t, const Disc& d, int y0, int y1) {
    const int W = t.img.width;
    if (d.R < 0.7f) {  // smaller than a pixel: one pixel, so that no sphere vanishes
        const int x = (int)std::floor(d.x), y = (int)std::floor(d.y);
        if (x >= 0 && x < W && y >= y0 && y < y1) t.plot(x, y, d.depth - d.r, shade(d.color, make_float3(0, 0, 1), 0.3f));
        return;
    }
    const int ys = std::max(y0, (int)std::ceil(d.y - d.R - 0.5f)), ye = std::min(y1 - 1, (int)std::floor(d.y + d.R - 0.5f));
    const float inv = 1.f / d.R;
    for (int y = ys; y <= ye; y++) {
        const float dy = (float)y + 0.5f - d.y;
        const float half = std::sqrt(std::max(0.f, d.R * d.R - dy * dy));
        const int xs = std::max(0, (int)std::ceil(d.x - half - 0.5f)), xe = std::min(W - 1, (int)std::floor(d.x + half - 0.5f));
        const size_t row = (size_t)y * W;
        for (int x = xs; x <= xe; x++) {
            if (d.depth - d.r >= t.z[row + x]) continue;  // behind what is there wherever it is hit
            const float nx = ((float)x + 0.5f - d.x) * inv, ny = -dy * inv;
            const float nz = std::sqrt(std::max(0.f, 1.f - nx * nx - ny * ny));
            const float depth = d.depth - d.r * nz;
            if (depth < t.z[row + x]) t.plot(x, y, depth, shade(d.color, make_float3(nx, ny, nz), 0.3f));
        }
    }
}

void drawTriangle(Target& t, const View& v, const float3* w, const Rgb& base, int y0, int y1) {
    float3 p[3];
    for (int k = 0; k < 3; k++) {
        const float3 q = v.local(w[k]);
        p[k] = make_float3(v.px(q.x), v.py(q.y), q.z);
    }
    const float area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
    if (!(std::fabs(area) > 1e-12f)) return;
    float3 n = cross(w[1] - w[0], w[2] - w[0]);
    n = normalized(make_float3(dot(n, v.right), dot(n, v.up), -dot(n, v.dir)));
    if (n.z < 0.f) n = -n;  // both sides lit alike
    const Rgb c = shade(base, n, 0.35f);
    const int xs = std::max(0, (int)std::floor(std::min({p[0].x, p[1].x, p[2].x})));
    const int xe = std::min(t.img.width - 1, (int)std::ceil(std::max({p[0].x, p[1].x, p[2].x})));
    const int ys = std::max(y0, (int)std::floor(std::min({p[0].y, p[1].y, p[2].y})));
    const int ye = std::min(y1 - 1, (int)std::ceil(std::max({p[0].y, p[1].y, p[2].y})));
    const float inv = 1.f / area;
    for (int y = ys; y <= ye; y++)
        for (int x = xs; x <= xe; x++) {
            const float cx = (float)x + 0.5f, cy = (float)y + 0.5f;
            // Barycentric weights from the edge functions, positive inside whichever way round.
            const float b0 = ((p[1].x - cx) * (p[2].y - cy) - (p[1].y - cy) * (p[2].x - cx)) * inv;
            const float b1 = ((p[2].x - cx) * (p[0].y - cy) - (p[2].y - cy) * (p[0].x - cx)) * inv;
            const float b2 = 1.f - b0 - b1;
            // A little slack, so that rounding never opens a crack along an edge two triangles share.
            const float slack = -1e-4f;
            if (b0 < slack || b1 < slack || b2 < slack) continue;
            const float depth = b0 * p[0].z + b1 * p[1].z + b2 * p[2].z;
            if (v.clip && !v.inside(v.world(cx, cy, depth))) continue;
            t.plot(x, y, depth, c);
        }
}

}  // namespace

void validateSnapshotOptions(const SnapshotOptions& o, const std::string& call) {
    if (o.width < 16 || o.height < 16 || o.width > 16384 || o.height > 16384)
        throwError(call, "image size " + std::to_string(o.width) + " x " + std::to_string(o.height) +
                             " is outside 16..16384 pixels per side");
    if (!(length(o.direction) > 0.f) || !std::isfinite(length(o.direction)))
        throwError(call, "the view direction must be a non-zero finite vector");
    if (!std::isfinite(length(o.up))) throwError(call, "the up vector must be finite");
    const bool anyBox = o.boxMin.x != 0.f || o.boxMin.y != 0.f || o.boxMin.z != 0.f || o.boxMax.x != 0.f ||
                        o.boxMax.y != 0.f || o.boxMax.z != 0.f;
    if (anyBox && !hasBox(o))
        throwError(call, "the zoom box needs boxMax above boxMin on every axis (or both left at 0 to fit everything)");
    if (o.colorMin > o.colorMax) throwError(call, "colorMin is above colorMax");
}

RgbImage renderSnapshot(const SnapshotScene& s, const SnapshotOptions& o) {
    const View v = makeView(s, o);
    RgbImage img;
    img.width = o.width, img.height = o.height;
    img.rgb.resize(3 * (size_t)o.width * o.height);
    for (size_t i = 0; i < img.rgb.size(); i += 3) std::copy(o.background.begin(), o.background.end(), &img.rgb[i]);
    std::vector<float> z((size_t)o.width * o.height, std::numeric_limits<float>::infinity());

    // The colour range over the spheres drawn, unless given.
    const long n = (long)s.spherePos.size();
    std::vector<uint8_t> drawn(n);
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
#pragma omp parallel for reduction(min : lo) reduction(max : hi) if (n > 4096)
    for (long i = 0; i < n; i++) {
        const float3 p = s.spherePos[i];
        drawn[i] = std::isfinite(p.x + p.y + p.z) && (!v.clip || v.inside(p));
        if (drawn[i] && !s.value.empty() && std::isfinite(s.value[i])) lo = std::min(lo, s.value[i]), hi = std::max(hi, s.value[i]);
    }
    if (!std::isnan(o.colorMin)) lo = o.colorMin;
    if (!std::isnan(o.colorMax)) hi = o.colorMax;
    if (!(hi >= lo)) lo = hi = 0.f;

    std::vector<Disc> discs(n);
#pragma omp parallel for if (n > 4096)
    for (long i = 0; i < n; i++) {
        Disc& d = discs[i];
        if (!drawn[i]) {
            d.R = -1.f;
            continue;
        }
        const float3 q = v.local(s.spherePos[i]);
        d.x = v.px(q.x), d.y = v.py(q.y), d.depth = q.z, d.r = s.sphereRadius[i], d.R = d.r * v.scale;
        d.color = s.value.empty() ? o.grainColor
                  : s.categorical ? familyColor((int)s.value[i])
                                  : colorMap(hi > lo ? (s.value[i] - lo) / (hi - lo) : 0.5f);
    }

    // The discs nearest first (sorted by depth into 1024 buckets, O(n)), so that a hidden sphere's
    // pixels fail the depth test before any shading; each band then picks those that reach into it.
    const int bands = 16, nb = 1024;
    float dmin = std::numeric_limits<float>::infinity(), dmax = -dmin;
#pragma omp parallel for reduction(min : dmin) reduction(max : dmax) if (n > 4096)
    for (long i = 0; i < n; i++)
        if (discs[i].R >= 0.f) dmin = std::min(dmin, discs[i].depth), dmax = std::max(dmax, discs[i].depth);
    const float k = dmax > dmin ? (float)(nb - 1) / (dmax - dmin) : 0.f;
    std::vector<uint16_t> key(n);
#pragma omp parallel for if (n > 4096)
    for (long i = 0; i < n; i++)
        key[i] = discs[i].R >= 0.f ? (uint16_t)std::min(nb - 1, std::max(0, (int)((discs[i].depth - dmin) * k))) : (uint16_t)nb;
    std::vector<uint32_t> start(nb + 2, 0);
    for (long i = 0; i < n; i++) start[key[i] + 1]++;
    for (int b = 0; b <= nb; b++) start[b + 1] += start[b];
    std::vector<Disc> sorted(start[nb]);  // the culled ones (key nb) are left out
    std::vector<float> rows(2 * sorted.size());  // each disc's top and bottom row, scanned by every band
    for (long i = 0; i < n; i++)
        if (key[i] < nb) {
            const Disc& d = discs[i];
            const uint32_t at = start[key[i]]++;
            sorted[at] = d;
            rows[2 * at] = d.y - d.R - 1.f, rows[2 * at + 1] = d.y + d.R + 1.f;
        }
    const long nTri = (long)(s.triVert.size() / 3);
#pragma omp parallel for schedule(dynamic, 1)
    for (int b = 0; b < bands; b++) {
        const int y0 = o.height * b / bands, y1 = o.height * (b + 1) / bands;
        Target t{img, z};
        for (long k = 0; k < nTri; k++) drawTriangle(t, v, &s.triVert[3 * k], o.meshColor, y0, y1);
        for (size_t i = 0; i < sorted.size(); i++)
            if (rows[2 * i + 1] >= (float)y0 && rows[2 * i] < (float)y1) drawDisc(t, sorted[i], y0, y1);
    }

    if (o.colorBar && o.colorBy != "none") {
        // The overlay's strip is cleared, so that a zoomed scene never runs under the labels.
        for (int y = 0; y < img.height; y++)
            for (int x = v.sceneWidth; x < img.width; x++)
                std::copy(o.background.begin(), o.background.end(), &img.rgb[3 * ((size_t)y * img.width + x)]);
        if (s.categorical) {
            bool present[256] = {};
            for (long i = 0; i < n; i++)
                if (drawn[i]) present[(int)s.value[i] & 255] = true;
            std::vector<int> families;
            for (int f = 0; f < 256; f++)
                if (present[f]) families.push_back(f);
            drawFamilyLegend(img, families, o.background);
        } else {
            drawColorBar(img, lo, hi, s.label, o.background);
        }
    }
    return img;
}

}  // namespace deme
