// read_integer_list: the shared reader of vertex index lists and label files.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "posekit/error.hpp"
#include "posekit/integer_list.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

struct IntegerList : ::testing::Test {
  std::string write(const std::string& name, const std::string& text) {
    const std::string file = (folder.path() / name).string();
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }
  std::string error_of(const std::string& text, int end = 10) {
    try {
      read_integer_list(write("bad.txt", text), "vertex index", 0, end);
    } catch (const InputError& error) {
      return error.what();
    }
    return "no error";
  }
  testing::TemporaryDirectory folder;
};

TEST_F(IntegerList, ReadsWordsInFileOrderAcrossLinesCommentsAndTabs) {
  const std::string file = write("list.txt", "# header\n3 1\t4\r\n\n1 # a comment 7\n  5\n");
  EXPECT_EQ(read_integer_list(file, "vertex index", 0, 10), (std::vector<int>{3, 1, 4, 1, 5}));
  EXPECT_TRUE(read_integer_list(write("empty.txt", "# nothing\n"), "vertex index", 0, 10).empty());
}

TEST_F(IntegerList, NamesTheFileTheLineAndTheWord) {
  EXPECT_NE(error_of("1 2\n3 x\n").find("bad.txt:2: 'x' is not a vertex index"), std::string::npos) << error_of("1 2\n3 x\n");
  EXPECT_NE(error_of("2.5\n").find(":1: '2.5' is not a vertex index"), std::string::npos);
  EXPECT_NE(error_of("\n\n10\n").find(":3: vertex index 10 is outside [0, 10)"), std::string::npos);
  EXPECT_NE(error_of("-1\n").find(":1: vertex index -1 is outside [0, 10)"), std::string::npos);
  EXPECT_NE(error_of("99999999999999999999\n").find("is not a vertex index"), std::string::npos);
  try {
    read_integer_list(folder.path() / "missing.txt", "part id", 0, 5);
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("missing.txt"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace posekit
