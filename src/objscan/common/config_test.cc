#include "objscan/common/config.h"

#include <gtest/gtest.h>

#include "objscan/common/error.h"

namespace objscan::config {
namespace {

struct Inner {
  double size_m = 0.5;
  std::vector<double> weights = {1.0, 2.0};
  template <class V>
  void Visit(V& v) {
    v("size_m", size_m);
    v("weights", weights);
  }
  void Validate() const { RequirePositive("inner.size_m", size_m); }
};

struct Outer {
  int count = 3;
  bool noise = true;
  std::string name = "a";
  Inner inner;
  template <class V>
  void Visit(V& v) {
    v("count", count);
    v("noise", noise);
    v("name", name);
    v("inner", inner);
  }
  void Validate() const { inner.Validate(); }
};

TEST(ConfigTest, AppliesYamlAndOverrides) {
  RawConfig raw = RawConfig::FromYamlString("count: 7\ninner:\n  size_m: 0.25\n  weights: [3, 4.5]\n", "t.yaml");
  raw.SetFromAssignment("noise=false");
  Outer o;
  Apply(raw, &o);
  EXPECT_EQ(o.count, 7);
  EXPECT_FALSE(o.noise);
  EXPECT_DOUBLE_EQ(o.inner.size_m, 0.25);
  ASSERT_EQ(o.inner.weights.size(), 2u);
  EXPECT_DOUBLE_EQ(o.inner.weights[1], 4.5);
  EXPECT_EQ(o.name, "a");
}

TEST(ConfigTest, RejectsUnknownKeyNamingIt) {
  RawConfig raw = RawConfig::FromYamlString("inner:\n  sise_m: 0.25\n", "t.yaml");
  Outer o;
  try {
    Apply(raw, &o);
    FAIL() << "unknown key accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("inner.sise_m"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("t.yaml"), std::string::npos) << e.what();
  }
}

TEST(ConfigTest, RejectsBadValuesAndInvalidRanges) {
  Outer o;
  RawConfig bad_type;
  bad_type.SetFromAssignment("count=three");
  EXPECT_THROW(Apply(bad_type, &o), ConfigError);
  RawConfig bad_range;
  bad_range.SetFromAssignment("inner.size_m=-1");
  EXPECT_THROW(Apply(bad_range, &o), ConfigError);
  RawConfig nan_value;
  nan_value.SetFromAssignment("inner.size_m=nan");
  EXPECT_THROW(Apply(nan_value, &o), ConfigError);
  RawConfig not_assignment;
  EXPECT_THROW(not_assignment.SetFromAssignment("count"), ConfigError);
  EXPECT_THROW(RawConfig::FromYamlString("a: [1, 2\n", "broken.yaml"), InputError);
}

// Infinities are no config value (they would reach float-to-integer conversions), and a YAML key that
// is a list or a mapping is a config error naming the file, not a yaml-cpp exception.
TEST(ConfigTest, RejectsInfinitiesAndKeysThatAreNotNames) {
  Outer o;
  for (const char* value : {"inf", "-inf", "infinity", "1e999"}) {
    RawConfig raw;
    raw.SetFromAssignment(std::string("inner.size_m=") + value);
    try {
      Apply(raw, &o);
      ADD_FAILURE() << value << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()), std::string("--set: config key 'inner.size_m' must be a finite number (got '") +
                                           value + "')");
    }
  }
  try {
    RawConfig::FromYamlString("inner:\n  [a, b]: 1\n", "keys.yaml");
    ADD_FAILURE() << "a list as key accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "keys.yaml: a key under 'inner' is not a name (a list or a mapping)");
  }
  try {
    RawConfig::FromYamlString("{a: 1}: 2\n", "keys.yaml");
    ADD_FAILURE() << "a mapping as key accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "keys.yaml: a key at the top level is not a name (a list or a mapping)");
  }
}

// An InputError is one line whatever it quotes: control characters come out as escapes.
TEST(InputErrorTest, ControlCharactersAreEscapedIntoOneLine) {
  EXPECT_STREQ(InputError("f.yaml: bad value 'a\nb\r\tc\x01\x7f'").what(), "f.yaml: bad value 'a\\nb\\r\\tc\\x01\\x7f'");
  EXPECT_STREQ(ConfigError("plain: kept as it is, UTF-8 \xc3\xa9 too").what(), "plain: kept as it is, UTF-8 \xc3\xa9 too");
  EXPECT_EQ(OneLine(std::string("a\0b", 3)), "a\\x00b");
}

struct Leaf {
  double gap_m = 0.1;
  double step_m = 0.1;
  template <class V>
  void Visit(V& v) {
    v("gap_m", gap_m);
    v("step_m", step_m);
  }
  void Validate() const {
    RequirePositive("gap_m", gap_m);
    RequirePositive("leaf.step_m", step_m);  // written with its section, as some Validate()s do
  }
};

struct Middle {
  Leaf leaf;
  template <class V>
  void Visit(V& v) {
    v("leaf", leaf);
  }
  void Validate() const { leaf.Validate(); }
};

struct Top {
  Middle middle;
  Inner inner;
  template <class V>
  void Visit(V& v) {
    v("middle", middle);
    v("inner", inner);
  }
  void Validate() const {
    middle.Validate();
    inner.Validate();
  }
};

std::string ApplyError(const std::string& assignment) {
  RawConfig raw;
  raw.SetFromAssignment(assignment);
  Top top;
  try {
    Apply(raw, &top);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ConfigTest, InvalidValueErrorsNameTheWholeKey) {
  EXPECT_EQ(ApplyError("middle.leaf.gap_m=-1").rfind("config: middle.leaf.gap_m must be > 0", 0), 0u)
      << ApplyError("middle.leaf.gap_m=-1");
  EXPECT_EQ(ApplyError("middle.leaf.step_m=0").rfind("config: middle.leaf.step_m must be > 0", 0), 0u)
      << ApplyError("middle.leaf.step_m=0");
  // Already the whole key: unchanged.
  EXPECT_EQ(ApplyError("inner.size_m=-2").rfind("config: inner.size_m must be > 0", 0), 0u)
      << ApplyError("inner.size_m=-2");
  EXPECT_EQ(ApplyError("middle.leaf.gap_m=0.5"), "");
}

TEST(ConfigTest, DumpRoundTripsThroughYaml) {
  Outer a;
  a.count = 11;
  a.inner.weights = {0.5};
  const std::string yaml = ToYaml(Dump(a));
  Outer b;
  Apply(RawConfig::FromYamlString(yaml, "dump"), &b);
  EXPECT_EQ(b.count, 11);
  ASSERT_EQ(b.inner.weights.size(), 1u);
  EXPECT_DOUBLE_EQ(b.inner.weights[0], 0.5);
  EXPECT_NE(ToJson(Dump(a)).find("\"size_m\": 0.5"), std::string::npos);
}

}  // namespace
}  // namespace objscan::config
