#include "io/CsvFrameWriter.h"

#include <algorithm>
#include <charconv>
#include <string>

namespace deme {

namespace {

constexpr size_t FLUSH_BYTES = 1 << 20;

struct Cursor {
    char* p;
    void put(double v) { p = std::to_chars(p, p + 32, v, std::chars_format::general, 9).ptr; }
    void put(long v) { p = std::to_chars(p, p + 24, v).ptr; }
};

}  // namespace

void writeFrameCsv(const OutputFrame& frame, AtomicFile& out) {
    std::string header;
    for (const FrameColumn& c : frame.columns)
        for (const std::string& name : c.csvNames) header += (header.empty() ? "" : ",") + name;
    header += '\n';
    out.write(header);

    // The widest row: 32 characters per value (to_chars of a double in %.9g needs at most 16), or
    // the longest label.
    size_t rowMax = 2;
    for (const FrameColumn& c : frame.columns) {
        size_t w = 32;
        for (const std::string& l : c.labels) w = std::max(w, l.size() + 1);
        rowMax += w * (size_t)c.components;
    }
    std::string buf(FLUSH_BYTES + rowMax, '\0');
    Cursor cur{&buf[0]};
    for (size_t row = 0; row < frame.rows; row++) {
        bool first = true;
        for (const FrameColumn& c : frame.columns) {
            for (int k = 0; k < c.components; k++) {
                if (!first) *cur.p++ = ',';
                first = false;
                const size_t i = row * (size_t)c.components + (size_t)k;
                switch (c.type) {
                case ValueType::FLOAT64: cur.put(c.values<double>()[i]); break;
                case ValueType::FLOAT32: cur.put((double)c.values<float>()[i]); break;
                case ValueType::INT32: cur.put((long)c.values<int32_t>()[i]); break;
                case ValueType::UINT8: {
                    const uint8_t v = c.values<uint8_t>()[i];
                    if (v < c.labels.size()) {
                        const std::string& l = c.labels[v];
                        cur.p = std::copy(l.begin(), l.end(), cur.p);
                    } else {
                        cur.put((long)v);
                    }
                    break;
                }
                }
            }
        }
        *cur.p++ = '\n';
        if ((size_t)(cur.p - buf.data()) >= FLUSH_BYTES) {
            out.write(buf.data(), (size_t)(cur.p - buf.data()));
            cur.p = &buf[0];
        }
    }
    out.write(buf.data(), (size_t)(cur.p - buf.data()));
}

}  // namespace deme
