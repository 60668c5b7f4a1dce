// MATLAB .mat files, read through matio: the variables a user saves in
// MATLAB (`save plant.mat A B C D`, `save -v7.3 frame.mat f_hz zeta phi_in
// phi_out`) as deb's matrices, vectors and name lists. Versions 5 and 7
// (uncompressed and compressed) and 7.3 (HDF5) are read; version 4 files are
// not. The file is treated as possibly hostile, like every input file
// (deb/core/input_file.h): only a regular file of at most
// limits::kMaxMatFileBytes is opened, a version 5 file whose variables run
// past its end is refused (matio would read the missing part as zeros), a
// variable's size is checked against limits::kMaxMatElements from its header
// before its data is read, and anything matio reports as damaged is an error.
// WriteMatFile writes a tree of values (matrices, text, name lists, structs)
// as a version 7 file (the version 5 format, compressed; see
// docs/result_files.md for why). This is the one module that uses matio.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace deb::formats {

class MatFile {
 public:
  // @throws InputError "<path>: ..." if the file does not exist, is not a
  //         regular file, is larger than the bound, is not a MAT-file of
  //         version 5, 7 or 7.3, or is truncated.
  explicit MatFile(const std::string& path);
  ~MatFile();
  MatFile(const MatFile&) = delete;
  MatFile& operator=(const MatFile&) = delete;

  const std::string& path() const { return path_; }
  // The variables in the file, in its order.
  const std::vector<std::string>& variables() const { return variables_; }
  bool Has(const std::string& name) const;

  // Every @throws below is an InputError "<path>: variable 'NAME' ..." that
  // names the variable, its class and its size, for a missing variable, a
  // variable that cannot be read, or one of another kind than asked for.
  // A name "a.b.c" is the field c of the 1x1 struct field b of the 1x1
  // struct variable a (a missing field: the struct's fields are listed).

  // A real, full 2-D numeric array (double; single, integer and logical
  // classes are converted to double), every entry finite. 0xn and nx0 are
  // returned as they are.
  // @throws for complex, sparse, char, cell, struct or other classes, more
  //         than 2 dimensions, more than limits::kMaxMatElements values, a
  //         value that is not finite.
  Eigen::MatrixXd Matrix(const std::string& name) const;

  // A 1xn or nx1 Matrix (a scalar is 1x1), n >= 1.
  std::vector<double> Vector(const std::string& name) const;

  // A list of names: a cell array (1xn or nx1) of char row vectors, or a char
  // matrix with one name per row, trailing blanks trimmed (char(...) pads
  // shorter names with blanks). 16-bit characters are returned as UTF-8.
  // @throws for another class, an element that is not a char row vector, an
  //         empty name, more than limits::kMaxChannels names.
  std::vector<std::string> Names(const std::string& name) const;

 private:
  struct Handle;
  std::string path_;
  std::unique_ptr<Handle> handle_;
  std::vector<std::string> variables_;
};

// A value to write into a MAT-file: a real double matrix (NaN allowed), a
// char row vector, a column cell array of char row vectors, or a 1x1 struct
// whose fields (valid MATLAB names, at most 63 characters) are values, in
// order.
struct MatValue {
  enum class Kind { kMatrix, kText, kNames, kStruct };
  Kind kind = Kind::kMatrix;
  Eigen::MatrixXd matrix;
  std::string text;                 // UTF-8
  std::vector<std::string> names;   // UTF-8; empty strings allowed
  std::vector<std::string> field_names;
  std::vector<MatValue> fields;

  static MatValue Matrix(Eigen::MatrixXd m);
  static MatValue Scalar(double v);
  static MatValue Column(const std::vector<double>& v);  // n x 1
  static MatValue Text(std::string text);
  static MatValue Names(std::vector<std::string> names);  // n x 1
  static MatValue Struct();
  // Adds a field to a struct; returns *this.
  MatValue& Add(const std::string& field, MatValue value);
};

// Writes `variables` (valid MATLAB names) into a new version 7 MAT-file at
// `path` (replaced if it exists); on failure nothing is left at `path`.
// `description` goes into the file's 116-character text header after
// "MATLAB 5.0 MAT-file, ".
// @throws WriteError "<path>: ..." if a value cannot
//         be made (naming the variable and field) or the file cannot be
//         written.
void WriteMatFile(const std::string& path, const std::vector<std::pair<std::string, MatValue>>& variables,
                  const std::string& description);

}  // namespace deb::formats
