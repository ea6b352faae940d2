// format_bytes: decimal units with the precision the memory messages use.
#include <panelrad/support/byte_size.hpp>

#include <gtest/gtest.h>

namespace {

using panelrad::format_bytes;

TEST(ByteSize, DecimalUnits) {
  EXPECT_EQ(format_bytes(0), "0 B");
  EXPECT_EQ(format_bytes(999), "999 B");
  EXPECT_EQ(format_bytes(1000), "1.0 kB");
  EXPECT_EQ(format_bytes(4096), "4.1 kB");
  EXPECT_EQ(format_bytes(2.7e6), "2.7 MB");
  EXPECT_EQ(format_bytes(999.9e6), "999.9 MB");
  EXPECT_EQ(format_bytes(1e9), "1.00 GB");
  EXPECT_EQ(format_bytes(309.2412e9), "309.24 GB");
  EXPECT_EQ(format_bytes(12345e9), "12345.00 GB");
}

}  // namespace
