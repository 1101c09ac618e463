#include <deme/Error.h>
#include <gtest/gtest.h>

#include "ScratchDirTest.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/ClumpCsvReader.h"

using namespace deme;
namespace fs = std::filesystem;

namespace {

class ClumpCsv : public deme_test::ScratchDirTest {
  protected:
    // The reader must throw deme::Error naming the call, the file and the line.
    void expectError(const std::string& path, size_t line, const std::string& fragment) {
        try {
            readClumpCsv(path, "LoadClumpType");
            ADD_FAILURE() << "no throw for " << path;
        } catch (const Error& e) {
            const std::string w = e.what();
            EXPECT_NE(w.find("LoadClumpType"), std::string::npos) << w;
            EXPECT_NE(w.find(path + ":" + std::to_string(line) + ":"), std::string::npos) << w;
            EXPECT_NE(w.find(fragment), std::string::npos) << w;
        }
    }
};

}  // namespace

TEST_F(ClumpCsv, ReadsSharedDataFile) {
#ifndef DEME_SHARED_DATA_DIR
    GTEST_SKIP() << "DEME_SHARED_DATA_DIR not defined";
#else
    const std::string path = std::string(DEME_SHARED_DATA_DIR) + "/3_clump.csv";
    if (!fs::exists(path)) GTEST_SKIP() << path << " not present";
    const ClumpSpheres c = readClumpCsv(path, "test");
    ASSERT_EQ(c.radii.size(), 3u);  // trailing '#' comment lines are skipped
    EXPECT_FLOAT_EQ(c.positions[0].x, 0.5f);
    EXPECT_FLOAT_EQ(c.positions[1].y, -0.658271f);
    EXPECT_FLOAT_EQ(c.positions[2].z, 0.f);
    for (float r : c.radii) EXPECT_FLOAT_EQ(r, 0.8f);
#endif
}

TEST_F(ClumpCsv, CommentsReorderedColumnsAndCrlf) {
    const std::string p = write("good.csv",
                                "\xEF\xBB\xBF# leading comment\r\n"
                                "\r\n"
                                "   # indented comment\r\n"
                                " R , Z,x ,Y ,id\r\n"
                                "0.5, 3, 1, 2, 7\r\n"
                                "\t\r\n"
                                "# mid comment\r\n"
                                "1e-1,-3.5e0 ,  -1,+2 ,8\r\n"
                                "# trailing comment");
    const ClumpSpheres c = readClumpCsv(p, "test");
    ASSERT_EQ(c.positions.size(), 2u);
    ASSERT_EQ(c.radii.size(), 2u);
    EXPECT_FLOAT_EQ(c.positions[0].x, 1.f);
    EXPECT_FLOAT_EQ(c.positions[0].y, 2.f);
    EXPECT_FLOAT_EQ(c.positions[0].z, 3.f);
    EXPECT_FLOAT_EQ(c.radii[0], 0.5f);
    EXPECT_FLOAT_EQ(c.positions[1].x, -1.f);
    EXPECT_FLOAT_EQ(c.positions[1].y, 2.f);
    EXPECT_FLOAT_EQ(c.positions[1].z, -3.5f);
    EXPECT_FLOAT_EQ(c.radii[1], 0.1f);
}

TEST_F(ClumpCsv, MissingFile) { expectError((dir / "nope.csv").string(), 0, "cannot open"); }

TEST_F(ClumpCsv, NoHeader) {
    expectError(write("empty.csv", ""), 0, "no header");
    expectError(write("comments.csv", "# a\n\n# b\n"), 3, "no header");
}

TEST_F(ClumpCsv, HeaderMissingOrRepeatedColumn) {
    expectError(write("nor.csv", "# c\nx,y,z,radius\n1,2,3,4\n"), 2, "'r'");
    expectError(write("numeric.csv", "1,2,3,4\n"), 1, "'x'");
    expectError(write("dup.csv", "x,y,z,r,X\n1,2,3,4,5\n"), 1, "repeats column 'x'");
}

TEST_F(ClumpCsv, WrongFieldCount) {
    expectError(write("few.csv", "x,y,z,r\n1,2,3,4\n\n1,2,3\n"), 4, "expected 4 fields, got 3");
    expectError(write("many.csv", "x,y,z,r\r\n1,2,3,4,5\r\n"), 2, "got 5");
}

TEST_F(ClumpCsv, NonNumericField) {
    expectError(write("word.csv", "r,x,y,z\n1,2,abc,4\n"), 2, "column 'y'");
    expectError(write("trail.csv", "x,y,z,r\n1,2,3,0.5mm\n"), 2, "column 'r'");
    expectError(write("emptyfield.csv", "x,y,z,r\n1,,3,4\n"), 2, "column 'y'");
}

TEST_F(ClumpCsv, NonFiniteField) {
    expectError(write("nan.csv", "x,y,z,r\n1,2,3,1\nnan,2,3,1\n"), 3, "column 'x': 'nan' is not finite");
    expectError(write("inf.csv", "x,y,z,r\n1,2,-inf,1\n"), 2, "column 'z'");
    expectError(write("big.csv", "x,y,z,r\n1,2,1e300,1\n"), 2, "column 'z'");  // overflows float
}

TEST_F(ClumpCsv, NonPositiveRadius) {
    expectError(write("zero.csv", "x,y,z,r\n1,2,3,1\n# c\n1,2,3,0\n"), 4, "radius");
    expectError(write("neg.csv", "x,y,z,r\n1,2,3,-0.5\n"), 2, "radius");
}

TEST_F(ClumpCsv, NoSpheres) { expectError(write("hdr.csv", "# c\nx,y,z,r\n# none\n"), 2, "no spheres"); }
