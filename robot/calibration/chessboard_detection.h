// Chessboard views for calibration: OpenCV's inner-corner detector with
// sub-pixel refinement (the detection is plumbing; the calibration is ours).
#pragma once

#include <string>
#include <vector>

#include "robot/calibration/calibration_problem.h"

namespace lineloc {

struct ChessboardSize {
  int columns = 9;  // inner corners per row
  int rows = 6;     // inner corners per column
};

// Parses "COLUMNSxROWS" (e.g. "9x6"); throws std::invalid_argument otherwise.
ChessboardSize parseChessboardSize(const std::string& text);

// The image files matching a shell pattern (e.g. "dir/left*.jpg"), sorted;
// throws std::runtime_error when none match.
std::vector<std::string> expandImagePattern(const std::string& pattern);

// Inner corners in OpenCV's order: row by row, X = column * square_m,
// Y = row * square_m.
std::vector<Eigen::Vector2d> chessboardModelPoints(ChessboardSize board, double square_m);

struct ChessboardViews {
  PlanarViews views;
  std::vector<std::string> images_with_board;  // one per view
  std::vector<std::string> images_without_board;
  // Images with a board but of another size than most views (another camera).
  std::vector<std::string> images_of_other_size;
};

// Detects the board in every image; the views are those of the image size
// most boards were found in. Throws std::runtime_error naming the file when an
// image cannot be read.
ChessboardViews detectChessboards(const std::vector<std::string>& image_paths, ChessboardSize board,
                                  double square_m);

}  // namespace lineloc
