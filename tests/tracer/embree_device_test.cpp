// Tests of the Embree device wrapper.
#include "tracer/embree/embree_device.h"

#include <string>

#include <embree3/rtcore.h>
#include <gtest/gtest.h>

#include "common/error.h"

namespace arbor::tracer {

TEST(EmbreeDevice, CreatesADeviceOfVersion3_13) {
  EmbreeDevice device("threads=1");
  EXPECT_NE(device.get(), nullptr);
  EXPECT_EQ(EmbreeDevice::version().rfind("3.13.", 0), 0u) << EmbreeDevice::version();
  EXPECT_NO_THROW(device.check("doing nothing"));
}

TEST(EmbreeDevice, ErrorsBecomeExceptionsWithEmbreesMessage) {
  EmbreeDevice device("threads=1");
  RTCGeometry g = rtcNewGeometry(device.get(), static_cast<RTCGeometryType>(9999));
  EXPECT_EQ(g, nullptr);
  try {
    device.check("making a geometry");
    FAIL() << "no error reported";
  } catch (const RuntimeFailure& e) {
    EXPECT_NE(std::string(e.what()).find("Embree failed while making a geometry"),
              std::string::npos);
  }
  EXPECT_NO_THROW(device.check("nothing"));  // the error was consumed
}

}  // namespace arbor::tracer
