// How the engine's small vector types and their arrays cross into Python. Included by every
// binding source before any binding, so that each translation unit sees the same conversions.
//
//   deme::float3            in: list, tuple or 1-D numpy array of 3 numbers; out: numpy float32 (3,)
//   deme::float4            the same with 4 numbers, in the C++ member order (x, y, z, w): for a
//                           quaternion w is the scalar part, so the identity is [0, 0, 0, 1]
//   std::vector<float3>     in: (N, 3) array or nested lists; out: numpy float32 (N, 3), C order
//   std::vector<float4>     (N, 4), columns x, y, z, w
//   std::vector<float>      in: 1-D sequence or array; out: numpy float32 (N,)
//   std::vector<deme::int3> in: (N, 3) array of integers; out: numpy int32 (N, 3)
// A value that does not fit (wrong length or shape, strings, None, non-integers for indices) is
// refused, and pybind11 raises TypeError naming the call and the signatures it accepts.
// The names in signatures are the type aliases the package defines (deme.Float3, ...).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <limits>
#include <vector>

#include <deme/Mesh.h>
#include <deme/VectorTypes.h>

static_assert(sizeof(deme::float3) == 3 * sizeof(float), "float3 arrays are copied as packed floats");
static_assert(sizeof(deme::float4) == 4 * sizeof(float), "float4 arrays are copied as packed floats");
static_assert(sizeof(deme::int3) == 3 * sizeof(int), "int3 arrays are copied as packed ints");

namespace deme_py {

namespace py = pybind11;

// Strings are sequences too, but never vectors.
inline bool isTextOrNone(py::handle src) {
    return src.is_none() || PyUnicode_Check(src.ptr()) || PyBytes_Check(src.ptr());
}

// n numbers from a list or tuple (the common case, without numpy) or anything numpy turns into a
// 1-D array of n numbers.
inline bool loadNumbers(py::handle src, float* out, size_t n) {
    if (isTextOrNone(src)) return false;
    if (PyList_Check(src.ptr()) || PyTuple_Check(src.ptr())) {
        if ((size_t)PySequence_Fast_GET_SIZE(src.ptr()) != n) return false;
        PyObject** items = PySequence_Fast_ITEMS(src.ptr());
        for (size_t i = 0; i < n; i++) {
            if (!PyNumber_Check(items[i]) || PyUnicode_Check(items[i])) return false;
            const double v = PyFloat_AsDouble(items[i]);
            if (v == -1.0 && PyErr_Occurred()) {
                PyErr_Clear();
                return false;
            }
            out[i] = (float)v;
        }
        return true;
    }
    auto arr = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(src);
    if (!arr) {
        PyErr_Clear();
        return false;
    }
    if (arr.ndim() != 1 || (size_t)arr.shape(0) != n) return false;
    std::memcpy(out, arr.data(), n * sizeof(float));
    return true;
}

// An (N, cols) float32 C-order array from an array or nested lists; N = 0 also from an empty list.
// (A default-constructed array_t is an empty array, not a null handle: hence the flag.)
inline bool loadRows(py::handle src, size_t cols, py::array_t<float>& out) {
    if (isTextOrNone(src)) return false;
    auto arr = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(src);
    if (!arr) {
        PyErr_Clear();
        return false;
    }
    if (arr.size() == 0 && arr.ndim() <= 2) {
        out = py::array_t<float>(std::vector<py::ssize_t>{0, (py::ssize_t)cols});
        return true;
    }
    if (arr.ndim() != 2 || (size_t)arr.shape(1) != cols) return false;
    out = arr;
    return true;
}

template <class T, size_t Cols>
py::array_t<float> rowsToArray(const std::vector<T>& v) {
    py::array_t<float> out(std::vector<py::ssize_t>{(py::ssize_t)v.size(), (py::ssize_t)Cols});
    if (!v.empty()) std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(T));
    return out;
}

template <class T, size_t N>
py::array_t<float> smallToArray(const T& v) {
    py::array_t<float> out((py::ssize_t)N);
    std::memcpy(out.mutable_data(), &v, sizeof(T));
    return out;
}

}  // namespace deme_py

namespace pybind11 {
namespace detail {

template <>
struct type_caster<deme::float3> {
    PYBIND11_TYPE_CASTER(deme::float3, const_name("Float3"));
    bool load(handle src, bool) { return deme_py::loadNumbers(src, &value.x, 3); }
    static handle cast(const deme::float3& v, return_value_policy, handle) {
        return deme_py::smallToArray<deme::float3, 3>(v).release();
    }
};

template <>
struct type_caster<deme::float4> {
    PYBIND11_TYPE_CASTER(deme::float4, const_name("Quaternion"));
    bool load(handle src, bool) { return deme_py::loadNumbers(src, &value.x, 4); }
    static handle cast(const deme::float4& v, return_value_policy, handle) {
        return deme_py::smallToArray<deme::float4, 4>(v).release();
    }
};

template <>
struct type_caster<std::vector<deme::float3>> {
    PYBIND11_TYPE_CASTER(std::vector<deme::float3>, const_name("Float3Array"));
    bool load(handle src, bool) {
        array_t<float> arr;
        if (!deme_py::loadRows(src, 3, arr)) return false;
        value.resize((size_t)arr.shape(0));
        if (!value.empty()) std::memcpy(value.data(), arr.data(), value.size() * sizeof(deme::float3));
        return true;
    }
    static handle cast(const std::vector<deme::float3>& v, return_value_policy, handle) {
        return deme_py::rowsToArray<deme::float3, 3>(v).release();
    }
};

template <>
struct type_caster<std::vector<deme::float4>> {
    PYBIND11_TYPE_CASTER(std::vector<deme::float4>, const_name("QuaternionArray"));
    bool load(handle src, bool) {
        array_t<float> arr;
        if (!deme_py::loadRows(src, 4, arr)) return false;
        value.resize((size_t)arr.shape(0));
        if (!value.empty()) std::memcpy(value.data(), arr.data(), value.size() * sizeof(deme::float4));
        return true;
    }
    static handle cast(const std::vector<deme::float4>& v, return_value_policy, handle) {
        return deme_py::rowsToArray<deme::float4, 4>(v).release();
    }
};

template <>
struct type_caster<std::vector<float>> {
    PYBIND11_TYPE_CASTER(std::vector<float>, const_name("FloatArray"));
    bool load(handle src, bool) {
        if (deme_py::isTextOrNone(src)) return false;
        auto arr = array_t<float, array::c_style | array::forcecast>::ensure(src);
        if (!arr) {
            PyErr_Clear();
            return false;
        }
        if (arr.ndim() != 1) return false;
        value.assign(arr.data(), arr.data() + arr.size());
        return true;
    }
    static handle cast(const std::vector<float>& v, return_value_policy, handle) {
        array_t<float> out((ssize_t)v.size());
        if (!v.empty()) std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(float));
        return out.release();
    }
};

// Indices must be integers: a float array is refused rather than truncated, and a value that does
// not fit an int is refused rather than wrapped.
template <>
struct type_caster<std::vector<deme::int3>> {
    PYBIND11_TYPE_CASTER(std::vector<deme::int3>, const_name("Int3Array"));
    bool load(handle src, bool) {
        if (deme_py::isTextOrNone(src)) return false;
        array raw = array::ensure(src);
        if (!raw) {
            PyErr_Clear();
            return false;
        }
        const char kind = raw.dtype().kind();
        if (raw.size() == 0 && raw.ndim() <= 2) {
            value.clear();
            return true;
        }
        if ((kind != 'i' && kind != 'u') || raw.ndim() != 2 || raw.shape(1) != 3) return false;
        auto wide = array_t<long long, array::c_style | array::forcecast>::ensure(raw);
        if (!wide) {
            PyErr_Clear();
            return false;
        }
        const long long* p = wide.data();
        value.resize((size_t)wide.shape(0));
        for (size_t i = 0; i < value.size(); i++) {
            for (int k = 0; k < 3; k++)
                if (p[3 * i + k] < std::numeric_limits<int>::min() || p[3 * i + k] > std::numeric_limits<int>::max())
                    return false;
            value[i] = deme::make_int3((int)p[3 * i], (int)p[3 * i + 1], (int)p[3 * i + 2]);
        }
        return true;
    }
    static handle cast(const std::vector<deme::int3>& v, return_value_policy, handle) {
        array_t<int> out(std::vector<ssize_t>{(ssize_t)v.size(), 3});
        if (!v.empty()) std::memcpy(out.mutable_data(), v.data(), v.size() * sizeof(deme::int3));
        return out.release();
    }
};

}  // namespace detail
}  // namespace pybind11
