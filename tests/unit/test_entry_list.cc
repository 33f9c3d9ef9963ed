// EntryList: one list declares the entries and reads them back; a plug-in that names
// its Entries struct gets them declared by the registry.
#include <gtest/gtest.h>

#include <lme_mpm/base/parameters.h>
#include <lme_mpm/base/registry.h>

#include <memory>

using namespace lme_mpm;

namespace
{
struct Sample
{
  double length      = 0;
  unsigned int count = 0;
  bool flag          = false;
  std::string name   = "unset";
  void entries(EntryList &list)
  {
    list.add("Length", length, "2.5", dealii::Patterns::Double(0), "A length.");
    list.add("Count", count, "3", dealii::Patterns::Integer(0), "A count.");
    list.add("Flag", flag, "true", dealii::Patterns::Bool(), "A flag.");
    list.add("Name", name, "alpha", dealii::Patterns::Anything(), "A name.");
  }
};

struct Plugin
{
  virtual ~Plugin() = default;
};
struct Context
{
};
struct WithEntries : Plugin
{
  using Entries = Sample;
  WithEntries(dealii::ParameterHandler &prm, const Context &)
      : values(EntryList::parse<Sample>(prm))
  {
  }
  Sample values;
};
using SampleRegistry = Registry<Plugin, Context>;
} // namespace

TEST(EntryList, DeclaresDefaultsAndReadsTheSameEntries)
{
  dealii::ParameterHandler prm;
  EntryList::declare<Sample>(prm);
  const Sample defaults = EntryList::parse<Sample>(prm);
  EXPECT_EQ(defaults.length, 2.5);
  EXPECT_EQ(defaults.count, 3u);
  EXPECT_TRUE(defaults.flag);
  EXPECT_EQ(defaults.name, "alpha");

  prm.set("Length", "0.125");
  prm.set("Count", "7");
  prm.set("Flag", "false");
  prm.set("Name", "  beta gamma  ");
  const Sample read = EntryList::parse<Sample>(prm);
  EXPECT_EQ(read.length, 0.125);
  EXPECT_EQ(read.count, 7u);
  EXPECT_FALSE(read.flag);
  // Text entries come without the blanks around them.
  EXPECT_EQ(read.name, "beta gamma");
  // An entry the list does not declare is unknown to the handler.
  EXPECT_ANY_THROW(prm.set("Width", "1"));
}

TEST(EntryList, RegistryDeclaresAPluginsEntriesStruct)
{
  ASSERT_TRUE((register_plugin<SampleRegistry, WithEntries>(
      "with entries", "a plug-in with an Entries struct",
      PluginEntries::own_subsection)));
  dealii::ParameterHandler prm;
  SampleRegistry::instance().declare_all(prm);
  prm.enter_subsection("with entries");
  prm.set("Length", "4");
  prm.leave_subsection();
  const auto plugin = SampleRegistry::instance().create("with entries", prm, Context());
  EXPECT_EQ(dynamic_cast<const WithEntries &>(*plugin).values.length, 4.0);
  EXPECT_EQ(dynamic_cast<const WithEntries &>(*plugin).values.name, "alpha");
}
