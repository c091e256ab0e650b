#include "terratin/geometry/triangle_attributes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace terratin {
namespace {

// Angles come from atan2 of products of coordinate differences: a few ulps of 360 degrees.
constexpr double kAngleToleranceDeg = 1e-9;

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

// A counter-clockwise right triangle with legs of 10 m on the plane z = z0 + p x + q y,
// placed at UTM-like coordinates so that the large-offset case is what is tested.
struct PlaneTriangle {
    Point3 a, b, c;
};

PlaneTriangle onPlane(double p, double q, double z0 = 100.0) {
    constexpr double kX0 = 500000.0;
    constexpr double kY0 = 5000000.0;
    auto at = [&](double dx, double dy) {
        return Point3{kX0 + dx, kY0 + dy, z0 + p * dx + q * dy};
    };
    return {at(0.0, 0.0), at(10.0, 0.0), at(0.0, 10.0)};
}

TriangleAttributes attributesOf(const PlaneTriangle& t) {
    return computeTriangleAttributes(t.a, t.b, t.c);
}

TEST(TriangleAttributes, AspectIs90_WhenPlaneDipsToTheEast) {
    const auto attributes = attributesOf(onPlane(-0.5, 0.0));
    EXPECT_NEAR(attributes.aspectDeg, 90.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs0_WhenPlaneDipsToTheNorth) {
    const auto attributes = attributesOf(onPlane(0.0, -0.5));
    EXPECT_NEAR(attributes.aspectDeg, 0.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs180_WhenPlaneDipsToTheSouth) {
    const auto attributes = attributesOf(onPlane(0.0, 0.5));
    EXPECT_NEAR(attributes.aspectDeg, 180.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs270_WhenPlaneDipsToTheWest) {
    const auto attributes = attributesOf(onPlane(0.5, 0.0));
    EXPECT_NEAR(attributes.aspectDeg, 270.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIs225_WhenPlaneDipsToTheSouthWest) {
    // z rises to the north-east, so water runs south-west.
    const auto attributes = attributesOf(onPlane(0.3, 0.3));
    EXPECT_NEAR(attributes.aspectDeg, 225.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIsJustBelow360_WhenDownhillIsSlightlyWestOfNorth) {
    const auto attributes = attributesOf(onPlane(1e-6, -1.0));
    EXPECT_LT(attributes.aspectDeg, 360.0);
    EXPECT_NEAR(attributes.aspectDeg, 360.0 - 1e-6 * kDegreesPerRadian, 1e-6);
}

TEST(TriangleAttributes, AspectStaysInRange_WhenDownhillIsATinyAngleWestOfNorth) {
    // -5.7e-299 degrees + 360 rounds to 360, which is outside [0, 360): it must come out as 0.
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 0.0}, {1.0, 0.0, 1e-300}, {0.0, 1.0, -1.0});
    EXPECT_GE(attributes.aspectDeg, 0.0);
    EXPECT_LT(attributes.aspectDeg, 360.0);
    EXPECT_EQ(attributes.aspectDeg, 0.0);
}

TEST(TriangleAttributes, SlopeIs45_WhenGradientIsOne) {
    const auto attributes = attributesOf(onPlane(-1.0, 0.0));
    EXPECT_NEAR(attributes.slopeDeg, 45.0, kAngleToleranceDeg);
    EXPECT_NEAR(attributes.aspectDeg, 90.0, kAngleToleranceDeg);
}

TEST(TriangleAttributes, SlopeMatchesArctanOfGradient_WhenGradientIsOblique) {
    const double p = 0.3;
    const double q = -0.4; // |grad z| = 0.5
    const auto attributes = attributesOf(onPlane(p, q));
    EXPECT_NEAR(attributes.slopeDeg, std::atan(0.5) * kDegreesPerRadian, kAngleToleranceDeg);
    // Downhill is (-p, -q) = (-0.3, 0.4): north-west.
    EXPECT_NEAR(attributes.aspectDeg, std::atan2(-0.3, 0.4) * kDegreesPerRadian + 360.0,
                kAngleToleranceDeg);
}

TEST(TriangleAttributes, AspectIsMinusOneAndSlopeZero_WhenTriangleIsFlat) {
    const auto attributes = attributesOf(onPlane(0.0, 0.0, 1234.5));
    EXPECT_EQ(attributes.aspectDeg, -1.0);
    EXPECT_EQ(attributes.slopeDeg, 0.0);
    EXPECT_EQ(attributes.zMin, 1234.5);
    EXPECT_EQ(attributes.zMax, 1234.5);
    EXPECT_EQ(attributes.zMean, 1234.5);
}

TEST(TriangleAttributes, ResultsAreTheSame_WhenCornersAreClockwise) {
    const auto t = onPlane(0.2, -0.7);
    const auto ccw = computeTriangleAttributes(t.a, t.b, t.c);
    for (const auto& cw :
         {computeTriangleAttributes(t.a, t.c, t.b), computeTriangleAttributes(t.c, t.b, t.a),
          computeTriangleAttributes(t.b, t.a, t.c)}) {
        EXPECT_NEAR(cw.slopeDeg, ccw.slopeDeg, kAngleToleranceDeg);
        EXPECT_NEAR(cw.aspectDeg, ccw.aspectDeg, kAngleToleranceDeg);
        EXPECT_DOUBLE_EQ(cw.area2d, ccw.area2d);
        EXPECT_EQ(cw.zMin, ccw.zMin);
        EXPECT_EQ(cw.zMax, ccw.zMax);
        EXPECT_DOUBLE_EQ(cw.zMean, ccw.zMean);
    }
}

TEST(TriangleAttributes, AreaIsPlanimetric_WhenTriangleIsSteep) {
    // Legs of 10 m: the plan area is 50 m^2 however steep the plane.
    EXPECT_DOUBLE_EQ(attributesOf(onPlane(0.0, 0.0)).area2d, 50.0);
    EXPECT_DOUBLE_EQ(attributesOf(onPlane(3.0, -2.0)).area2d, 50.0);
}

TEST(TriangleAttributes, ZStatisticsAreOfTheCorners_WhenCornersDiffer) {
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 7.0}, {4.0, 0.0, -2.0}, {0.0, 3.0, 1.0});
    EXPECT_EQ(attributes.zMin, -2.0);
    EXPECT_EQ(attributes.zMax, 7.0);
    EXPECT_DOUBLE_EQ(attributes.zMean, 2.0);
    EXPECT_DOUBLE_EQ(attributes.area2d, 6.0);
}

TEST(TriangleAttributes, SlopeZeroAspectMinusOneAreaZero_WhenCornersAreCollinearInPlan) {
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 0.0}, {1.0, 1.0, 5.0}, {2.0, 2.0, 1.0});
    EXPECT_EQ(attributes.slopeDeg, 0.0);
    EXPECT_EQ(attributes.aspectDeg, -1.0);
    EXPECT_EQ(attributes.area2d, 0.0);
    EXPECT_EQ(attributes.zMin, 0.0);
    EXPECT_EQ(attributes.zMax, 5.0);
}

TEST(TriangleAttributes, SlopeApproaches90_WhenPlaneIsNearlyVertical) {
    const auto attributes = attributesOf(onPlane(0.0, -1e6));
    EXPECT_GT(attributes.slopeDeg, 89.99);
    EXPECT_LE(attributes.slopeDeg, 90.0);
    EXPECT_NEAR(attributes.aspectDeg, 0.0, kAngleToleranceDeg);
}

// A 3-4-5 tilted plane where every attribute is exact in floating point: legs of 20 m, the
// corners 9 m and 12 m above the first, so the normal is (-180, -240, 400) with length 500
// (horizontal part 300 = 3/4 of 400). UTM-like offsets make the edge differences the test.
struct ExactTiltedPlane {
    static constexpr double kX0 = 500000.0;
    static constexpr double kY0 = 5000000.0;
    static constexpr double kZ0 = 1000.0;
    Point3 a{kX0, kY0, kZ0};
    Point3 b{kX0 + 20.0, kY0, kZ0 + 9.0};
    Point3 c{kX0, kY0 + 20.0, kZ0 + 12.0};
};

TEST(TriangleAttributesExact, AreasNormalAndSlopePercentAreExact_WhenPlaneIsTilted345) {
    const ExactTiltedPlane plane;
    const auto attributes = computeTriangleAttributes(plane.a, plane.b, plane.c);
    EXPECT_EQ(attributes.area2d, 200.0);
    EXPECT_EQ(attributes.area3d, 250.0); // 3D area = 2D area / cos(slope) = 200 / 0.8
    EXPECT_EQ(attributes.nx, -0.36);
    EXPECT_EQ(attributes.ny, -0.48);
    EXPECT_EQ(attributes.nz, 0.8);
    EXPECT_EQ(attributes.slopePct, 75.0); // rise over run 3/4
    EXPECT_EQ(attributes.slopeDeg, std::atan2(3.0, 4.0) * kDegreesPerRadian);
    // Uphill is north-east (z grows with x and y), so the plane faces south-west:
    // downhill (-0.36, -0.48) is atan2(-3, -4) clockwise from north, + 360.
    EXPECT_EQ(attributes.aspectDeg, std::atan2(-3.0, -4.0) * kDegreesPerRadian + 360.0);
    EXPECT_NEAR(attributes.aspectDeg, 216.86989764584402, 1e-12);
    EXPECT_EQ(attributes.z1, 1000.0);
    EXPECT_EQ(attributes.z2, 1009.0);
    EXPECT_EQ(attributes.z3, 1012.0);
    EXPECT_EQ(attributes.zMin, 1000.0);
    EXPECT_EQ(attributes.zMax, 1012.0);
    EXPECT_EQ(attributes.zMean, 3021.0 / 3.0);
}

TEST(TriangleAttributesExact, EveryAttributeButCornerZIsTheSame_WhenCornersAreClockwise) {
    const ExactTiltedPlane plane;
    const auto ccw = computeTriangleAttributes(plane.a, plane.b, plane.c);
    const auto cw = computeTriangleAttributes(plane.a, plane.c, plane.b);
    EXPECT_EQ(cw.area2d, ccw.area2d);
    EXPECT_EQ(cw.area3d, ccw.area3d);
    EXPECT_EQ(cw.nx, ccw.nx);
    EXPECT_EQ(cw.ny, ccw.ny);
    EXPECT_EQ(cw.nz, ccw.nz);
    EXPECT_EQ(cw.slopePct, ccw.slopePct);
    EXPECT_EQ(cw.slopeDeg, ccw.slopeDeg);
    EXPECT_EQ(cw.aspectDeg, ccw.aspectDeg);
    EXPECT_EQ(cw.z2, ccw.z3); // corner z follow the corners as given
    EXPECT_EQ(cw.z3, ccw.z2);
}

TEST(TriangleAttributesExact, NormalIsUpAndAreasEqual_WhenTriangleIsFlat) {
    const auto attributes = computeTriangleAttributes(
        {500000.0, 5000000.0, 7.0}, {500010.0, 5000000.0, 7.0}, {500000.0, 5000010.0, 7.0});
    EXPECT_EQ(attributes.nx, 0.0);
    EXPECT_EQ(attributes.ny, 0.0);
    EXPECT_EQ(attributes.nz, 1.0);
    EXPECT_EQ(attributes.area2d, 50.0);
    EXPECT_EQ(attributes.area3d, 50.0);
    EXPECT_EQ(attributes.slopePct, 0.0);
    EXPECT_EQ(attributes.aspectDeg, -1.0);
}

TEST(TriangleAttributesExact, SlopePercentIs100_WhenSlopeIs45Degrees) {
    const auto attributes = attributesOf(onPlane(0.0, 1.0));
    EXPECT_EQ(attributes.slopePct, 100.0);
    EXPECT_EQ(attributes.area3d, 50.0 * std::sqrt(2.0));
    EXPECT_NEAR(attributes.slopeDeg, 45.0, kAngleToleranceDeg);
    EXPECT_EQ(attributes.aspectDeg, 180.0);
}

TEST(TriangleAttributesExact, VerticalPlaneHasHorizontalNormalAndNoSlope_WhenCollinearInPlan) {
    // Corners on the line y = x in plan, z varying: a vertical triangle of 3D area
    // |(1,1,5) x (2,2,1)| / 2 = |(-9, 9, 0)| / 2.
    const auto attributes =
        computeTriangleAttributes({0.0, 0.0, 0.0}, {1.0, 1.0, 5.0}, {2.0, 2.0, 1.0});
    EXPECT_EQ(attributes.area2d, 0.0);
    EXPECT_EQ(attributes.area3d, 0.5 * std::hypot(9.0, 9.0));
    EXPECT_EQ(attributes.nz, 0.0);
    EXPECT_DOUBLE_EQ(attributes.nx, std::sqrt(0.5)); // first non-zero component positive
    EXPECT_DOUBLE_EQ(attributes.ny, -std::sqrt(0.5));
    EXPECT_EQ(attributes.slopePct, 0.0);
}

} // namespace
} // namespace terratin

namespace terratin {
namespace {

// Centres of the first row of a 30-degree rotated geotransform at UTM coordinates, computed
// as HeightGrid::cellCentre does: collinear in exact arithmetic, not after rounding.
Point3 rotatedRowCentre(int col) {
    const double angle = 30.0 * std::numbers::pi / 180.0;
    const double c[6] = {455900.0,  10.0 * std::cos(angle), 10.0 * std::sin(angle),
                         5104100.0, 10.0 * std::sin(angle), -10.0 * std::cos(angle)};
    const double px = col + 0.5;
    const double py = 0.5;
    return {c[0] + px * c[1] + py * c[2], c[3] + px * c[4] + py * c[5], 100.0 + 3.0 * col};
}

// Border slivers of a rotated raster's TIN (corners collinear but for rounding) get the slope
// and aspect of a triangle without planimetric extent, not slopes of up to 1e15 %, and keep
// their tiny positive area.
TEST(TriangleAttributes, SliverOfRoundedCollinearCentresHasNoSlope_D19) {
    int slivers = 0;
    for (int i = 0; i < 40; ++i)
        for (int j = i + 1; j < 40; ++j) {
            const Point3 a = rotatedRowCentre(i);
            const Point3 b = rotatedRowCentre(j);
            const Point3 c = rotatedRowCentre((i + j) / 2 == i ? j + 1 : (i + j) / 2);
            const double doubleArea = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            if (doubleArea == 0.0)
                continue;
            ++slivers;
            const TriangleAttributes attributes = computeTriangleAttributes(a, b, c);
            EXPECT_EQ(attributes.slopeDeg, 0.0);
            EXPECT_EQ(attributes.slopePct, 0.0);
            EXPECT_EQ(attributes.aspectDeg, -1.0);
            EXPECT_GT(attributes.area2d, 0.0);
            EXPECT_LT(attributes.area2d, 1e-6);
            EXPECT_TRUE(std::isfinite(attributes.nx) && std::isfinite(attributes.ny) &&
                        std::isfinite(attributes.nz));
        }
    EXPECT_GT(slivers, 0) << "no rounded-off triple found: the test tests nothing";
}

// The rule is about rounding, not thinness: a real thin triangle (1 mm high over a 30 m
// edge, at UTM coordinates) keeps its slope and aspect.
TEST(TriangleAttributes, ThinTriangleKeepsItsSlope_WhenHeightIsFarAboveRounding_D19) {
    const Point3 a{500000.0, 5000000.0, 100.0};
    const Point3 b{500030.0, 5000000.0, 100.0};
    const Point3 c{500015.0, 5000000.001, 100.0005}; // rises 0.5 mm over 1 mm northwards
    const TriangleAttributes attributes = computeTriangleAttributes(a, b, c);
    EXPECT_NEAR(attributes.slopePct, 50.0, 1e-3);
    EXPECT_NEAR(attributes.aspectDeg, 180.0, 1e-3); // downhill to the south
}

} // namespace
} // namespace terratin
