// A file written under a temporary name beside its target and renamed onto it only once every byte
// is written and the file closed: a crash, a full disk or an error midway never leaves a
// half-written file under the real name, and the previous file of that name stays as it was.
#pragma once

#include <cstddef>
#include <cstdio>
#include <string>

namespace deme {

class AtomicFile {
  public:
    // Opens "<dir>/.<name>.<pid>.<n>.tmp" for writing; throws deme::Error (call: path: reason).
    AtomicFile(const std::string& path, const std::string& call);
    // Without commit(): the temporary file is removed, the target left untouched.
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* data, size_t bytes);
    void write(const std::string& s) { write(s.data(), s.size()); }
    // Flushes, closes and renames onto the target; throws deme::Error on failure (then the target
    // is unchanged and the temporary file removed).
    void commit();
    size_t bytesWritten() const { return m_bytes; }
    const std::string& path() const { return m_path; }

  private:
    [[noreturn]] void fail(const std::string& what);
    std::string m_path, m_tmp, m_call;
    std::FILE* m_file = nullptr;
    size_t m_bytes = 0;
};

// Fault injection for the tests of failed writes: while set (non-zero), every AtomicFile of the
// process fails with an I/O error once it has written this many bytes; 0 turns it off.
void failAtomicFilesAfterBytes(size_t bytes);

}  // namespace deme
