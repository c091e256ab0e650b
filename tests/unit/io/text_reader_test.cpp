// Tests of TextReader: every delimiter, header lines, column choice, exact number conversion,
// errors with line numbers, reads across buffer boundaries, and the shared NCSU points file.

#include "terratin/error.hpp"
#include "terratin/io/text_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace terratin::io {
namespace {

namespace fs = std::filesystem;

PointCloud parse(const std::string& text, const TextReadOptions& options = {}) {
    return readTextPointsFromMemory(text, "points.xyz", options);
}

TextReadOptions withColumns(std::vector<std::string> columns) {
    TextReadOptions options;
    options.columns = std::move(columns);
    return options;
}

/// The message of the InvalidInputError that `text` raises, its options named the `naming` way;
/// "" when none.
std::string rejection(const std::string& text, const TextReadOptions& options = {},
                      const OptionNaming& naming = {}) {
    try {
        parse(text, options);
    } catch (InvalidInputError& error) {
        error.nameOptions(naming);
        return error.what();
    }
    return {};
}

TEST(TextReader, ReadsEveryDelimiter) {
    const std::vector<Point3> expected{{1.5, -2.25, 3.0}, {4e3, 5.0, -6.125}};
    for (const std::string& text : {std::string("1.5 -2.25 3\n4e3   5 -6.125\n"),
                                    std::string("1.5\t-2.25\t3\n4e3\t5\t-6.125"),
                                    std::string("1.5,-2.25,3\n4e3, 5 ,-6.125\n"),
                                    std::string("1.5;-2.25;3\r\n4e3;5;-6.125\r\n"),
                                    std::string("1.5|-2.25|3\n4e3|5|-6.125\n"),
                                    std::string("+1.5 -2.25 +3\n4000 5 -6.125\n")}) {
        const PointCloud cloud = parse(text);
        EXPECT_EQ(cloud.points, expected) << text;
        EXPECT_EQ(cloud.recordsRead, 2U);
        EXPECT_EQ(cloud.kind, InputKind::Text);
        EXPECT_TRUE(cloud.crsWkt.empty());
    }
}

TEST(TextReader, SkipsBlankAndCommentLines_AndExtraColumns) {
    const PointCloud cloud = parse("# exported\n\n  \n1 2 3 id=7 extra\n# more\n4 5 6 8\n");
    EXPECT_EQ(cloud.points, (std::vector<Point3>{{1, 2, 3}, {4, 5, 6}}));
}

TEST(TextReader, FindsColumnsByHeaderName) {
    const std::string text = "id,Easting,Northing,Elevation\n7,100.5,200.5,10\n8,101,201,11\n";
    EXPECT_EQ(parse(text).points, (std::vector<Point3>{{100.5, 200.5, 10}, {101, 201, 11}}));
    const std::string quoted = "\"z\";\"y\";\"x\"\n1;2;3\n";
    EXPECT_EQ(parse(quoted).points, (std::vector<Point3>{{3, 2, 1}}));
}

TEST(TextReader, UsesColumnsOption_ByNumberAndByName) {
    TextReadOptions byNumber;
    byNumber.columns = {"3", "1", "5"};
    EXPECT_EQ(parse("10 20 30 40 50\n", byNumber).points, (std::vector<Point3>{{30, 10, 50}}));

    TextReadOptions byName;
    byName.columns = {"lon", "LAT", "h_m"};
    EXPECT_EQ(parse("h_m|lat|lon\n5|45|-71\n", byName).points, (std::vector<Point3>{{-71, 45, 5}}));

    // A header skipped when the numbered columns of the first line are not numbers.
    TextReadOptions skipName;
    skipName.columns = {"2", "3", "4"};
    EXPECT_EQ(parse("name x y z\nA 1 2 3\n", skipName).points, (std::vector<Point3>{{1, 2, 3}}));
}

TEST(TextReader, ConvertsNumbersExactly) {
    std::mt19937_64 random(42);
    std::uniform_real_distribution<double> coordinate(-1e7, 1e7);
    std::string text;
    std::vector<Point3> expected;
    for (int i = 0; i < 1000; ++i) {
        const Point3 p{coordinate(random), coordinate(random), coordinate(random) * 1e-4};
        char line[128];
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", p.x, p.y, p.z);
        text += line;
        expected.push_back(p);
    }
    EXPECT_EQ(parse(text).points, expected);
}

TEST(TextReader, NamesTheLine_OfEveryBadRecord) {
    EXPECT_NE(rejection("1 2 3\n4 5 six\n").find("line 2: column 3 ('six') is not a finite number"),
              std::string::npos);
    EXPECT_NE(rejection("1 2 3\n\n4 5\n").find("line 3: has 2 column(s); column 3 is needed"),
              std::string::npos);
    EXPECT_NE(rejection("1 2 nan\n").find("line 1"), std::string::npos);
    EXPECT_NE(rejection("1 2 1e999\n").find("not a finite number"), std::string::npos);
    EXPECT_NE(rejection("1,2,\n").find("line 1"), std::string::npos);
    EXPECT_NE(rejection("1 2 3\n1.2.3 4 5\n").find("line 2"), std::string::npos);
}

TEST(TextReader, ReadsANumberBelowTheSmallestDouble_AsItsRoundedValue) {
    // Finite, though from_chars calls it out of range: a double holds it as 0, or as a
    // subnormal near the smallest one.
    const PointCloud cloud = parse("1e-999 2 -1e-999\n1 2.5e-320 3\n0 1 1\n");
    ASSERT_EQ(cloud.points.size(), 3U);
    EXPECT_EQ(cloud.points[0].x, 0.0);
    EXPECT_EQ(cloud.points[0].z, 0.0);
    EXPECT_TRUE(std::signbit(cloud.points[0].z));
    EXPECT_GT(cloud.points[1].y, 0.0);
    EXPECT_LT(cloud.points[1].y, 1e-300);
    // Past the largest double is no number.
    EXPECT_NE(rejection("1 2 -1e999\n").find("not a finite number"), std::string::npos);
}

TEST(TextReader, RejectsFilesWithoutPoints_AndBinaryContent) {
    EXPECT_NE(rejection("").find("holds no point"), std::string::npos);
    EXPECT_NE(rejection("x y z\n# nothing\n").find("holds no point"), std::string::npos);
    EXPECT_NE(rejection(std::string("1 2 3\n\0\1\2", 9)).find("NUL"), std::string::npos);
    EXPECT_NE(rejection(std::string(2 << 20, '1')).find("longer than 1 MiB"), std::string::npos);
}

TEST(TextReader, RejectsBadColumnsOption) {
    EXPECT_NE(rejection("1 2 3\n", withColumns({"0", "1", "2"})).find("numbered from 1"),
              std::string::npos);
    EXPECT_NE(rejection("1 2 3\n", withColumns({"1", "2"})).find("three columns"),
              std::string::npos);
    EXPECT_NE(rejection("1 2 3\n", withColumns({"x", "y", "z"})).find("no header line"),
              std::string::npos);
    EXPECT_NE(rejection("a b c\n1 2 3\n", withColumns({"a", "b", "elev"})).find("no column 'elev'"),
              std::string::npos);
}

/// `pattern` with each "{}" replaced by `name`.
std::string spelled(std::string pattern, const std::string& name) {
    for (std::size_t at = pattern.find("{}"); at != std::string::npos; at = pattern.find("{}"))
        pattern.replace(at, 2, name);
    return pattern;
}

// A library caller's message names `columns`, the keyword it gave, not the command line's
// --columns; the error carries the keyword, and the pipeline names it the command line's way
// (Error::nameOptions).
TEST(TextReader, NamesTheColumnsOptionByKeyword_UnlessTheCallerNamesItOtherwise) {
    struct Case {
        std::vector<std::string> columns;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"1", "2"}, "{} takes three columns (x,y,z), got 2"},
        {{"1", "", "3"}, "empty entry in {}"},
        {{"1", "2", "0"}, "column '0' in {}: columns are numbered from 1"},
        {{"x", "y", "z"}, "no header line to find the columns named in {} (the first line"},
    };
    TextReadOptions named;
    const OptionNaming bracketed = [](std::string_view keyword) {
        return "<" + std::string(keyword) + ">";
    };
    for (const auto& [columns, message] : cases) {
        const std::string byKeyword = rejection("1 2 3\n", withColumns(columns));
        EXPECT_NE(byKeyword.find(spelled(message, "columns")), std::string::npos) << byKeyword;
        EXPECT_EQ(byKeyword.find("--"), std::string::npos) << byKeyword;

        named.columns = columns;
        const std::string byCaller = rejection("1 2 3\n", named, bracketed);
        EXPECT_NE(byCaller.find(spelled(message, "<columns>")), std::string::npos) << byCaller;
    }
}

TEST(TextReader, HonoursAnExplicitDelimiter) {
    TextReadOptions options;
    options.delimiter = ',';
    // With ',' a space-separated line is one field.
    EXPECT_NE(rejection("1 2 3\n", options), "");
    EXPECT_EQ(parse("1,2,3\n", options).points, (std::vector<Point3>{{1, 2, 3}}));
    options.delimiter = 'x';
    EXPECT_THROW(parse("1x2x3\n", options), InvalidInputError);
}

/// A scratch file removed at the end of the test.
class ScratchFile {
public:
    explicit ScratchFile(const std::string& name)
        : m_path(fs::temp_directory_path() /
                 ("terratin_text_" +
                  std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" + name)) {
    }
    ~ScratchFile() {
        std::error_code ignored;
        fs::remove(m_path, ignored);
    }
    ScratchFile(const ScratchFile&) = delete;
    ScratchFile& operator=(const ScratchFile&) = delete;
    [[nodiscard]] std::string path() const { return m_path.string(); }

private:
    fs::path m_path;
};

TEST(TextReader, ReadsLinesAcrossBufferBoundaries_FromAFile) {
    // About 9 MiB: two 4 MiB buffers and a partial third, lines straddling each boundary.
    ScratchFile file("big.csv");
    {
        std::ofstream out(file.path(), std::ios::binary);
        out << "x;y;z\r\n";
        for (int i = 0; i < 400000; ++i)
            out << i << ".25;" << -(i + 1) << ".5;" << (i % 977) << ".125\r\n";
    }
    int calls = 0;
    const PointCloud cloud =
        readTextPoints(file.path(), {}, [&](double fraction, std::string_view) {
            ++calls;
            EXPECT_LE(fraction, 1.0);
            return true;
        });
    EXPECT_GE(calls, 3);
    ASSERT_EQ(cloud.points.size(), 400000U);
    for (std::size_t i = 0; i < cloud.points.size(); ++i) {
        const double n = static_cast<double>(i);
        ASSERT_EQ(cloud.points[i],
                  (Point3{n + 0.25, -n - 1.5, static_cast<double>(i % 977) + 0.125}))
            << "line " << i + 2;
    }
}

// A UTF-8 byte order mark at the start of a file is skipped, not read as part of the first
// field ("column 1 is not a finite number").
TEST(TextReader, SkipsAUtf8ByteOrderMark_D20) {
    const PointCloud cloud = parse("\xEF\xBB\xBF"
                                   "1 2 3\n4 5 6\n");
    ASSERT_EQ(cloud.points.size(), 2u);
    EXPECT_EQ(cloud.points[0].x, 1.0);
    const PointCloud named = parse("\xEF\xBB\xBF"
                                   "x,y,z\n1,2,3\n");
    ASSERT_EQ(named.points.size(), 1u);
    // Only at the start of the file.
    EXPECT_NE(rejection("1 2 3\n\xEF\xBB\xBF"
                        "4 5 6\n"),
              "");
}

TEST(TextReader, ThrowsIoError_ForAMissingFile) {
    EXPECT_THROW(readTextPoints("/no/such/points.xyz"), IoError);
}

TEST(TextReader, ReadsNcsuPipeDelimitedPoints) {
    const fs::path path = fs::path(TERRATIN_SHARED_DEMS) / "ncsu__lid_mr_pts.txt";
    if (!fs::exists(path))
        GTEST_SKIP() << path << " not available";
    const PointCloud cloud = readTextPoints(path.string());
    EXPECT_EQ(cloud.points.size(), 36944U);
    EXPECT_EQ(cloud.recordsRead, 36944U);
    // The file's first line: 639046.19571947|220854.10657942|117.7127155|1|1
    EXPECT_EQ(cloud.points.front(), (Point3{639046.19571947, 220854.10657942, 117.7127155}));
    // The line count of the file, independently.
    std::ifstream in(path);
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);)
        lines += line.empty() ? 0 : 1;
    EXPECT_EQ(lines, cloud.points.size());
}

} // namespace
} // namespace terratin::io
