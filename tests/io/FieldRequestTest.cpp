#include "IoTestSupport.h"

#include "octrace/io/FieldRequest.h"
#include "octrace/util/Error.h"

using namespace octrace;

TEST(FieldRequest, ParsesFourCommaSeparatedDegrees) {
    auto r = io::parseRegion("120,180, 10 ,60");
    EXPECT_EQ(r, (std::array<double, 4>{120, 180, 10, 60}));
    EXPECT_EQ(io::parseRegion("170,-170,-5.5,5.5")[1], -170.0);
}

TEST(FieldRequest, RejectsMalformedRegions) {
    EXPECT_THROW_WITH(io::parseRegion("120,180,10"), UsageError, "expected 4 values LON0,LON1,LAT0,LAT1 in degrees, got 3");
    EXPECT_THROW_WITH(io::parseRegion("120,east,10,60"), UsageError, "'east' is not a number");
    EXPECT_THROW_WITH(io::parseRegion("120,180,60,10"), UsageError, "LAT0 must be less than LAT1");
    EXPECT_THROW_WITH(io::parseRegion("0,10,-95,10"), UsageError, "latitudes must lie in -90..90");
    EXPECT_THROW_WITH(io::parseRegion("-180,360,0,10"), UsageError, "spans 540 degrees, at most 360 allowed");
}
