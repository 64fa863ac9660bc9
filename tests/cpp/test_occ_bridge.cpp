#include <gtest/gtest.h>
TEST(OccBridge, Placeholder) {}
