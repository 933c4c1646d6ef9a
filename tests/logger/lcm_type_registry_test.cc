#include "logger/lcm_type_registry.h"

#include <gtest/gtest.h>

namespace mrsim {
namespace {

// Fingerprints against the generated code: all_types_test.cc (generated).

TEST(LoggerTypes, EveryBuiltinTypeHasAFingerprint) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  EXPECT_TRUE(registry.warnings().empty())
      << "a file in lcmtypes/mrsim does not parse: " << registry.warnings()[0];
  const auto structs = registry.structs();
  EXPECT_GE(structs.size(), 7u);
  for (const LcmStruct* s : structs) {
    EXPECT_EQ(registry.FindByHash(registry.Fingerprint(*s)), s)
        << s->full_name();
  }
}

TEST(LoggerTypes, ParseErrorNamesFileLineAndExpectation) {
  LcmTypeRegistry registry;
  try {
    registry.AddDefinitions("package p;\nstruct a_t {\n  double x[n];\n}\n",
                            "bad.lcm");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.lcm:3"), std::string::npos) << what;
    EXPECT_NE(what.find("'n'"), std::string::npos) << what;
  }
}

TEST(LoggerTypes, ConstantsAndCommentsDoNotChangeTheFingerprint) {
  LcmTypeRegistry a;
  a.AddDefinitions("package q; struct t { int64_t utime; double v[3]; }", "a");
  LcmTypeRegistry b;
  b.AddDefinitions(
      "package q;\n/* block */ struct t {\n // line\n int64_t utime;\n"
      " const int8_t K = 1, L = 2;\n double v[3];\n}\n",
      "b");
  EXPECT_EQ(a.Fingerprint(*a.FindByName("q.t")),
            b.Fingerprint(*b.FindByName("q.t")));
}

}  // namespace
}  // namespace mrsim
