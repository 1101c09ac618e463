#include "io/AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include <deme/Error.h>

namespace deme {

namespace {

std::atomic<size_t> g_failAfter{0};
std::atomic<unsigned long> g_counter{0};

// Beside the target (a rename is atomic only within one file system), hidden, and unique per
// process and file so that two writers never share a temporary name.
std::string temporaryName(const std::string& path) {
    const std::filesystem::path p(path);
    const std::string name = "." + p.filename().string() + "." + std::to_string((long)::getpid()) + "." +
                             std::to_string(g_counter++) + ".tmp";
    return (p.parent_path() / name).string();
}

}  // namespace

void failAtomicFilesAfterBytes(size_t bytes) { g_failAfter = bytes; }

AtomicFile::AtomicFile(const std::string& path, const std::string& call)
    : m_path(path), m_tmp(temporaryName(path)), m_call(call) {
    if (path.empty()) throwError(call, "empty file name");
    m_file = std::fopen(m_tmp.c_str(), "wb");
    if (!m_file) throwError(call, "cannot open \"" + path + "\" for writing: " + std::strerror(errno));
    // Large writes bypass stdio's buffer anyway; a 1 MiB buffer batches the small header pieces.
    std::setvbuf(m_file, nullptr, _IOFBF, 1 << 20);
}

AtomicFile::~AtomicFile() {
    if (m_file) {
        std::fclose(m_file);
        std::remove(m_tmp.c_str());
    }
}

void AtomicFile::fail(const std::string& what) {
    std::fclose(m_file);
    m_file = nullptr;
    std::remove(m_tmp.c_str());
    throwError(m_call, "failed writing \"" + m_path + "\": " + what + " (the previous file of that name, if any, is unchanged)");
}

void AtomicFile::write(const void* data, size_t bytes) {
    if (!m_file) throwError(m_call, "write to \"" + m_path + "\" after it was closed");
    const size_t limit = g_failAfter;
    if (limit && m_bytes + bytes > limit) {
        std::fwrite(data, 1, limit - m_bytes, m_file);  // half a file, as a crash would leave it
        fail("simulated I/O error after " + std::to_string(limit) + " bytes");
    }
    if (bytes && std::fwrite(data, 1, bytes, m_file) != bytes) fail(std::strerror(errno));
    m_bytes += bytes;
}

void AtomicFile::commit() {
    if (!m_file) throwError(m_call, "\"" + m_path + "\" committed twice");
    // A full disk often shows only when the last buffer is flushed or the file closed.
    if (std::fflush(m_file) != 0 || std::ferror(m_file)) fail(std::strerror(errno));
    std::FILE* f = m_file;
    m_file = nullptr;
    if (std::fclose(f) != 0) {
        std::remove(m_tmp.c_str());
        throwError(m_call, "failed writing \"" + m_path + "\": " + std::strerror(errno));
    }
    if (std::rename(m_tmp.c_str(), m_path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(m_tmp.c_str());
        throwError(m_call, "cannot rename the finished file onto \"" + m_path + "\": " + why);
    }
}

}  // namespace deme
