#include "rockfit/core/contact.hpp"

#include <gtest/gtest.h>

#include "rockfit/core/errors.hpp"

namespace rockfit::core {
namespace {

TEST(Contact, EdgeIsStoredInCyclicOrderWhateverTheArgumentOrder) {
  EXPECT_EQ(Contact::Edge(1, 2), (Contact{1, 2}));
  EXPECT_EQ(Contact::Edge(2, 1), (Contact{1, 2}));
  EXPECT_EQ(Contact::Edge(3, 4), (Contact{3, 4}));
  EXPECT_EQ(Contact::Edge(1, 4), (Contact{4, 1}));
  EXPECT_EQ(Contact::Edge(4, 1), (Contact{4, 1}));
  EXPECT_EQ(Contact::Edge(0, 1), (Contact{4, 1}));  // indices are cyclic: V0 is V4
}

TEST(Contact, EdgeOfNonNeighboursIsRejected) {
  EXPECT_THROW(Contact::Edge(1, 3), InvalidArgument);
  EXPECT_THROW(Contact::Edge(2, 2), InvalidArgument);
}

TEST(Contact, ToStringNamesTheVerticesOrNone) {
  EXPECT_EQ(Contact::Vertex(4).ToString(), "V4");
  EXPECT_EQ(Contact::Vertex(5).ToString(), "V1");
  EXPECT_EQ(Contact::Edge(4, 3).ToString(), "V3V4");
  EXPECT_EQ(Contact::Edge(1, 4).ToString(), "V4V1");
  EXPECT_EQ(Contact{}.ToString(), "none");
  EXPECT_TRUE(Contact::Vertex(2).is_vertex());
  EXPECT_FALSE(Contact::Vertex(2).is_edge());
  EXPECT_TRUE(Contact::Edge(2, 3).is_edge());
  EXPECT_FALSE(Contact{}.is_vertex());
  EXPECT_FALSE(Contact{}.is_edge());
}

}  // namespace
}  // namespace rockfit::core
