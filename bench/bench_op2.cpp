// Reading modes from a large Nastran OP2 file (deb/formats/nastran_modes.h):
// writes a normal-modes OP2 of 10 000 grids x 1 000 modes in 64-bit words
// (480 MB of float64 shape values, 640 MB with each grid's id and type
// words), then times opening it (the scan of its records and the eigenvalue
// table) and reading 40 DOFs of every mode, and checks the values read.
//
//   build/bin/bench_op2 [--grids N] [--modes N] [--word 4|8] [--dir DIR] [--keep]
//
// The file is written to DIR (default: the system's temporary directory)
// and removed unless --keep. The times are those of a file in the page
// cache (it was just written); a cold read adds the disk's time to stream
// the eigenvalue and directory records, not the file's size.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "deb/formats/nastran_modes.h"
#include "tests/support/op2_writer.h"

namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

double Value(std::size_t k, std::size_t g, int c) {
  return 1e-3 * static_cast<double>((k * 7919 + g * 104729 + static_cast<std::size_t>(c) * 13) % 100003) - 50.0;
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t grids = 10000, modes = 1000;
  int word = 8;
  bool keep = false;
  std::filesystem::path dir = std::filesystem::temp_directory_path();
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&] {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return std::string(argv[++i]);
    };
    if (a == "--grids") grids = std::stoul(next());
    else if (a == "--modes") modes = std::stoul(next());
    else if (a == "--word") word = std::stoi(next());
    else if (a == "--dir") dir = next();
    else if (a == "--keep") keep = true;
    else {
      std::fprintf(stderr, "usage: bench_op2 [--grids N] [--modes N] [--word 4|8] [--dir DIR] [--keep]\n");
      return 2;
    }
  }
  const std::string path = (dir / "bench_op2_modes.op2").string();
  std::vector<deb::test::Op2Mode> table;
  for (std::size_t k = 0; k < modes; ++k) {
    const double f = 1.0 + 2.0 * static_cast<double>(k);
    const double w = 6.283185307179586 * f;
    table.push_back({static_cast<long long>(k + 1), w * w, w, f, 1.0 + 1e-3 * static_cast<double>(k), w * w});
  }
  std::vector<long long> ids(grids);
  for (std::size_t g = 0; g < grids; ++g) ids[g] = static_cast<long long>(1000 + 3 * g);
  deb::test::Op2Layout layout;
  layout.word = word;
  auto t0 = std::chrono::steady_clock::now();
  deb::test::WriteModesOp2(path, layout, table, ids, Value);
  const double write_s = Seconds(t0);
  const double mb = static_cast<double>(std::filesystem::file_size(path)) / 1e6;

  // 40 DOFs: 20 grids spread over the model, T3 and R1 of each.
  std::vector<deb::formats::NastranDof> dofs;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < 20; ++i) {
    const std::size_t g = (i * 997 + 13) % grids;
    dofs.push_back({ids[g], 3});
    dofs.push_back({ids[g], 4});
    index.push_back(g);
    index.push_back(g);
  }
  t0 = std::chrono::steady_clock::now();
  const deb::formats::NastranModeFile file(path);
  const double open_s = Seconds(t0);
  t0 = std::chrono::steady_clock::now();
  const Eigen::MatrixXd phi = file.Shapes(dofs, static_cast<int>(file.modes().size()));
  const double shapes_s = Seconds(t0);

  double worst = 0.0;
  for (std::size_t k = 0; k < modes; ++k)
    for (std::size_t i = 0; i < dofs.size(); ++i) {
      double expected = Value(k, index[i], dofs[i].component - 1);
      if (word == 4) expected = static_cast<float>(expected);
      worst = std::max(worst, std::abs(phi(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) - expected));
    }
  std::printf("OP2 of %zu grids x %zu modes, %d-byte words: %.0f MB, written in %.2f s\n", grids, modes, word, mb,
              write_s);
  std::printf("  open (scan of the records, LAMA):   %.3f s\n", open_s);
  std::printf("  %zu DOFs of %zu modes:               %.3f s\n", dofs.size(), file.modes().size(), shapes_s);
  std::printf("  total read:                         %.3f s\n", open_s + shapes_s);
  std::printf("  largest difference from the values written: %g\n", worst);
  if (!keep) std::filesystem::remove(path);
  return worst == 0.0 ? 0 : 1;
}
