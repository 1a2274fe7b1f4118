#pragma once
// A gtest suite sharing one database of the analytic shapes (test_database.h), built once per suite.
#include <gtest/gtest.h>

#include "objscan/recognition/test_database.h"

namespace objscan::recognition::testing {

// `Base` is ::testing::Test or a ::testing::TestWithParam<T>.
template <class Base = ::testing::Test>
class ShapeDatabaseSuite : public Base {
 protected:
  static void SetUpTestSuite() { db_ = new ModelDatabase(BuildDatabaseFromScans(ShapeModels(0.01), SmallDatabaseOptions())); }
  static void TearDownTestSuite() {
    delete db_;
    db_ = nullptr;
  }
  static inline ModelDatabase* db_ = nullptr;
};

}  // namespace objscan::recognition::testing
