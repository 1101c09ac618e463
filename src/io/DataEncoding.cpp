#include "io/DataEncoding.h"

#include <zlib.h>

#include <algorithm>

#include <deme/Error.h>

namespace deme {

namespace {

const char BASE64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
constexpr size_t TEXT_CHUNK = 1 << 20;  // characters handed to the sink at a time

}  // namespace

void Base64Stream::emit(const uint8_t* in, size_t groups) {
    const size_t at = m_text.size();
    m_text.resize(at + 4 * groups);
    char* o = &m_text[at];
    for (size_t g = 0; g < groups; g++, in += 3, o += 4) {
        const uint32_t v = (uint32_t)in[0] << 16 | (uint32_t)in[1] << 8 | in[2];
        o[0] = BASE64[v >> 18];
        o[1] = BASE64[(v >> 12) & 63];
        o[2] = BASE64[(v >> 6) & 63];
        o[3] = BASE64[v & 63];
    }
    if (m_text.size() >= TEXT_CHUNK) {
        m_sink(m_text.data(), m_text.size());
        m_text.clear();
    }
}

void Base64Stream::put(const void* data, size_t bytes) {
    const uint8_t* in = static_cast<const uint8_t*>(data);
    if (m_nCarry) {  // complete the group begun by the previous piece
        while (m_nCarry < 3 && bytes) {
            m_carry[m_nCarry++] = *in++;
            bytes--;
        }
        if (m_nCarry < 3) return;
        emit(m_carry, 1);
        m_nCarry = 0;
    }
    // Whole groups straight from the input, in slices that keep the text buffer near TEXT_CHUNK.
    const size_t sliceGroups = TEXT_CHUNK / 4;
    while (bytes >= 3) {
        const size_t groups = std::min(bytes / 3, sliceGroups);
        emit(in, groups);
        in += 3 * groups;
        bytes -= 3 * groups;
    }
    for (size_t i = 0; i < bytes && i < 2; i++) m_carry[m_nCarry++] = in[i];
}

void Base64Stream::finish() {
    if (m_nCarry) {
        const uint32_t v = (uint32_t)m_carry[0] << 16 | (m_nCarry > 1 ? (uint32_t)m_carry[1] << 8 : 0u);
        const char last[4] = {BASE64[v >> 18], BASE64[(v >> 12) & 63], m_nCarry > 1 ? BASE64[(v >> 6) & 63] : '=',
                              '='};
        m_text.append(last, 4);
        m_nCarry = 0;
    }
    if (!m_text.empty()) m_sink(m_text.data(), m_text.size());
    m_text.clear();
}

std::vector<uint64_t> CompressedBlocks::header() const {
    std::vector<uint64_t> h = {(uint64_t)blocks.size(), (uint64_t)BLOCK_BYTES, (uint64_t)(rawBytes % BLOCK_BYTES)};
    for (const auto& b : blocks) h.push_back(b.size());
    return h;
}

size_t CompressedBlocks::compressedBytes() const {
    size_t n = 0;
    for (const auto& b : blocks) n += b.size();
    return n;
}

CompressedBlocks compressBlocks(size_t rawBytes, const std::function<void(size_t, size_t, uint8_t*)>& fill,
                                int level) {
    CompressedBlocks out;
    out.rawBytes = rawBytes;
    const long n = (long)((rawBytes + CompressedBlocks::BLOCK_BYTES - 1) / CompressedBlocks::BLOCK_BYTES);
    out.blocks.resize(n);
    bool failed = false;
#pragma omp parallel if (n > 1)
    {
        std::vector<uint8_t> raw(CompressedBlocks::BLOCK_BYTES);
#pragma omp for schedule(dynamic, 1)
        for (long b = 0; b < n; b++) {
            const size_t first = (size_t)b * CompressedBlocks::BLOCK_BYTES;
            const size_t bytes = std::min(CompressedBlocks::BLOCK_BYTES, rawBytes - first);
            fill(first, bytes, raw.data());
            uLongf size = compressBound((uLong)bytes);
            std::vector<uint8_t>& z = out.blocks[b];
            z.resize(size);
            if (compress2(z.data(), &size, raw.data(), (uLong)bytes, level) != Z_OK) {
#pragma omp atomic write
                failed = true;
            }
            z.resize(size);
        }
    }
    if (failed) throw Error("zlib compression failed (out of memory)");
    return out;
}

}  // namespace deme
