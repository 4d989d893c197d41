// The report's data and page: poses stored once, positions quantized within half a step, binary
// arrays in base64, a document that is not whole refused, and data that cannot end its <script>.
#include "base64.hpp"
#include "html_page.hpp"
#include "report_document.hpp"

#include <posekit/error.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace posekit::report {
namespace {

std::vector<unsigned char> decoded(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  unsigned group = 0;
  int bits = 0;
  for (const char c : text) {
    if (c == '=') break;
    group = (group << 6) | static_cast<unsigned>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((group >> bits) & 0xFF));
    }
  }
  return bytes;
}

Eigen::MatrixX3i two_triangles() {
  Eigen::MatrixX3i faces(2, 3);
  faces << 0, 1, 2, 0, 2, 3;
  return faces;
}

Eigen::MatrixX3d square(double lift) {
  Eigen::MatrixX3d v(4, 3);
  v << 0, 0, 0, 1, 0, lift, 1, 1, 0, 0, 1, 0.3;
  return v;
}

TEST(Base64, MatchesTheStandardVectors) {
  EXPECT_EQ(base64(""), "");
  EXPECT_EQ(base64("f"), "Zg==");
  EXPECT_EQ(base64("fo"), "Zm8=");
  EXPECT_EQ(base64("foo"), "Zm9v");
  EXPECT_EQ(base64("foob"), "Zm9vYg==");
  EXPECT_EQ(base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64("foobar"), "Zm9vYmFy");
}

TEST(ReportDocument, StoresEqualPosesOnce) {
  ReportDocument document("correct", "t", "c", two_triangles(), 1.0);
  const int first = document.add_pose(square(0.0));
  EXPECT_EQ(document.add_pose(square(0.0)), first);
  EXPECT_NE(document.add_pose(square(0.5)), first);
  document.frame_names = {"result"};
  EXPECT_EQ(document.data().at("poses").size(), 2u);
}

TEST(ReportDocument, QuantizesPositionsWithinHalfAStep) {
  ReportDocument document("correct", "t", "c", two_triangles(), 1.0);
  const Eigen::MatrixX3d pose = square(0.7);
  document.frame_names = {"result"};
  document.panels.push_back({"result", std::nullopt, {{document.add_pose(pose), {}, {}, {}, {}}}});
  const nlohmann::json data = document.data();
  const nlohmann::json& mesh = data.at("mesh");
  EXPECT_EQ(mesh.at("index_bytes"), 2);
  const std::vector<unsigned char> faces = decoded(mesh.at("faces"));
  ASSERT_EQ(faces.size(), 12u);
  EXPECT_EQ(faces[10], 3);  // second face, last corner, little endian
  const std::vector<unsigned char> bytes = decoded(data.at("poses")[0]);
  ASSERT_EQ(bytes.size(), 4u * 3u * 2u);
  for (int v = 0; v < 4; ++v) {
    for (int k = 0; k < 3; ++k) {
      std::uint16_t q = 0;
      std::memcpy(&q, &bytes[static_cast<size_t>(2 * (3 * v + k))], 2);
      const double step = mesh.at("step")[k];
      const double position = mesh.at("origin")[k].get<double>() + q * step;
      EXPECT_NEAR(position, pose(v, k), 0.5 * step + 1e-12) << "vertex " << v << " axis " << k;
    }
  }
}

TEST(ReportDocument, RefusesADocumentThatIsNotWhole) {
  ReportDocument document("correct-sequence", "t", "c", two_triangles(), 1.0);
  const int pose = document.add_pose(square(0.0));
  document.frame_names = {"a", "b"};
  document.panels.push_back({"target", std::nullopt, {{pose, {}, {}, {}, {}}}});
  EXPECT_THROW(document.data(), Error);  // one frame for two names
  document.panels.back().frames.push_back({pose + 1, {}, {}, {}, {}});
  EXPECT_THROW(document.data(), Error);  // a pose that is not stored
}

TEST(HtmlPage, DataCannotEndItsScriptElement) {
  ReportDocument document("correct", "</script><script>alert(1)</script>", "posekit correct a b", two_triangles(), 1.0);
  document.frame_names = {"</script>"};
  document.panels.push_back({"p", std::nullopt, {{document.add_pose(square(0.0)), {}, {}, {}, {}}}});
  const std::string page = html_page(document);
  size_t closing = 0;
  for (size_t at = page.find("</script>"); at != std::string::npos; at = page.find("</script>", at + 1)) ++closing;
  EXPECT_EQ(closing, 4u) << "three.js, its controls, the data and the viewer";
  EXPECT_NE(page.find("<title>&lt;/script&gt;"), std::string::npos);
  EXPECT_NE(page.find("<\\/script>"), std::string::npos);
}

TEST(HtmlPage, DestinationInAMissingFolderIsRefused) {
  EXPECT_THROW(check_report_destination("/nonexistent-folder/report.html", "--html"), ArgumentError);
  EXPECT_NO_THROW(check_report_destination("report.html", "--html"));
}

}  // namespace
}  // namespace posekit::report
