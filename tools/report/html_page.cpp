#include "html_page.hpp"

#include "report_assets.hpp"

#include <posekit/atomic_file.hpp>
#include <posekit/error.hpp>

namespace posekit::report {
namespace {

std::string escaped_html(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

// JSON inside a <script> element: "</" would end the element, so it is written "<\/" (the same
// string to a JSON reader).
std::string script_safe_json(const nlohmann::json& data) {
  std::string text = data.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

}  // namespace

std::string html_page(const ReportDocument& document) {
  const ReportAssets& assets = report_assets();
  const std::string data = script_safe_json(document.data());
  std::string page;
  page.reserve(data.size() + assets.three.size() + assets.orbit_controls.size() + assets.viewer.size() +
               assets.style.size() + 1024);
  page += "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
          "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>";
  page += escaped_html(document.title());
  page += "</title>\n<style>";
  page += assets.style;
  page += "</style>\n</head><body>\n<script>";
  page += assets.three;
  page += "</script>\n<script>";
  page += assets.orbit_controls;
  page += "</script>\n<script type=\"application/json\" id=\"posekit-report-data\">";
  page += data;
  page += "</script>\n<script>";
  page += assets.viewer;
  page += "</script>\n</body></html>\n";
  return page;
}

void write_html_report(const std::filesystem::path& file, const ReportDocument& document) {
  write_file_atomically(file, html_page(document));
}

void check_report_destination(const std::filesystem::path& file, const std::string& flag) {
  const std::filesystem::path folder = file.has_parent_path() ? file.parent_path() : std::filesystem::path(".");
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    throw ArgumentError(flag + ": " + file.string() + ": the folder " + folder.string() + " does not exist");
  }
  if (std::filesystem::is_directory(file, error)) throw ArgumentError(flag + ": " + file.string() + " is a folder");
}

}  // namespace posekit::report
