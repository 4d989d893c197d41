#include <posekit/atomic_file.hpp>
#include <posekit/blend_files.hpp>
#include <posekit/error.hpp>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

namespace posekit {
namespace {

// The fields of each line that holds any, with its line number.
class FieldReader {
 public:
  FieldReader(const std::filesystem::path& file, const char* what) : name_(file.string()), stream_(file, std::ios::binary) {
    if (!stream_) throw InputError(name_, 0, std::string("cannot open the ") + what);
  }
  bool next(std::vector<std::string>& fields) {
    std::string line;
    while (std::getline(stream_, line)) {
      ++line_number_;
      const size_t comment = line.find('#');
      if (comment != std::string::npos) line.resize(comment);
      for (char& c : line) {
        if (c == '\t' || c == '\r') c = ' ';
      }
      std::istringstream words(line);
      fields.clear();
      std::string word;
      while (words >> word) fields.push_back(word);
      if (!fields.empty()) return true;
    }
    if (stream_.bad()) throw InputError(name_, line_number_, "read error");
    return false;
  }
  long line() const { return line_number_; }
  const std::string& name() const { return name_; }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(name_, line_number_, problem); }

  double number(const std::string& word, const char* what) const {
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(word.c_str(), &end);
    if (end == word.c_str() || *end != '\0') fail("'" + word + "' is not a number (" + what + ")");
    if (!std::isfinite(value)) fail(std::string(what) + " '" + word + "' is not finite");
    return value;
  }

 private:
  std::string name_;
  std::ifstream stream_;
  long line_number_ = 0;
};

}  // namespace

PointConstraints read_point_constraints(const std::filesystem::path& file, int vertex_count) {
  FieldReader reader(file, "constraint file");
  PointConstraints result;
  std::vector<Eigen::RowVector3d> positions;
  std::map<int, long> seen;
  std::vector<std::string> fields;
  while (reader.next(fields)) {
    if (fields.size() != 4 && fields.size() != 5) {
      reader.fail("expected 'VERTEX X Y Z [GROUP]', found " + std::to_string(fields.size()) + " fields");
    }
    errno = 0;
    char* end = nullptr;
    const long long index = std::strtoll(fields[0].c_str(), &end, 10);
    if (end == fields[0].c_str() || *end != '\0' || errno == ERANGE) {
      reader.fail("'" + fields[0] + "' is not a vertex index");
    }
    if (index < 0 || index >= vertex_count) {
      reader.fail("vertex index " + fields[0] + " is outside [0, " + std::to_string(vertex_count) + ")");
    }
    const auto [previous, inserted] = seen.emplace(static_cast<int>(index), reader.line());
    if (!inserted) {
      reader.fail("vertex " + fields[0] + " is already constrained on line " + std::to_string(previous->second));
    }
    const char* axes[3] = {"x", "y", "z"};
    Eigen::RowVector3d position;
    for (int a = 0; a < 3; ++a) position(a) = reader.number(fields[static_cast<size_t>(a) + 1], axes[a]);
    result.vertices.push_back(static_cast<int>(index));
    positions.push_back(position);
    result.groups.push_back(fields.size() == 5 ? fields[4] : std::string());
    result.lines.push_back(reader.line());
  }
  if (result.vertices.empty()) throw InputError(reader.name(), 0, "the file lists no constraint");
  result.positions.resize(static_cast<Eigen::Index>(positions.size()), 3);
  for (size_t r = 0; r < positions.size(); ++r) result.positions.row(static_cast<Eigen::Index>(r)) = positions[r];
  return result;
}

Eigen::MatrixXd read_skinning_weights(const std::filesystem::path& file, int vertex_count) {
  FieldReader reader(file, "skinning weight file");
  std::vector<double> values;
  size_t columns = 0;
  long rows = 0;
  std::vector<std::string> fields;
  while (reader.next(fields)) {
    if (columns == 0) columns = fields.size();
    if (fields.size() != columns) {
      reader.fail("row has " + std::to_string(fields.size()) + " weights; the first row has " + std::to_string(columns));
    }
    if (rows >= vertex_count) reader.fail("more rows than the " + std::to_string(vertex_count) + " vertices");
    bool any = false;
    for (const std::string& word : fields) {
      const double value = reader.number(word, "weight");
      any = any || value != 0.0;
      values.push_back(value);
    }
    if (!any) reader.fail("every weight of vertex " + std::to_string(rows) + " is zero");
    ++rows;
  }
  if (rows != vertex_count) {
    throw InputError(reader.name(), 0, "has " + std::to_string(rows) + " weight rows for " + std::to_string(vertex_count) +
                                           " vertices");
  }
  Eigen::MatrixXd weights(vertex_count, static_cast<Eigen::Index>(columns));
  for (long r = 0; r < rows; ++r) {
    for (size_t c = 0; c < columns; ++c) weights(r, static_cast<Eigen::Index>(c)) = values[static_cast<size_t>(r) * columns + c];
  }
  return weights;
}

namespace {

constexpr const char* kSkinningMagic = "posekit-skinning-decomposition";
constexpr int kSkinningFormat = 1;

// FNV-1a over the bytes of `data`, continuing from `hash`.
std::uint64_t fingerprint(const void* data, size_t bytes, std::uint64_t hash = 1469598103934665603ULL) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < bytes; ++i) {
    hash ^= p[i];
    hash *= 1099511628211ULL;
  }
  return hash;
}

std::string connectivity_fingerprint(const PoseSet& examples) {
  const Eigen::MatrixX3i& f = examples.faces();
  std::uint64_t hash = fingerprint(nullptr, 0);
  for (Eigen::Index r = 0; r < f.rows(); ++r) {
    const std::int32_t corners[3] = {f(r, 0), f(r, 1), f(r, 2)};
    hash = fingerprint(corners, sizeof corners, hash);
  }
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::string poses_fingerprint(const PoseSet& examples) {
  std::uint64_t hash = fingerprint(nullptr, 0);
  for (int k = 0; k < examples.pose_count(); ++k) {
    const Eigen::MatrixX3d& x = examples.pose(k);
    for (Eigen::Index r = 0; r < x.rows(); ++r) {
      const double row[3] = {x(r, 0), x(r, 1), x(r, 2)};
      hash = fingerprint(row, sizeof row, hash);
    }
  }
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

long long whole_number(const FieldReader& reader, const std::string& word, const char* what) {
  errno = 0;
  char* end = nullptr;
  const long long value = std::strtoll(word.c_str(), &end, 10);
  if (end == word.c_str() || *end != '\0' || errno == ERANGE) reader.fail("'" + word + "' is not " + what);
  return value;
}

}  // namespace

void write_skinning_decomposition(const std::filesystem::path& file, const SkinningDecomposition& d,
                                  const PoseSet& examples) {
  check_skinning_decomposition(d);
  if (d.vertex_count() != examples.vertex_count() || d.example_count() != examples.pose_count()) {
    throw ArgumentError("write_skinning_decomposition: the decomposition does not belong to these examples");
  }
  std::string out;
  out.reserve(static_cast<size_t>(d.vertex_count()) * 64);
  char line[512];
  const auto add = [&](int written) { out.append(line, static_cast<size_t>(std::max(0, written))); };
  add(std::snprintf(line, sizeof line, "# skinning weights, bone motions and skeleton learned from %d example poses\n",
                    examples.pose_count()));
  add(std::snprintf(line, sizeof line, "%s %d\n", kSkinningMagic, kSkinningFormat));
  add(std::snprintf(line, sizeof line, "mesh %d %d %s\n", examples.vertex_count(), static_cast<int>(examples.faces().rows()),
                    connectivity_fingerprint(examples).c_str()));
  add(std::snprintf(line, sizeof line, "examples %d %s\n", examples.pose_count(), poses_fingerprint(examples).c_str()));
  add(std::snprintf(line, sizeof line, "bones %d\n", d.bone_count()));
  add(std::snprintf(line, sizeof line, "error %.17g %.17g\n", d.rms_error, d.max_error));
  add(std::snprintf(line, sizeof line, "# bone parent joint-x joint-y joint-z\n"));
  for (int j = 0; j < d.bone_count(); ++j) {
    add(std::snprintf(line, sizeof line, "joint %d %d %.17g %.17g %.17g\n", j, d.parents[static_cast<size_t>(j)],
                      d.joints(j, 0), d.joints(j, 1), d.joints(j, 2)));
  }
  add(std::snprintf(line, sizeof line, "# example bone rotation (row by row) translation\n"));
  for (int k = 0; k < d.example_count(); ++k) {
    for (int j = 0; j < d.bone_count(); ++j) {
      const BoneMotion& m = d.motions[static_cast<size_t>(k)][static_cast<size_t>(j)];
      add(std::snprintf(line, sizeof line, "motion %d %d", k, j));
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) add(std::snprintf(line, sizeof line, " %.17g", m.rotation(r, c)));
      }
      for (int r = 0; r < 3; ++r) add(std::snprintf(line, sizeof line, " %.17g", m.translation(r)));
      out += '\n';
    }
  }
  add(std::snprintf(line, sizeof line, "# vertex then (bone weight) pairs\n"));
  for (int i = 0; i < d.vertex_count(); ++i) {
    add(std::snprintf(line, sizeof line, "weights %d", i));
    for (int j = 0; j < d.bone_count(); ++j) {
      if (d.weights(i, j) != 0.0) add(std::snprintf(line, sizeof line, " %d %.17g", j, d.weights(i, j)));
    }
    out += '\n';
  }
  write_file_atomically(file, out);
}

SkinningDecomposition read_skinning_decomposition(const std::filesystem::path& file, const PoseSet& examples) {
  FieldReader reader(file, "skinning decomposition cache");
  std::vector<std::string> fields;
  const auto expect = [&](const char* keyword, size_t count) {
    if (!reader.next(fields)) reader.fail(std::string("ends before its '") + keyword + "' line");
    if (fields[0] != keyword || fields.size() != count) {
      reader.fail(std::string("expected a '") + keyword + "' line with " + std::to_string(count - 1) + " fields");
    }
  };
  if (!reader.next(fields) || fields.size() != 2 || fields[0] != kSkinningMagic) {
    reader.fail("not a posekit skinning decomposition cache");
  }
  if (whole_number(reader, fields[1], "a format number") != kSkinningFormat) {
    reader.fail("format " + fields[1] + " is not the supported " + std::to_string(kSkinningFormat));
  }
  expect("mesh", 4);
  const std::string here = std::to_string(examples.vertex_count()) + " vertices and " +
                           std::to_string(examples.faces().rows()) + " faces";
  if (whole_number(reader, fields[1], "a vertex count") != examples.vertex_count() ||
      whole_number(reader, fields[2], "a face count") != examples.faces().rows()) {
    reader.fail("the cache is for a mesh of " + fields[1] + " vertices and " + fields[2] + " faces, not this one of " + here);
  }
  if (fields[3] != connectivity_fingerprint(examples)) {
    reader.fail("the cache is for another mesh with the same counts (the connectivity differs)");
  }
  expect("examples", 3);
  if (whole_number(reader, fields[1], "an example count") != examples.pose_count() ||
      fields[2] != poses_fingerprint(examples)) {
    reader.fail("the cache was made from other example poses (" + fields[1] + " of them); remove it to make it anew");
  }
  expect("bones", 2);
  const long long bones = whole_number(reader, fields[1], "a bone count");
  if (bones < 1 || bones > examples.vertex_count()) reader.fail("bone count " + fields[1] + " is out of range");
  const int b = static_cast<int>(bones);
  SkinningDecomposition d;
  expect("error", 3);
  d.rms_error = reader.number(fields[1], "RMS error");
  d.max_error = reader.number(fields[2], "largest error");
  d.parents.assign(static_cast<size_t>(b), -1);
  d.joints.resize(b, 3);
  for (int j = 0; j < b; ++j) {
    expect("joint", 6);
    if (whole_number(reader, fields[1], "a bone index") != j) reader.fail("expected joint " + std::to_string(j));
    const long long parent = whole_number(reader, fields[2], "a parent bone");
    if (parent < -1 || parent >= bones) reader.fail("parent " + fields[2] + " is outside [-1, " + fields[1] + ")");
    d.parents[static_cast<size_t>(j)] = static_cast<int>(parent);
    for (int a = 0; a < 3; ++a) d.joints(j, a) = reader.number(fields[static_cast<size_t>(a) + 3], "joint coordinate");
  }
  d.motions.assign(static_cast<size_t>(examples.pose_count()), std::vector<BoneMotion>(static_cast<size_t>(b)));
  for (int k = 0; k < examples.pose_count(); ++k) {
    for (int j = 0; j < b; ++j) {
      expect("motion", 15);
      if (whole_number(reader, fields[1], "an example index") != k || whole_number(reader, fields[2], "a bone index") != j) {
        reader.fail("expected the motion of bone " + std::to_string(j) + " to example " + std::to_string(k));
      }
      BoneMotion& m = d.motions[static_cast<size_t>(k)][static_cast<size_t>(j)];
      for (int e = 0; e < 9; ++e) m.rotation(e / 3, e % 3) = reader.number(fields[static_cast<size_t>(e) + 3], "rotation");
      for (int e = 0; e < 3; ++e) m.translation(e) = reader.number(fields[static_cast<size_t>(e) + 12], "translation");
    }
  }
  d.weights = Eigen::MatrixXd::Zero(examples.vertex_count(), b);
  for (int i = 0; i < examples.vertex_count(); ++i) {
    if (!reader.next(fields)) reader.fail("ends after " + std::to_string(i) + " of " + std::to_string(examples.vertex_count()) + " weight rows");
    if (fields[0] != "weights" || fields.size() < 4 || fields.size() % 2 != 0) {
      reader.fail("expected 'weights VERTEX BONE WEIGHT [BONE WEIGHT ...]'");
    }
    if (whole_number(reader, fields[1], "a vertex index") != i) reader.fail("expected the weights of vertex " + std::to_string(i));
    for (size_t f = 2; f < fields.size(); f += 2) {
      const long long bone = whole_number(reader, fields[f], "a bone index");
      if (bone < 0 || bone >= bones) reader.fail("bone " + fields[f] + " is outside [0, " + std::to_string(bones) + ")");
      d.weights(i, static_cast<Eigen::Index>(bone)) = reader.number(fields[f + 1], "weight");
    }
  }
  if (reader.next(fields)) reader.fail("unexpected line after the last vertex");
  try {
    check_skinning_decomposition(d);
  } catch (const ArgumentError& error) {
    throw InputError(reader.name(), 0, error.what());
  }
  return d;
}

}  // namespace posekit
