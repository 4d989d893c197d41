// The malformed-file corpus in tests/data/malformed, driven by its cases.tsv (also read by the CLI tests).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "posekit/error.hpp"
#include "posekit/mesh_io.hpp"
#include "test_data.hpp"

namespace posekit {
namespace {

struct MalformedCase {
  std::string file;
  std::string fragment;
};

std::filesystem::path corpus_folder() { return testing::project_test_data() / "malformed"; }

std::vector<MalformedCase> load_cases() {
  std::vector<MalformedCase> cases;
  std::ifstream table(corpus_folder() / "cases.tsv");
  std::string line;
  while (std::getline(table, line)) {
    if (line.empty() || line.front() == '#') continue;
    const std::size_t tab = line.find('\t');
    if (tab == std::string::npos) continue;
    cases.push_back({line.substr(0, tab), line.substr(tab + 1)});
  }
  return cases;
}

class MalformedMesh : public ::testing::TestWithParam<MalformedCase> {};

TEST_P(MalformedMesh, IsRefusedWithOneLineNamingTheFileAndTheProblem) {
  const MalformedCase& malformed = GetParam();
  const std::filesystem::path file = corpus_folder() / malformed.file;
  ASSERT_TRUE(std::filesystem::is_regular_file(file)) << file;
  try {
    const Mesh mesh = read_mesh(file);
    FAIL() << malformed.file << " was accepted: " << mesh.vertices.rows() << " vertices, " << mesh.faces.rows()
           << " faces";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.file(), file.string());
    EXPECT_NE(message.find(malformed.file), std::string::npos) << message;
    EXPECT_NE(message.find(malformed.fragment), std::string::npos)
        << "message: " << message << "\nexpected fragment: " << malformed.fragment;
    EXPECT_TRUE(
        std::none_of(message.begin(), message.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; }))
        << "not one printable line: " << message;
  }
}

std::string case_name(const ::testing::TestParamInfo<MalformedCase>& info) {
  std::string name = info.param.file;
  std::replace_if(
      name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) == 0; }, '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedMesh, ::testing::ValuesIn(load_cases()), case_name);

TEST(MalformedCorpus, TableAndReadmeListEveryFile) {
  const std::vector<MalformedCase> cases = load_cases();
  EXPECT_GE(cases.size(), 22U);
  std::set<std::string> listed;
  for (const MalformedCase& malformed : cases) {
    EXPECT_FALSE(malformed.fragment.empty()) << malformed.file;
    EXPECT_TRUE(listed.insert(malformed.file).second) << malformed.file << " is listed twice";
  }
  std::set<std::string> present;
  for (const auto& entry : std::filesystem::directory_iterator(corpus_folder())) {
    const std::string name = entry.path().filename().string();
    if (name != "README.md" && name != "cases.tsv") present.insert(name);
  }
  EXPECT_EQ(present, listed);

  std::ifstream readme_stream(corpus_folder() / "README.md");
  std::stringstream readme;
  readme << readme_stream.rdbuf();
  for (const MalformedCase& malformed : cases) {
    EXPECT_NE(readme.str().find("`" + malformed.file + "`"), std::string::npos)
        << malformed.file << " is not in README.md";
  }
}

}  // namespace
}  // namespace posekit
