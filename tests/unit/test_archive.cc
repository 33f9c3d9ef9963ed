// Archive and checkpoint files: what is saved is read back, and a foreign or truncated
// file is refused.
#include <gtest/gtest.h>

#include <lme_mpm/base/archive.h>
#include <lme_mpm/base/checkpoint.h>
#include <lme_mpm/base/input.h>

#include "../test_helpers.h"

#include <fstream>
#include <sstream>

using namespace lme_mpm;

namespace
{
struct Fields
{
  int i    = 0;
  double x = 0;
  std::vector<double> v;
  std::string s;
  std::vector<std::string> names;
  std::pair<int, double> p;
  void serialize(Archive &ar) { ar(i, x, v, s, names, p); }
};
} // namespace

TEST(Archive, WhatIsWrittenIsReadBack)
{
  Fields out;
  out.i     = -7;
  out.x     = 0.1;
  out.v     = {1, 2.5, -3};
  out.s     = "with spaces\nand a line";
  out.names = {"a", "", "ccc"};
  out.p     = {4, 1e-300};
  std::stringstream buffer;
  {
    Archive ar(static_cast<std::ostream &>(buffer));
    out.serialize(ar);
    EXPECT_TRUE(ar.good());
    EXPECT_FALSE(ar.loading());
  }
  Fields in;
  Archive ar(static_cast<std::istream &>(buffer));
  EXPECT_TRUE(ar.loading());
  in.serialize(ar);
  EXPECT_TRUE(ar.good());
  EXPECT_EQ(in.i, out.i);
  EXPECT_EQ(in.x, out.x);
  EXPECT_EQ(in.v, out.v);
  EXPECT_EQ(in.s, out.s);
  EXPECT_EQ(in.names, out.names);
  EXPECT_EQ(in.p, out.p);
}

TEST(Archive, TruncatedInputIsNotGood)
{
  Fields out;
  out.v.assign(100, 1.0);
  std::stringstream buffer;
  Archive writer(static_cast<std::ostream &>(buffer));
  out.serialize(writer);
  std::stringstream cut(buffer.str().substr(0, 200));
  Fields in;
  Archive reader(static_cast<std::istream &>(cut));
  in.serialize(reader);
  EXPECT_FALSE(reader.good());
}

TEST(Checkpoint, FileRoundTripAndForeignFilesAreRefused)
{
  const std::string dir = lme_mpm_test::scratch("archive");
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/checkpoint.bin";
  Fields out;
  out.v = {3, 4};
  checkpoint::write(file, [&](Archive &ar) { out.serialize(ar); });
  Fields in;
  checkpoint::read(file, [&](Archive &ar) { in.serialize(ar); });
  EXPECT_EQ(in.v, out.v);
  // Written again: the file it replaces is kept beside it.
  checkpoint::write(file, [&](Archive &ar) { out.serialize(ar); });
  EXPECT_TRUE(std::filesystem::exists(file + ".prev"));

  std::ofstream(dir + "/foreign.bin") << "not a checkpoint at all";
  std::string message;
  try
  {
    checkpoint::read(dir + "/foreign.bin", [&](Archive &ar) { in.serialize(ar); });
  }
  catch (const std::exception &e)
  {
    message = input::concise_message(e);
  }
  EXPECT_NE(message.find("--resume"), std::string::npos) << message;
  message.clear();
  try
  {
    checkpoint::read(dir + "/missing.bin", [&](Archive &ar) { in.serialize(ar); });
  }
  catch (const std::exception &e)
  {
    message = input::concise_message(e);
  }
  EXPECT_NE(message.find("missing.bin"), std::string::npos) << message;
}
