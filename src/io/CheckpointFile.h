// The container of a checkpoint (docs/checkpoint.md): a fixed header (magic, format version,
// byte-order mark, payload length, CRC-32 of the payload, CRC-32 of the header), then the payload,
// a list of named sections. This file knows bytes, not simulations: io/Checkpoint.h fills and reads
// the sections.
//
// Reading checks, in this order, and throws deme::Error naming the call and the file: not a
// checkpoint (magic), truncated (shorter than its header says), corrupted (a checksum does not
// match), wrong version (a format this build does not read). Nothing is returned before the whole
// file has passed, so a caller that changes its state only afterwards is left as it was.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <type_traits>
#include <vector>

namespace deme {

// Version 1: the first. Version 2: the owners' travel counts from the contact set's snapshot (a
// float per owner in the state section), and the clock holds whether the set can go on serving
// instead of every owner's travel at its snapshot. Raise it when the meaning of a section's bytes
// changes; a field added to the state lists (state/StateFields.h) needs no new version, since
// fields are stored by name. A build reads its own version and the ones before
// (OLDEST_CHECKPOINT_FORMAT_VERSION).
constexpr uint32_t CHECKPOINT_FORMAT_VERSION = 2;
constexpr uint32_t OLDEST_CHECKPOINT_FORMAT_VERSION = 1;

// Appends plain values, strings and arrays to a byte buffer.
class ByteWriter {
  public:
    template <class T>
    void value(const T& v) {
        static_assert(std::is_trivially_copyable<T>::value, "plain values only");
        bytes(&v, sizeof(T));
    }
    void text(const std::string& s) {
        value((uint32_t)s.size());
        bytes(s.data(), s.size());
    }
    template <class T>
    void array(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable<T>::value, "plain values only");
        value((uint32_t)sizeof(T));
        value((uint64_t)v.size());
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
    void bytes(const void* p, size_t n) { m_buf.append(static_cast<const char*>(p), n); }
    std::string& buffer() { return m_buf; }

  private:
    std::string m_buf;
};

// Reads what ByteWriter wrote; any read past the end or an array of another element size throws
// deme::Error(call, "<path> is corrupted: <what>").
class ByteReader {
  public:
    ByteReader(const char* data, size_t size, std::string call, std::string path)
        : m_p(data), m_end(data + size), m_call(std::move(call)), m_path(std::move(path)) {}
    template <class T>
    T value(const char* what) {
        static_assert(std::is_trivially_copyable<T>::value, "plain values only");
        T v;
        std::memcpy(&v, take(sizeof(T), what), sizeof(T));
        return v;
    }
    std::string text(const char* what);
    template <class T>
    void array(std::vector<T>& out, const std::string& what) {
        const uint32_t elem = value<uint32_t>(what.c_str());
        const uint64_t n = value<uint64_t>(what.c_str());
        if (elem != sizeof(T))
            malformed(what + " has elements of " + std::to_string(elem) + " bytes, this build's of " +
                      std::to_string(sizeof(T)));
        if (n > (uint64_t)(m_end - m_p) / sizeof(T)) malformed(what + " runs past the end of its section");
        out.resize((size_t)n);
        if (n) std::memcpy(out.data(), take((size_t)n * sizeof(T), what.c_str()), (size_t)n * sizeof(T));
    }
    const char* take(size_t n, const char* what);
    bool atEnd() const { return m_p == m_end; }
    [[noreturn]] void malformed(const std::string& what) const;

  private:
    const char* m_p;
    const char* m_end;
    std::string m_call, m_path;
};

// A checkpoint's sections by name, as written (each name at most once).
struct CheckpointSections {
    uint32_t version = CHECKPOINT_FORMAT_VERSION;           // the file's format (written as it is)
    std::vector<std::pair<std::string, std::string>> list;  // (name, bytes) in file order
    void add(const std::string& name, std::string bytes) { list.emplace_back(name, std::move(bytes)); }
};

// Writes header and sections to `path` through io/AtomicFile.h (temporary name, then rename).
void writeCheckpointFile(const std::string& path, const CheckpointSections& sections, const std::string& call);

// Reads and checks the whole file (see above); returns its sections.
CheckpointSections readCheckpointFile(const std::string& path, const std::string& call);

}  // namespace deme
