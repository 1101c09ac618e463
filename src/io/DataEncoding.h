// Encodings of binary data in VTK XML files: base64 text (RFC 4648, streamed so that arrays of
// gigabytes need no second copy) and zlib compression in independent blocks, the layout of VTK's
// vtkZLibDataCompressor.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace deme {

// Appends the base64 text of everything put() to `sink` in pieces; finish() pads the last group.
class Base64Stream {
  public:
    explicit Base64Stream(std::function<void(const char*, size_t)> sink) : m_sink(std::move(sink)) {}
    void put(const void* data, size_t bytes);
    void finish();

  private:
    void emit(const uint8_t* in, size_t groups);
    std::function<void(const char*, size_t)> m_sink;
    uint8_t m_carry[3] = {};
    size_t m_nCarry = 0;
    std::string m_text;
};

// Bytes compressed as zlib streams of at most BLOCK_BYTES input each; blocks are compressed in
// parallel (OpenMP), each independently, as VTK's readers expect.
struct CompressedBlocks {
    static constexpr size_t BLOCK_BYTES = 1 << 20;
    size_t rawBytes = 0;
    std::vector<std::vector<uint8_t>> blocks;
    // The VTK header (UInt64): number of blocks, block size, size of the last partial block (0 if
    // full), then each block's compressed size.
    std::vector<uint64_t> header() const;
    size_t compressedBytes() const;
};

// `fill(first, bytes, out)` writes bytes [first, first + bytes) of the data into out.
CompressedBlocks compressBlocks(size_t rawBytes, const std::function<void(size_t, size_t, uint8_t*)>& fill,
                                int level);

}  // namespace deme
