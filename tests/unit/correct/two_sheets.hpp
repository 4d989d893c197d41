// Two parallel square sheets, the top one dented towards the bottom one: the smallest shape on which
// one part is pressed into another, for the stages that deal with what integration left behind.
#pragma once

#include <Eigen/Core>

#include <cmath>

namespace posekit::detail {

// Two parallel square sheets of n by n vertices, 0.2 apart: the bottom at z = 0, the top at z = 0.2.
struct TwoSheets {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  int n = 0;
  int top(int i, int j) const { return n * n + i * n + j; }
};

inline TwoSheets two_sheets(int n) {
  TwoSheets sheets;
  sheets.n = n;
  sheets.vertices.resize(2 * n * n, 3);
  sheets.faces.resize(2 * 2 * (n - 1) * (n - 1), 3);
  int face = 0;
  for (int sheet = 0; sheet < 2; ++sheet) {
    const int base = sheet * n * n;
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        sheets.vertices.row(base + i * n + j) << i / double(n - 1), j / double(n - 1), 0.2 * sheet;
      }
    }
    for (int i = 0; i + 1 < n; ++i) {
      for (int j = 0; j + 1 < n; ++j) {
        const int a = base + i * n + j;
        sheets.faces.row(face++) << a, a + n, a + 1;
        sheets.faces.row(face++) << a + 1, a + n, a + n + 1;
      }
    }
  }
  return sheets;
}

// The top sheet with a dent of the given depth around its middle.
inline Eigen::MatrixX3d dented(const TwoSheets& sheets, double depth) {
  Eigen::MatrixX3d pose = sheets.vertices;
  for (int i = 0; i < sheets.n; ++i) {
    for (int j = 0; j < sheets.n; ++j) {
      const double x = i / double(sheets.n - 1) - 0.5;
      const double y = j / double(sheets.n - 1) - 0.5;
      pose(sheets.top(i, j), 2) -= depth * std::exp(-(x * x + y * y) / 0.01);
    }
  }
  return pose;
}

}  // namespace posekit::detail
