// Tests of the run-time compilation infrastructure in src/jit/: cache keys, the on-disk artifact cache
// and its atomic publication, the embedded sources, and host compilation into loaded shared objects.
// Every test uses its own scratch cache directory, so a cache hit can only come from the test itself.
#include <gtest/gtest.h>

#include <deme/Error.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "ScratchDirTest.h"
#include "TestHelpers.h"
#include "dynamics/ContactInputsGather.h"
#include "jit/EmbeddedSources.h"
#include "jit/HostCompiler.h"
#include "jit/KernelCache.h"
#include "physics/Quaternion.h"
#include "state/SimState.h"

using namespace deme;
using namespace deme::jit;
namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    return names;
}

void reportTime(const char* what, double seconds) {
    std::cout << "[   jit    ] " << what << ": " << seconds << " s" << std::endl;
}

const char* const kAddSource = R"(extern "C" int add(int a, int b) { return a + b; })";

}  // namespace

// ---- cache keys

TEST(JitCacheKey, SameInputsGiveTheSameKey) {
    EXPECT_EQ(cacheKey({"source", "g++ 12", "-O3"}), cacheKey({"source", "g++ 12", "-O3"}));
    EXPECT_EQ(cacheKey({"a", "b"}), cacheKey(std::vector<std::string>{"a", "b"}));
    const std::string key = cacheKey({"x"});
    EXPECT_EQ(key.size(), 32u);
    EXPECT_TRUE(std::regex_match(key, std::regex("[0-9a-f]{32}")));
}

TEST(JitCacheKey, DifferentInputsGiveDifferentKeys) {
    std::set<std::string> keys = {cacheKey({}),
                                  cacheKey({""}),
                                  cacheKey({"", ""}),
                                  cacheKey({"source"}),
                                  cacheKey({"sourcf"}),
                                  cacheKey({"source", "-O3"}),
                                  cacheKey({"-O3", "source"}),
                                  cacheKey({"source", "-O2"})};
    EXPECT_EQ(keys.size(), 8u);
}

TEST(JitCacheKey, PartBoundariesMatter) {
    EXPECT_NE(cacheKey({"ab", "c"}), cacheKey({"a", "bc"}));
    EXPECT_NE(cacheKey({"abc"}), cacheKey({"ab", "c"}));
    // Embedded NULs are content like any other byte.
    EXPECT_NE(cacheKey({std::string_view("a\0b", 3)}), cacheKey({std::string_view("a\0c", 3)}));
}

// ---- cache directory

TEST(JitCacheDirectory, ResolvedInDocumentedOrder) {
    EXPECT_EQ(cacheDirectoryFor({"/d/cache", "/xdg", "/home/u"}), "/d/cache");
    EXPECT_EQ(cacheDirectoryFor({nullptr, "/xdg", "/home/u"}), "/xdg/deme");
    EXPECT_EQ(cacheDirectoryFor({"", "/xdg", "/home/u"}), "/xdg/deme");  // empty means unset
    EXPECT_EQ(cacheDirectoryFor({nullptr, nullptr, "/home/u"}), "/home/u/.cache/deme");
    EXPECT_EQ(cacheDirectoryFor({nullptr, "", ""}), "/tmp/deme-cache-" + std::to_string(getuid()));
}

// ---- publish and lookup

class JitKernelCache : public deme_test::ScratchDirTest {};

TEST_F(JitKernelCache, CreatesItsDirectory) {
    const fs::path nested = dir / "a" / "b";
    KernelCache cache(nested.string());
    EXPECT_TRUE(fs::is_directory(nested));
    EXPECT_EQ(cache.directory(), nested.string());
}

TEST_F(JitKernelCache, LookupFindsWhatWasPublished) {
    KernelCache cache(dir.string());
    EXPECT_FALSE(cache.lookup("k1", ".bin"));
    const std::string path = cache.publish("k1", ".bin", [&](const std::string& temp) {
        EXPECT_EQ(fs::path(temp).parent_path(), dir);
        std::ofstream(temp) << "artifact";
    });
    EXPECT_EQ(path, cache.artifactPath("k1", ".bin"));
    EXPECT_EQ(fs::path(path).parent_path(), dir);
    const auto found = cache.lookup("k1", ".bin");
    ASSERT_TRUE(found);
    EXPECT_EQ(*found, path);
    EXPECT_EQ(readFile(path), "artifact");
    EXPECT_FALSE(cache.lookup("k1", ".other"));
    const CacheStats s = cache.stats();
    EXPECT_EQ(s.hits, 1u);
    EXPECT_EQ(s.misses, 2u);
    EXPECT_EQ(s.published, 1u);
    EXPECT_EQ(entries(dir), std::vector<std::string>{"k1.bin"});
}

TEST_F(JitKernelCache, TemporaryFilesLiveInTheCacheDirectoryAndAreUnique) {
    KernelCache cache(dir.string());
    std::set<std::string> names;
    for (int i = 0; i < 100; i++) {
        const std::string t = cache.temporaryPath(".so");
        EXPECT_EQ(fs::path(t).parent_path(), dir);  // same file system, so rename() is atomic
        EXPECT_EQ(fs::path(t).extension(), ".so");
        names.insert(t);
    }
    EXPECT_EQ(names.size(), 100u);
}

TEST_F(JitKernelCache, FailedProducerLeavesNothingBehind) {
    KernelCache cache(dir.string());
    EXPECT_THROW(cache.publish("k", ".bin",
                               [](const std::string& temp) {
                                   std::ofstream(temp) << "half";
                                   throw std::runtime_error("compiler crashed");
                               }),
                 std::runtime_error);
    EXPECT_TRUE(entries(dir).empty());
    EXPECT_FALSE(cache.lookup("k", ".bin"));
    // A producer that writes nothing is an error, not an empty artifact.
    EXPECT_THROW(cache.publish("k", ".bin", [](const std::string&) {}), deme::Error);
    EXPECT_TRUE(entries(dir).empty());
}

// A cache directory removed while the program runs (a user clearing the cache) comes back on the
// next publish instead of failing every compile from then on.
TEST_F(JitKernelCache, DirectoryRemovedWhileRunningIsRecreated) {
    KernelCache cache(dir.string());
    std::filesystem::remove_all(dir);
    const std::string path = cache.publish("k", ".bin", [](const std::string& temp) { std::ofstream(temp) << "x"; });
    EXPECT_TRUE(std::filesystem::is_regular_file(path));
    EXPECT_TRUE(cache.lookup("k", ".bin"));
}

// Several threads produce the same artifact at once, slowly, while a reader polls for it: the reader
// only ever sees the whole file, and in the end there is exactly that one file.
TEST_F(JitKernelCache, ConcurrentPublishersLeaveOneCompleteFile) {
    KernelCache cache(dir.string());
    constexpr int kThreads = 8;
    constexpr size_t kChunk = 64 * 1024, kChunks = 32;
    std::string expected(kChunk * kChunks, '\0');
    for (size_t i = 0; i < expected.size(); i++) expected[i] = (char)((i * 31) % 251);

    std::atomic<int> ready{0};
    std::atomic<bool> done{false};
    std::atomic<int> partialSeen{0}, completeSeen{0};
    std::thread reader([&] {
        while (!done) {
            const std::string path = cache.artifactPath("shared", ".bin");
            std::error_code ec;
            if (fs::exists(path, ec)) {
                (readFile(path) == expected ? completeSeen : partialSeen)++;
            }
        }
    });
    std::vector<std::thread> writers;
    std::vector<std::string> results(kThreads);
    for (int t = 0; t < kThreads; t++) {
        writers.emplace_back([&, t] {
            ready++;
            while (ready < kThreads) std::this_thread::yield();
            results[t] = cache.publish("shared", ".bin", [&](const std::string& temp) {
                std::ofstream out(temp, std::ios::binary);
                for (size_t c = 0; c < kChunks; c++) {
                    out.write(expected.data() + c * kChunk, kChunk);
                    out.flush();  // let the reader catch the temporary half-written, if it could
                }
            });
        });
    }
    for (auto& w : writers) w.join();
    done = true;
    reader.join();

    for (const std::string& r : results) EXPECT_EQ(r, cache.artifactPath("shared", ".bin"));
    EXPECT_EQ(entries(dir), std::vector<std::string>{"shared.bin"});
    EXPECT_EQ(readFile(dir / "shared.bin"), expected);
    EXPECT_EQ(partialSeen, 0);
    EXPECT_GE(cache.stats().published, 1u);
}

// ---- embedded sources

class JitEmbeddedSources : public deme_test::ScratchDirTest {};

TEST_F(JitEmbeddedSources, HoldTheForceLoopHeadersUnderTheirIncludePaths) {
    std::set<std::string> paths;
    for (const EmbeddedFile& f : embeddedSources()) {
        paths.insert(f.path);
        EXPECT_EQ(std::strlen(f.text), f.size) << f.path;
        EXPECT_GT(f.size, 0u) << f.path;
    }
    for (const char* p : {"deme/HostDevice.h", "deme/VectorTypes.h", "deme/VariableTypes.h", "physics/Quaternion.h",
                          "physics/BuiltInForceModels.h", "physics/models/HertzMindlin.inl", "state/SimState.h",
                          "dynamics/ContactInputsGather.h", "backend/cpu/ForcePassLoop.h", "dynamics/KinematicCache.h"})
        EXPECT_TRUE(paths.count(p)) << p;
    EXPECT_TRUE(
        std::is_sorted(embeddedSources().begin(), embeddedSources().end(),
                       [](const EmbeddedFile& a, const EmbeddedFile& b) { return std::strcmp(a.path, b.path) < 0; }));
    EXPECT_EQ(embeddedSourcesHash().size(), 32u);
}

// Every non-system include of an embedded file resolves to an embedded file (the build checks this
// too; this says so where the tests are read).
TEST_F(JitEmbeddedSources, AreClosedUnderInclusion) {
    std::set<std::string> paths;
    for (const EmbeddedFile& f : embeddedSources()) paths.insert(f.path);
    const std::regex quoted(R"(^\s*#\s*include\s*"([^"]+)\")"), angled(R"(^\s*#\s*include\s*<(deme/[^>]+)>)");
    for (const EmbeddedFile& f : embeddedSources()) {
        const std::string dirOf = fs::path(f.path).parent_path().string();
        std::istringstream in(std::string(f.text, f.size));
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (std::regex_search(line, m, quoted)) {
                const std::string name = m[1];
                EXPECT_TRUE(paths.count(dirOf + "/" + name) || paths.count(name)) << f.path << " includes " << name;
            } else if (std::regex_search(line, m, angled)) {
                EXPECT_TRUE(paths.count(m[1])) << f.path << " includes " << m[1];
            }
        }
    }
}

TEST_F(JitEmbeddedSources, MaterializeOnceIntoAHashedDirectory) {
    const std::string root = materializeEmbeddedSources(dir.string());
    EXPECT_EQ(fs::path(root).parent_path(), dir);
    EXPECT_EQ(fs::path(root).filename().string(), "include-" + embeddedSourcesHash());
    for (const EmbeddedFile& f : embeddedSources()) EXPECT_EQ(readFile(fs::path(root) / f.path), f.text) << f.path;
    EXPECT_EQ(materializeEmbeddedSources(dir.string()), root);
    EXPECT_EQ(entries(dir), std::vector<std::string>{fs::path(root).filename().string()});  // no temporaries left
}

// ---- host compilation

class JitHostCompiler : public deme_test::ScratchDirTest {};

TEST_F(JitHostCompiler, CompilesLoadsAndThenHitsTheCache) {
    KernelCache cache(dir.string());
    {
        HostCompileResult r = compileHostModule("JitTest", kAddSource, cache);
        reportTime("tiny TU, compile", r.compileSeconds);
        EXPECT_FALSE(r.cacheHit);
        EXPECT_GT(r.compileSeconds, 0.0);
        EXPECT_EQ(r.module.function<int(int, int)>("add")(2, 40), 42);
    }
    const CacheStats first = cache.stats();
    EXPECT_EQ(first.misses, 1u);
    EXPECT_EQ(first.published, 1u);

    const auto start = std::chrono::steady_clock::now();
    HostCompileResult again = compileHostModule("JitTest", kAddSource, cache);
    reportTime("tiny TU, cache hit (key, lookup, dlopen)",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    EXPECT_TRUE(again.cacheHit);
    EXPECT_EQ(again.compileSeconds, 0.0);
    EXPECT_EQ(again.module.function<int(int, int)>("add")(-1, 1), 0);
    const CacheStats second = cache.stats();
    EXPECT_EQ(second.hits, 1u);
    EXPECT_EQ(second.published, 1u);  // nothing was compiled the second time

    // Different flags are a different artifact.
    HostCompileResult other = compileHostModule("JitTest", kAddSource, cache, {"-DUNUSED_MACRO=1"});
    EXPECT_FALSE(other.cacheHit);
    EXPECT_NE(other.key, again.key);
    // Only artifacts and the embedded include tree remain; the compiler's temporaries are gone.
    for (const std::string& name : entries(dir)) EXPECT_NE(name.rfind(".tmp-", 0), 0u) << name;
}

// The run-time compiled copy of the physics code computes bit for bit what the copy compiled into this
// test does. Both are built with -ffp-contract=off (see tests/CMakeLists.txt): this file is not built
// with the library's -march=native, and with it GCC would fuse multiply-adds that this file does not.
TEST_F(JitHostCompiler, EmbeddedQuaternionCodeMatchesTheBuiltInCode) {
    KernelCache cache(dir.string());
    const char* source = R"(
#include <deme/VectorTypes.h>
#include "physics/Quaternion.h"
extern "C" void rotate(const float* q, const float* v, float* out) {
    const deme::float3 r = deme::rotateToGlobal(deme::make_float4(q[0], q[1], q[2], q[3]),
                                                deme::make_float3(v[0], v[1], v[2]));
    out[0] = r.x;
    out[1] = r.y;
    out[2] = r.z;
}
)";
    HostCompileResult r = compileHostModule("JitTest", source, cache, {"-ffp-contract=off"});
    reportTime("TU with Quaternion.h, compile", r.compileSeconds);
    auto* rotate = r.module.function<void(const float*, const float*, float*)>("rotate");
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 1000; i++) {
        const float4 q = quatNormalize(make_float4(u(rng), u(rng), u(rng), u(rng)));
        const float3 v = make_float3(10 * u(rng), 10 * u(rng), 10 * u(rng));
        const float qa[4] = {q.x, q.y, q.z, q.w}, va[3] = {v.x, v.y, v.z};
        float out[3];
        rotate(qa, va, out);
        const float3 expected = rotateToGlobal(q, v);
        ASSERT_EQ(out[0], expected.x) << i;
        ASSERT_EQ(out[1], expected.y) << i;
        ASSERT_EQ(out[2], expected.z) << i;
    }
}

// The force loop's gather code compiles from the embedded tree alone, with the same layout as here.
TEST_F(JitHostCompiler, ContactInputsGatherCompilesFromTheEmbeddedTree) {
    KernelCache cache(dir.string());
    const char* source = R"(
#include "dynamics/ContactInputsGather.h"
#include "dynamics/KinematicCache.h"
#include "state/SimState.h"
extern "C" size_t sizeOfContactInputs() { return sizeof(deme::ContactInputs); }
extern "C" size_t sizeOfSimState() { return sizeof(deme::SimState); }
extern "C" void gather(const deme::SimState* s, size_t c, float time, float ts, deme::ContactInputs* in) {
    deme::gatherContactInputs(*s, c, time, ts, *in);
}
)";
    HostCompileResult r = compileHostModule("JitTest", source, cache);
    reportTime("TU with ContactInputsGather.h, compile", r.compileSeconds);
    EXPECT_EQ(r.module.function<size_t()>("sizeOfContactInputs")(), sizeof(ContactInputs));
    EXPECT_EQ(r.module.function<size_t()>("sizeOfSimState")(), sizeof(SimState));
    EXPECT_NE(r.module.symbol("gather"), nullptr);
}

TEST_F(JitHostCompiler, SyntaxErrorNamesTheSnippetLine) {
    KernelCache cache(dir.string());
    const char* source = R"(extern "C" int f(int a) {
#line 1 "user_snippet"
    int b = a + 1;
    int c = b * 2;
    int d = c + ;
#line 7 "generated"
    return d;
}
)";
    const std::string msg =
        deme_test::demeErrorMessage([&] { compileHostModule("DEMSolver::DefineContactForceModel", source, cache); });
    EXPECT_EQ(msg.rfind("DEMSolver::DefineContactForceModel: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("user_snippet:3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("error"), std::string::npos) << msg;
    // A failed compilation publishes nothing and leaves no temporaries.
    for (const std::string& name : entries(dir)) EXPECT_EQ(name.rfind("include-", 0), 0u) << name;
}

TEST_F(JitHostCompiler, UnknownIdentifierNamesTheLine) {
    KernelCache cache(dir.string());
    const char* source = R"(
#line 1 "force_model"
float force(float overlap) {
    return overlap * stiffnes;
}
)";
    const std::string msg = deme_test::demeErrorMessage([&] { compileHostModule("JitTest", source, cache); });
    EXPECT_NE(msg.find("force_model:2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("stiffnes"), std::string::npos) << msg;
}

TEST_F(JitHostCompiler, MissingSymbolIsAnError) {
    KernelCache cache(dir.string());
    HostCompileResult r = compileHostModule("JitTest", kAddSource, cache);
    const std::string msg = deme_test::demeErrorMessage([&] { r.module.symbol("subtract"); });
    EXPECT_EQ(msg.rfind("JitTest: ", 0), 0u) << msg;
    EXPECT_NE(msg.find("subtract"), std::string::npos) << msg;
    EXPECT_THROW(CompiledModule("JitTest", (dir / "no-such.so").string()), deme::Error);
}
