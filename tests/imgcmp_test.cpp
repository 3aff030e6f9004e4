// host/imgcmp's defect metric: clusters of wrong pixels, 8-connected, against a
// threshold on the channel error.
#include <gtest/gtest.h>

#include "image.hpp"

namespace {

namespace imgcmp = mc1::imgcmp;

// b is a copy of a with the green channel of the given pixels off by `delta`.
imgcmp::Image with_errors(const imgcmp::Image& a, std::initializer_list<std::pair<int, int>> pixels, int delta) {
  imgcmp::Image b = a;
  for (auto [x, y] : pixels) b.at(x, y)[1] = static_cast<std::uint8_t>(b.at(x, y)[1] + delta);
  return b;
}

TEST(ImgcmpDefects, IdenticalImagesHaveNone) {
  imgcmp::Image a(7, 5);
  imgcmp::Defects d = imgcmp::defects(a, a, 32);
  EXPECT_EQ(d.wrong_pixels, 0);
  EXPECT_TRUE(d.clusters.empty());
}

TEST(ImgcmpDefects, DiagonalNeighboursJoinAClusterAndTheThresholdIsExclusive) {
  imgcmp::Image a(10, 8);
  // A diagonal run of 3 (one cluster), a lone pixel, and a pixel exactly at the
  // threshold (not wrong).
  imgcmp::Image b = with_errors(a, {{1, 1}, {2, 2}, {3, 3}, {8, 6}}, 33);
  b.at(5, 0)[0] = 32;
  imgcmp::Defects d = imgcmp::defects(a, b, 32);
  EXPECT_EQ(d.wrong_pixels, 4);
  ASSERT_EQ(d.clusters.size(), 2u);
  EXPECT_EQ(d.clusters[0].pixels, 3);
  EXPECT_EQ(d.clusters[0].x0, 1);
  EXPECT_EQ(d.clusters[0].y0, 1);
  EXPECT_EQ(d.clusters[0].x1, 3);
  EXPECT_EQ(d.clusters[0].y1, 3);
  EXPECT_EQ(d.clusters[1].pixels, 1);
  EXPECT_EQ(d.clusters[1].x0, 8);
  EXPECT_EQ(d.clusters[1].y1, 6);
  EXPECT_EQ(imgcmp::defects(a, b, 31).wrong_pixels, 5);
}

TEST(ImgcmpDefects, ASkippedPixelSplitsClustersAndAFrameSizedOneIsCounted) {
  imgcmp::Image a(6, 3);
  imgcmp::Defects d = imgcmp::defects(a, with_errors(a, {{0, 0}, {2, 0}, {4, 2}, {5, 2}}, 100), 32);
  ASSERT_EQ(d.clusters.size(), 3u);
  EXPECT_EQ(d.clusters[0].pixels, 2);
  EXPECT_EQ(d.clusters[0].x0, 4);
  imgcmp::Image big(300, 200), other(300, 200);
  for (auto& v : other.rgb) v = 200;
  d = imgcmp::defects(big, other, 32);
  ASSERT_EQ(d.clusters.size(), 1u);
  EXPECT_EQ(d.clusters[0].pixels, 300 * 200);
  EXPECT_EQ(d.clusters[0].x1, 299);
  EXPECT_EQ(d.clusters[0].y1, 199);
}

TEST(ImgcmpDefects, DifferentSizesAreRefused) {
  EXPECT_THROW(imgcmp::defects(imgcmp::Image(2, 2), imgcmp::Image(2, 3), 32), imgcmp::ImageError);
}

}  // namespace
