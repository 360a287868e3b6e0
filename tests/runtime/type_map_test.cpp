// TypeMap: at most one value of each type, found by its type (a scene's effects, what they resolve
// to). What it must do: find what was set and nothing else, replace on a second set, forget on
// drop, refuse get() of a type it does not hold, and copy as a value.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "core/runtime/type_map.h"

namespace bleedsim {
namespace {

struct Reach {
  double mm = 1.5;
};
struct Name {
  std::string text;
};

TEST(TypeMap, FindsEachValueByItsTypeAndNothingElse) {
  TypeMap map;
  EXPECT_EQ(map.find<Reach>(), nullptr);
  EXPECT_FALSE(map.has<Reach>());
  map.set(Reach{2.5});
  ASSERT_TRUE(map.has<Reach>());
  EXPECT_EQ(map.get<Reach>().mm, 2.5);
  EXPECT_EQ(map.find<Name>(), nullptr);  // another type is not there because one is
  map.set(Name{"suction"});
  EXPECT_EQ(map.get<Name>().text, "suction");
  EXPECT_EQ(map.get<Reach>().mm, 2.5);  // and setting it left the first alone
}

TEST(TypeMap, ASecondSetReplacesAndDropForgets) {
  TypeMap map;
  map.set(Reach{1.0});
  map.set(Reach{3.0});
  EXPECT_EQ(map.get<Reach>().mm, 3.0);
  map.get<Reach>().mm = 4.0;  // get() of a non-const map edits the value held
  EXPECT_EQ(map.find<Reach>()->mm, 4.0);
  map.drop<Reach>();
  EXPECT_FALSE(map.has<Reach>());
  map.drop<Reach>();  // dropping what is not there does nothing
  EXPECT_FALSE(map.has<Reach>());
}

TEST(TypeMap, GetOfATypeNotHeldThrowsALogicError) {
  const TypeMap map;
  EXPECT_THROW(map.get<Reach>(), std::logic_error);
}

TEST(TypeMap, CopiesAreValues) {
  TypeMap map;
  map.set(Reach{1.0});
  TypeMap copy = map;
  copy.get<Reach>().mm = 9.0;
  copy.set(Name{"copy"});
  EXPECT_EQ(map.get<Reach>().mm, 1.0);
  EXPECT_FALSE(map.has<Name>());
}

}  // namespace
}  // namespace bleedsim