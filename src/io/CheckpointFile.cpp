#include "io/CheckpointFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <zlib.h>

#include <deme/Error.h>

#include "io/AtomicFile.h"

namespace deme {

namespace {

constexpr char MAGIC[8] = {'D', 'E', 'M', 'E', 'C', 'K', 'P', 'T'};
constexpr uint32_t BYTE_ORDER_MARK = 0x01020304u;
constexpr size_t HEADER_BYTES = 32;  // magic 8, version 4, byte order 4, payload length 8, CRCs 4 + 4

// zlib's CRC-32, in pieces that fit its length type.
uint32_t checksum(const char* data, size_t n) {
    uLong crc = crc32(0L, Z_NULL, 0);
    while (n > 0) {
        const uInt piece = (uInt)std::min<size_t>(n, 1u << 30);
        crc = crc32(crc, reinterpret_cast<const Bytef*>(data), piece);
        data += piece;
        n -= piece;
    }
    return (uint32_t)crc;
}

std::string quoted(const std::string& path) { return "\"" + path + "\""; }

}  // namespace

std::string ByteReader::text(const char* what) {
    const uint32_t n = value<uint32_t>(what);
    const char* p = take(n, what);
    return std::string(p, n);
}

const char* ByteReader::take(size_t n, const char* what) {
    if (n > (size_t)(m_end - m_p)) malformed(std::string(what) + " runs past the end of its section");
    const char* p = m_p;
    m_p += n;
    return p;
}

void ByteReader::malformed(const std::string& what) const {
    throwError(m_call, quoted(m_path) + " is corrupted: " + what);
}

void writeCheckpointFile(const std::string& path, const CheckpointSections& sections, const std::string& call) {
    ByteWriter payload;
    for (const auto& [name, bytes] : sections.list) {
        payload.text(name);
        payload.value((uint64_t)bytes.size());
        payload.bytes(bytes.data(), bytes.size());
    }
    const std::string& p = payload.buffer();
    ByteWriter header;
    header.bytes(MAGIC, sizeof(MAGIC));
    header.value(sections.version);
    header.value(BYTE_ORDER_MARK);
    header.value((uint64_t)p.size());
    header.value(checksum(p.data(), p.size()));
    header.value(checksum(header.buffer().data(), header.buffer().size()));
    AtomicFile file(path, call);
    file.write(header.buffer());
    file.write(p);
    file.commit();
}

CheckpointSections readCheckpointFile(const std::string& path, const std::string& call) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throwError(call, "cannot open " + quoted(path) + ": " + std::strerror(errno));
    std::string data;
    char chunk[1 << 16];
    size_t got;
    while ((got = std::fread(chunk, 1, sizeof(chunk), f)) > 0) data.append(chunk, got);
    const bool readError = std::ferror(f) != 0;
    std::fclose(f);
    if (readError) throwError(call, "cannot read " + quoted(path) + ": " + std::strerror(errno));

    const std::string file = quoted(path);
    if (std::memcmp(data.data(), MAGIC, std::min(data.size(), sizeof(MAGIC))) != 0)
        throwError(call, file + " is not a checkpoint (it does not start with \"DEMECKPT\")");
    if (data.size() < HEADER_BYTES)
        throwError(call, file + " is truncated: " + std::to_string(data.size()) + " bytes, shorter than the " +
                             std::to_string(HEADER_BYTES) + "-byte header");
    ByteReader h(data.data(), HEADER_BYTES, call, path);
    h.take(sizeof(MAGIC), "magic");
    const uint32_t version = h.value<uint32_t>("version");
    const uint32_t order = h.value<uint32_t>("byte order");
    const uint64_t length = h.value<uint64_t>("payload length");
    const uint32_t payloadCrc = h.value<uint32_t>("payload checksum");
    const uint32_t headerCrc = h.value<uint32_t>("header checksum");
    if (checksum(data.data(), HEADER_BYTES - 4) != headerCrc)
        throwError(call, file + " is corrupted: the header's checksum does not match");
    if (version < OLDEST_CHECKPOINT_FORMAT_VERSION || version > CHECKPOINT_FORMAT_VERSION)
        throwError(call, file + " has checkpoint format version " + std::to_string(version) +
                             "; this build reads versions " + std::to_string(OLDEST_CHECKPOINT_FORMAT_VERSION) +
                             " to " + std::to_string(CHECKPOINT_FORMAT_VERSION) + " (docs/checkpoint.md)");
    if (order != BYTE_ORDER_MARK)
        throwError(call, file + " was written on a machine of the other byte order");
    const uint64_t have = data.size() - HEADER_BYTES;
    if (have < length)
        throwError(call, file + " is truncated: " + std::to_string(data.size()) + " bytes of " +
                             std::to_string(HEADER_BYTES + length) + " (was it copied or written only in part?)");
    if (have > length)
        throwError(call, file + " is corrupted: " + std::to_string(have - length) + " bytes after its end");
    if (checksum(data.data() + HEADER_BYTES, (size_t)length) != payloadCrc)
        throwError(call, file + " is corrupted: the checksum (CRC-32) of its contents does not match");

    CheckpointSections out;
    out.version = version;
    ByteReader r(data.data() + HEADER_BYTES, (size_t)length, call, path);
    while (!r.atEnd()) {
        std::string name = r.text("a section name");
        const uint64_t n = r.value<uint64_t>("a section length");
        const char* bytes = r.take((size_t)n, ("section \"" + name + "\"").c_str());
        for (const auto& s : out.list)
            if (s.first == name) r.malformed("section \"" + name + "\" appears twice");
        out.add(name, std::string(bytes, (size_t)n));
    }
    return out;
}

}  // namespace deme
