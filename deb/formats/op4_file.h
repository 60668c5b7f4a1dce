// Nastran OUTPUT4 (.op4) files: the matrices a finite-element run exports
// with OUTPUT4 (a reduced model's state-space matrices, mass and stiffness,
// mode shapes) read as deb's matrices.
//
// A file is a sequence of matrices, each a header and then its columns:
//  - the header gives ncol, nrow, form (1 square, 2 rectangular, 6
//    symmetric, ...: Nastran's description, every column is stored anyway),
//    type (1 real single, 2 real double, 3 complex single, 4 complex double
//    precision) and a name of up to 8 characters;
//  - a column record gives the column number (from 1), the first row and a
//    count of words, then the values down the column from that row; a
//    complex value is two numbers, real then imaginary;
//  - sparse layouts give 0 as the first row and cut the column into strings
//    of consecutive nonzero values, each with its own first row and length
//    (in words): packed as IS = row + 65536 (length + 1) in one word, or as
//    the two words length + 1 and row when nrow is negative ("bigmat";
//    |nrow| is the count) or 65536 or more;
//  - the column number ncol + 1 ends the matrix (its record is skipped);
//    columns left out are zero.
// A text file writes each record on its own lines: the header as four
// 8-character integers, the name in columns 33-40 and the Fortran format of
// the numbers (1P,3E23.16: 3 numbers of 23 characters a line; D exponents
// and Fortran's 1.0-100 for 1.0E-100 are read); a record's 3 integers in 8
// characters each, a packed IS alone on its line, a bigmat string's two
// integers in 8 characters each, and every run of values from a new line.
// There a dense column's record counts its numbers, a sparse one's its
// words (a double is 2, as in a binary file of 4-byte words); the end
// record's value lines are skipped unread (Nastran writes them in another
// width at times). A binary file is Fortran unformatted records, each
// framed by its length in bytes (4 bytes before and after), little- or
// big-endian, in 4-byte words (a double is 2 words) or 8-byte words (every
// number a double, the name 16 bytes); the byte order and word size are
// taken from the first record, the header of 6 words.
//
// The file is treated as possibly hostile, like every input file
// (deb/core/input_file.h): a regular file of at most
// limits::kMaxOp4FileBytes, read whole and checked whole when opened (every
// record complete and framed, columns increasing and within ncol, strings in
// order and within nrow, word counts that add up, every number finite), at
// most limits::kMaxOp4Matrices matrices; a matrix's size is checked against
// limits::kMaxMatElements numbers (a complex value is two) before it is
// allocated. Every error names the
// file, the line (text) or byte offset (binary), the matrix and the rule.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace deb::formats {

// One matrix of the file, as its header describes it.
struct Op4Matrix {
  std::string name;  // without the blanks that pad it to 8 characters
  int rows = 0;      // |nrow|
  int cols = 0;
  int form = 0;      // Nastran's matrix form, as the file gives it
  int type = 0;      // 1..4: real single, real double, complex single, complex double
  bool complex() const { return type >= 3; }
};

// "real single precision", ..., "complex double precision" for types 1..4.
std::string Op4TypeText(int type);

class Op4File {
 public:
  enum class Encoding { kText, kBinary };

  // Reads and checks the whole file.
  // @throws InputError "<path>: ..." if the file does not exist, is not a
  //         regular file, is larger than the bound, holds no matrix, or
  //         breaks a rule of the format ("<path>:LINE:COL: matrix 'NAME': ..."
  //         in a text file, "<path>: byte N: matrix 'NAME': ..." in a
  //         binary one).
  explicit Op4File(const std::string& path);

  const std::string& path() const { return path_; }
  Encoding encoding() const { return encoding_; }
  // "text", "binary, little-endian, 4-byte words", ...
  std::string EncodingText() const;
  // The matrices in the file's order.
  const std::vector<Op4Matrix>& matrices() const { return matrices_; }
  bool Has(const std::string& name) const;
  // "EYE10, LOW, NULL" (the first 20, then "...").
  std::string NamesText() const;

  // Matrix `name` (nrow x ncol), real; single precision is widened exactly.
  // @throws InputError "<path>: ..." for a missing name (listing those the
  //         file holds), a name given to two matrices, a complex matrix, or
  //         more than limits::kMaxMatElements values.
  Eigen::MatrixXd Matrix(const std::string& name) const;
  // The same for a matrix of any type (a real one has zero imaginary
  // parts); here a value is two numbers of the bound.
  Eigen::MatrixXcd ComplexMatrix(const std::string& name) const;

 private:
  std::size_t IndexOf(const std::string& name) const;
  // Matrix `index` into `real` or `complex` (the other null).
  void Read(std::size_t index, Eigen::MatrixXd* real, Eigen::MatrixXcd* complex) const;

  std::string path_;
  std::string content_;
  Encoding encoding_ = Encoding::kText;
  bool little_endian_ = true;
  int word_bytes_ = 4;
  std::vector<Op4Matrix> matrices_;
};

// Whether the file at `path` starts as an OP4 file does (a binary header
// record, or a text header of four integers in 8-character fields), from its
// first bytes only: for a key that takes files of several formats. False,
// without an error, for a file that cannot be read.
bool LooksLikeOp4File(const std::string& path);

}  // namespace deb::formats
