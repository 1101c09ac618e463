// One frame of output staged for the writer thread: a table of typed columns copied out of the
// simulation's state, so that the file can be written while the simulation moves on. The CSV
// writer prints the columns in order; the VTU writer makes the points column the grid's points and
// every other column a point-data array (meshes: triangle cells with cell-data columns).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace deme {

enum class ValueType : uint8_t { FLOAT64, FLOAT32, INT32, UINT8 };

inline size_t valueBytes(ValueType t) {
    return t == ValueType::FLOAT64 ? 8 : t == ValueType::UINT8 ? 1 : 4;
}

struct FrameColumn {
    std::string name;                   // the VTU array's name
    std::vector<std::string> csvNames;  // one CSV column per component
    ValueType type = ValueType::FLOAT32;
    int components = 1;
    size_t rows = 0;
    // UINT8 codes written as text in CSV (the contact type: "SS", "SA", "SM").
    std::vector<std::string> labels;
    // rows x components values, row-major; uninitialised storage (staging fills every value).
    std::unique_ptr<unsigned char[]> data;

    size_t bytes() const { return rows * (size_t)components * valueBytes(type); }
    template <class T>
    T* values() {
        return reinterpret_cast<T*>(data.get());
    }
    template <class T>
    const T* values() const {
        return reinterpret_cast<const T*>(data.get());
    }
};

struct OutputFrame {
    std::string call;   // the API call that staged it, for messages
    double time = 0.0;  // simulated time of the frame
    size_t rows = 0;    // points: spheres, clumps, contact points, or 3 corners per triangle
    std::deque<FrameColumn> columns;  // in CSV order (a deque: addColumn keeps earlier references valid)
    int pointsColumn = -1;             // a 3-component FLOAT64 column: the VTU grid's points
    // Meshes: consecutive point triples are triangles, with one value per triangle in cellColumns.
    // Otherwise each point is a vertex cell.
    bool triangleCells = false;
    std::deque<FrameColumn> cellColumns;

    size_t cells() const { return triangleCells ? rows / 3 : rows; }
    // Allocates a column of `rows` rows and returns it for filling.
    FrameColumn& addColumn(const std::string& name, std::vector<std::string> csvNames, ValueType type,
                           size_t nRows, bool cellData = false) {
        std::deque<FrameColumn>& list = cellData ? cellColumns : columns;
        list.emplace_back();
        FrameColumn& c = list.back();
        c.name = name;
        c.components = (int)csvNames.size();
        c.csvNames = std::move(csvNames);
        c.type = type;
        c.rows = nRows;
        c.data.reset(new unsigned char[c.bytes() ? c.bytes() : 1]);
        return c;
    }
};

}  // namespace deme
