#include "output/exr_writer.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>

#include <vector>

#include "tests/output/test_dir.h"

namespace radfarm {
namespace {

TEST(ExrWriterTest, RoundTripsLinearFloats) {
  TestDir dir;
  const std::string path = dir.File("image.exr");
  Image image;
  image.width = 5;
  image.height = 3;
  for (uint32_t i = 0; i < 15; ++i) image.pixels.push_back({0.1 * i, 1000.5 + i, 1e-6 * i});
  ASSERT_TRUE(WriteExr(path, image).ok());

  Imf::InputFile file(path.c_str());
  const Imath::Box2i window = file.header().dataWindow();
  ASSERT_EQ(window.max.x - window.min.x + 1, 5);
  ASSERT_EQ(window.max.y - window.min.y + 1, 3);
  for (const char* name : {"R", "G", "B"}) {
    const Imf::Channel* channel = file.header().channels().findChannel(name);
    ASSERT_NE(channel, nullptr) << name;
    EXPECT_EQ(channel->type, Imf::FLOAT);
  }
  std::vector<float> r(15), g(15), b(15);
  Imf::FrameBuffer frame;
  frame.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.data()), sizeof(float),
                               5 * sizeof(float)));
  frame.insert("G", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(g.data()), sizeof(float),
                               5 * sizeof(float)));
  frame.insert("B", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(b.data()), sizeof(float),
                               5 * sizeof(float)));
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  for (uint32_t i = 0; i < 15; ++i) {
    EXPECT_EQ(r[i], static_cast<float>(image.pixels[i].r)) << i;
    EXPECT_EQ(g[i], static_cast<float>(image.pixels[i].g)) << i;
    EXPECT_EQ(b[i], static_cast<float>(image.pixels[i].b)) << i;
  }
  EXPECT_EQ(dir.Entries(), std::vector<std::string>{"image.exr"});
}

TEST(ExrWriterTest, ErrorsNameThePath) {
  TestDir dir;
  Image image;
  image.width = 1;
  image.height = 1;
  image.pixels = {{1, 2, 3}};
  const std::string missing = dir.File("missing/image.exr");
  const Status status = WriteExr(missing, image);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.error().find(missing), std::string::npos) << status.error();

  image.pixels.clear();  // size mismatch
  const Status bad = WriteExr(dir.File("bad.exr"), image);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("bad.exr"), std::string::npos);
}

}  // namespace
}  // namespace radfarm
