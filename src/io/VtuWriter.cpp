#include "io/VtuWriter.h"

#include <algorithm>
#include <charconv>
#include <cstring>
#include <functional>
#include <limits>

#include "io/DataEncoding.h"

namespace deme {

namespace {

constexpr size_t CHUNK_BYTES = 1 << 20;  // a multiple of every value size
constexpr uint8_t VTK_VERTEX = 1, VTK_TRIANGLE = 5;

// One DataArray: contiguous bytes, or a generator of byte ranges for the implicit cell arrays.
struct VtuArray {
    std::string name;
    const char* type;
    int components = 1;
    std::vector<std::string> componentNames;
    size_t bytes = 0;
    const uint8_t* data = nullptr;
    std::function<void(size_t first, size_t bytes, uint8_t* out)> generate;

    void fill(size_t first, size_t n, uint8_t* out) const {
        if (data)
            std::memcpy(out, data + first, n);
        else
            generate(first, n, out);
    }
    // Hands the data to `put` in pieces: the array itself, or generated chunks.
    void stream(const std::function<void(const void*, size_t)>& put) const {
        if (data) {
            put(data, bytes);
            return;
        }
        std::vector<uint8_t> buf(std::min(bytes, CHUNK_BYTES));
        for (size_t at = 0; at < bytes; at += CHUNK_BYTES) {
            const size_t n = std::min(CHUNK_BYTES, bytes - at);
            generate(at, n, buf.data());
            put(buf.data(), n);
        }
    }
};

const char* vtkType(ValueType t) {
    switch (t) {
    case ValueType::FLOAT64: return "Float64";
    case ValueType::FLOAT32: return "Float32";
    case ValueType::INT32: return "Int32";
    case ValueType::UINT8: return "UInt8";
    }
    return "";
}

VtuArray columnArray(const FrameColumn& c, bool points) {
    VtuArray a;
    a.name = points ? "Points" : c.name;
    a.type = vtkType(c.type);
    a.components = c.components;
    a.bytes = c.bytes();
    a.data = c.data.get();
    // "v_x" -> "x", "Qw" -> "w": ParaView shows these as the component names.
    if (!points && c.components > 1)
        for (const std::string& n : c.csvNames) {
            std::string s = n.compare(0, c.name.size(), c.name) == 0 ? n.substr(c.name.size()) : n;
            if (!s.empty() && s[0] == '_') s.erase(0, 1);
            a.componentNames.push_back(s);
        }
    return a;
}

// Values i * step + start for i in a byte range, as T (connectivity and offsets are implicit:
// every cell's points are consecutive).
template <class T>
VtuArray sequence(const char* name, const char* type, size_t count, T start, T step) {
    VtuArray a;
    a.name = name;
    a.type = type;
    a.bytes = count * sizeof(T);
    a.generate = [start, step](size_t first, size_t n, uint8_t* out) {
        T* v = reinterpret_cast<T*>(out);
        const size_t i0 = first / sizeof(T);
        for (size_t i = 0; i < n / sizeof(T); i++) v[i] = (T)(start + step * (T)(i0 + i));
    };
    return a;
}

VtuArray cellTypes(size_t count, uint8_t type) {
    VtuArray a;
    a.name = "types";
    a.type = "UInt8";
    a.bytes = count;
    a.generate = [type](size_t, size_t n, uint8_t* out) { std::memset(out, type, n); };
    return a;
}

std::string num(double v) {
    char b[32];
    return std::string(b, std::to_chars(b, b + sizeof b, v).ptr);
}

bool littleEndian() {
    const uint16_t one = 1;
    uint8_t first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

}  // namespace

void writeFrameVtu(const OutputFrame& f, const VtuOptions& o, AtomicFile& out) {
    const size_t nCells = f.cells();
    // Arrays in document order: point data, cell data, points, cells.
    std::vector<VtuArray> arrays;
    std::vector<size_t> pointData, cellData;
    for (size_t i = 0; i < f.columns.size(); i++)
        if ((int)i != f.pointsColumn) {
            pointData.push_back(arrays.size());
            arrays.push_back(columnArray(f.columns[i], false));
        }
    for (const FrameColumn& c : f.cellColumns) {
        cellData.push_back(arrays.size());
        arrays.push_back(columnArray(c, false));
    }
    const size_t pointsArray = arrays.size();
    arrays.push_back(columnArray(f.columns.at(f.pointsColumn), true));
    const size_t cellsFirst = arrays.size();
    const int perCell = f.triangleCells ? 3 : 1;
    // 32-bit indices halve the cell arrays; 64-bit only where the point count needs them.
    if (f.rows < (size_t)std::numeric_limits<int32_t>::max()) {
        arrays.push_back(sequence<int32_t>("connectivity", "Int32", f.rows, 0, 1));
        arrays.push_back(sequence<int32_t>("offsets", "Int32", nCells, perCell, perCell));
    } else {
        arrays.push_back(sequence<int64_t>("connectivity", "Int64", f.rows, 0, 1));
        arrays.push_back(sequence<int64_t>("offsets", "Int64", nCells, perCell, perCell));
    }
    arrays.push_back(cellTypes(nCells, f.triangleCells ? VTK_TRIANGLE : VTK_VERTEX));

    std::vector<CompressedBlocks> packed;
    if (o.zlib)
        for (const VtuArray& a : arrays)
            packed.push_back(compressBlocks(a.bytes, [&a](size_t first, size_t n, uint8_t* dst) { a.fill(first, n, dst); },
                                            o.zlibLevel));
    // Bytes of each array in the appended section: its header, then its (compressed) data.
    std::vector<size_t> offsets(arrays.size() + 1, 0);
    for (size_t i = 0; i < arrays.size(); i++)
        offsets[i + 1] = offsets[i] + (o.zlib ? 8 * packed[i].header().size() + packed[i].compressedBytes()
                                              : 8 + arrays[i].bytes);

    auto base64Body = [&](size_t i) {
        Base64Stream b64([&out](const char* s, size_t n) { out.write(s, n); });
        if (o.zlib) {
            // VTK's layout: the header as one base64 text, the blocks as another.
            const std::vector<uint64_t> h = packed[i].header();
            b64.put(h.data(), 8 * h.size());
            b64.finish();
            for (const auto& blk : packed[i].blocks) b64.put(blk.data(), blk.size());
        } else {
            const uint64_t n = arrays[i].bytes;
            b64.put(&n, 8);
            arrays[i].stream([&b64](const void* d, size_t n) { b64.put(d, n); });
        }
        b64.finish();
    };
    auto dataArray = [&](size_t i, const std::string& indent) {
        const VtuArray& a = arrays[i];
        std::string s = indent + "<DataArray type=\"" + a.type + "\" Name=\"" + a.name + "\"";
        if (a.components > 1) s += " NumberOfComponents=\"" + std::to_string(a.components) + "\"";
        for (size_t k = 0; k < a.componentNames.size(); k++)
            s += " ComponentName" + std::to_string(k) + "=\"" + a.componentNames[k] + "\"";
        if (o.base64) {
            out.write(s + " format=\"binary\">\n" + indent + "  ");
            base64Body(i);
            out.write("\n" + indent + "</DataArray>\n");
        } else {
            out.write(s + " format=\"appended\" offset=\"" + std::to_string(offsets[i]) + "\"/>\n");
        }
    };

    std::string head = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"";
    head += littleEndian() ? "LittleEndian" : "BigEndian";
    head += "\" header_type=\"UInt64\"";
    if (o.zlib) head += " compressor=\"vtkZLibDataCompressor\"";
    head += ">\n  <UnstructuredGrid>\n    <FieldData>\n"
            "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">" +
            num(f.time) + "</DataArray>\n    </FieldData>\n    <Piece NumberOfPoints=\"" + std::to_string(f.rows) +
            "\" NumberOfCells=\"" + std::to_string(nCells) + "\">\n      <PointData>\n";
    out.write(head);
    for (size_t i : pointData) dataArray(i, "        ");
    out.write("      </PointData>\n      <CellData>\n");
    for (size_t i : cellData) dataArray(i, "        ");
    out.write("      </CellData>\n      <Points>\n");
    dataArray(pointsArray, "        ");
    out.write("      </Points>\n      <Cells>\n");
    for (size_t i = cellsFirst; i < arrays.size(); i++) dataArray(i, "        ");
    out.write("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n");
    if (!o.base64) {
        // Raw bytes follow the underscore; readers take each array's offset from there.
        out.write("  <AppendedData encoding=\"raw\">\n   _");
        for (size_t i = 0; i < arrays.size(); i++) {
            if (o.zlib) {
                const std::vector<uint64_t> h = packed[i].header();
                out.write(h.data(), 8 * h.size());
                for (const auto& blk : packed[i].blocks) out.write(blk.data(), blk.size());
            } else {
                const uint64_t n = arrays[i].bytes;
                out.write(&n, 8);
                arrays[i].stream([&out](const void* d, size_t n) { out.write(d, n); });
            }
        }
        out.write("\n  </AppendedData>\n");
    }
    out.write("</VTKFile>\n");
}

}  // namespace deme
