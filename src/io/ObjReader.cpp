#include "io/ObjReader.h"

#include <deme/Error.h>

#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace deme {
namespace {

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Parses a float that must span exactly [b, e). from_chars is locale-independent (strtof would read "0,5"
// under a German LC_NUMERIC); libraries without floating-point from_chars fall back to strtof.
bool parseFloat(const char* b, const char* e, float& out) {
    if (b != e && *b == '+') b++;  // from_chars rejects an explicit '+', which some exporters write
    if (b == e) return false;
#if defined(__cpp_lib_to_chars)
    const std::from_chars_result r = std::from_chars(b, e, out);
    return r.ec == std::errc() && r.ptr == e && std::isfinite(out);  // out-of-range also lands here
#else
    std::string tok(b, e);  // strtof needs a terminated token
    char* end = nullptr;
    out = std::strtof(tok.c_str(), &end);
    return end == tok.c_str() + tok.size() && std::isfinite(out);
#endif
}

// Splits an OBJ file already held in memory into lines and whitespace-separated tokens without copying.
struct Line {
    const char* p;    // cursor
    const char* end;  // end of the line, '#' comment and '\r' excluded
    // Returns the next token as [b, e), or false at the end of the line.
    bool next(const char*& b, const char*& e) {
        while (p < end && isSpace(*p)) p++;
        if (p == end) return false;
        b = p;
        while (p < end && !isSpace(*p)) p++;
        e = p;
        return true;
    }
};

enum class FaceToken { Ok, Malformed, Huge };

// Parses one face vertex `i`, `i/t`, `i//n` or `i/t/n` spanning exactly [b, e) into its vertex index i;
// t and n are checked for form only, since a DEM mesh uses neither texture coordinates nor normals.
FaceToken parseFaceToken(const char* b, const char* e, long long& idx) {
    auto r = std::from_chars(b, e, idx);
    if (r.ptr == b) return FaceToken::Malformed;
    if (r.ec == std::errc::result_out_of_range) return FaceToken::Huge;
    const char* q = r.ptr;
    if (q == e) return FaceToken::Ok;                           // i
    if (*q++ != '/' || q == e) return FaceToken::Malformed;     // "i/" alone is not a form
    long long dummy;
    if (*q != '/') {                                            // i/t...
        const char* tb = q;
        q = std::from_chars(q, e, dummy).ptr;
        if (q == tb) return FaceToken::Malformed;
        if (q == e) return FaceToken::Ok;                       // i/t
        if (*q != '/') return FaceToken::Malformed;
    }
    const char* nb = ++q;                                       // past the second '/': n is required
    q = std::from_chars(q, e, dummy).ptr;
    return (q != nb && q == e) ? FaceToken::Ok : FaceToken::Malformed;  // i//n, i/t/n
}

// A face whose largest positive index exceeded the vertex count at its line: OBJ does not forbid vertices
// after the faces using them, so it can only be judged once the whole file has been read.
struct ForwardRef {
    size_t line;
    long long index;  // 1-based
};

}  // namespace

ObjMesh readObj(const std::string& path, const std::string& call) {
    // Slurping the file once and scanning it with pointers is several times faster than getline + streams.
    std::string buf;
    {
        std::FILE* f = std::fopen(path.c_str(), "rb");
        if (!f) throwFileError(call, path, 0, std::string("cannot open file: ") + std::strerror(errno));
        char chunk[1 << 16];
        size_t n;
        while ((n = std::fread(chunk, 1, sizeof chunk, f)) > 0) buf.append(chunk, n);
        const bool failed = std::ferror(f) != 0;  // e.g. the path is a directory
        std::fclose(f);
        if (failed) throwFileError(call, path, 0, "cannot read file");
    }

    ObjMesh mesh;
    std::vector<ForwardRef> forward;
    std::vector<int> poly;  // resolved 0-based indices of the current face, reused across lines
    size_t lineNo = 0;
    const char* p = buf.data();
    const char* const bufEnd = p + buf.size();
    if (buf.compare(0, 3, "\xEF\xBB\xBF") == 0) p += 3;  // UTF-8 BOM

    while (p < bufEnd) {
        lineNo++;
        const char* nl = static_cast<const char*>(std::memchr(p, '\n', bufEnd - p));
        const char* lineEnd = nl ? nl : bufEnd;
        const char* hash = static_cast<const char*>(std::memchr(p, '#', lineEnd - p));
        Line line{p, hash ? hash : lineEnd};
        p = nl ? nl + 1 : bufEnd;

        const char *kb, *ke;
        if (!line.next(kb, ke)) continue;  // blank or comment-only line
        const size_t klen = ke - kb;

        if (klen == 1 && *kb == 'v') {
            float c[3];
            int n = 0;
            const char *b, *e;
            while (line.next(b, e)) {
                float x;
                if (!parseFloat(b, e, x))
                    throwFileError(call, path, lineNo,
                                   "vertex coordinate '" + std::string(b, e) + "' is not a finite number");
                if (n < 3) c[n] = x;
                n++;
            }
            if (n < 3)
                throwFileError(call, path, lineNo,
                               "vertex has " + std::to_string(n) + " coordinates, expected at least 3 (x y z)");
            mesh.vertices.push_back(make_float3(c[0], c[1], c[2]));
        } else if (klen == 1 && *kb == 'f') {
            poly.clear();
            long long maxForward = 0;
            const long long nv = (long long)mesh.vertices.size();
            const char *b, *e;
            while (line.next(b, e)) {
                long long idx = 0;
                const FaceToken t = parseFaceToken(b, e, idx);
                if (t == FaceToken::Malformed)
                    throwFileError(call, path, lineNo, "malformed face vertex '" + std::string(b, e) + "'");
                if (t == FaceToken::Huge)
                    throwFileError(call, path, lineNo, "face vertex index " + std::string(b, e) + " is out of range");
                if (idx == 0) throwFileError(call, path, lineNo, "face vertex index 0 (OBJ indices start at 1)");
                if (idx < 0) {
                    // Relative indices count back from the vertices read so far, so they resolve right here.
                    if (-idx > nv)
                        throwFileError(call, path, lineNo,
                                       "face vertex index " + std::to_string(idx) + " reaches before the first of " +
                                           std::to_string(nv) + " vertices read so far");
                    idx = nv + idx;
                } else {
                    if (idx > nv && idx > maxForward) maxForward = idx;
                    idx -= 1;
                }
                // Beyond INT_MAX it cannot be valid; it is already in maxForward, so the range check reports it.
                poly.push_back(idx > INT_MAX ? INT_MAX : (int)idx);
            }
            if (poly.size() < 3)
                throwFileError(call, path, lineNo,
                               "face has " + std::to_string(poly.size()) + " vertices, expected at least 3");
            if (maxForward > 0) forward.push_back({lineNo, maxForward});
            for (size_t k = 1; k + 1 < poly.size(); k++) mesh.faces.push_back(make_int3(poly[0], poly[k], poly[k + 1]));
        }
        // Any other statement (vt, vn, vp, o, g, s, usemtl, mtllib, l, p, ...) carries nothing a DEM mesh needs.
    }

    if (mesh.vertices.size() > (size_t)INT_MAX)
        throwFileError(call, path, lineNo, "more vertices than a mesh can index");
    for (const ForwardRef& fr : forward)
        if (fr.index > (long long)mesh.vertices.size())
            throwFileError(call, path, fr.line,
                           "face vertex index " + std::to_string(fr.index) + " is out of range (file has " +
                               std::to_string(mesh.vertices.size()) + " vertices)");
    if (mesh.faces.empty()) throwFileError(call, path, lineNo, "file has no faces");
    return mesh;
}

}  // namespace deme
