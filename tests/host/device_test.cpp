// device_test.cpp: device discovery and the --device / RAYDRIVE_DEVICE choice.
#include <gtest/gtest.h>

#include <cstdlib>

#include "ocl/device.h"

using namespace rd;

TEST(Devices, ListsPocl) {
    auto devices = listDevices();
    ASSERT_FALSE(devices.empty());
    bool pocl = false;
    for (const auto& d : devices) pocl |= d.isPocl();
    EXPECT_TRUE(pocl) << "PoCL is the device every test runs on";
}

TEST(Devices, DefaultIsPoclCpu) {
    unsetenv("RAYDRIVE_DEVICE");
    DeviceInfo d = selectDevice("");
    EXPECT_TRUE(d.isPocl());
    EXPECT_TRUE(d.type & CL_DEVICE_TYPE_CPU);
}

TEST(Devices, ByIndexAndSubstring) {
    EXPECT_EQ(selectDevice("0").index, 0);
    EXPECT_TRUE(selectDevice("PORTABLE computing").isPocl());  // case-insensitive
}

TEST(Devices, EnvironmentVariable) {
    setenv("RAYDRIVE_DEVICE", "nosuchdevice", 1);
    EXPECT_THROW(selectDevice(""), std::runtime_error);
    EXPECT_NO_THROW(selectDevice("0"));  // the command line wins over the environment
    unsetenv("RAYDRIVE_DEVICE");
}

TEST(Devices, UnknownDeviceNamesTheAvailableOnes) {
    try {
        selectDevice("99");
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("available"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("0: "), std::string::npos) << e.what();
    }
}
