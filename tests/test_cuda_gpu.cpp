// Tests of the CUDA backend that need a GPU: device buffers, the CUB primitives and launching an
// NVRTC-compiled kernel. Each is skipped where usableDevices() is empty (CI: no GPU, no driver), and
// runs on a GPU machine.
#include <gtest/gtest.h>

#include <deme/Error.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <vector>

#include "ScratchDirTest.h"
#include "TestKernels.h"
#include "backend/cuda/CudaModule.h"
#include "backend/cuda/Device.h"
#include "backend/cuda/DeviceBuffer.h"
#include "backend/cuda/DevicePrimitives.h"
#include "backend/cuda/NvrtcCompiler.h"
#include "jit/EmbeddedSources.h"
#include "physics/ContactGeometry.h"
#include "physics/Quaternion.h"

using namespace deme;
using namespace deme::cuda;

#define SKIP_WITHOUT_GPU()                                                                        \
    do {                                                                                          \
        if (usableDevices().empty()) GTEST_SKIP() << "no usable GPU: " << queryDevices().whyNone; \
    } while (0)

// ---- DeviceBuffer

TEST(CudaDeviceBuffer, UploadsAndDownloads) {
    SKIP_WITHOUT_GPU();
    std::vector<int> host(1000);
    std::iota(host.begin(), host.end(), -500);
    DeviceBuffer<int> buf;
    buf.upload(host);
    EXPECT_EQ(buf.size(), host.size());
    EXPECT_EQ(buf.download(), host);
    // Part of it, at an offset.
    std::vector<int> part(10, 0);
    buf.downloadAsync(part.data(), 10, nullptr, 990);
    synchronize(nullptr);
    EXPECT_EQ(part, std::vector<int>(host.end() - 10, host.end()));
    EXPECT_THROW(buf.downloadAsync(part.data(), 10, nullptr, 995), deme::Error);
    buf.zeroAsync(nullptr);
    EXPECT_EQ(buf.download(), std::vector<int>(1000, 0));
}

// A buffer that grows without keeping its contents lets its old memory go before it makes the new:
// the process's peak is the new allocation, not the two together (a large contact set's arrays are
// resized so at each installation).
TEST(CudaDeviceBuffer, GrowingWithoutKeepingHoldsOneAllocationAtATime) {
    SKIP_WITHOUT_GPU();
    const size_t mib = 1u << 20, base = deviceBytesAllocated();
    DeviceBuffer<char> buf;
    // Larger than this process's peak so far, so that the peak below is this test's.
    const size_t first = std::max<size_t>(256 * mib, deviceBytesAllocatedPeak() + 64 * mib);
    buf.resizeDiscarding(first);
    ASSERT_EQ(deviceBytesAllocated(), base + first);
    buf.resizeDiscarding(first + 1);  // grows by half
    const size_t grown = buf.capacity();
    EXPECT_GE(grown, first + first / 2);
    EXPECT_EQ(deviceBytesAllocated(), base + grown);
    EXPECT_EQ(deviceBytesAllocatedPeak(), base + grown);  // never first + grown
    buf.release();
    EXPECT_EQ(deviceBytesAllocated(), base);
}

TEST(CudaDeviceBuffer, GrowsGeometricallyKeepsContentsAndNeverShrinksUnlessAsked) {
    SKIP_WITHOUT_GPU();
    DeviceBuffer<uint32_t> buf;
    std::vector<uint32_t> host(100);
    std::iota(host.begin(), host.end(), 7u);
    buf.upload(host);
    const size_t capacity100 = buf.capacity();
    EXPECT_GE(capacity100, 100u);

    buf.resize(101);  // just past the capacity: grows by half, not by one
    EXPECT_GE(buf.capacity(), capacity100 + capacity100 / 2);
    std::vector<uint32_t> grown = buf.download();
    EXPECT_TRUE(std::equal(host.begin(), host.end(), grown.begin()));

    const size_t big = buf.capacity();
    buf.resize(10);
    EXPECT_EQ(buf.size(), 10u);
    EXPECT_EQ(buf.capacity(), big);  // shrinking keeps the memory
    buf.resize(100);
    EXPECT_EQ(buf.capacity(), big);  // and growing back within it costs nothing
    buf.resize(10);
    buf.shrinkToFit();
    EXPECT_EQ(buf.capacity(), 10u);
    EXPECT_EQ(buf.download(), std::vector<uint32_t>(host.begin(), host.begin() + 10));
}

TEST(CudaDeviceBuffer, CountsTheBytesItHolds) {
    SKIP_WITHOUT_GPU();
    const size_t before = deviceBytesAllocated();
    {
        DeviceBuffer<double> a(1000);
        EXPECT_EQ(deviceBytesAllocated(), before + a.capacity() * sizeof(double));
        DeviceBuffer<double> b = std::move(a);  // moving hands the memory over, no new allocation
        EXPECT_EQ(deviceBytesAllocated(), before + b.capacity() * sizeof(double));
        EXPECT_EQ(a.capacity(), 0u);
        EXPECT_EQ(a.size(), 0u);
        EXPECT_GE(deviceBytesAllocatedPeak(), deviceBytesAllocated());
    }
    EXPECT_EQ(deviceBytesAllocated(), before);
}

// Device-to-device copies (what the kinematics exchange uses), and a buffer stays on the GPU it was
// allocated on: growing it with another GPU current, or copying between two GPUs, keeps each buffer
// where it is and counts its bytes there. The second half needs two GPUs.
TEST(CudaDeviceBuffer, CopiesBetweenBuffersAndStaysOnItsGpu) {
    SKIP_WITHOUT_GPU();
    const int first = usableDevices()[0].id;
    useDevice("test", first);
    std::vector<int> host(500);
    std::iota(host.begin(), host.end(), 3);
    DeviceBuffer<int> a, b(500);
    a.upload(host);
    b.copyFromAsync(a, 500, nullptr);
    EXPECT_EQ(b.download(), host);
    EXPECT_EQ(a.device(), first);
    const size_t onFirst = deviceBytesAllocatedOn(first);
    EXPECT_GE(onFirst, a.capacity() * sizeof(int) + b.capacity() * sizeof(int));
    if (usableDevices().size() < 2) return;
    const int second = usableDevices()[1].id;
    useDevice("test", second);
    const size_t onSecond = deviceBytesAllocatedOn(second);
    DeviceBuffer<int> c(500);  // on the second GPU
    EXPECT_EQ(c.device(), second);
    EXPECT_EQ(deviceBytesAllocatedOn(second), onSecond + c.capacity() * sizeof(int));
    c.copyFromAsync(a, 500, nullptr);  // from the first GPU
    synchronize(nullptr);
    a.resize(5000);  // grows on the first GPU although the second is current
    EXPECT_EQ(a.device(), first);
    EXPECT_EQ(deviceBytesAllocatedOn(second), onSecond + c.capacity() * sizeof(int));
    EXPECT_EQ(c.download(), host);
    useDevice("test", first);
    a.release();  // freed on its own GPU
    EXPECT_EQ(deviceBytesAllocatedOn(first), onFirst - 500 * sizeof(int));  // a held exactly 500 before it grew
}

// Each buffer counts to the group of the scope that allocates it first (or the one setGroup gives),
// and moves keep the group: the groups' sum is what all buffers hold.
TEST(CudaDeviceBuffer, BuffersCountToTheirGroup) {
    SKIP_WITHOUT_GPU();
    const size_t geometry = deviceBytesInGroup(MemoryGroup::GEOMETRY), scratch = deviceBytesInGroup(MemoryGroup::STEP_SCRATCH);
    DeviceBuffer<double> a;
    {
        const MemoryGroupScope group(MemoryGroup::GEOMETRY);
        a.resize(1000);
    }
    a.resize(5000);  // grows outside the scope: still geometry
    EXPECT_EQ(deviceBytesInGroup(MemoryGroup::GEOMETRY), geometry + a.capacity() * sizeof(double));
    DeviceBuffer<double> b(100);  // no scope: step scratch
    EXPECT_EQ(deviceBytesInGroup(MemoryGroup::STEP_SCRATCH), scratch + 100 * sizeof(double));
    b.setGroup(MemoryGroup::GEOMETRY);
    EXPECT_EQ(deviceBytesInGroup(MemoryGroup::STEP_SCRATCH), scratch);
    DeviceBuffer<double> c(std::move(a));
    a = std::move(b);
    EXPECT_EQ(deviceBytesInGroup(MemoryGroup::GEOMETRY), geometry + (c.capacity() + a.capacity()) * sizeof(double));
    c.release();
    a.release();
    EXPECT_EQ(deviceBytesInGroup(MemoryGroup::GEOMETRY), geometry);
}

TEST(CudaDeviceBuffer, OutOfMemoryIsAnError) {
    SKIP_WITHOUT_GPU();
    const size_t tooMuch = usableDevices().front().totalMemoryBytes * 4;
    const size_t before = deviceBytesAllocated(), contactsBefore = deviceBytesInGroup(MemoryGroup::CONTACTS);
    try {
        // The message names the size asked and the group the buffer counts to.
        const MemoryGroupScope group(MemoryGroup::CONTACTS);
        DeviceBuffer<char> huge(tooMuch);
        ADD_FAILURE() << "allocated " << tooMuch << " bytes";
    } catch (const deme::Error& e) {
        EXPECT_NE(std::string(e.what()).find("out of GPU memory allocating " + std::to_string(tooMuch) +
                                             " bytes for contacts and history"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(deviceBytesAllocated(), before);
    EXPECT_EQ(deviceBytesInGroup(MemoryGroup::CONTACTS), contactsBefore);
    DeviceBuffer<char> fine(16);  // the failure left the runtime usable
    EXPECT_EQ(fine.size(), 16u);
}

// ---- DevicePrimitives, each against the obvious host computation

namespace {

template <class T>
std::vector<T> randomValues(size_t n, uint64_t seed, T hi = std::numeric_limits<T>::max()) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<T> dist(0, hi);
    std::vector<T> v(n);
    for (T& x : v) x = dist(rng);
    return v;
}

template <class Key>
void checkSortPairs(size_t n, Key keyMax, int endBit) {
    const std::vector<Key> keys = randomValues<Key>(n, 1, keyMax);  // many equal keys: checks stability
    std::vector<uint32_t> values(n);
    std::iota(values.begin(), values.end(), 0u);
    DeviceBuffer<Key> keysIn, keysOut(n);
    DeviceBuffer<uint32_t> valuesIn, valuesOut(n);
    keysIn.upload(keys);
    valuesIn.upload(values);
    DevicePrimitives prim;
    prim.sortPairs(keysIn.data(), keysOut.data(), valuesIn.data(), valuesOut.data(), n, nullptr, 0, endBit);

    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
    std::vector<Key> sortedKeys(n);
    for (size_t i = 0; i < n; i++) sortedKeys[i] = keys[order[i]];
    EXPECT_EQ(keysOut.download(), sortedKeys);
    EXPECT_EQ(valuesOut.download(), order);
}

}  // namespace

TEST(CudaPrimitives, SortsPairsWith64BitKeys) {
    SKIP_WITHOUT_GPU();
    checkSortPairs<uint64_t>(100000, (uint64_t(1) << 63) - 1, 63);
    checkSortPairs<uint64_t>(5000, 1000, 64);
}

TEST(CudaPrimitives, SortsPairsWith32BitKeys) {
    SKIP_WITHOUT_GPU();
    checkSortPairs<uint32_t>(100000, 0xffffffffu, 32);
    checkSortPairs<uint32_t>(3, 2, 32);
    DevicePrimitives prim;
    EXPECT_NO_THROW(prim.sortPairs((uint32_t*)nullptr, nullptr, nullptr, nullptr, 0, nullptr));  // nothing to do
    DeviceBuffer<uint32_t> k(4), v(4);
    EXPECT_THROW(prim.sortPairs(k.data(), k.data(), v.data(), v.data(), 4, nullptr, 0, 33), deme::Error);
}

TEST(CudaPrimitives, ExclusiveSums) {
    SKIP_WITHOUT_GPU();
    DevicePrimitives prim;
    const std::vector<uint32_t> in32 = randomValues<uint32_t>(123457, 2, 50);
    std::vector<uint32_t> expected32(in32.size());
    std::exclusive_scan(in32.begin(), in32.end(), expected32.begin(), 0u);
    DeviceBuffer<uint32_t> a, b(in32.size());
    a.upload(in32);
    prim.exclusiveSum(a.data(), b.data(), in32.size(), nullptr);
    EXPECT_EQ(b.download(), expected32);
    prim.exclusiveSum(a.data(), a.data(), in32.size(), nullptr);  // in place
    EXPECT_EQ(a.download(), expected32);

    const std::vector<uint64_t> in64 = randomValues<uint64_t>(70000, 3, uint64_t(1) << 40);
    std::vector<uint64_t> expected64(in64.size());
    std::exclusive_scan(in64.begin(), in64.end(), expected64.begin(), uint64_t(0));
    DeviceBuffer<uint64_t> c, d(in64.size());
    c.upload(in64);
    prim.exclusiveSum(c.data(), d.data(), in64.size(), nullptr);
    EXPECT_EQ(d.download(), expected64);
}

// A 64-bit exclusive sum over more than 2^32 - 1 items (a GPU set's per-pair marks past 4.29e9
// pairs, history mapping's persistent merge): ones in three runs of 1,000 (the start, across item
// 2^32, the end), zeros elsewhere; each run's sums read back. Needs 34.4 GB of device memory.
TEST(CudaPrimitives, ExclusiveSumOf64BitsPastTwoToThe32Items) {
    SKIP_WITHOUT_GPU();
    const size_t n = (size_t(1) << 32) + 3000;
    if (usableDevices()[0].totalMemoryBytes < n * sizeof(uint64_t) + (size_t(8) << 30))
        GTEST_SKIP() << "needs a GPU of 43 GB or more (this one: " << usableDevices()[0].totalMemoryBytes << " B)";
    DeviceBuffer<uint64_t> a(n);
    a.zeroAsync(nullptr);
    const std::vector<uint64_t> ones(1000, 1);
    const size_t runs[3] = {0, (size_t(1) << 32) - 500, n - 1000};
    for (size_t r : runs) a.uploadAsync(ones.data(), ones.size(), nullptr, r);
    DevicePrimitives prim;
    prim.exclusiveSum(a.data(), a.data(), n, nullptr);  // in place: one buffer of 34.4 GB
    for (int k = 0; k < 3; k++) {
        std::vector<uint64_t> got(1000);
        a.downloadAsync(got.data(), got.size(), nullptr, runs[k]);
        synchronize(nullptr);
        for (size_t j = 0; j < got.size(); j++)
            ASSERT_EQ(got[j], 1000 * (uint64_t)k + j) << "run " << k << ", item " << j;
    }
    // The 32-bit sums stay limited to 2^32 - 1 items, and say so.
    EXPECT_THROW(prim.exclusiveSum((const uint32_t*)nullptr, nullptr, size_t(1) << 32, nullptr), deme::Error);
}

// Counts summed in 64 bits: detection checks its 32-bit offsets' total against this sum
// (runtime/IndexLimits.h), so counts whose total passes 2^32 must come back whole, not wrapped.
TEST(CudaPrimitives, SumsCountsIn64Bits) {
    SKIP_WITHOUT_GPU();
    DevicePrimitives prim;
    const std::vector<uint32_t> in = randomValues<uint32_t>(100003, 5);  // each up to 2^32 - 1
    uint64_t expected = 0;
    for (uint32_t v : in) expected += v;
    ASSERT_GT(expected, uint64_t(1) << 40);  // a 32-bit sum would have wrapped many times
    DeviceBuffer<uint32_t> a;
    a.upload(in);
    DeviceBuffer<uint64_t> total(1);
    prim.sum(a.data(), total.data(), in.size(), nullptr);
    EXPECT_EQ(total.download(), std::vector<uint64_t>{expected});
    prim.sum(a.data(), total.data(), 0, nullptr);  // nothing to sum: zero
    EXPECT_EQ(total.download(), std::vector<uint64_t>{0});
}

TEST(CudaPrimitives, Reductions) {
    SKIP_WITHOUT_GPU();
    DevicePrimitives prim;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> dist(-1e3, 1e3);
    std::vector<float> f(99999);
    std::vector<double> g(77777);
    for (float& x : f) x = (float)dist(rng);
    for (double& x : g) x = dist(rng);
    const std::vector<uint32_t> u = randomValues<uint32_t>(55555, 5, 0xfffffff0u);

    DeviceBuffer<float> df, fmax(1);
    DeviceBuffer<double> dg, gmax(1);
    DeviceBuffer<uint32_t> du, umin(1);
    df.upload(f);
    dg.upload(g);
    du.upload(u);
    prim.reduceMax(df.data(), fmax.data(), f.size(), nullptr);
    prim.reduceMax(dg.data(), gmax.data(), g.size(), nullptr);
    prim.reduceMin(du.data(), umin.data(), u.size(), nullptr);
    EXPECT_EQ(fmax.download()[0], *std::max_element(f.begin(), f.end()));
    EXPECT_EQ(gmax.download()[0], *std::max_element(g.begin(), g.end()));
    EXPECT_EQ(umin.download()[0], *std::min_element(u.begin(), u.end()));

    prim.reduceMax(df.data(), fmax.data(), 0, nullptr);  // empty: the lowest float
    EXPECT_EQ(fmax.download()[0], std::numeric_limits<float>::lowest());
    EXPECT_GT(prim.scratchBytes(), 0u);
}

// ---- an NVRTC-compiled kernel, loaded and launched

class CudaModuleLaunch : public deme_test::ScratchDirTest {};

TEST_F(CudaModuleLaunch, RunsTheExampleKernelLikeTheHost) {
    SKIP_WITHOUT_GPU();
    jit::KernelCache cache(dir.string());
    const std::string source = deme_test::testKernelText("Example.cu");
    ASSERT_FALSE(source.empty());
    // Both image kinds: CUBIN for this GPU (the default), and PTX that the driver compiles.
    const CudaCompileResult cubin = compileCudaSource("test", deme_test::kExampleKernelPath, source, {}, cache);
    CudaCompileOptions ptxOptions;
    ptxOptions.architecture =
        "compute_" + std::to_string(usableDevices().front().major * 10 + usableDevices().front().minor);
    const CudaCompileResult ptx =
        compileCudaSource("test", deme_test::kExampleKernelPath, source, ptxOptions, cache);

    const unsigned int n = 1000;
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double3> pos(n + 1);
    std::vector<float> radius(n + 1);
    std::vector<float4> ori(n + 1);
    for (unsigned int i = 0; i <= n; i++) {
        pos[i] = make_double3(0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng));
        radius[i] = (float)(0.005 + 0.002 * u(rng));
        ori[i] = quatNormalize(make_float4((float)u(rng), (float)u(rng), (float)u(rng), (float)u(rng)));
    }
    DeviceBuffer<double3> dPos;
    DeviceBuffer<float> dRadius;
    DeviceBuffer<float4> dOri;
    DeviceBuffer<double> dOverlap(n);
    DeviceBuffer<float3> dNormal(n);
    dPos.upload(pos);
    dRadius.upload(radius);
    dOri.upload(ori);

    for (const CudaCompileResult* image : {&cubin, &ptx}) {
        SCOPED_TRACE(image->architecture);
        CudaModule module("test", image->image);
        const CudaKernel k = module.kernel("exampleSpherePairOverlap");
        dOverlap.zeroAsync(nullptr);
        launch(k, Dim3(blocksFor(n, 128)), Dim3(128), 0, nullptr, dPos.data(), dRadius.data(), dOri.data(),
               dOverlap.data(), dNormal.data(), n);
        const std::vector<double> overlap = dOverlap.download();
        const std::vector<float3> normal = dNormal.download();
        for (unsigned int i = 0; i < n; i++) {
            const ContactPoint c = sphereSphereContact(pos[i], radius[i], pos[i + 1], radius[i + 1]);
            const float3 local = rotateToLocal(ori[i], c.B2A);
            ASSERT_NEAR(overlap[i], c.overlap, 1e-15) << i;  // double, correctly rounded on both
            ASSERT_NEAR(normal[i].x, local.x, 1e-6f) << i;   // float: the GPU may fuse multiply-adds
            ASSERT_NEAR(normal[i].y, local.y, 1e-6f) << i;
            ASSERT_NEAR(normal[i].z, local.z, 1e-6f) << i;
        }
        EXPECT_THROW(module.kernel("noSuchKernel"), deme::Error);
    }
}
